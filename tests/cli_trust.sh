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
#   repair        overlays (and an EXR file) of stored cells deleted from the
#                 results folder, then --resume (one process, and --jobs 2):
#                 exit 0, just those cells recomputed, the files back byte
#                 for byte (an EXR file but its header's time), the rows one
#                 per key, equal to before, verified
#   symlinks      a symlink where the run would write (store, cache, results
#                 folder, .jobs-NAME, slurm/) is refused naming it, exit 2,
#                 nothing written through it
#   one_frame     (motion::one_frame) a path of one frame: computed, flicker
#                 not defined, no plot, exit 0, and --resume exits 0 too; a
#                 --cells slice holding the second frame of two alone: its
#                 flicker against the first (computed as a warm-up, not
#                 stored) is the whole run's
#   split         (motion::split) a path's sweep run whole, as --cells slices
#                 cut inside frames, as --jobs 2, and killed then resumed
#                 (one process, and --jobs 2): the same cells and figures,
#                 flicker included (doc/guide.md, Errors over motion)
set -u
bin=${1:?usage: cli_trust.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
# the store's cells with every column but timings and ids, one line per
# cell (the digest covers those: left out too), sorted; their figures the same; the overlays' names and bytes.
# runs and runs_map are timings too: how many runs the repetitions policy timed (reps.h), which the
# time each run took decides
cells_of() {
  local cols
  cols=$(sqlite3 "$1" "SELECT group_concat(name, ' || ''|'' || ') FROM pragma_table_info('cells')
                       WHERE name NOT LIKE 'ms%' AND name NOT IN ('cell_id', 'run_id', 'digest', 'runs', 'runs_map')")
  sqlite3 "$1" "SELECT $cols FROM cells" | sort
}
figs_of() {
  local cols
  cols=$(sqlite3 "$1" "SELECT group_concat(name, ' || ''|'' || ') FROM pragma_table_info('figures')
                       WHERE name NOT IN ('cell_id')")
  sqlite3 "$1" "SELECT $cols FROM figures" | sort
}
ovl_of() { (cd "$1" && find . -name '*.png' -print0 | sort -z | xargs -0 -r md5sum); }
same_as() {   # $1 reference root, $2 root, $3 study, $4 what
  diff <(cells_of "$1/shadowlab.db") <(cells_of "$2/shadowlab.db") >"$tmp/diff" ||
    { head -4 "$tmp/diff"; fail "$4: the cells differ from an uninterrupted run's"; }
  diff <(figs_of "$1/shadowlab.db") <(figs_of "$2/shadowlab.db") >"$tmp/diff" ||
    { head -4 "$tmp/diff"; fail "$4: the figures differ from an uninterrupted run's"; }
  diff <(ovl_of "$1/$3/overlays") <(ovl_of "$2/$3/overlays") >"$tmp/diff" ||
    { head -4 "$tmp/diff"; fail "$4: the overlays differ from an uninterrupted run's ($(wc -l <"$tmp/diff") lines)"; }
}
in_shards() {   # cells in the workers' stores of $1
  local n=0 f
  for f in "$1"/.jobs-*/task-*/shadowlab.db; do
    [ -f "$f" ] && n=$((n + $(sqlite3 "$f" 'SELECT COUNT(*) FROM cells' 2>/dev/null || echo 0)))
  done
  echo $n
}

# 2 views x 2 map sizes x 2 labels = 8 cells; the views split between two workers
cat >"$tmp/small.yaml" <<'YAML'
name: small
scenes:
  - {scene: primitives, viewpoints: [side, with]}
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
    n=$(sqlite3 "$tmp/${p%/*}/shadowlab.db" "SELECT COUNT(*) FROM cells")
    [ "$n" -eq 1 ] || fail "$p: $n cell(s) stored, want 1"
  done
  m=$tmp/a/still/motion
  ls "$m" | grep -q '\.png$' && fail "a/still: a plot was drawn: $(ls -l "$m")"
  ls "$m" | grep -q '\.dat$' || fail "a/still: no .dat file"
  grep -q "| not defined |" "$tmp/a/still/motion.md" || { cat "$tmp/a/still/motion.md"; fail "a/still: flicker not marked 'not defined'"; }
  grep -q "1 plot(s) not drawn" "$tmp/a/still/motion.md" || { cat "$tmp/a/still/motion.md"; fail "a/still: no note on the plot"; }
  # both frames of the two-frame path in one run: a compared pair, a plot
  "$bin" run "$tmp/two.yaml" --out "$tmp/c" -q >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; fail "two frames"; }
  ls "$tmp/c/two/motion" | grep -q '\.png$' || fail "two frames: no plot"
  # the slice's frame 1 was compared with frame 0 as the whole run's was
  q="SELECT flicker, flicker_compared FROM cells WHERE viewpoint LIKE '%.001'"
  whole=$(sqlite3 "$tmp/c/shadowlab.db" "$q") slice=$(sqlite3 "$tmp/b/shadowlab.db" "$q")
  echo "frame 1 flicker|compared: whole run $whole, slice --cells 1:2 $slice"
  [ "${whole#*|}" -gt 0 ] || fail "the whole run compared no pixel of frame 1"
  [ "$whole" = "$slice" ] || fail "frame 1's flicker: $slice in a slice of one frame, $whole in the whole run"
  ls "$tmp/b/two/motion" | grep -q '\.png$' || fail "the slice's pair: no plot"
  ;;
split)
  cat >"$tmp/m.yaml" <<'YAML'
name: m_motion
base: primitives
viewpoints:
  - {name: side, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}
paths:
  - {name: sun, frames: 6, camera: {viewpoint: side}, light: {elevation: [25, 65], azimuth: [20, 80]}}
YAML
  # 6 frames x 2 map sizes x 2 labels = 24 cells, 4 per frame
  cat >"$tmp/split.yaml" <<YAML
name: split
scenes: [{scene: $tmp/m.yaml, paths: [sun]}]
viewports: [{width: 160, height: 160}]
map_sizes: [256, 512]
methods: [{label: ff, method: nsm}, {label: texel, method: texel}]
outputs: {tables: true, overlays: true}
# timed stages repeated: each cell takes longer (its figures do not change),
# so a loaded machine's polls below still land inside the run they kill
repetitions: {warmup: 0, runs: 4}
YAML
  go() { "$bin" run "$tmp/split.yaml" --no-cache -q "$@" >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; fail "run $*"; }; }
  go --out "$tmp/ref"
  q="SELECT COUNT(*), SUM(flicker_compared > 0), SUM(flicker) > 0 FROM cells"
  n=$(sqlite3 "$tmp/ref/shadowlab.db" "$q")
  [ "$n" = "24|20|1" ] || fail "whole run: cells|compared|any flicker = $n, want 24|20|1"
  # slices cut inside frames 1, 3 and 4, each its own run into one store (the
  # later ones with --resume, which carries the earlier ones' overlays)
  go --out "$tmp/slices" --cells 0:5
  for cut in 5:14 14:17 17:24; do go --out "$tmp/slices" --cells $cut --resume; done
  same_as "$tmp/ref" "$tmp/slices" split "--cells 0:5, 5:14, 14:17, 17:24"
  echo "slices: the same cells and figures as the whole run"
  go --out "$tmp/jobs" --jobs 2
  same_as "$tmp/ref" "$tmp/jobs" split "--jobs 2"
  echo "--jobs 2: the same"
  go --out "$tmp/jobs3" --jobs 3
  same_as "$tmp/ref" "$tmp/jobs3" split "--jobs 3"
  echo "--jobs 3: the same"
  # killed when 7, then 15 cells are stored (frames 1 and 3 begun), resumed
  # A kill that lands after the run stored every cell (a loaded machine:
  # the run finished between two polls) tests nothing: that trial starts
  # again from an empty folder, at most 5 times; the assertion is unchanged.
  for how in run jobs; do
    out=$tmp/k$how
    flags=""
    [ $how = jobs ] && flags="--jobs 2"
    for try in 1 2 3 4 5; do
      rm -rf "$out"
      log=""
      landed=1
      for at in 7 15; do
        setsid "$bin" run "$tmp/split.yaml" --out "$out" --no-cache -q $flags $( [ $at = 15 ] && echo --resume ) \
          >"$tmp/run.out" 2>&1 &
        pid=$!
        for _ in $(seq 1 1000); do
          n=$(sqlite3 "$out/shadowlab.db" "SELECT COUNT(*) FROM cells" 2>/dev/null || echo 0)
          [ $how = jobs ] && n=$((n + $(in_shards "$out")))
          [ "$n" -ge $at ] && break
          sleep 0.01
        done
        kill -KILL -- -"$pid" 2>/dev/null || landed=0
        wait "$pid" 2>/dev/null
        sleep 0.05
        n=$(sqlite3 "$out/shadowlab.db" "SELECT COUNT(*) FROM cells" 2>/dev/null || echo 0)
        log="$log killed at $n stored + $(in_shards "$out") in shards;"
        [ $((n + $(in_shards "$out"))) -lt 24 ] || landed=0
        [ $landed = 1 ] || break
      done
      [ $landed = 1 ] && break
      echo "$how, try $try: a kill came after every cell was stored ($log); again"
    done
    [ $landed = 1 ] || fail "$how: in 5 tries no kill landed before every cell was stored: make the sweep longer"
    go --out "$out" $flags --resume
    same_as "$tmp/ref" "$out" split "$how killed at 7 and 15 cells, resumed"
    echo "$how$log resumed: the same"
  done
  ;;
