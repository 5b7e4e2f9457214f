#!/usr/bin/env bash
# package::* (shell) — issue 36: technique packages as the command line meets
# them.
#   copy       pcf copied out of the tree under another name and named by a
#              config's `techniques:` gives the shipped pcf's figures, every
#              count of every region; SHADOWLAB_TECHNIQUES finds it too
#   broken     a GLSL error in the copy: exit 2, the message names the
#              package's file and line, nothing written under --out, at run
#              and at validate (glslang, no GL); an error after lines reading
#              sl_map_pos and sl_home_texel: its own line, at validate and
#              run; a guard band too wide for a 16384 map: refused at
#              validate naming the config's line and the parameter; a YAML
#              error in its technique.yaml: exit 2 naming that file's line
#   sweep      `kernel: [1, 3, 5]` makes three labels (validate prints them)
#   nsm_cross  the nsm package (the GL lookup) and the C nsm (self_shadow
#              none: the same plain test of the same layer) agree on every
#              figure of every region of the default scene's three views and
#              Moderno 2011's four scenes; pcf with kernel 1 agrees with both
set -u
bin=${1:?usage: cli_packages.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
# figures.csv rows of one label, without the label and method columns (and the
# provenance after percent_of), sorted
rows() { awk -F, -v l="$2" 'NR > 1 && $6 == l { print $1","$2","$3","$4","$7","$8","$9","$10 }' "$1" | sort; }
# the same without the fractional figures (soft_*: a package's visibility,
# which a C method has not)
hard_rows() { rows "$1" "$2" | awk -F, '$6 !~ /^soft_/'; }

mkdir -p "$tmp/pk"
cp -r techniques/pcf "$tmp/pk/my_pcf"
sed -i 's/^name: pcf$/name: my_pcf/' "$tmp/pk/my_pcf/technique.yaml"
grep -q '^name: my_pcf$' "$tmp/pk/my_pcf/technique.yaml" || fail "renaming the copy"

case $case_ in
copy)
  cat >"$tmp/c.yaml" <<'YAML'
name: copy
techniques: [pk]
scenes: [{scene: primitives, viewpoints: [side, against]}]
viewports: [{width: 256, height: 256}]
map_sizes: [512]
methods:
  - {label: shipped, method: pcf, kernel: 3}
  - {label: copied, method: my_pcf, kernel: 3}
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/out" || fail "run with the copy"
  a=$(rows "$tmp/out/copy/figures.csv" shipped); b=$(rows "$tmp/out/copy/figures.csv" copied)
  [ -n "$a" ] && [ "$(echo "$a" | wc -l)" -gt 100 ] || fail "no figures for the shipped pcf"
  [ "$a" = "$b" ] || { diff <(echo "$a") <(echo "$b") | head; fail "the copy's figures differ from the shipped package's"; }
  # the same through SHADOWLAB_TECHNIQUES, no config key
  sed '/^techniques:/d' "$tmp/c.yaml" >"$tmp/e.yaml"
  "$bin" validate "$tmp/e.yaml" >/dev/null 2>&1 && fail "my_pcf found without a search path"
  SHADOWLAB_TECHNIQUES="$tmp/pk" "$bin" validate "$tmp/e.yaml" >/dev/null || fail "SHADOWLAB_TECHNIQUES not searched"
  SHADOWLAB_TECHNIQUES="$tmp/pk" "$bin" list techniques | grep -q "^my_pcf .*SHADOWLAB_TECHNIQUES" ||
    fail "list techniques does not show the copy and where it was found"
  # an edited package is another study: --resume computes its cells again
  # (the config hash covers the package's files), an unchanged one does not
  "$bin" run "$tmp/c.yaml" --no-cache --resume -o "$tmp/out" >"$tmp/r1" 2>&1 || fail "resume"
  grep -q "0 cell(s) computed, 4 already stored" "$tmp/r1" || { cat "$tmp/r1"; fail "an unchanged package's cells were computed again"; }
  echo "// edited" >>"$tmp/pk/my_pcf/lookup.glsl"
  "$bin" run "$tmp/c.yaml" --no-cache --resume -o "$tmp/out" >"$tmp/r2" 2>&1 || fail "resume after the edit"
  grep -q "4 cell(s) computed, 0 already stored" "$tmp/r2" || { cat "$tmp/r2"; fail "cells of the edited package taken as stored"; }
  # where a method comes from is the method's own metadata, stored per cell:
  # a package's `family:` (else "package"), a built-in's sl_method.family
  fam=$(sqlite3 "$tmp/out/shadowlab.db" "SELECT DISTINCT label || '=' || family FROM cells ORDER BY 1" | tr '\n' ' ')
  [ "$fam" = "copied=filtered shipped=filtered " ] || fail "cells.family: $fam"
  sed -i '/^family:/d' "$tmp/pk/my_pcf/technique.yaml"
  "$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/nofam" >/dev/null || fail "run without family"
  [ "$(sqlite3 "$tmp/nofam/shadowlab.db" "SELECT family FROM cells WHERE label = 'copied' LIMIT 1")" = package ] ||
    fail "a package without family: is not 'package'"
  echo "family: Filtered" >>"$tmp/pk/my_pcf/technique.yaml"
  out=$("$bin" validate "$tmp/c.yaml" 2>&1); rc=$?
  [ $rc -eq 2 ] && echo "$out" | grep -q "my_pcf/technique.yaml.*family" || fail "a bad family: rc $rc: $out"
  echo "ok copy: $(echo "$a" | wc -l) figure rows equal"
  ;;
