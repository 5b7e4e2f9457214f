#!/usr/bin/env bash
# scripts/table_outputs.sh SHADOWLAB DB OUT [BASELINE] — every table the
# program writes from one results store, into OUT: `shadowlab table` in each
# format with its options (the thesis tables, --figures, the summaries, the
# pivots), `shadowlab report` (HTML, Markdown, the tables' .tex; --latex) and
# `shadowlab check` against BASELINE (text, md, --json, --junit). For a change
# that must not move a byte of a table (a restructuring of the writers): run
# it with the old binary and with the new one on the SAME store, then
# `diff -r -I "Written by shadowlab" OUT_OLD OUT_NEW` (the report's footer names
# the binary's git SHA and the time). Each command's exit status is kept beside its
# output (NAME.rc), so a refusal is compared too. The store is copied first
# (nothing here writes to DB) into one fixed folder, $SL_TABLE_OUTPUTS_WORK
# (default /tmp/sl-table-outputs, emptied first), as the outputs name the
# store's path.
set -u
bin=${1:?usage: table_outputs.sh SHADOWLAB DB OUT [BASELINE]}
db=${2:?usage: table_outputs.sh SHADOWLAB DB OUT [BASELINE]}
out=${3:?usage: table_outputs.sh SHADOWLAB DB OUT [BASELINE]}
baseline=${4:-}
mkdir -p "$out"
work=${SL_TABLE_OUTPUTS_WORK:-/tmp/sl-table-outputs}
rm -rf "$work"
mkdir -p "$work" || exit 2
trap 'rm -rf "$work"' EXIT
cp "$db" "$work/store.db"
db="$work/store.db"

# t NAME ARGS...: `shadowlab table DB ARGS` into OUT/NAME (stdout), NAME.err, NAME.rc
t() {
  local name=$1
  shift
  "$bin" table "$db" "$@" >"$out/$name" 2>"$out/$name.err"
  echo $? >"$out/$name.rc"
}

for f in md csv latex json; do
  t "table.$f" --format "$f"
  t "table-figures.$f" --format "$f" --figures wrong,light_incorrect,soft_mae
  t "table-all.$f" --format "$f" --figures all
  t "table-ci-map.$f" --format "$f" --label nsm,chain --map 1024
  t "table-scene.$f" --format "$f" --scene primitives --viewpoint side
  t "summary.$f" --format "$f" --summary wrong,light_incorrect
  t "summary-contours.$f" --format "$f" --summary wrong --region contours --lower-is-better
  t "summary-avg.$f" --format "$f" --summary wrong --region 2 --average-case bench/with/2
  t "pivot.$f" --format "$f" --rows label --cols map_size
  t "pivot-scene.$f" --format "$f" --rows scene --cols label --figure uncertain --agg median
  t "pivot-ms.$f" --format "$f" --rows label --cols scene --figure ms_method --agg max
  t "pivot-count.$f" --format "$f" --rows label --cols region --figure wrong --of count --where scene=bench
  t "pivot-pfl.$f" --format "$f" --rows map_size --cols label --figure light_incorrect --of pfl --agg sum
  t "pivot-soft.$f" --format "$f" --rows label --cols viewport --figure soft_mae
  t "pivot-wide.$f" --format "$f" --rows viewpoint --cols label
done
t "summary-motion.md" --format md --summary wrong --label nsm

"$bin" report "$db" -o "$work/report" --latex >"$out/report.out" 2>"$out/report.err"
echo $? >"$out/report.rc"
"$bin" report "$db" -o "$work/report-one" --self-contained >/dev/null 2>"$out/report-one.err"
echo $? >"$out/report-one.rc"
if [ -d "$work/report" ]; then
  mkdir -p "$out/report"
  cp "$work/report/report.md" "$work/report/report.html" "$work/report/report.tex" "$out/report/" 2>/dev/null
  [ -d "$work/report/tex" ] && cp -r "$work/report/tex" "$out/report/"
fi
[ -f "$work/report-one/report.html" ] && cp "$work/report-one/report.html" "$out/report-one.html"

if [ -n "$baseline" ]; then
  "$bin" check "$db" --baseline "$baseline" --study ci >"$out/check.txt" 2>"$out/check.err"
  echo $? >"$out/check.rc"
  "$bin" check "$db" --baseline "$baseline" --study ci --format md --rows 50 \
    --json "$out/check.json" --junit "$out/check.xml" >"$out/check.md" 2>"$out/check-md.err"
  echo $? >"$out/check-md.rc"
fi
exit 0