resume)
  "$bin" run "$tmp/small.yaml" --out "$tmp/a" --jobs 2 --no-cache >"$tmp/1.out" 2>&1 || { cat "$tmp/1.out"; fail "--jobs 2"; }
  "$bin" run "$tmp/small.yaml" --out "$tmp/a" --jobs 2 --no-cache --resume >"$tmp/2.out" 2>&1 ||
    { cat "$tmp/2.out"; fail "--jobs 2 --resume"; }
  n=$(sqlite3 "$tmp/a/shadowlab.db" "SELECT COUNT(*), COUNT(DISTINCT scene || viewpoint || map_size || label) FROM cells")
  [ "$n" = "8|8" ] || fail "after --jobs 2 --resume: cells|keys = $n, want 8|8"
  grep -q "0 copied" "$tmp/2.out" || { cat "$tmp/2.out"; fail "the resume copied cells"; }
  # half the sweep stored by one process: the workers compute only the other half
  "$bin" run "$tmp/small.yaml" --out "$tmp/b" --cells 0:3 --no-cache -q >/dev/null 2>&1 || fail "--cells 0:3"
  "$bin" run "$tmp/small.yaml" --out "$tmp/b" --jobs 2 --no-cache --resume >"$tmp/3.out" 2>&1 ||
    { cat "$tmp/3.out"; fail "--jobs 2 --resume over 3 stored cells"; }
  n=$(sqlite3 "$tmp/b/shadowlab.db" "SELECT COUNT(*), COUNT(DISTINCT scene || viewpoint || map_size || label) FROM cells")
  [ "$n" = "8|8" ] || fail "after --cells 0:3, then --jobs 2 --resume: cells|keys = $n, want 8|8"
  grep -q "; 5 copied" "$tmp/3.out" || { cat "$tmp/3.out"; fail "want 5 cells computed by the workers"; }
  "$bin" run "$tmp/small.yaml" --out "$tmp/ref" --no-cache -q >/dev/null 2>&1 || fail "one process"
  same_as "$tmp/ref" "$tmp/b" small "--cells 0:3 then --jobs 2 --resume"
  ;;
