#!/usr/bin/env bash
# cli::hostile — one writer per results store (a second run is refused with
# the holder's pid, and two concurrent --resume runs leave each cell once),
# a damaged store is refused before anything is written into it, readers open
# the store read-only beside a writer. (issue 15)
set -u
bin=${1:?usage: cli_hostile.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'kill $(jobs -p) 2>/dev/null; rm -rf "$tmp"' EXIT
pass=0 fail=0
ok()  { echo "ok   $1"; pass=$((pass + 1)); }
bad() { echo "FAIL $1"; fail=$((fail + 1)); }

cat >"$tmp/small.yaml" <<'YAML'
name: small
scenes:
  - {scene: primitives, viewpoints: [side, with, against]}
viewports: [{width: 128, height: 128}]
map_sizes: [64, 128]
contours: [2]
methods: [{label: nsm, method: nsm}]
outputs: {tables: true, overlays: true, overlay_contour: 2}
YAML
out=$tmp/res db=$tmp/res/shadowlab.db

# 1. a held lock: a writer is refused at once, exit 2, naming the holder
mkdir -p "$out"
( exec 9>>"$db.lock"; flock 9; exec sleep 30 ) &   # the sleep holds the lock
holder=$!
sleep 0.5
timeout 60 "$bin" run "$tmp/small.yaml" --out "$out" >"$tmp/o" 2>"$tmp/e"; rc=$?
if [ $rc -eq 2 ] && grep -q "results store in use by another run" "$tmp/e"; then ok "held lock refused: $(head -1 "$tmp/e")"
else bad "held lock: exit $rc: $(cat "$tmp/e")"; fi
# 2. readers open read-only beside the writer (no lock taken)
kill $holder; wait $holder 2>/dev/null
timeout 120 "$bin" run "$tmp/small.yaml" --out "$out" >/dev/null 2>"$tmp/e" || bad "first run: $(cat "$tmp/e")"
( exec 9>>"$db.lock"; flock 9; exec sleep 30 ) &   # the sleep holds the lock
holder=$!
sleep 0.5
if timeout 60 "$bin" table "$db" >"$tmp/o" 2>"$tmp/e"; then ok "table beside a writer"
else bad "table beside a writer: $(cat "$tmp/e")"; fi
kill $holder; wait $holder 2>/dev/null

# 3. two concurrent --resume runs of one config into one store: each cell once
rm -rf "$out"
"$bin" run "$tmp/small.yaml" --out "$out" --resume >"$tmp/o1" 2>"$tmp/e1" &
a=$!
"$bin" run "$tmp/small.yaml" --out "$out" --resume >"$tmp/o2" 2>"$tmp/e2" &
b=$!
wait $a; ra=$?
wait $b; rb=$?
for r in "$ra:$tmp/e1" "$rb:$tmp/e2"; do
  rc=${r%%:*} e=${r#*:}
  if [ "$rc" -ne 0 ] && ! { [ "$rc" -eq 2 ] && grep -q "in use by another run (pid [0-9]" "$e"; }; then
    bad "concurrent run: exit $rc: $(cat "$e")"
  fi
done
# whichever was refused, a last --resume completes the sweep
timeout 120 "$bin" run "$tmp/small.yaml" --out "$out" --resume >/dev/null 2>"$tmp/e" || bad "last resume: $(cat "$tmp/e")"
n=$(sqlite3 "$db" "SELECT count(*) FROM cells")
u=$(sqlite3 "$db" "SELECT count(*) FROM (SELECT DISTINCT scene, viewpoint, map_size, label FROM cells)" 2>/dev/null || echo "?")
if [ "$n" = 6 ] && [ "$u" = 6 ]; then ok "two concurrent --resume runs: $n cells, $u distinct (exits $ra, $rb)"
else bad "two concurrent --resume runs: $n cells, $u distinct (want 6, 6; exits $ra, $rb)"; fi
ls "$out"/small/ >/dev/null 2>&1 || bad "no run folder"

# 4. a damaged store is refused before anything is written, exit 2
cp "$db" "$tmp/damaged.db"
size=$(stat -c %s "$tmp/damaged.db")
head -c 3000 /dev/urandom | dd of="$tmp/damaged.db" bs=1 seek=$((size / 2)) conv=notrunc status=none
timeout 60 "$bin" run "$tmp/small.yaml" --out "$tmp/res2" --db "$tmp/damaged.db" --resume >"$tmp/o" 2>"$tmp/e"; rc=$?
if [ $rc -eq 2 ] && grep -Eq "damaged\.db.*(damaged|malformed)" "$tmp/e"; then ok "damaged store refused: $(head -1 "$tmp/e")"
else bad "damaged store: exit $rc: $(cat "$tmp/e")"; fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
