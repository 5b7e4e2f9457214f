#!/usr/bin/env bash
# grade::* (shell) — `shadowlab grade`, a visibility image rendered elsewhere
# scored as a cell of method external (doc/grade.md).
#   roundtrip  a run with outputs.visibility: exr; each package cell's file
#              (pcf) graded back — primitives registered by the file's own
#              depth, spider by its background — gives every figure of the
#              package's own cell, count and percent; NSM's file (a C
#              method: 1/0/NaN) gives every figure of NSM's cell too
#   refused    the same files flipped or shifted by one pixel: exit 2, the
#              message naming the share and the cause (y flipped, off by one
#              pixel), no cell stored, no store left where there was none
#   tables     external cells in table (method `external`), a pivot
#              (--rows label), check (a baseline written with --update
#              holds the label and passes) and report (its HTML names it)
#   example    examples/primitives_shadows.py (needs Debian's python3-numpy,
#              else skipped, exit 77) graded with its depth: registered,
#              light correct >= 99 %; the same image graded as another
#              viewpoint is refused naming the field of view or camera
#   bad_input  exit 2 with the file named: an 8-bit PNG, the wrong size,
#              colour channels that differ, values outside 0..1, a missing
#              file, window depth without --near/--far, an unknown
#              viewpoint; a config running method external
set -u
bin=${1:?usage: cli_grade.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
export OMP_WAIT_POLICY=passive

# the run whose visibility files are graded back
run_rt() {
  cat >"$tmp/rt.yaml" <<'YAML'
name: rt
scenes:
  - {scene: primitives, viewpoints: [side]}
  - {scene: spider, viewpoints: [low]}
viewports: [{width: 128, height: 96}]
map_sizes: [512]
methods:
  - {label: pcf, method: pcf}
  - {label: nsm, method: nsm, self_shadow: front_faces}
outputs: {tables: true, overlays: false, visibility: exr}
repetitions: {warmup: 0, runs: 1}
YAML
  "$bin" run "$tmp/rt.yaml" --out "$tmp/out" -q >/dev/null || fail "the run"
  vis=$tmp/out/rt/visibility
  for f in primitives-side-128x96-512-pcf spider-low-128x96-512-pcf primitives-side-128x96-512-nsm; do
    [ -s "$vis/$f.exr" ] || fail "no $f.exr"
  done
}

# grade SCENE VIEWPOINT FILE LABEL [more options]: into $tmp/g and the run's store
grade() {
  local s=$1 v=$2 f=$3 l=$4
  shift 4
  "$bin" grade --scene "$s" --viewpoint "$v" --viewport 128x96 --map 512 --image "$f" --label "$l" \
    -o "$tmp/g" --db "$tmp/out/shadowlab.db" "$@"
}

# the figures of LABEL's cell on SCENE in a figures.csv: key, region, figure, count, percent
figs() { awk -F, -v l="$2" -v s="$3" '$6 == l && $1 == s { print $1, $2, $3, $4, $7, $8, $9, $10, $11 }' "$1" | sort; }

case $case_ in
roundtrip)
  run_rt
  # one grade a label: a label's results folder holds its latest grade
  grade primitives side "$vis/primitives-side-128x96-512-pcf.exr" pcf-back \
    --depth "$vis/primitives-side-128x96-512-pcf.exr" >/dev/null 2>"$tmp/err1" || { cat "$tmp/err1"; fail "grade primitives"; }
  grep -q 'registered by depth: 0.000 %' "$tmp/err1" || { cat "$tmp/err1"; fail "primitives not registered by depth"; }
  figs "$tmp/g/grade-pcf-back/figures.csv" pcf-back primitives >"$tmp/b-primitives"
  grade spider low "$vis/spider-low-128x96-512-pcf.exr" pcf-back >/dev/null 2>"$tmp/err2" || { cat "$tmp/err2"; fail "grade spider"; }
  grep -q 'registered by background: 0.000 %' "$tmp/err2" || { cat "$tmp/err2"; fail "spider not registered by background"; }
  figs "$tmp/g/grade-pcf-back/figures.csv" pcf-back spider >"$tmp/b-spider"
  for s in primitives spider; do
    figs "$tmp/out/rt/figures.csv" pcf $s >"$tmp/a"
    [ "$(wc -l <"$tmp/a")" -ge 40 ] || fail "$s: only $(wc -l <"$tmp/a") figures of pcf"
    diff "$tmp/a" "$tmp/b-$s" || fail "$s: the graded figures differ from pcf's own"
  done
  # NSM's file: verdicts as 1/0 (a C method); its figures all there, equal
  grade primitives side "$vis/primitives-side-128x96-512-nsm.exr" nsm-back >/dev/null 2>&1 || fail "grade nsm"
  figs "$tmp/out/rt/figures.csv" nsm primitives >"$tmp/a"
  figs "$tmp/g/grade-nsm-back/figures.csv" nsm-back primitives >"$tmp/b"
  [ "$(wc -l <"$tmp/a")" -ge 40 ] || fail "only $(wc -l <"$tmp/a") figures of nsm"
  comm -23 "$tmp/a" "$tmp/b" >"$tmp/c"
  [ ! -s "$tmp/c" ] || { cat "$tmp/c"; fail "nsm's figures not all equal in the grade"; }
  # the graded cells are method external under their labels
  n=$(sqlite3 "$tmp/out/shadowlab.db" "select count(*) from cells where method = 'external' and label = 'pcf-back'")
  [ "$n" = 2 ] || fail "$n stored cells of pcf-back (want 2, method external)"
  echo "ok roundtrip"
  ;;
