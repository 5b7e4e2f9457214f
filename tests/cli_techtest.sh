#!/usr/bin/env bash
# techtest::* (shell) — `shadowlab test technique NAME`, the packages' linter.
#   shipped    every package under techniques/ passes on the default scene
#              (exit 0, every check ok); pcf and vsm on the spot-lit scene
#              and on the room's point light (per face of its cube)
#   reach      tests/techniques/overreach (a 3 x 3 PCF declaring reach 1 and
#              reading 4 texels beyond it) fails the reach check, exit 1,
#              naming how many pixels change; the same package with its far
#              taps brought within the reach (beyond 0) passes
#   findings   a lookup returning NaN (tests/techniques/nonfinite) fails the
#              non-finite check naming the count; a pcf copy declaring 4 taps
#              where it reads 9 fails the taps check; each exit 1
#   bad_input  exit 2: an unknown package (the message names those found), a
#              GLSL error (the package file and line), an unknown scene or
#              viewpoint, a missing NAME
set -u
bin=${1:?usage: cli_techtest.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }

case $case_ in
shipped)
  n=0
  for dir in techniques/*/; do
    name=$(awk '/^name:/ { print $2; exit }' "$dir/technique.yaml")
    [ -n "$name" ] || fail "no name in $dir/technique.yaml"
    "$bin" test technique "$name" >"$tmp/out" 2>&1 || { cat "$tmp/out"; fail "$name: exit $? on primitives"; }
    cat "$tmp/out"
    grep -q '^passes$' "$tmp/out" || fail "$name: no 'passes'"
    for check in compile determinism reach non-finite taps; do
      grep -q "^  ok   $check " "$tmp/out" || fail "$name: check $check not ok"
    done
    grep -q ' 0 pixel(s) change (0 verdicts)' "$tmp/out" || fail "$name: reach"
    n=$((n + 1))
  done
  [ "$n" -ge 7 ] || fail "only $n shipped packages tested"
  for name in pcf vsm; do
    "$bin" test technique "$name" --scene primitives_spot >"$tmp/out" 2>&1 ||
      { cat "$tmp/out"; fail "$name: exit $? on primitives_spot"; }
    # a point light: per face of its cube
    "$bin" test technique "$name" --scene room >"$tmp/out" 2>&1 || { cat "$tmp/out"; fail "$name: exit $? on room"; }
    cat "$tmp/out"
    grep -Eq 'map x [2-6] cube faces' "$tmp/out" || fail "$name: room not drawn per cube face"
  done
  ;;
reach)
  SHADOWLAB_TECHNIQUES=tests/techniques "$bin" test technique overreach >"$tmp/out" 2>&1
  rc=$?
  cat "$tmp/out"
  [ "$rc" -eq 1 ] || fail "overreach: exit $rc, not 1"
  grep -Eq '^  FAIL reach +[1-9][0-9]* pixel\(s\) change' "$tmp/out" || fail "overreach: the reach check does not name its pixels"
  grep -q 'reads beyond its declared reach' "$tmp/out" || fail "overreach: no word on the reach"
  grep -q '^  ok   determinism' "$tmp/out" || fail "overreach: determinism should pass"
  # the far taps within the reach: the same package passes
  mkdir -p "$tmp/pk"
  cp -r tests/techniques/overreach "$tmp/pk/within"
  sed -i -e 's/^name: overreach$/name: within/' -e 's/default: 4,/default: 0,/' "$tmp/pk/within/technique.yaml"
  SHADOWLAB_TECHNIQUES="$tmp/pk" "$bin" test technique within >"$tmp/out" 2>&1 ||
    { cat "$tmp/out"; fail "overreach with beyond 0: exit $?"; }
  grep -Eq '^  ok   reach +0 pixel' "$tmp/out" || fail "beyond 0: reach"
  ;;
findings)
  SHADOWLAB_TECHNIQUES=tests/techniques "$bin" test technique nonfinite >"$tmp/out" 2>&1
  rc=$?
  cat "$tmp/out"
  [ "$rc" -eq 1 ] || fail "nonfinite: exit $rc, not 1"
  grep -Eq '^  FAIL non-finite +[1-9][0-9]* lookup\(s\) NaN' "$tmp/out" || fail "nonfinite: count not named"
  mkdir -p "$tmp/pk"
  cp -r techniques/pcf "$tmp/pk/taps4"
  sed -i -e 's/^name: pcf$/name: taps4/' "$tmp/pk/taps4/technique.yaml"
  sed -i -e '/^taps:/,/^params:/{/^taps:/!{/^params:/!d}}' -e 's/^taps:$/taps: {texels: 4}/' "$tmp/pk/taps4/technique.yaml"
  grep -q '^taps: {texels: 4}$' "$tmp/pk/taps4/technique.yaml" || fail "editing the copy's taps"
  SHADOWLAB_TECHNIQUES="$tmp/pk" "$bin" test technique taps4 >"$tmp/out" 2>&1
  rc=$?
  cat "$tmp/out"
  [ "$rc" -eq 1 ] || fail "taps4: exit $rc, not 1"
  grep -q '^  FAIL taps  *4 declared; counted 9 \.\. 9' "$tmp/out" || fail "taps4: the taps check"
  ;;
bad_input)
  "$bin" test technique no_such >"$tmp/out" 2>&1
  rc=$?
  [ "$rc" -eq 2 ] || fail "unknown package: exit $rc"
  grep -q "no technique package of that name (found: .*pcf" "$tmp/out" || { cat "$tmp/out"; fail "unknown package: message"; }
  mkdir -p "$tmp/pk"
  cp -r techniques/pcf "$tmp/pk/broken"
  sed -i 's/^name: pcf$/name: broken/' "$tmp/pk/broken/technique.yaml"
  line=$(grep -n 'int h = kernel / 2;' "$tmp/pk/broken/lookup.glsl" | cut -d: -f1)
  sed -i 's/int h = kernel \/ 2;/int h = kernel \/ 2 +;/' "$tmp/pk/broken/lookup.glsl"
  SHADOWLAB_TECHNIQUES="$tmp/pk" "$bin" test technique broken >"$tmp/out" 2>&1
  rc=$?
  [ "$rc" -eq 2 ] || { cat "$tmp/out"; fail "GLSL error: exit $rc"; }
  grep -q "broken/lookup.glsl:$line:" "$tmp/out" || { cat "$tmp/out"; fail "GLSL error: not at lookup.glsl:$line"; }
  "$bin" test technique pcf --scene no_such_scene >"$tmp/out" 2>&1
  rc=$?
  [ "$rc" -eq 2 ] || { cat "$tmp/out"; fail "unknown scene: exit $rc"; }
  "$bin" test technique pcf --viewpoint no_such_view >"$tmp/out" 2>&1
  rc=$?
  [ "$rc" -eq 2 ] || { cat "$tmp/out"; fail "unknown viewpoint: exit $rc"; }
  grep -q "no such viewpoint (the scene has: side" "$tmp/out" || { cat "$tmp/out"; fail "unknown viewpoint: message"; }
  "$bin" test technique >"$tmp/out" 2>&1
  [ $? -eq 2 ] || fail "no NAME: exit not 2"
  ;;
*) fail "unknown case $case_" ;;
esac
echo "ok $case_"
