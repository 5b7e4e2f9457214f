#!/usr/bin/env bash
# cli::kill_resume — kill a sweep mid-way (SIGKILL, no chance to clean up),
# then --resume: the store must end with exactly the rows of an
# uninterrupted run, and the killed run must have left no partial cell and
# no half-written results folder.
set -u
bin=${1:?usage: cli_resume.sh path/to/shadowlab}
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

"$bin" run "$tmp/sweep.yaml" --out "$tmp/a" --no-cache >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 400); do
  [ -f "$tmp/a/shadowlab.db" ] && [ "$(cells "$tmp/a/shadowlab.db")" -ge 3 ] && break
  sleep 0.05
done
if ! kill -9 "$pid" 2>/dev/null; then
  echo "FAIL the sweep finished before it could be killed: make it longer"; exit 1
fi
wait "$pid" 2>/dev/null
stored=$(cells "$tmp/a/shadowlab.db")
echo "killed after $stored of 36 cells"
[ -e "$tmp/a/sweep" ] && { echo "FAIL a killed run left results/sweep/"; exit 1; }
# every stored cell is whole: 4 regions x every figure of harness/score/figrec.h + background
nfig=$(grep -A200 "define SL_FIGURES(X)" harness/score/figrec.h | sed "/^enum/q" | grep -c "^    X(")
rows=$("$bin" table "$tmp/a/shadowlab.db" --format csv | tail -n +2 | wc -l)
[ "$rows" -eq $((stored * (4 * nfig + 1))) ] || { echo "FAIL $rows figure rows for $stored cells ($nfig figures)"; exit 1; }

"$bin" run "$tmp/sweep.yaml" --out "$tmp/a" --resume --no-cache >"$tmp/resume.out" 2>&1 || { cat "$tmp/resume.out"; exit 1; }
grep -q "$((36 - stored)) cell(s) computed, $stored already stored" "$tmp/resume.out" ||
  { echo "FAIL resume did not skip exactly the stored cells:"; tail -3 "$tmp/resume.out"; exit 1; }
# the overlays of the cells stored before the kill were carried over from its staging folder
n=$(ls "$tmp/a/sweep/overlays" | wc -l)
[ "$n" -eq 36 ] || { echo "FAIL $n overlays after the resume, want 36"; exit 1; }
ls -a "$tmp/a" | grep -q partial && { echo "FAIL the killed run's staging folder is left behind"; exit 1; }
"$bin" run "$tmp/sweep.yaml" --out "$tmp/b" --no-cache >/dev/null 2>&1 || exit 1
"$bin" table "$tmp/a/shadowlab.db" --format csv | sort >"$tmp/a.csv"
"$bin" table "$tmp/b/shadowlab.db" --format csv | sort >"$tmp/b.csv"
if ! diff -q "$tmp/a.csv" "$tmp/b.csv" >/dev/null; then
  echo "FAIL resumed store differs from an uninterrupted run:"; diff "$tmp/a.csv" "$tmp/b.csv" | head; exit 1
fi
echo "1 passed, 0 failed"
