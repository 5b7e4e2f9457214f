#!/usr/bin/env bash
# cli::startup — the verbs that render nothing load neither OpenImageIO, nor
# Mesa (libOSMesa, libEGL), nor Embree: the dynamic loader's own log
# (LD_DEBUG=libs) of version, help, validate, table and check lists none of
# them; a run that renders, traces and writes an overlay lists Mesa and
# Embree and not OpenImageIO (the sheets have a module of their own), one
# that writes EXR lists OpenImageIO (so the check can see them when they
# are there). How long start-up
# takes is the bench's business (`bench --only startup`), not a test's.
set -u
bin=${1:?usage: cli_startup.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
heavy='libOpenImageIO|libOSMesa|libEGL|libembree|libLLVM|shadowlab-oiio'

# the libraries the process loaded, one per line, from the loader's log
loaded() {
  rm -f "$tmp"/ld.*
  LD_DEBUG=libs LD_DEBUG_OUTPUT=$tmp/ld "$@" >"$tmp/out" 2>&1
  local rc=$?
  cat "$tmp"/ld.* 2>/dev/null | sed -n 's/.*calling init: //p' | sort -u
  return $rc
}

cat >"$tmp/c.yaml" <<'YAML'
name: lazy
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 96, height: 96}]
map_sizes: [256]
methods:
  - {label: nsm, method: nsm}
  - {label: rt, method: raytrace}
outputs: {overlays: true}
YAML
libs=$(loaded "$bin" run "$tmp/c.yaml" -o "$tmp/r" --no-cache -q) || fail "run: $(cat "$tmp/out")"
for k in 'libOSMesa|libEGL' 'libembree' 'shadowlab-sheet'; do
  echo "$libs" | grep -Eq "$k" || fail "a rendering run did not load $k (the log cannot be read?)"
done
# its overlay sheets take their glyphs from FreeType, not OpenImageIO
# (issue 20), unless the font file is missing (OpenImageIO's font search then)
if [ -r /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] && ! readelf -d "$bin" 2>/dev/null | grep -q 'libasan'; then
  echo "$libs" | grep -Eq 'libOpenImageIO|shadowlab-oiio' && fail "a run writing overlays and no EXR loaded OpenImageIO"
fi
# a run writing EXR layers loads it
sed 's/outputs: {overlays: true}/outputs: {overlays: true, exr: true}/' "$tmp/c.yaml" >"$tmp/e.yaml"
libs=$(loaded "$bin" run "$tmp/e.yaml" -o "$tmp/re" --no-cache -q) || fail "run with exr: $(cat "$tmp/out")"
echo "$libs" | grep -q 'libOpenImageIO' || fail "a run writing EXR did not load libOpenImageIO (the log cannot be read?)"
db=$tmp/r/shadowlab.db
[ -f "$db" ] || { echo "FAIL no store from the run"; exit 1; }
"$bin" check "$db" --baseline "$tmp/b.yaml" --update >/dev/null 2>&1 || fail "check --update"

# A sanitized build links those libraries at start on purpose (CMakeLists.txt:
# LeakSanitizer's tracer and Mesa's libglapi loaded late): there only the
# rendering run above is checked.
if readelf -d "$bin" 2>/dev/null | grep -q 'libasan'; then
  echo "sanitized build: the lazy libraries are linked at start; the light verbs are not checked here"
  echo "$fails failed"
  [ $fails -eq 0 ]
  exit
fi

check_light() {
  local what=$1; shift
  local libs
  libs=$(loaded "$@") || fail "$what exited $?: $(head -3 "$tmp/out")"
  local bad
  bad=$(echo "$libs" | grep -E "$heavy")
  [ -z "$bad" ] || fail "$what loaded: $(echo $bad)"
  [ -n "$libs" ] || fail "$what: the loader's log is empty"
}
check_light version "$bin" version
check_light --version "$bin" --version
check_light "help run" "$bin" help run
check_light validate "$bin" validate configs/default.yaml
check_light "validate a scene" "$bin" validate scenes/bench.yaml
check_light table "$bin" table "$db"
check_light check "$bin" check "$db" --baseline "$tmp/b.yaml"
check_light "list methods" "$bin" list methods
check_light "list scenes" "$bin" list scenes
# the bench's start-up stage runs the three verbs both ways; no timing is
# asserted, but the eager side maps OpenImageIO and LLVM, which the lazy one
# must not: its peak RSS is far above the lazy side's
"$bin" bench --only startup --reps 1 --csv "$tmp/b.csv" >"$tmp/bench.md" 2>&1 || fail "bench --only startup: $(tail -3 "$tmp/bench.md")"
rows=$(grep -cE '^\| (version|validate|help run) \|' "$tmp/bench.md")
[ "$rows" -eq 3 ] || fail "bench start-up table has $rows rows, want 3"
awk -F'|' '/^\| validate \|/ { gsub(/[^0-9.]/, "", $6); gsub(/[^0-9.]/, "", $10); lazy = $6 + 0; eager = $10 + 0 }
           END { exit !(lazy > 0 && eager > lazy + 50) }' "$tmp/bench.md" ||
  fail "validate: eager RSS not 50 MiB above lazy: $(grep '^| validate |' "$tmp/bench.md")"
grep -q '^[^,]*,startup,' "$tmp/b.csv" || fail "no startup row in the bench CSV"
echo "$fails failed"
[ $fails -eq 0 ]
