#!/usr/bin/env bash
# merge::* and cli::jobs — a sweep split into shards and merged back
# (shadowlab merge), and run --jobs N (worker processes, then a merge).
#   halves        configs/ci.yaml in two --cells halves, merged: the same store as one process
#                 (check with exact counts against a baseline written from the one-process run,
#                 and the same table rows), overlays gathered beside the merged store
#   other_config  a shard of another config is refused (exit 2, naming it), nothing written
#   missing       a shard that is not there: its cells are named, exit 1
#   twice         merging the same shards twice adds nothing
#   jobs          run --jobs 2 gives the same table rows as one process
#   bench         bench CONFIG --only jobs: both runs complete, their table and the row printed
set -u
bin=${1:?usage: cli_merge.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
rows() { "$bin" table "$1" --format csv | tail -n +2 | sort; }
ncells() { sqlite3 "$1" 'SELECT COUNT(*) FROM cells'; }

# a small sweep: 2 scenes x 2 map sizes x 3 labels = 12 cells, 2 views
cat >"$tmp/small.yaml" <<'YAML'
name: small
scenes:
  - {scene: primitives, viewpoints: [side]}
  - {scene: bench, viewpoints: [with]}
viewports: [{width: 256, height: 256}]
map_sizes: [512, 1024]
methods:
  - {label: ff, method: nsm}
  - {label: coherence4, method: coherence, texels: 4}
  - {label: texel, method: texel}
outputs: {overlays: true}
YAML

case $case_ in
halves)
  "$bin" run configs/ci.yaml --out "$tmp/one" --no-cache >"$tmp/one.out" 2>&1 || { cat "$tmp/one.out"; fail "one-process run"; }
  n=$("$bin" validate configs/ci.yaml | head -1 | sed 's/.* \([0-9]*\) cell(s)/\1/')
  half=$((n / 2))
  "$bin" run configs/ci.yaml --cells 0:$half --out "$tmp/a" --db "$tmp/a/shadowlab.db" --no-cache >"$tmp/a.out" 2>&1 ||
    { cat "$tmp/a.out"; fail "first half"; }
  "$bin" run configs/ci.yaml --cells $half: --out "$tmp/b" --db "$tmp/b/shadowlab.db" --no-cache >"$tmp/b.out" 2>&1 ||
    { cat "$tmp/b.out"; fail "second half"; }
  "$bin" merge "$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" -o "$tmp/m/shadowlab.db" >"$tmp/merge.out" 2>&1 ||
    { cat "$tmp/merge.out"; fail "merge exit $?"; }
  grep -q "$n of $n cell(s) of the sweep stored, 0 missing" "$tmp/merge.out" || { cat "$tmp/merge.out"; fail "merge summary"; }
  # exact: a baseline written from the one-process store, the merged store checked against it
  cp tests/baselines/ci.yaml "$tmp/base.yaml"
  "$bin" check "$tmp/one/shadowlab.db" --baseline "$tmp/base.yaml" --update 2>/dev/null || fail "baseline update"
  "$bin" check "$tmp/m/shadowlab.db" --baseline "$tmp/base.yaml" --rows 20 >"$tmp/check.out" 2>&1 ||
    { cat "$tmp/check.out"; fail "merged store differs from the one-process run"; }
  grep -q "0 moved, 0 outside tolerance, 0 cell(s) missing" "$tmp/check.out" || { cat "$tmp/check.out"; fail "check"; }
  grep -q "Counts compared exactly" "$tmp/check.out" || { cat "$tmp/check.out"; fail "counts not compared exactly"; }
  diff <(rows "$tmp/one/shadowlab.db") <(rows "$tmp/m/shadowlab.db") >"$tmp/diff" || { head "$tmp/diff"; fail "table rows differ"; }
  # every overlay the merged store names is beside it
  no=$(sqlite3 "$tmp/m/shadowlab.db" "SELECT overlay FROM cells WHERE overlay IS NOT NULL" | while read -r p; do
         [ -f "$tmp/m/$p" ] || echo "$p"; done | wc -l)
  [ "$no" -eq 0 ] || fail "$no overlay(s) the merged store names are not under its folder"
  [ "$(ls "$tmp/m/ci/overlays" | wc -l)" -eq "$n" ] || fail "overlays gathered: $(ls "$tmp/m/ci/overlays" | wc -l), want $n"
  ;;
other_config)
  sed 's/^name: small/name: other/' "$tmp/small.yaml" >"$tmp/other.yaml"
  "$bin" run "$tmp/small.yaml" --cells 0:2 --out "$tmp/a" --db "$tmp/a/shadowlab.db" >/dev/null 2>&1 || fail "run a"
  "$bin" run "$tmp/other.yaml" --cells 0:2 --out "$tmp/b" --db "$tmp/b/shadowlab.db" >/dev/null 2>&1 || fail "run b"
  "$bin" merge "$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" -o "$tmp/m.db" >"$tmp/merge.out" 2>&1
  rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/merge.out"; fail "a shard of another config: exit $rc, want 2"; }
  grep -q "$tmp/b/shadowlab.db.*not a shard of the same sweep" "$tmp/merge.out" ||
    { cat "$tmp/merge.out"; fail "the message does not name the other shard"; }
  # refused before anything was written
  [ -e "$tmp/m.db" ] && fail "a refused merge wrote $tmp/m.db"
  ;;
