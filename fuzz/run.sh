#!/usr/bin/env bash
# fuzz/run.sh BUILD SECONDS [ENTRY...] — run libFuzzer entries (FUZZ_JOBS at
# a time, default the cores), each for SECONDS with its seed corpus, and print one summary line
# each (execs, exec/s, coverage). Exits 1 if any entry found a crash, a
# timeout or a leak (its input is kept and shown), 0 otherwise. Mesh
# entries built with SL_FUZZ_MESH_HERE run in libFuzzer's fork mode and fail
# only on crashes not in assimp's own code (fork_check below).
#   CC=clang CXX=clang++ cmake -S . -B build-fuzz -DSL_FUZZ=ON -DSL_TESTS=OFF -DSL_FUZZ_MESH_HERE=ON
#   cmake --build build-fuzz --target fuzz_config fuzz_scene fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_gltf
#   fuzz/run.sh build-fuzz 60            # what CI runs
# Seeds (copied, never written): tests/bad/ and the repository's configs,
# scenes and model files, plus Debian's assimp-testmodels where installed
# (files up to 64 KiB: larger ones only slow each input down). New inputs
# go to $FUZZ_WORK (default: a temporary folder, removed unless a finding
# was kept there).
set -u
cd "$(dirname "$0")/.."
build=${1:?usage: fuzz/run.sh BUILD SECONDS [ENTRY...]}
secs=${2:?usage: fuzz/run.sh BUILD SECONDS [ENTRY...]}
shift 2
entries=("$@")
[ ${#entries[@]} -eq 0 ] && entries=(fuzz_config fuzz_scene fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_gltf)
work=${FUZZ_WORK:-$(mktemp -d /tmp/sl-fuzz-run.XXXXXX)}
# assimp's own leaks on malformed models are not findings (fuzz/lsan.supp)
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
mkdir -p "$work"
assimp=/usr/share/assimp/models

# seeds ENTRY DIR: copy the entry's seed files into DIR
seeds() {
  local n=0 f dst=$2
  case $1 in
    fuzz_config) set -- tests/bad/*.yaml configs/*.yaml ;;
    fuzz_scene) set -- tests/bad/scenes/*.yaml tests/scenes/*.yaml scenes/*.yaml scenes/*/*.yaml ;;
    fuzz_mesh_obj) set -- tests/models/*.obj tests/bad/models/*.obj "$assimp"/OBJ/*.obj ;;
    fuzz_mesh_ply) set -- tests/models/*.ply tests/bad/models/*.ply "$assimp"/PLY/*.ply ;;
    fuzz_mesh_gltf) # embedded buffers only load: an external .bin is not beside the input
      set -- tests/models/*.gltf tests/bad/models/*.gltf $(find "$assimp"/glTF2 -name '*.gltf' 2>/dev/null) ;;
    *) echo "fuzz/run.sh: unknown entry $1" >&2; return 1 ;;
  esac
  for f in "$@"; do
    [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 65536 ] || continue
    n=$((n + 1))
    cp "$f" "$dst/$n-$(basename "$f")" || return 1
  done
}

# show INPUT: its size and first bytes
show() {
  echo "  input $1 ($(stat -c %s "$1") bytes):"
  head -c 512 "$1" | od -c | head -n 8 | sed 's/^/    /'
}

# fork_check ENTRY BIN ASAN: the verdict of an in-process mesh entry run in
# fork mode (uses one()'s variables). Each sanitizer report in reports/ is
# classified by its stack (fuzz/classify.awk): one whose first frame outside
# the sanitizers and the system libraries is in libassimp is assimp's own, a
# crash the reader's child contains at run time; any other (shadowlab's
# code, a UBSan report, a stack it cannot place) fails, with the inputs
# that crash again in-process in shadowlab's code (or all kept inputs when
# none does). Each kept input (crash-, timeout-, oom-) is then read as at
# run time, through the child (SL_FUZZ_CHILD=1: sl_mesh_load_file): it
# must come back, as a result or an error, not crash or hang this process.
fork_check() {
  local e=$1 bin=$2 asan=$3 r v f ours= nassimp=0 nrep=0 bad= loaded=0 refused=0 shown=0
  local last
  last=$(grep -E '^#[0-9]+: cov: ' "$work/$e/log" | tail -n 1)
  # the parent's exec/s is its last job's; the rate here is all its jobs'
  # inputs over its time (jobs' start-up included)
  local secs_run
  execs=$(sed -E 's/^#([0-9]+):.*/\1/' <<<"$last")
  secs_run=$(sed -nE 's/.* time: ([0-9]+)s .*/\1/p' <<<"$last")
  [ -n "$execs" ] && [ "${secs_run:-0}" -gt 0 ] && rate=$((execs / secs_run))
  local crashes
  crashes=$(sed -nE 's/.* oom\/timeout\/crash: ([0-9]+\/[0-9]+\/[0-9]+) .*/\1/p' <<<"$last")
  for r in "$work/$e/reports"/r.*; do
    [ -f "$r" ] || continue
    nrep=$((nrep + 1))
    v=$(awk -f fuzz/classify.awk "$r")
    if [ "$v" = assimp ]; then
      nassimp=$((nassimp + 1))
    else
      ours="$ours$r: ${v#ours }"$'\n'
    fi
  done
  for f in $found; do
    if ! SL_FUZZ_CHILD=1 ASAN_OPTIONS=$asan timeout 120 "$bin" -runs=1 -timeout=60 \
        -artifact_prefix="$work/$e/rerun-" "$work/$e/found/$f" >"$work/$e/child.log" 2>&1 \
        || ! grep -q '^sl-fuzz-child: ' "$work/$e/child.log"; then
      bad="$bad $f"
    elif grep -q '^sl-fuzz-child: .*(loaded)' "$work/$e/child.log"; then
      loaded=$((loaded + 1))
    else
      refused=$((refused + 1))
    fi
  done
  # libFuzzer's fork mode passes on the exit code of a job that ended in a
  # timeout (70) or a crash (77) although -ignore_timeouts/-ignore_crashes
  # kept it fuzzing: such a run is judged by its reports and by the child
  # check of its kept inputs above, when it fuzzed for its whole time
  local rc_ok=0
  if [ $rc -eq 0 ] || { { [ $rc -eq 70 ] || [ $rc -eq 77 ]; } && grep -q '^INFO: fuzzed for' "$work/$e/log"; }; then
    rc_ok=1
  fi
  if [ -n "$ours" ] || [ -n "$bad" ] || [ $rc_ok -eq 0 ]; then
    echo "FAIL $e: exit $rc after ${wall} s, ${execs:-?} execs, oom/timeout/crash ${crashes:-?}"
    if [ -n "$ours" ]; then
      echo "  crash(es) not in assimp (report: first frame outside the sanitizers):"
      printf '%s' "$ours" | head -n 10 | sed 's/^/    /'
      for f in $found; do
        [ $shown -ge 5 ] && { echo "  (more kept inputs in $work/$e/found)"; break; }
        ASAN_OPTIONS=$asan timeout 120 "$bin" -runs=1 -timeout=60 -artifact_prefix="$work/$e/rerun-" \
          "$work/$e/found/$f" >"$work/$e/rerun.log" 2>&1 && continue
        [ "$(awk -f fuzz/classify.awk "$work/$e/rerun.log")" = assimp ] && continue
        show "$work/$e/found/$f"; shown=$((shown + 1))
      done
      if [ $shown -eq 0 ]; then
        echo "  (no kept input crashes again in shadowlab's code on its own; all kept inputs:)"
        for f in $(echo $found | tr ' ' '\n' | head -n 5); do show "$work/$e/found/$f"; done
      fi
    fi
    for f in $bad; do
      echo "  read through the reader's child, this input crashed or hung the parent:"
      show "$work/$e/found/$f"
    done
    [ $rc -ne 0 ] && grep -E '^(==[0-9]+==|SUMMARY|.*ERROR)' "$work/$e/log" | head -n 5
    return 1
  fi
  echo "ok   $e: ${secs} s (fork mode), $nseed seeds, ${execs:-?} execs, ${rate:-?} exec/s, ${cov:-no coverage line}, $slow slow inputs; oom/timeout/crash ${crashes:-?}: $nassimp sanitizer report(s) in assimp's own code (contained by the reader's child at run time); $(echo $found | wc -w) kept input(s) read through the child: $refused refused, $loaded loaded, none crashed or hung it"
}

