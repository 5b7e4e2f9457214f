#!/usr/bin/env bash
# jobs::* and motion::one_frame — what a run writes can be trusted (issue 34):
#   cache_counts  a cell whose truth came from the cache (hard and area light)
#                 stores the counts of one that traced it (truth_rays included)
#   resume        run --jobs 2, then --jobs 2 --resume: nothing recomputed, one
#                 cell per key
#   kill          run --jobs 2 killed (SIGKILL to the group, SIGKILL to the
#                 parent only, SIGTERM to the parent) at several moments, then
#                 --resume: the store row for row (counts and figures, no
#                 timings or ids) and the overlays byte for byte equal an
#                 uninterrupted run's; a SIGTERM leaves no worker running
#   symlinks      a symlink where the run would write (store, cache, results
#                 folder, .jobs-NAME, slurm/) is refused naming it, exit 2,
#                 nothing written through it
#   one_frame     (motion::one_frame) a path of one frame, and a --cells slice
#                 of one frame: computed, flicker not defined, no plot, exit 0,
#                 and --resume exits 0 too
set -u
bin=${1:?usage: cli_trust.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
# the store's cells with every column but timings, ids and the overlay's
# folder, one line per cell, sorted; and their figures
cells_of() {
  local cols
  cols=$(sqlite3 "$1" "SELECT group_concat(name, ' || ''|'' || ') FROM pragma_table_info('cells')
                       WHERE name NOT LIKE 'ms%' AND name NOT IN ('cell_id', 'run_id', 'overlay')")
  sqlite3 "$1" "SELECT $cols FROM cells" | sort
}
figs_of() {
  local cols
  cols=$(sqlite3 "$1" "SELECT group_concat('f.' || name, ' || ''|'' || ') FROM pragma_table_info('figures')
                       WHERE name NOT LIKE 'ms%' AND name NOT IN ('cell_id')")
  sqlite3 "$1" "SELECT c.scene || c.viewpoint || c.map_size || c.label || '|' || $cols
                FROM figures f JOIN cells c USING (cell_id)" | sort
}
ovl_of() { (cd "$1" && find . -name '*.png' -type f -print0 | sort -z | xargs -0 -r md5sum); }

# 2 views x 2 map sizes x 2 labels = 8 cells; the views split between two workers
cat >"$tmp/small.yaml" <<'YAML'
name: small
scenes:
  - {scene: primitives, viewpoints: [side, front]}
viewports: [{width: 192, height: 192}]
map_sizes: [256, 512]
methods:
  - {label: ff, method: nsm}
  - {label: texel, method: texel}
outputs: {overlays: true}
repetitions: {warmup: 0, runs: 1}
YAML

case $case_ in
cache_counts)
  cat >"$tmp/c.yaml" <<'YAML'
name: c
scenes:
  - {scene: primitives, viewpoints: [side]}
  - {scene: curtis_box, viewpoints: [above]}
viewports: [{width: 128, height: 128}]
map_sizes: [256]
methods:
  - {label: ff, method: nsm}
  - {label: mc, method: soft_mc}
area_samples: 4
repetitions: {warmup: 0, runs: 1}
YAML
  "$bin" run "$tmp/c.yaml" --out "$tmp/a" --cache "$tmp/cache" -q >"$tmp/a.out" 2>&1 || { cat "$tmp/a.out"; fail "traced run"; }
  "$bin" run "$tmp/c.yaml" --out "$tmp/b" --cache "$tmp/cache" -q >"$tmp/b.out" 2>&1 || { cat "$tmp/b.out"; fail "cached run"; }
  ls "$tmp/cache" | grep -q '^area-' || fail "no area truth in the cache"
  ls "$tmp/cache" | grep -q '^truth-' || fail "no hard truth in the cache"
  # the second run read both truths from the cache
  [ "$(cut -d, -f15 "$tmp/b/c/costs.csv" | tail -n +2 | sort -u)" = 1 ] || { cat "$tmp/b/c/costs.csv"; fail "the second run did not read the cache"; }
  a=$(sqlite3 "$tmp/a/shadowlab.db" "SELECT scene, label, truth_rays FROM cells ORDER BY 1, 2")
  b=$(sqlite3 "$tmp/b/shadowlab.db" "SELECT scene, label, truth_rays FROM cells ORDER BY 1, 2")
  echo "traced: $(echo $a)"; echo "cached: $(echo $b)"
  [ "$a" = "$b" ] || fail "truth_rays differ between a traced and a cached truth"
  sqlite3 "$tmp/b/shadowlab.db" "SELECT COUNT(*) FROM cells WHERE truth_rays = 0" | grep -qx 0 || fail "a cell stores truth_rays 0"
  diff <(cells_of "$tmp/a/shadowlab.db") <(cells_of "$tmp/b/shadowlab.db") >"$tmp/diff" || { head "$tmp/diff"; fail "the cells' counts differ"; }
  ;;
one_frame)
  cat >"$tmp/one.yaml" <<'YAML'
name: one_motion
base: primitives
viewpoints:
  - {name: side, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}
paths:
  - {name: still, frames: 1, camera: {viewpoint: side}, light: {elevation: [25, 65], azimuth: [20, 80]}}
  - {name: two, frames: 2, camera: {viewpoint: side}, light: {elevation: [25, 65], azimuth: [20, 80]}}
YAML
  for p in still two; do
    cat >"$tmp/$p.yaml" <<YAML
name: $p
scenes: [{scene: $tmp/one.yaml, paths: [$p]}]
viewports: [{width: 128, height: 128}]
map_sizes: [256]
methods: [{label: ff, method: nsm}]
outputs: {tables: true, overlays: true}
repetitions: {warmup: 0, runs: 1}
YAML
  done
  # a path of one frame; then the second frame of two alone (a --cells slice), twice (--resume)
  for run in "still.yaml --out $tmp/a" "still.yaml --out $tmp/a --resume" "two.yaml --cells 1:2 --out $tmp/b" \
             "two.yaml --cells 1:2 --out $tmp/b --resume"; do
    set -- $run
    "$bin" run "$tmp/$@" -q >"$tmp/run.out" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { cat "$tmp/run.out"; fail "run $run: exit $rc, want 0"; }
  done
  for p in a/still b/two; do
    m=$tmp/$p/motion
    n=$(sqlite3 "$tmp/${p%/*}/shadowlab.db" "SELECT COUNT(*) FROM cells")
    [ "$n" -eq 1 ] || fail "$p: $n cell(s) stored, want 1"
    ls "$m" | grep -q '\.png$' && fail "$p: a plot was drawn: $(ls -l "$m")"
    ls "$m" | grep -q '\.dat$' || fail "$p: no .dat file"
    grep -q "| not defined |" "$tmp/$p/motion.md" || { cat "$tmp/$p/motion.md"; fail "$p: flicker not marked 'not defined'"; }
    grep -q "1 plot(s) not drawn" "$tmp/$p/motion.md" || { cat "$tmp/$p/motion.md"; fail "$p: no note on the plot"; }
  done
  # both frames of the two-frame path in one run: a compared pair, a plot
  "$bin" run "$tmp/two.yaml" --out "$tmp/c" -q >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; fail "two frames"; }
  ls "$tmp/c/two/motion" | grep -q '\.png$' || fail "two frames: no plot"
  ;;
*) echo "unknown case $case_"; exit 2 ;;
esac
echo "1 passed, 0 failed"