missing)
  "$bin" run "$tmp/small.yaml" --cells 0:6 --out "$tmp/a" --db "$tmp/a/shadowlab.db" >/dev/null 2>&1 || fail "run a"
  "$bin" merge "$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" -o "$tmp/m.db" >"$tmp/merge.out" 2>&1
  rc=$?
  [ $rc -eq 1 ] || { cat "$tmp/merge.out"; fail "a missing shard: exit $rc, want 1"; }
  grep -q "$tmp/b/shadowlab.db: not there" "$tmp/merge.out" || { cat "$tmp/merge.out"; fail "absent shard not named"; }
  [ "$(grep -c 'missing cell' "$tmp/merge.out")" -eq 6 ] || { cat "$tmp/merge.out"; fail "want 6 missing cells named"; }
  grep -q "missing cell 6: bench/with 256x256 map 512 'ff'" "$tmp/merge.out" || { cat "$tmp/merge.out"; fail "cell 6 not named"; }
  grep -q "6 of 12 cell(s) of the sweep stored, 6 missing" "$tmp/merge.out" || { cat "$tmp/merge.out"; fail "summary"; }
  ;;
twice)
  "$bin" run "$tmp/small.yaml" --cells 0:6 --out "$tmp/a" --db "$tmp/a/shadowlab.db" >/dev/null 2>&1 || fail "run a"
  "$bin" run "$tmp/small.yaml" --cells 6: --out "$tmp/b" --db "$tmp/b/shadowlab.db" >/dev/null 2>&1 || fail "run b"
  "$bin" merge "$tmp/a/shadowlab.db" "$tmp/b/shadowlab.db" -o "$tmp/m/shadowlab.db" >"$tmp/1.out" 2>&1 || { cat "$tmp/1.out"; fail "merge 1"; }
  before=$(sqlite3 "$tmp/m/shadowlab.db" 'SELECT (SELECT COUNT(*) FROM runs), (SELECT COUNT(*) FROM cells), (SELECT COUNT(*) FROM figures)')
  [ "${before%%|*}" -eq 2 ] || fail "runs after one merge: $before"
  "$bin" merge "$tmp/b/shadowlab.db" "$tmp/a/shadowlab.db" -o "$tmp/m/shadowlab.db" >"$tmp/2.out" 2>&1 || { cat "$tmp/2.out"; fail "merge 2"; }
  after=$(sqlite3 "$tmp/m/shadowlab.db" 'SELECT (SELECT COUNT(*) FROM runs), (SELECT COUNT(*) FROM cells), (SELECT COUNT(*) FROM figures)')
  [ "$before" = "$after" ] || fail "a second merge changed runs|cells|figures from $before to $after"
  grep -q "12 of 12 cell(s) of the sweep stored, 0 missing; 0 copied, 12 duplicate(s)" "$tmp/2.out" || { cat "$tmp/2.out"; fail "summary"; }
  ;;
jobs)
  "$bin" run "$tmp/small.yaml" --out "$tmp/one" >"$tmp/one.out" 2>&1 || { cat "$tmp/one.out"; fail "one process"; }
  "$bin" run "$tmp/small.yaml" --out "$tmp/two" --jobs 2 >"$tmp/two.out" 2>&1 || { cat "$tmp/two.out"; fail "--jobs 2"; }
  grep -q "2 worker(s)" "$tmp/two.out" || { cat "$tmp/two.out"; fail "not two workers"; }
  grep -q "0 of 2 view(s) started twice" "$tmp/two.out" || { cat "$tmp/two.out"; fail "the split cut a view"; }
  diff <(rows "$tmp/one/shadowlab.db") <(rows "$tmp/two/shadowlab.db") >"$tmp/diff" || { head "$tmp/diff"; fail "--jobs 2 differs from one process"; }
  [ "$(ls "$tmp/two/small/overlays" | wc -l)" -eq 12 ] || fail "overlays gathered: $(ls "$tmp/two/small/overlays" | wc -l), want 12"
  [ -e "$tmp/two/.jobs-small" ] && fail "the workers' folder is left behind"
  ;;
bench)
  # its temporary folder under a TMPDIR of its own: a folder another bench
  # left in /tmp is not this one's
  mkdir "$tmp/t"
  TMPDIR="$tmp/t" "$bin" bench "$tmp/small.yaml" --only jobs >"$tmp/bench.md" 2>"$tmp/bench.err" || { cat "$tmp/bench.err"; fail "bench exit $?"; }
  grep -q '^## One process against `run --jobs 2` (.*small.yaml): 12 cells$' "$tmp/bench.md" || { cat "$tmp/bench.md"; fail "heading"; }
  grep -qE '^\| one process \| [0-9.]+ \| [0-9.]+ \|$' "$tmp/bench.md" || fail "one-process row"
  grep -qE '^\| --jobs 2 \| [0-9.]+ \| [0-9.]+ \|$' "$tmp/bench.md" || fail "--jobs row"
  # two views, cut between them: none computed twice; 12 cells merged
  grep -q '^--jobs 2: 0 of 2 view(s) started in both workers.*merge of 12 cells' "$tmp/bench.md" || { cat "$tmp/bench.md"; fail "split/merge line"; }
  grep -qE '\| small, --jobs 2 over one process, wall \|' "$tmp/bench.md" || { cat "$tmp/bench.md"; fail "summary row"; }
  ls "$tmp/t" | grep -q "^shadowlab-bench-jobs\." && fail "temporary folder left" || true
  # the folder is made under TMPDIR: one that does not exist fails the stage, naming it
  TMPDIR="$tmp/none" "$bin" bench "$tmp/small.yaml" --only jobs >/dev/null 2>"$tmp/bench.err" &&
    fail "bench ran with TMPDIR a missing folder"
  grep -q "$tmp/none/shadowlab-bench-jobs" "$tmp/bench.err" || { cat "$tmp/bench.err"; fail "the missing TMPDIR not named"; }
  ;;
*) echo "unknown case $case_"; exit 2 ;;
esac
echo "1 passed, 0 failed"