kill)
  # 3 views x 4 map sizes x 3 labels = 36 cells, about 2 s in two workers
  cat >"$tmp/k.yaml" <<'YAML'
name: k
scenes:
  - {scene: primitives, viewpoints: [side, with, against]}
viewports: [{width: 384, height: 384}]
map_sizes: [512, 1024, 2048, 4096]
methods:
  - {label: ff, method: nsm}
  - {label: slope, method: nsm, self_shadow: slope}
  - {label: texel, method: texel}
outputs: {overlays: true}
repetitions: {warmup: 0, runs: 1}
YAML
  "$bin" run "$tmp/k.yaml" --out "$tmp/ref" --no-cache -q >/dev/null 2>&1 || fail "uninterrupted run"
  # start --jobs 2 in its own process group; when its workers have stored $3 cells in this attempt,
  # send $4 to the group (g: parent and workers) or to the parent only (p)
  attempt() {   # $1 out, $2 g|p, $3 cells, $4 signal, $5 extra flags
    local before n
    before=$(in_shards "$1")
    setsid "$bin" run "$tmp/k.yaml" --out "$1" --jobs 2 --no-cache $5 >"$tmp/run.out" 2>"$tmp/run.err" &
    local pid=$!
    for _ in $(seq 1 500); do
      n=$(in_shards "$1")
      [ $((n - before)) -ge "$3" ] && break
      sleep 0.02
    done
    kids=$(pgrep -P "$pid" | tr '\n' ' ')
    if [ "$2" = g ]; then kill -"$4" -- -"$pid" 2>/dev/null; else kill -"$4" "$pid" 2>/dev/null; fi ||
      fail "the run ended before $2 $3 $4: make the sweep longer"
    wait "$pid" 2>/dev/null; rc=$?
    log="$log $2:$3:$4 (exit $rc, $(in_shards "$1") in shards, $(sqlite3 "$1/shadowlab.db" 'SELECT COUNT(*) FROM cells' 2>/dev/null || echo 0) merged)"
  }
  live_workers() { local k c=0; for k in $kids; do kill -0 "$k" 2>/dev/null && c=$((c + 1)); done; echo $c; }
  t0=$(date +%s.%N)
  trial=0
  for plan in "g:3:KILL p:4:KILL g:6:KILL" "p:2:KILL g:10:KILL" "p:5:TERM g:4:KILL p:6:TERM" "g:1:KILL p:12:TERM"; do
    trial=$((trial + 1))
    out=$tmp/t$trial
    flags=""
    log=""
    for step in $plan; do
      IFS=: read -r who at sig <<<"$step"
      attempt "$out" "$who" "$at" "$sig" "$flags"
      if [ "$sig" = TERM ]; then
        # the parent passes SIGTERM on, waits for its workers, merges, says how to go on
        [ $rc -eq 143 ] || [ $rc -eq 0 ] || { cat "$tmp/run.err"; fail "trial $trial $step: exit $rc, want 143"; }
        [ "$(live_workers)" -eq 0 ] || fail "trial $trial $step: workers left running after the parent's exit"
        [ $rc -eq 143 ] && { grep -q "interrupted (SIGTERM)" "$tmp/run.err" || { cat "$tmp/run.err"; fail "trial $trial: no message"; }; }
      elif [ "$who" = p ]; then
        # the workers die with their parent
        for _ in $(seq 1 100); do [ "$(live_workers)" -eq 0 ] && break; sleep 0.02; done
        [ "$(live_workers)" -eq 0 ] || fail "trial $trial $step: the workers outlived a SIGKILLed parent"
      fi
      flags=--resume
    done
    "$bin" run "$tmp/k.yaml" --out "$out" --jobs 2 --no-cache --resume >"$tmp/resume.out" 2>&1
    rc=$?
    [ $rc -eq 0 ] || { cat "$tmp/resume.out"; fail "trial $trial ($plan): the resume exits $rc"; }
    n=$(sqlite3 "$out/shadowlab.db" "SELECT COUNT(*), COUNT(DISTINCT scene || viewpoint || map_size || label) FROM cells")
    [ "$n" = "36|36" ] || fail "trial $trial ($plan): cells|keys = $n, want 36|36"
    same_as "$tmp/ref" "$out" k "trial $trial ($plan)"
    ls -a "$out" | grep -q '^\.jobs-' && fail "trial $trial: the workers' folder is left behind"
    echo "trial $trial:$log; resumed: the same as an uninterrupted run"
  done
  echo "$trial trials in $(echo "$(date +%s.%N) - $t0" | bc) s"
  ;;