broken)
  cat >"$tmp/c.yaml" <<'YAML'
name: broken
techniques: [pk]
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64]
methods:
  - {label: nsm, method: nsm}
  - {label: copied, method: my_pcf}
YAML
  # line 20 of the lookup gets a statement GLSL refuses
  sed -i '20i\    this_is_not_glsl = 1;' "$tmp/pk/my_pcf/lookup.glsl"
  "$bin" run "$tmp/c.yaml" --no-cache -o "$tmp/out" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/e"; fail "broken shader: exit $rc, not 2"; }
  head -1 "$tmp/e" | grep -q "pk/my_pcf/lookup.glsl:20: .*GLSL" || { cat "$tmp/e"; fail "the message names not lookup.glsl:20"; }
  [ "$(wc -l <"$tmp/e")" -le 2 ] || { cat "$tmp/e"; fail "more than one message"; }
  [ -z "$(ls -A "$tmp/out" 2>/dev/null)" ] || { find "$tmp/out"; fail "a broken package left files under --out"; }
  echo "ok broken shader: $(head -1 "$tmp/e")"
  # validate finds it too, without GL (glslang), at the same line; and an
  # error after lines reading the harness's sl_map_pos and sl_home_texel is
  # reported at its own line, not at a warning about them
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/e"; fail "validate of a broken shader: exit $rc, not 2"; }
  head -1 "$tmp/e" | grep -q "pk/my_pcf/lookup.glsl:20: .*GLSL: error" || { cat "$tmp/e"; fail "validate names not lookup.glsl:20"; }
  sed -i '20d' "$tmp/pk/my_pcf/lookup.glsl"
  body=$(grep -n '^{' "$tmp/pk/my_pcf/lookup.glsl" | head -1 | cut -d: -f1)
  sed -i "$((body))a\    vec2 sl_p = sl_map_pos;\n    ivec2 sl_h = sl_home_texel;\n    float typo = sl_p.x + float(sl_h.y) + undeclared_name;" \
    "$tmp/pk/my_pcf/lookup.glsl"
  line=$(grep -n 'undeclared_name' "$tmp/pk/my_pcf/lookup.glsl" | cut -d: -f1)
  for verb in validate run; do
    args=(); [ $verb = run ] && args=(--no-cache -o "$tmp/out")
    "$bin" $verb "$tmp/c.yaml" "${args[@]}" >"$tmp/o" 2>"$tmp/e"; rc=$?
    [ $rc -eq 2 ] || { cat "$tmp/e"; fail "$verb: an error after harness reads: exit $rc, not 2"; }
    head -1 "$tmp/e" | grep -q "pk/my_pcf/lookup.glsl:$line: .*GLSL: error: .*undeclared_name" ||
      { cat "$tmp/e"; fail "$verb names not lookup.glsl:$line"; }
  done
  [ -z "$(ls -A "$tmp/out" 2>/dev/null)" ] || { find "$tmp/out"; fail "a broken package left files under --out"; }
  echo "ok error after harness reads: $(head -1 "$tmp/e")"
  # a guard band too wide for a 16384 map: refused at validate, before any truth
  sed -i "/undeclared_name/d; /sl_p = sl_map_pos/d; /sl_h = sl_home_texel/d" "$tmp/pk/my_pcf/lookup.glsl"
  sed 's/^map_sizes: \[64\]/map_sizes: [16384]/; s/{label: copied, method: my_pcf}/{label: copied, method: my_pcf, kernel: 9}/' \
    "$tmp/c.yaml" >"$tmp/wide.yaml"
  "$bin" validate "$tmp/wide.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] && head -1 "$tmp/e" | grep -q "wide.yaml:8: 'methods\[1\]\.kernel': kernel = 9 gives label copied a guard band of 4" ||
    { cat "$tmp/e"; fail "a guard band too wide: rc $rc"; }
  echo "ok guard band: $(head -1 "$tmp/e")"
  # a YAML error in the package: its own file and line, exit 2, before GL
  sed -i 's/^  - {name: kernel, type: int,/  - {name: kernel, type: integer,/' "$tmp/pk/my_pcf/technique.yaml"
  line=$(grep -n 'type: integer' "$tmp/pk/my_pcf/technique.yaml" | cut -d: -f1)
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/e"; fail "broken technique.yaml: exit $rc, not 2"; }
  grep -q "my_pcf/technique.yaml:$line: " "$tmp/e" || { cat "$tmp/e"; fail "the message names not technique.yaml:$line"; }
  echo "ok broken yaml: $(head -1 "$tmp/e")"
  ;;