refused)
  run_rt
  oiiotool "$vis/spider-low-128x96-512-pcf.exr" --flip -o "$tmp/flip.exr" || fail oiiotool
  oiiotool "$vis/spider-low-128x96-512-pcf.exr" --origin +1+0 --crop 128x96+0+0 -o "$tmp/shift.exr" || fail oiiotool
  oiiotool "$vis/primitives-side-128x96-512-pcf.exr" --flip -o "$tmp/pflip.exr" || fail oiiotool
  oiiotool "$vis/primitives-side-128x96-512-pcf.exr" --origin +0+1 --crop 128x96+0+0 -o "$tmp/pshift.exr" || fail oiiotool
  before=$(sqlite3 "$tmp/out/shadowlab.db" "select count(*) from cells")
  check() {   # WHAT CAUSE grade-args...
    local what=$1 cause=$2
    shift 2
    grade "$@" >/dev/null 2>"$tmp/err"
    local rc=$?
    [ $rc = 2 ] || { cat "$tmp/err"; fail "$what: exit $rc, want 2"; }
    grep -q "not registered with the view: [0-9.]* % of the pixels" "$tmp/err" || { cat "$tmp/err"; fail "$what: no share"; }
    grep -q "likely cause: $cause" "$tmp/err" || { cat "$tmp/err"; fail "$what: cause not '$cause'"; }
    cat "$tmp/err"
  }
  check "spider flipped" "y flipped" spider low "$tmp/flip.exr" bad
  check "spider shifted" "off by one pixel: the image is shifted one pixel right" spider low "$tmp/shift.exr" bad
  check "primitives flipped (depth)" "y flipped" primitives side "$tmp/pflip.exr" bad --depth "$tmp/pflip.exr"
  check "primitives shifted (depth)" "off by one pixel: the image is shifted one pixel down" primitives side \
    "$tmp/pshift.exr" bad --depth "$tmp/pshift.exr"
  after=$(sqlite3 "$tmp/out/shadowlab.db" "select count(*) from cells")
  [ "$before" = "$after" ] || fail "a refused grade stored a cell ($before -> $after)"
  [ ! -e "$tmp/g/grade-bad.yaml" ] && [ ! -e "$tmp/g/grade-bad" ] || fail "a refused grade left its files"
  # a fresh output folder: no store is left behind
  "$bin" grade --scene spider --viewpoint low --viewport 128x96 --map 512 --image "$tmp/flip.exr" --label bad \
    -o "$tmp/fresh" 2>/dev/null && fail "fresh: graded"
  [ ! -e "$tmp/fresh/shadowlab.db" ] || fail "a refused grade left a store"
  # primitives has no background: without depth nothing can be checked, and it says so
  "$bin" grade --scene primitives --viewpoint side --viewport 128x96 --map 512 --image "$tmp/pflip.exr" \
    --label unchecked -o "$tmp/u" >/dev/null 2>"$tmp/err" || { cat "$tmp/err"; fail "unchecked: exit $?"; }
  grep -q 'warning: .*registration not checked' "$tmp/err" || { cat "$tmp/err"; fail "no warning"; }
  echo "ok refused"
  ;;
