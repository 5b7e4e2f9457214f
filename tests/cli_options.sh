#!/usr/bin/env bash
# cli::options — the command line (issue 17): --out=DIR and -o DIR,
# -V/--version, help VERB = VERB --help, unknown options named (exit 2),
# -D overriding a key and refused at a bad path or value with the option
# named, -j, --quiet (one line on stdout), off-terminal progress lines,
# check --json/--junit read back by python3's json and xml modules, the
# plain check table and its colour rules, list scenes (scenes only, origin),
# and on a terminal the live progress line cleared before the summary.
set -u
bin=${1:?usage: cli_options.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0; passes=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
ok() { passes=$((passes + 1)); }
cat >"$tmp/small.yaml" <<'YAML'
name: small
scenes: [{scene: primitives, viewpoints: [side, with]}]
viewports: [{width: 128, height: 128}]
map_sizes: [256, 512]
methods:
  - {label: ff, method: nsm}
  - {label: slope, method: nsm, self_shadow: slope}
outputs: {overlays: false}
YAML

# version and help
v=$("$bin" --version) && [ "$v" = "$("$bin" -V)" ] && [ "$v" = "$("$bin" version)" ] && ok || fail "--version/-V/version differ: $v"
[ "$("$bin" help run)" = "$("$bin" run --help)" ] && ok || fail "help run != run --help"
"$bin" help run | grep -q -- "--threads" && ok || fail "help run is not run's help"
[ "$("$bin" help check)" = "$("$bin" check -h)" ] && ok || fail "help check != check -h"
# unknown options are named, exit 2
err=$("$bin" run "$tmp/small.yaml" --frobnicate 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "unknown option '--frobnicate'" && ok || fail "unknown long option: rc $rc, '$err'"
err=$("$bin" table x.db -Z 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "unknown option '-Z'" && ok || fail "unknown short option: rc $rc"
err=$("$bin" run "$tmp/small.yaml" --out 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "missing value for '--out'" && ok || fail "missing value: rc $rc, '$err'"
err=$("$bin" run "$tmp/small.yaml" -j 0 2>&1 >/dev/null); rc=$?
[ $rc -eq 2 ] && ok || fail "-j 0 accepted"

# -D: a key replaced by its path, checked as the file is
out=$("$bin" validate "$tmp/small.yaml" -D 'map_sizes=[1024]' -D 'methods[1].bias=0.01' -D outputs.exr=true) ||
  fail "validate with -D: $out"
echo "$out" | grep -q "cell(s)" && echo "$out" | grep -q '^map_sizes: \[1024\]$' && ok || fail "-D map_sizes not applied: $out"
echo "$out" | grep -q 'label: slope, method: nsm, self_shadow: slope, bias: 0.01' && ok || fail "-D methods[1].bias not applied"
echo "$out" | grep -q 'exr: true' && ok || fail "-D outputs.exr not applied"
echo "$out" | grep -q "ok: 1 scene(s), 4 cell(s)" && ok || fail "-D map_sizes: want 4 cells: $(echo "$out" | head -1)"
err=$("$bin" validate "$tmp/small.yaml" -D 'methods[0].bias=0.01' 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "^shadowlab: -D methods\[0\].bias=0.01: 'methods\[0\].bias': bias applies to" && ok ||
  fail "a parameter the method does not take: rc $rc '$err'"
err=$("$bin" validate "$tmp/small.yaml" -D 'methods[7].bias=1' 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "'methods\[7\].bias': 'methods' has 2 entries" && ok || fail "bad index: '$err'"
err=$("$bin" validate "$tmp/small.yaml" -D 'nokey=3' 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "^shadowlab: -D nokey=3: 'nokey': unknown key 'nokey'" && ok || fail "unknown key: '$err'"
err=$("$bin" run "$tmp/small.yaml" -o "$tmp/x" -D 'map_sizes=[100]' 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "\-D map_sizes=\[100\]: 'map_sizes\[0\]': map size 100: must be a power of two" && ok ||
  fail "run -D bad value: '$err'"
[ -e "$tmp/x/small" ] && fail "a refused -D left output" || ok
err=$("$bin" validate "$tmp/small.yaml" -D 'justaword' 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "\-D wants KEY=VALUE" && ok || fail "-D without =: '$err'"
# an error elsewhere in the file keeps its own file and line
printf 'name: small\nscenes: [{scene: primitives}]\nmap_sizes: [256]\nmethods: [{method: nsm}]\nseed: -3\n' >"$tmp/bad.yaml"
err=$("$bin" validate "$tmp/bad.yaml" -D 'map_sizes=[512]' 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "bad.yaml:5" && ok || fail "file error under -D lost its line: '$err'"

# --out=DIR, -q: only the 'written to' line on stdout; -j; -D changes the hash
env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$bin" run "$tmp/small.yaml" --out="$tmp/o" -q -j 1 --no-cache >"$tmp/q.out" 2>"$tmp/q.err" ||
  fail "run -q: $(cat "$tmp/q.err")"
[ "$(wc -l <"$tmp/q.out")" -eq 1 ] && grep -q "^written to $tmp/o/small/ and $tmp/o/shadowlab.db$" "$tmp/q.out" && ok ||
  fail "--quiet stdout: $(cat "$tmp/q.out")"
[ -s "$tmp/q.err" ] && fail "--quiet wrote to stderr: $(head -3 "$tmp/q.err")" || ok
[ -f "$tmp/o/small/figures.csv" ] && ok || fail "--out=DIR: no $tmp/o/small/figures.csv"
grep -q "^threads: 1$" "$tmp/o/small/run.yaml" "$tmp/o/small/config.yaml" 2>/dev/null && ok || fail "-j 1 not in run.yaml/config.yaml"
# threads: 0 is the cores this process may use (its affinity mask, as under
# taskset or a Slurm allocation), not every core of the machine
taskset -c 0 "$bin" validate "$tmp/small.yaml" 2>/dev/null | grep -q "^threads: 1$" && ok ||
  fail "validate under taskset -c 0: threads not 1: $(taskset -c 0 "$bin" validate "$tmp/small.yaml" 2>&1 | grep threads)"
# OpenMP's threads wait passively unless the environment says otherwise (main.c)
grep -q "^omp_wait_policy: passive$" "$tmp/o/small/run.yaml" && ok || fail "run without OMP_WAIT_POLICY: not passive"
# default: the summary (one line per label) and progress lines off a terminal
OMP_WAIT_POLICY=active "$bin" run "$tmp/small.yaml" -o "$tmp/p" -D 'map_sizes=[256]' --no-cache >"$tmp/s.out" 2>"$tmp/s.err" ||
  fail "run: $(cat "$tmp/s.err")"
grep -q "^omp_wait_policy: active$" "$tmp/p/small/run.yaml" && ok || fail "OMP_WAIT_POLICY=active not kept"
grep -q "^small: 4 cell(s) computed, 0 already stored" "$tmp/s.out" && ok || fail "summary: $(cat "$tmp/s.out")"
grep -q "^ff  *2  *[0-9]" "$tmp/s.out" && grep -q "^slope  *2 " "$tmp/s.out" && ok || fail "no line per label: $(cat "$tmp/s.out")"
[ "$(wc -l <"$tmp/s.out")" -le 8 ] && ok || fail "summary longer than a screen's top: $(wc -l <"$tmp/s.out") lines"
grep -q "^shadowlab: 4/4 cells (100%), .* elapsed, ~.* left$" "$tmp/s.err" && ok || fail "no off-TTY progress: $(cat "$tmp/s.err")"
grep -q $'\r' "$tmp/s.err" && fail "carriage returns in off-TTY progress" || ok
"$bin" run "$tmp/small.yaml" -o "$tmp/v" -v --no-cache >"$tmp/v.out" 2>/dev/null || fail "run -v"
grep -q "^| " "$tmp/v.out" && grep -q "^written to " "$tmp/v.out" && ok || fail "--verbose: no tables"
# the same config with and without -D: different config hashes in the store
h1=$("$bin" table "$tmp/o/shadowlab.db" --format csv | awk -F, 'NR==2 {print $13}')
"$bin" run "$tmp/small.yaml" -o "$tmp/o" -q -D 'map_sizes=[256]' >/dev/null 2>&1 || fail "second run"
n=$("$bin" table "$tmp/o/shadowlab.db" --format csv | awk -F, 'NR>1 {print $13}' | sort -u | wc -l)
[ "$n" -eq 2 ] && ok || fail "-D did not change the config hash ($n hashes, first $h1)"

# check: --json and --junit parse, the plain table, colour rules
db="$tmp/o/shadowlab.db"
"$bin" check "$db" --baseline "$tmp/b.yaml" --study small --update 2>/dev/null || fail "check --update"
sed 's/^\(      wrong: \[\)\([0-9]*\)/\1999999/' "$tmp/b.yaml" >"$tmp/moved.yaml"
"$bin" check "$db" --baseline "$tmp/moved.yaml" --study small --json "$tmp/c.json" --junit "$tmp/c.xml" >"$tmp/c.txt"; rc=$?
[ $rc -eq 1 ] && ok || fail "moved baseline: rc $rc"
python3 - "$tmp/c.json" "$tmp/c.xml" <<'PY' && ok || fail "json/junit did not read back"
import json, sys, xml.etree.ElementTree as ET
j = json.load(open(sys.argv[1]))
assert j["passed"] is False and j["failed"] >= 1, j
cells = {r["cell"] for r in j["results"]}
assert len(cells) == 8, cells
bad = [(r["cell"], k) for r in j["results"] for k, v in r["classes"].items() if not v["passed"]]
assert bad and all(k == "error" for _, k in bad), bad
assert "first_failure" in j["results"][0]["classes"]["error"]
t = ET.parse(sys.argv[2]).getroot()
cases = t.findall(".//testcase")
assert int(t.get("tests")) == len(cases) and len(cases) >= 8 * 5, len(cases)
failed = [c for c in cases if c.find("failure") is not None]
assert int(t.get("failures")) == len(failed) == len(bad), (len(failed), len(bad))
assert {(c.get("classname"), c.get("name")) for c in failed} == set(bad)
PY
grep -q '\*\*' "$tmp/c.txt" && fail "markdown in the terminal table" || ok
grep -q "FAIL" "$tmp/c.txt" && ! grep -q $'\033' "$tmp/c.txt" && ok || fail "plain table: FAIL missing or colour off a TTY"
"$bin" check "$db" --baseline "$tmp/moved.yaml" --study small --format md | grep -q '| \*\*FAIL\*\* |$' && ok || fail "--format md"
if command -v script >/dev/null; then
  script -qec "'$bin' check '$db' --baseline '$tmp/moved.yaml' --study small" /dev/null | grep -q $'\033\[1;31mFAIL' && ok ||
    fail "no colour on a TTY"
  NO_COLOR=1 script -qec "'$bin' check '$db' --baseline '$tmp/moved.yaml' --study small" /dev/null | grep -q $'\033' &&
    fail "colour with NO_COLOR" || ok
fi
# a missing cell gets the table's header too
grep -v -- "- cell: \"primitives/side/128x128/256/ff\"" "$tmp/b.yaml" >/dev/null
python3 - "$tmp/b.yaml" "$tmp/miss.yaml" <<'PY'
import sys
s = open(sys.argv[1]).read()
head, cells = s.split("cells:\n", 1)
parts = cells.split("  - cell: ")
parts[1] = parts[1].replace("primitives/", "nowhere/", 1)
open(sys.argv[2], "w").write(head + "cells:\n" + "  - cell: ".join(parts))
PY
out=$("$bin" check "$db" --baseline "$tmp/miss.yaml" --study small --junit "$tmp/m.xml"); rc=$?
[ $rc -eq 1 ] && echo "$out" | sed -n 3p | grep -q "^cell  *region  *figure" && echo "$out" | grep -q "^nowhere/.*missing *FAIL" && ok ||
  fail "missing cell row without header: $out"
python3 -c "import sys,xml.etree.ElementTree as E; t=E.parse(sys.argv[1]); assert all(c.find('failure') is not None for c in t.findall('.//testcase') if c.get('classname').startswith('nowhere/'))" "$tmp/m.xml" && ok || fail "missing cell not failed in JUnit"

# list scenes: scene files only, each with where it came from; SHADOWLAB_SCENES in front
mkdir -p "$tmp/sc"
cp "$tmp/small.yaml" "$tmp/sc/notascene.yaml"
printf 'name: mine\ndescription: "my own"\nbase: primitives\n' >"$tmp/sc/mine.yaml"
out=$(SHADOWLAB_SCENES="$tmp/nope:$tmp/sc" "$bin" list scenes)
echo "$out" | grep -q "^mine .*my own.*\[SHADOWLAB_SCENES: $tmp/sc/mine.yaml\]" && ok || fail "SHADOWLAB_SCENES scene: $out"
echo "$out" | grep -q "^primitives .*\[source tree: " && ok || fail "the built-in folder is no longer searched: $out"
echo "$out" | grep -q notascene && fail "list scenes lists a config" || ok
"$bin" list scenes | grep -q "^default" && fail "list scenes lists configs/" || ok

# validate of a scene: per-mesh bounds inside the scene's bounds
out=$("$bin" validate scenes/primitives.yaml) || fail "validate scene"
[ "$(echo "$out" | grep -c '^  mesh ')" -eq "$(echo "$out" | sed -n 's/.* \([0-9]*\) mesh(es).*/\1/p')" ] && ok ||
  fail "validate: not one bounds line per mesh: $out"
echo "$out" | grep -q "^  mesh torus .* triangles, bounds (" && ok || fail "validate: no torus bounds: $out"

# a scene given where a config is expected: a default study, its config printed
cp scenes/blocks.yaml "$tmp/myscene.yaml"
"$bin" run "$tmp/myscene.yaml" -o "$tmp/st" -D 'viewports=[{width: 128, height: 128}]' -D 'map_sizes=[256]' \
  >"$tmp/st.out" 2>"$tmp/st.err" || fail "run SCENE: $(cat "$tmp/st.err")"
grep -q "is a scene: a default study" "$tmp/st.err" && grep -q "^  - {label: csm, method: csm, display: \"CSMa\"}" "$tmp/st.err" && ok ||
  fail "run SCENE: config not printed"
for l in nsm csm raytrace; do grep -q "^$l  *1 " "$tmp/st.out" && ok || fail "run SCENE: no $l line"; done
grep -q "^myscene: 3 cell(s) computed" "$tmp/st.out" && ok || fail "run SCENE summary: $(cat "$tmp/st.out")"
sed -n '/^# filled-in config/,$p' "$tmp/st.err" | grep -v "^shadowlab: [0-9]" >"$tmp/saved.yaml"
"$bin" validate "$tmp/saved.yaml" >/dev/null 2>&1 && ok || fail "the printed config does not validate"

# preview: a PNG per viewpoint, the size asked for, lit faces brighter than
# the background; an unknown viewpoint is refused naming the known ones
"$bin" preview scenes/primitives.yaml -o "$tmp/pv" --size 96x64 >"$tmp/pv.out" 2>"$tmp/pv.err" ||
  fail "preview: $(cat "$tmp/pv.err")"
[ "$(wc -l <"$tmp/pv.out")" -eq 3 ] && ok || fail "preview: want 3 files: $(cat "$tmp/pv.out")"
for vp in side with against; do
  f="$tmp/pv/primitives-$vp.png"
  # PNG header: width and height at bytes 16..23
  wh=$(python3 -c "import struct,sys; print('%dx%d' % struct.unpack('>II', open(sys.argv[1],'rb').read()[16:24]))" "$f" 2>/dev/null)
  [ "$wh" = 96x64 ] && ok || fail "preview $vp: size $wh"
  # the brightest pixel is a lit face (the background is 46,52,64; faces turned away 31)
  mx=$(oiiotool "$f" --printstats 2>/dev/null | sed -n 's/.*Stats Max: *\([0-9]*\) .*/\1/p')
  [ "${mx:-0}" -ge 128 ] && ok || fail "preview $vp: brightest $mx of 255"
done
"$bin" preview primitives --viewpoint nope -o "$tmp/pv2" >/dev/null 2>"$tmp/pv2.err"; rc=$?
[ $rc -eq 2 ] && grep -q "no such viewpoint (the scene has: side, with, against)" "$tmp/pv2.err" && ok ||
  fail "preview --viewpoint nope: exit $rc, $(cat "$tmp/pv2.err")"
[ ! -e "$tmp/pv2" ] && ok || fail "preview with a bad viewpoint made its folder"

# on a terminal: the live progress line is cleared ("\r\033[K") before the
# summary, so the summary's first line starts clean (issue 37)
if command -v script >/dev/null; then
  script -qec "'$bin' run '$tmp/small.yaml' -o '$tmp/tty' --no-cache" /dev/null >"$tmp/tty.out" 2>&1
  grep -qa $'\r\[8/8\]' "$tmp/tty.out" && ok || fail "no live progress line on a terminal: $(od -c "$tmp/tty.out" | head)"
  grep -qa $'\r\033\[K''small: 8 cell(s) computed' "$tmp/tty.out" && ok ||
    fail "the progress line is not cleared before the summary: $(od -c "$tmp/tty.out" | tail -n 12)"
  grep -qa 'left   '$'\r''\?$' "$tmp/tty.out" && fail "a progress line left on its own line" || ok
  # -v: the tables (stdout) come after the cleared line, not glued to its end
  script -qec "'$bin' run '$tmp/small.yaml' -o '$tmp/tty-v' --no-cache -v" /dev/null >"$tmp/tty-v.out" 2>&1
  grep -qa $'\r\033\[K''# ' "$tmp/tty-v.out" && ok ||
    fail "-v: the progress line is not cleared before the tables: $(grep -a -m1 -B1 '^# ' "$tmp/tty-v.out" | od -c | tail -n 6)"
  grep -qa 'left   # ' "$tmp/tty-v.out" && fail "-v: a table glued to the progress line" || ok
fi

# show method: a built-in method's parameters, from its declarations
out=$("$bin" show method nsm 2>&1) && ok || fail "show method nsm: $out"
echo "$out" | grep -qE '^    self_shadow +choice default front_faces +none, constant, slope, front_faces, triangle_id' && ok ||
  fail "show method nsm: no self_shadow line: $out"
echo "$out" | grep -qE '^    bias +float +default 1 +\[0, 1000\] +\(texels\)' && ok || fail "show method nsm: no bias line: $out"
out=$("$bin" show method soft_mc 2>&1)
echo "$out" | grep -qE '^    grid +int +default 3 +\[1, 16\]' && echo "$out" | grep -qE '^    blur +bool +default false' && ok ||
  fail "show method soft_mc: $out"
"$bin" show method texel | grep -q '^  parameters none$' && ok || fail "show method texel: parameters none"
err=$("$bin" show method pcf 2>&1); rc=$?
[ $rc -eq 2 ] && echo "$err" | grep -q "no built-in method of that name" && echo "$err" | grep -q "show technique NAME" && ok ||
  fail "show method pcf (a package): rc $rc '$err'"
# a C method's parameter swept as a list, like a package's
out=$("$bin" validate "$tmp/small.yaml" -D 'methods[1].bias=[0.5, 2]' 2>&1) && ok || fail "-D a C method's sweep: $out"
echo "$out" | grep -q 'label: "slope\[bias=0.5\]", method: nsm, self_shadow: slope, bias: 0.5, slope: 1' && ok ||
  fail "a C method's sweep is not two labels: $out"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