# one ENTRY: run it, print its summary line; 1 on a finding
one() {
  local e=$1 bin nseed start rc wall execs rate cov found slow f
  bin=$build/fuzz/$e
  if [ ! -x "$bin" ]; then echo "FAIL $e: $bin not built"; return 1; fi
  mkdir -p "$work/$e/seeds" "$work/$e/corpus" "$work/$e/found"
  rm -f "$work/$e/seeds"/*
  seeds "$e" "$work/$e/seeds" || return 1
  nseed=$(ls "$work/$e/seeds" | wc -l)
  start=$(date +%s)
  # -timeout: an input slower than this is a hang (a model reader is stopped
  # after a few seconds by shadowlab itself); -rss_limit_mb: libFuzzer's own.
  # Mesh entries: an allocation assimp asks for and cannot get throws, as in
  # the reader's child (its address space is limited: meshio_child.c), and
  # assimp turns that into an import error; here ASan would abort instead.
  # Mesh entries also run without libFuzzer's per-input leak check: assimp
  # leaks on most malformed glTF and PLY inputs (fuzz/lsan.supp), and each
  # such input cost a heap scan and the symbolizing of its stacks to be
  # suppressed (glTF: 83 inputs/s, 600 without); our reader's own frees are
  # checked by its tests under ASan (meshio::*), and LSan still runs at exit.
  local asan=${ASAN_OPTIONS:-} leaks=1 fork= here=0
  case $e in fuzz_mesh_*) asan="allocator_may_return_null=1${asan:+:$asan}" leaks=0 ;; esac
  # In-process mesh entries (SL_FUZZ_MESH_HERE) run in libFuzzer's fork
  # mode: fuzzing goes on after a crash, a timeout or an out-of-memory (each
  # input kept in found/), and every sanitizer report goes to its own file
  # in reports/ (log_path), to be classified below by its stack. -timeout
  # 10 s: the reader's child gets 3 CPU seconds for such inputs at run time
  # (meshio_child.c), and the parent waits for a hung job before it stops
  # (one 25 s assimp hang in PLY's post-processing made a 60 s run 85 s).

  if grep -q '^SL_FUZZ_MESH_HERE:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
    case $e in
      fuzz_mesh_obj | fuzz_mesh_gltf) here=1 ;;
      fuzz_mesh_ply) grep -q '^SL_FUZZ_PLY_HERE:BOOL=ON' "$build/CMakeCache.txt" && here=1 ;;
    esac
  fi
  if [ $here = 1 ]; then
    fork=1
    mkdir -p "$work/$e/reports"
    rm -f "$work/$e/reports"/*
  fi
  if [ -n "$fork" ]; then
    # exitcode=77: a job ASan kills (a SEGV in assimp) exits as libFuzzer's own
    # crashes do, so fork mode counts it and ends 77, judged below by the
    # reports; with ASan's default 1 the run ended 1 with "crash 0" counted
    ASAN_OPTIONS="$asan:exitcode=77:log_path=$work/$e/reports/r" \
    UBSAN_OPTIONS="print_stacktrace=1:log_path=$work/$e/reports/r${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}" \
    "$bin" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
      -max_total_time="$secs" -timeout=10 -rss_limit_mb=2560 -max_len=65536 \
      -detect_leaks=$leaks -print_final_stats=1 -artifact_prefix="$work/$e/found/" \
      "$work/$e/corpus" "$work/$e/seeds" >"$work/$e/log" 2>&1
  else
    ASAN_OPTIONS=$asan "$bin" -max_total_time="$secs" -timeout=25 -rss_limit_mb=2560 -max_len=65536 \
      -detect_leaks=$leaks \
      -print_final_stats=1 -artifact_prefix="$work/$e/found/" \
      "$work/$e/corpus" "$work/$e/seeds" >"$work/$e/log" 2>&1
  fi
  rc=$?
  wall=$(( $(date +%s) - start ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$e/log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/$e/log")
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+' "$work/$e/log" | tail -n 1)
  # slow-unit-* are inputs slower than 10 s: shown, not failures
  found=$(ls "$work/$e/found" | grep -v '^slow-unit-')
  slow=$(ls "$work/$e/found" | grep -c '^slow-unit-')
  if [ -n "$fork" ]; then
    fork_check "$e" "$bin" "$asan"
    return
  fi
  # A mesh entry reads the model in a forked child (meshio_child.c) unless
  # built with SL_FUZZ_MESH_HERE: when assimp dies there (or the child runs
  # into its memory limit), the sanitizer in the child may still write a
  # crash-* file, although shadowlab itself handled it (exit 2, as it
  # should). A finding is an input that fails the entry when run again on
  # its own; the others are counted as crashes the child contained.
  contained=0 kept=
  for f in $found; do
    if ASAN_OPTIONS=$asan timeout 120 "$bin" -runs=1 "$work/$e/found/$f" >"$work/$e/rerun.log" 2>&1; then
      contained=$((contained + 1))
    else
      kept="$kept $f"
    fi
  done
  found=$kept
  if [ $rc -ne 0 ] || [ -n "$found" ]; then
    echo "FAIL $e: exit $rc after ${wall} s, ${execs:-?} execs; libFuzzer says:"
    grep -E '^(==[0-9]+==|SUMMARY|.*ERROR)' "$work/$e/log" | head -n 5
    for f in $found; do
      echo "  input $work/$e/found/$f ($(stat -c %s "$work/$e/found/$f") bytes):"
      head -c 512 "$work/$e/found/$f" | od -c | head -n 8 | sed 's/^/    /'
    done
    return 1
  else
    echo "ok   $e: ${secs} s, $nseed seeds, ${execs:-?} execs, ${rate:-?} exec/s, ${cov:-no coverage line}, $slow slow inputs, $contained reader crash(es) contained in the child"
  fi
}

# The entries run FUZZ_JOBS at a time (default: the cores), each on one core,
# so CI's five 60 s runs take three minutes on two cores, not five; their
# lines are printed in the entries' order.
njobs=${FUZZ_JOBS:-$(nproc)}
for e in "${entries[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$njobs" ]; do wait -n; done
  mkdir -p "$work/$e"
  ( one "$e" >"$work/$e.summary" 2>&1; echo $? >"$work/$e.rc" ) &
done
wait
fail=0
for e in "${entries[@]}"; do
  cat "$work/$e.summary"
  [ "$(cat "$work/$e.rc" 2>/dev/null)" = 0 ] || fail=1
done
if [ $fail -eq 0 ] && [ -z "${FUZZ_WORK:-}" ]; then rm -rf "$work"; else echo "fuzz/run.sh: logs and inputs in $work"; fi
exit $fail