tables)
  run_rt
  grade spider low "$vis/spider-low-128x96-512-pcf.exr" engine-x >/dev/null 2>&1 || fail "grade"
  db=$tmp/out/shadowlab.db
  "$bin" table "$db" --label engine-x >"$tmp/t" 2>&1 || { cat "$tmp/t"; fail "table"; }
  grep -q '^## spider .* / engine-x$' "$tmp/t" || { cat "$tmp/t"; fail "table: no engine-x section"; }
  grep -q 'method `external`' "$tmp/t" || fail "table: not method external"
  "$bin" table "$db" --rows label --cols map_size --figure wrong --where scene=spider >"$tmp/p" 2>&1 || { cat "$tmp/p"; fail "pivot"; }
  grep -q '^| engine-x ' "$tmp/p" || { cat "$tmp/p"; fail "pivot: no engine-x row"; }
  grep -q '^| pcf ' "$tmp/p" || fail "pivot: no pcf row beside it"
  # the external cell has pcf's figures: the pivot's two rows are equal
  [ "$(grep '^| engine-x ' "$tmp/p" | cut -d'|' -f3-)" = "$(grep '^| pcf ' "$tmp/p" | cut -d'|' -f3-)" ] ||
    { cat "$tmp/p"; fail "pivot: engine-x and pcf differ"; }
  "$bin" check "$db" --baseline "$tmp/b.yaml" --update >/dev/null 2>&1 || fail "check --update"
  grep -q 'engine-x' "$tmp/b.yaml" || fail "baseline: no engine-x"
  "$bin" check "$db" --baseline "$tmp/b.yaml" >"$tmp/c" 2>&1 || { cat "$tmp/c"; fail "check: exit $?"; }
  "$bin" report "$db" -o "$tmp/rep" >/dev/null 2>"$tmp/r" || { cat "$tmp/r"; fail "report"; }
  grep -q 'engine-x' "$tmp/rep/report.html" || fail "report: no engine-x"
  grep -q 'engine-x' "$tmp/rep/report.md" || fail "report.md: no engine-x"
  echo "ok tables"
  ;;
example)
  py=/usr/bin/python3
  "$py" -c 'import numpy' 2>/dev/null || { echo "SKIP: no numpy for $py (Debian's python3-numpy)"; exit 77; }
  "$py" examples/primitives_shadows.py --viewpoint side --size 160x120 -o "$tmp/eng" || fail "the example"
  "$bin" grade --scene primitives --viewpoint side --viewport 160x120 --image "$tmp/eng/visibility.png" \
    --depth "$tmp/eng/depth.pfm" --label numpy-rt -o "$tmp/g" >"$tmp/out" 2>"$tmp/err" ||
    { cat "$tmp/err"; fail "grade: exit $?"; }
  cat "$tmp/err"
  grep -q 'registered by depth' "$tmp/err" || fail "not registered by depth"
  lc=$(awk -F, '$6 == "numpy-rt" && $7 == "image" && $8 == "light_correct" { print $10 }' \
    "$tmp/g/grade-numpy-rt/figures.csv")
  [ -n "$lc" ] && awk -v x="$lc" 'BEGIN { exit !(x >= 99 && x < 100.0001) }' || fail "light correct '$lc' < 99 %"
  # the same image is not the view from `with`
  "$bin" grade --scene primitives --viewpoint with --viewport 160x120 --image "$tmp/eng/visibility.png" \
    --depth "$tmp/eng/depth.pfm" --label wrong-camera -o "$tmp/g" >/dev/null 2>"$tmp/err"
  rc=$?
  [ $rc = 2 ] || fail "another viewpoint: exit $rc"
  grep -q 'likely cause: another' "$tmp/err" || { cat "$tmp/err"; fail "another viewpoint: cause"; }
  echo "ok example"
  ;;
