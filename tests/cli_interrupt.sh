#!/usr/bin/env bash
# cli::interrupt — SIGINT mid-sweep: the run stops after the cell under way,
# says how many cells are stored and the --resume command, exits 130, leaves
# no staging folder; the printed command completes the sweep and the run
# folder's figures.csv then holds every cell (rebuilt from the store), as
# `shadowlab table DB` does. SIGTERM exits 143 the same way.
set -u
bin=${1:?usage: cli_interrupt.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/sweep.yaml" <<'YAML'
name: sweep
scenes: [{scene: primitives}]
viewports: [{width: 512, height: 512}]
map_sizes: [512, 1024, 2048, 4096]
methods:
  - {label: ff, method: nsm}
  - {label: slope, method: nsm, self_shadow: slope}
  - {label: id, method: nsm, self_shadow: triangle_id}
outputs: {overlays: true}
YAML
cells() { "$bin" table "$1" --format csv 2>/dev/null | tail -n +2 | cut -d, -f1-6 | sort -u | wc -l; }
interrupt() {   # $1 signal, $2 output root; sets rc
  "$bin" run "$tmp/sweep.yaml" --out "$2" --no-cache >"$tmp/out" 2>"$tmp/err" &
  local pid=$!
  for _ in $(seq 1 600); do
    [ -f "$2/shadowlab.db" ] && [ "$(cells "$2/shadowlab.db")" -ge 3 ] && break
    sleep 0.05
  done
  kill -"$1" "$pid" 2>/dev/null || { echo "FAIL the sweep ended before the signal: make it longer"; exit 1; }
  wait "$pid"; rc=$?
}

interrupt INT "$tmp/a"
[ $rc -eq 130 ] || { echo "FAIL SIGINT: exit $rc, want 130"; cat "$tmp/err"; exit 1; }
stored=$(cells "$tmp/a/shadowlab.db")
grep -q "^shadowlab: interrupted (SIGINT): $stored of 36 cell(s) of this config are stored in $tmp/a/shadowlab.db; to go on:" "$tmp/err" ||
  { echo "FAIL no interrupt message for $stored cells:"; cat "$tmp/err"; exit 1; }
echo "interrupted after $stored of 36 cells"
[ "$stored" -lt 36 ] || { echo "FAIL the sweep finished: make it longer"; exit 1; }
ls -a "$tmp/a" | grep -q partial && { echo "FAIL staging folder left: $(ls -a "$tmp/a")"; exit 1; }
grep -q "^written to $tmp/a/sweep/" "$tmp/out" || { echo "FAIL no 'written to' line"; cat "$tmp/out"; exit 1; }
[ "$(tail -n +2 "$tmp/a/sweep/figures.csv" | cut -d, -f1-6 | sort -u | wc -l)" -eq "$stored" ] ||
  { echo "FAIL figures.csv after the interrupt does not hold the $stored stored cells"; exit 1; }
cmd=$(grep -A1 "to go on:" "$tmp/err" | tail -1)
case $cmd in "  shadowlab run "*" --resume") ;; *) echo "FAIL resume command: '$cmd'"; exit 1 ;; esac
eval "\"$bin\" ${cmd#  shadowlab }" >"$tmp/resume.out" 2>&1 || { echo "FAIL resume:"; cat "$tmp/resume.out"; exit 1; }
grep -q "$((36 - stored)) cell(s) computed, $stored already stored" "$tmp/resume.out" ||
  { echo "FAIL resume did not skip the stored cells:"; cat "$tmp/resume.out"; exit 1; }
# the folder holds every cell, as the store does
"$bin" table "$tmp/a/shadowlab.db" --format csv | tail -n +2 | sort >"$tmp/db.csv"
tail -n +2 "$tmp/a/sweep/figures.csv" | sort >"$tmp/folder.csv"
[ "$(cut -d, -f1-6 "$tmp/folder.csv" | sort -u | wc -l)" -eq 36 ] ||
  { echo "FAIL figures.csv after --resume: $(cut -d, -f1-6 "$tmp/folder.csv" | sort -u | wc -l) cells, want 36"; exit 1; }
diff -q "$tmp/db.csv" "$tmp/folder.csv" >/dev/null || { echo "FAIL figures.csv differs from the store:"; diff "$tmp/db.csv" "$tmp/folder.csv" | head -5; exit 1; }
for f in table.md table.tex; do
  n=$(grep -c "sweep" "$tmp/a/sweep/$f")
  [ "$n" -gt 0 ] || { echo "FAIL $f empty"; exit 1; }
done
[ "$(ls "$tmp/a/sweep/overlays" | wc -l)" -eq 36 ] || { echo "FAIL overlays after --resume: $(ls "$tmp/a/sweep/overlays" | wc -l)"; exit 1; }
ls -a "$tmp/a" | grep -q partial && { echo "FAIL staging folder left after resume"; exit 1; }

interrupt TERM "$tmp/t"
[ $rc -eq 143 ] || { echo "FAIL SIGTERM: exit $rc, want 143"; cat "$tmp/err"; exit 1; }
grep -q "interrupted (SIGTERM)" "$tmp/err" || { echo "FAIL no SIGTERM message"; exit 1; }
ls -a "$tmp/t" | grep -q partial && { echo "FAIL staging folder left after SIGTERM"; exit 1; }
echo "1 passed, 0 failed"