repair)
  sed 's/outputs: {overlays: true}/outputs: {overlays: true, exr: true}/; s/^name: small/name: rep/' \
    "$tmp/small.yaml" >"$tmp/rep.yaml"
  grep -q 'exr: true' "$tmp/rep.yaml" || fail "no EXR in the config"
  # an EXR file's header carries the time it was written (capDate): left out
  exr_of() {
    local f
    for f in $(cd "$1" && ls *.exr | sort); do
      echo "$f $(perl -0777 -pe 's/capDate\0string\0....\d{4}:\d\d:\d\d \d\d:\d\d:\d\d//s' "$1/$f" | md5sum)"
    done
  }
  for how in run jobs; do
    out=$tmp/$how
    flags=--no-cache
    [ $how = jobs ] && flags="--no-cache --jobs 2"
    "$bin" run "$tmp/rep.yaml" --out "$out" $flags >"$tmp/1.out" 2>&1 || { cat "$tmp/1.out"; fail "$how: first run"; }
    ovl_of "$out/rep/overlays" >"$tmp/ovl.before"
    exr_of "$out/rep/exr" >"$tmp/exr.before"
    cells_of "$out/shadowlab.db" >"$tmp/cells.before"
    [ "$(wc -l <"$tmp/ovl.before")" -eq 8 ] && [ "$(wc -l <"$tmp/exr.before")" -eq 8 ] ||
      fail "$how: want 8 overlays and 8 EXR files: $(cat "$tmp/ovl.before" "$tmp/exr.before")"
    # two overlays lost, then the EXR file of a third cell
    for pass in png exr; do
      if [ $pass = png ]; then
        gone=$(ls "$out/rep/overlays" | sort | sed -n '2p;7p'); want=2
        for f in $gone; do rm "$out/rep/overlays/$f"; done
      else
        gone=$(ls "$out/rep/exr" | sort | sed -n '4p'); want=1
        for f in $gone; do rm "$out/rep/exr/$f"; done
      fi
      "$bin" run "$tmp/rep.yaml" --out "$out" $flags --resume >"$tmp/2.out" 2>&1
      rc=$?
      [ $rc -eq 0 ] || { cat "$tmp/2.out"; fail "$how: --resume after losing $pass files $gone: exit $rc, want 0"; }
      if [ $how = run ]; then
        grep -q "rep: $want cell(s) computed, $((8 - want)) already stored" "$tmp/2.out" ||
          { cat "$tmp/2.out"; fail "$how: want $want cell(s) recomputed"; }
      else
        grep -q "; $want copied" "$tmp/2.out" || { cat "$tmp/2.out"; fail "$how: want $want cell(s) recomputed and copied"; }
      fi
      diff "$tmp/ovl.before" <(ovl_of "$out/rep/overlays") >"$tmp/diff" ||
        { cat "$tmp/diff"; fail "$how: the overlays are not back as they were ($pass lost: $gone)"; }
      diff "$tmp/exr.before" <(exr_of "$out/rep/exr") >"$tmp/diff" ||
        { cat "$tmp/diff"; fail "$how: the EXR files are not back as they were ($pass lost: $gone)"; }
      n=$(sqlite3 "$out/shadowlab.db" "SELECT COUNT(*), COUNT(DISTINCT scene || viewpoint || map_size || label) FROM cells")
      [ "$n" = "8|8" ] || fail "$how: cells|keys = $n, want 8|8"
      diff "$tmp/cells.before" <(cells_of "$out/shadowlab.db") >"$tmp/diff" ||
        { head -4 "$tmp/diff"; fail "$how: the recomputed rows differ from the first run's"; }
      "$bin" verify "$out/shadowlab.db" >"$tmp/v.out" 2>&1 || { cat "$tmp/v.out"; fail "$how: verify"; }
      echo "$how: lost $pass $(echo $gone): --resume recomputed $want cell(s), files back byte for byte, store verified"
    done
  done
  ;;