bad_input)
  g() { "$bin" grade --scene spider --viewpoint low --viewport 64x48 --label b -o "$tmp/g" "$@"; }
  expect() {   # WHAT PATTERN args...
    local what=$1 pat=$2
    shift 2
    g "$@" >/dev/null 2>"$tmp/err"
    local rc=$?
    [ $rc = 2 ] || { cat "$tmp/err"; fail "$what: exit $rc, want 2"; }
    [ "$(wc -l <"$tmp/err")" -le 40 ] || fail "$what: more than a message"
    grep -q -- "$pat" "$tmp/err" || { cat "$tmp/err"; fail "$what: no '$pat'"; }
    grep -qi 'segmentation\|assert\|sanitizer' "$tmp/err" && fail "$what: crashed"
    [ ! -e "$tmp/g/shadowlab.db" ] || fail "$what: a store was written"
  }
  oiiotool --pattern constant:color=1 64x48 1 -d uint8 -o "$tmp/eight.png"
  oiiotool --pattern constant:color=1 64x48 1 -d uint16 -o "$tmp/sixteen.png"
  oiiotool --pattern constant:color=1 32x48 1 -d half -o "$tmp/small.exr"
  oiiotool --pattern constant:color=2 64x48 1 -d float -o "$tmp/big.exr"
  oiiotool --pattern constant:color=1,0.5,1 64x48 3 -d half -o "$tmp/rgb.exr"
  expect "8-bit" "eight.png: 8-bit" --image "$tmp/eight.png"
  expect "size" "small.exr: 32 x 48 pixels where --viewport is 64 x 48" --image "$tmp/small.exr"
  expect "range" "big.exr: value 2 at pixel (0, 47 from the top) outside 0..1" --image "$tmp/big.exr"
  expect "rgb" "rgb.exr: channels R and G differ" --image "$tmp/rgb.exr"
  expect "missing" "nope.exr" --image "$tmp/nope.exr"
  expect "window depth" "window depth needs the engine's --near and --far" --image "$tmp/sixteen.png" \
    --depth "$tmp/sixteen.png" --depth-kind window
  expect "empty label" "'--label': '': 1 to 40 letters" --image "$tmp/sixteen.png" --label ""
  expect "label with a slash" "'--label': 'a/b'" --image "$tmp/sixteen.png" --label a/b
  "$bin" grade --scene spider --viewpoint nowhere --viewport 64x48 --label b --image "$tmp/sixteen.png" \
    -o "$tmp/g" >/dev/null 2>"$tmp/err"
  [ $? = 2 ] && grep -q "'--viewpoint': .*nowhere" "$tmp/err" || { cat "$tmp/err"; fail "unknown viewpoint"; }
  expect "no scene file" "nope.yaml: '--scene': no such scene file" --scene "$tmp/nope.yaml" --image "$tmp/sixteen.png"
  [ ! -e "$tmp/g/grade-b.yaml" ] || fail "unknown viewpoint: the config was left"
  # a config cannot run method external: nothing hands it an image
  cat >"$tmp/ext.yaml" <<'YAML'
scenes: [{scene: spider, viewpoints: [low]}]
viewports: [{width: 64, height: 48}]
map_sizes: [256]
methods: [{label: x, method: external}]
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/ext.yaml" --out "$tmp/r" -q >/dev/null 2>"$tmp/err"
  [ $? = 2 ] && grep -q 'shadowlab grade' "$tmp/err" || { cat "$tmp/err"; fail "run external"; }
  echo "ok bad_input"
  ;;
*) fail "unknown case $case_" ;;
esac