sweep)
  cat >"$tmp/c.yaml" <<'YAML'
name: sweep
scenes: [{scene: primitives}]
map_sizes: [512]
methods:
  - {method: pcf, kernel: [1, 3, 5]}
  - {label: b, method: nsm, self_shadow: constant, bias: [0.5, 2]}
YAML
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>&1 || { cat "$tmp/o"; fail "validate"; }
  for l in 'pcf\[kernel=1\]' 'pcf\[kernel=3\]' 'pcf\[kernel=5\]' 'b\[bias=0.5\]' 'b\[bias=2\]'; do
    grep -q "label: \"$l\", method: " "$tmp/o" || { cat "$tmp/o"; fail "validate does not print label $l"; }
  done
  [ "$(grep -c 'label: "pcf\[' "$tmp/o")" -eq 3 ] || fail "not three pcf labels"
  echo "ok sweep: 5 labels"
  ;;
nsm_cross)
  cat >"$tmp/c.yaml" <<'YAML'
name: cross
scenes:
  - {scene: primitives, viewpoints: [side, with, against]}
  - {scene: bench}
  - {scene: trees}
  - {scene: flowers}
viewports: [{width: 384, height: 384}]
map_sizes: [1024]
methods:
  - {label: c, method: nsm, self_shadow: none}
  - {label: glsl, method: nsm_glsl}
  - {label: pcf1, method: pcf, kernel: 1, bias: 0}
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/out" || fail "run"
  a=$(hard_rows "$tmp/out/cross/figures.csv" c)
  for l in glsl pcf1; do
    b=$(hard_rows "$tmp/out/cross/figures.csv" $l)
    [ "$a" = "$b" ] || { diff <(echo "$a") <(echo "$b") | head -20; fail "$l differs from the C nsm"; }
  done
  echo "ok nsm_cross: $(echo "$a" | wc -l) figure rows equal over $(cut -d, -f1,2 <<<"$a" | sort -u | wc -l) views"
  ;;
*) fail "unknown case $case_" ;;
esac