symlinks)
  n=0
  for how in run jobs; do
    for name in shadowlab.db cache small .jobs-small; do
      [ $how = run ] && [ $name = .jobs-small ] && continue
      n=$((n + 1))
      out=$tmp/o$n outside=$tmp/outside$n
      mkdir -p "$out" "$outside"
      ln -s "$outside/$name" "$out/$name"
      [ $name = shadowlab.db ] || mkdir "$outside/$name"
      if [ $how = run ]; then "$bin" run "$tmp/small.yaml" --out "$out" -q >"$tmp/out" 2>&1
      else "$bin" run "$tmp/small.yaml" --out "$out" --jobs 2 >"$tmp/out" 2>&1; fi
      rc=$?
      [ $rc -eq 2 ] || { cat "$tmp/out"; fail "$how with a link $name: exit $rc, want 2"; }
      grep -q "$out/$name: is a symbolic link" "$tmp/out" || { cat "$tmp/out"; fail "$how with a link $name: not named"; }
      [ -z "$(find "$outside" -mindepth 1 -not -path "$outside/$name")" ] && [ -z "$(ls -A "$outside/$name" 2>/dev/null)" ] ||
        fail "$how with a link $name: written through it: $(find "$outside")"
      echo "$how: a link named $name refused (exit 2)"
    done
  done
  # submit's slurm/
  mkdir -p "$tmp/s" "$tmp/outside_s/slurm"
  ln -s "$tmp/outside_s/slurm" "$tmp/s/slurm"
  "$bin" submit "$tmp/small.yaml" --slurm --out "$tmp/s" --dry-run >"$tmp/out" 2>&1
  rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/out"; fail "submit with a link slurm/: exit $rc, want 2"; }
  grep -q "$tmp/s/slurm: is a symbolic link" "$tmp/out" || { cat "$tmp/out"; fail "submit: slurm/ not named"; }
  [ -z "$(ls -A "$tmp/outside_s/slurm")" ] || fail "submit wrote through the link slurm/"
  echo "submit: a link named slurm refused (exit 2)"
  ;;
*) echo "unknown case $case_"; exit 2 ;;
esac
echo "1 passed, 0 failed"
