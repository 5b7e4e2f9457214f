#!/usr/bin/env bash
# scripts/kill_resume.sh BIN CONFIG [OUT] — issue 34's acceptance: CONFIG
# under `run --jobs 2`, killed three times (SIGKILL to the parent and its
# workers, SIGKILL to the parent only, SIGTERM to the parent) at a quarter,
# a half and three quarters of the cells left in each attempt, then
# resumed, against one uninterrupted process: the store row for row (every
# column but timings and ids; every figure) and the overlays byte for byte.
# No truth cache on either side (--no-cache). Prints each step and the
# verdict; exit 0 when equal.
set -u
bin=${1:?usage: kill_resume.sh BIN CONFIG [OUT]}
cfg=${2:?config}
out=${3:-$(mktemp -d)}
mkdir -p "$out"
name=$(sed -n 's/^name: *//p' "$cfg" | head -1)
total=$("$bin" validate "$cfg" | head -1 | sed 's/.* \([0-9]*\) cell(s)/\1/')
cells_of() {
  local cols
  cols=$(sqlite3 "$1" "SELECT group_concat(name, ' || ''|'' || ') FROM pragma_table_info('cells')
                       WHERE name NOT LIKE 'ms%' AND name NOT IN ('cell_id', 'run_id', 'digest')")
  sqlite3 "$1" "SELECT $cols FROM cells" | sort
}
figs_of() { sqlite3 "$1" "SELECT scene, viewpoint, viewport, map_size, label, region, figure, count, percent, percent_of FROM figures" | sort; }
ovl_of() { (cd "$1" && find . -name '*.png' -print0 | sort -z | xargs -0 -r md5sum); }
merged() { sqlite3 "$1/shadowlab.db" 'SELECT COUNT(*) FROM cells' 2>/dev/null || echo 0; }
stored() {   # cells in the workers' stores
  local n=0 f
  for f in "$1"/.jobs-*/task-*/shadowlab.db; do
    [ -f "$f" ] && n=$((n + $(sqlite3 "$f" 'SELECT COUNT(*) FROM cells' 2>/dev/null || echo 0)))
  done
  echo $n
}
t=$(date +%s.%N)
/usr/bin/time -f "%e s wall, %U+%S s CPU" "$bin" run "$cfg" --out "$out/one" --no-cache -q 2>"$out/one.time" >/dev/null ||
  { echo "the uninterrupted run failed"; exit 2; }
echo "uninterrupted, one process: $(tail -1 "$out/one.time")"
flags=
for step in g:KILL:25 p:KILL:50 p:TERM:75; do
  IFS=: read -r who sig pct <<<"$step"
  before=$(stored "$out/jobs")
  done_=$(merged "$out/jobs"); [ "$before" -gt "$done_" ] && done_=$before
  want=$(((total - done_) * pct / 100))
  setsid "$bin" run "$cfg" --out "$out/jobs" --jobs 2 --no-cache $flags >"$out/$who$sig.out" 2>&1 &
  pid=$!
  while kill -0 "$pid" 2>/dev/null && [ $(($(stored "$out/jobs") - before)) -lt "$want" ]; do sleep 0.05; done
  if [ "$who" = g ]; then kill -"$sig" -- -"$pid"; else kill -"$sig" "$pid"; fi 2>/dev/null
  wait "$pid" 2>/dev/null
  rc=$?
  sleep 0.2
  echo "--jobs 2 $flags: SIG$sig to the $([ "$who" = g ] && echo "parent and workers" || echo "parent") after $want more cell(s): exit $rc, $(stored "$out/jobs") cell(s) in the shards, $(merged "$out/jobs") in the store"
  flags=--resume
done
/usr/bin/time -f "%e s wall, %U+%S s CPU" "$bin" run "$cfg" --out "$out/jobs" --jobs 2 --no-cache --resume >"$out/resume.out" 2>"$out/resume.err"
rc=$?
echo "--jobs 2 --resume: exit $rc, $(tail -1 "$out/resume.err")"
bad=0
diff <(cells_of "$out/one/shadowlab.db") <(cells_of "$out/jobs/shadowlab.db") >"$out/cells.diff" || { echo "cells differ: $out/cells.diff"; bad=1; }
diff <(figs_of "$out/one/shadowlab.db") <(figs_of "$out/jobs/shadowlab.db") >"$out/figs.diff" || { echo "figures differ: $out/figs.diff"; bad=1; }
diff <(ovl_of "$out/one/$name/overlays") <(ovl_of "$out/jobs/$name/overlays") >"$out/overlays.diff" || { echo "overlays differ: $out/overlays.diff"; bad=1; }
echo "$(sqlite3 "$out/jobs/shadowlab.db" 'SELECT COUNT(*) FROM cells') cells for $total keys; $(sqlite3 "$out/jobs/shadowlab.db" 'SELECT COUNT(*) FROM figures') figure rows; $(ls "$out/jobs/$name/overlays" | wc -l) overlays"
[ $rc -eq 0 ] && [ $bad -eq 0 ] && echo "EQUAL: killed three times and resumed = one uninterrupted run (figures, counts, overlays)" && exit 0
echo "DIFFERENT"; exit 1
