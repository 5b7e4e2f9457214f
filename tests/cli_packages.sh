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
#   point      packages under a point light (the room, the grazing light):
#              each label runs on every view (the cell count holds them), per
#              face of the light's cube: nsm_glsl and pcf with kernel 1 agree
#              with the C nsm on every figure of every region, the faces
#              counted as the C methods' are; pcf, vsm and evsm run beside
#              them; the exact C methods keep 0 violations; a label that
#              cannot run there is named (a note without a list, exit 2 with
#              one)
#   nonfinite  a lookup returning NaN or -inf (tests/techniques/nonfinite) and
#              an rgba16f map holding +inf (inf_map): the cells store their
#              counts, the run's summary, stderr and table.md flag them, the
#              pixels are uncertain (not wrong); check fails against a
#              baseline without the counts and passes against one holding them;
#              `table --figure leaking` pivots, leaking + over_dark = soft_mae
#   hard_classes vsm and evsm under the directional light (filtered: their
#              visibility is almost never exactly 0 or 1): the soft classes
#              take the tolerance 0.05 (class right = within 0.05, no truth
#              pixel penumbra, EVSM's class right near VSM's, not 2.75 %),
#              and table.md and the table's LaTeX name the directional light
#              and the tolerance, never an area light
#   rules      a technique.yaml over 64 KiB: "at most 64 KiB"; a package
#              folder, a technique.yaml, a shader that is a symbolic link:
#              each exit 2 naming it; a linked folder of packages loads
#   trace      vsm_rt and msm_rt (vsm and msm with a traced band) beside vsm
#              and msm on the primitives and on the room (a point light: per
#              face): each view's wrong pixels at most the plain package's,
#              rays > 0 and below the PFL pixels (the plain packages' 0), 0
#              violations (every traced pixel equals the truth), the rays in
#              costs.csv, and `table --figure rays --of pfl` (rays per PFL
#              pixel: the share of raytrace's) as the cells give it
set -u
bin=${1:?usage: cli_packages.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
# figures.csv rows of one label, without the label and method columns (and the
# provenance after percent_of), sorted
rows() { awk -F, -v l="$2" 'NR > 1 && $6 == l { print $1","$2","$3","$4","$7","$8","$9","$10 }' "$1" | sort; }
# the same without the fractional figures (soft_*, leaking, over_dark: a
# package's visibility, which a C method has not)
hard_rows() { rows "$1" "$2" | awk -F, '$6 !~ /^(soft_|leaking$|over_dark$)/'; }

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
point)
  cat >"$tmp/c.yaml" <<'YAML'
name: point
scenes:
  - {scene: room}
  - {scene: grazing}
viewports: [{width: 256, height: 256}]
map_sizes: [512]
methods:
  - {label: c, method: nsm, self_shadow: none}
  - {label: glsl, method: nsm_glsl}
  - {label: pcf1, method: pcf, kernel: 1, bias: 0}
  - {label: pcf, method: pcf}
  - {label: vsm, method: vsm}
  - {label: evsm, method: evsm}
  - {label: bgsm, method: bgsm}
  - {label: sgsm, method: sgsm}
  - {label: csm, method: csm}
  - {label: hertel_exact, method: hertel_exact}
  - {label: raytrace, method: raytrace}
outputs: {overlays: false}
YAML
  views=$("$bin" validate "$tmp/c.yaml" -D 'methods=[{label: c, method: nsm}]' | sed -n '1s/.* \([0-9]*\) cell(s)$/\1/p')
  [ "${views:-0}" -gt 0 ] || fail "validate with the C nsm alone"
  out=$("$bin" validate "$tmp/c.yaml" 2>"$tmp/note") || fail "validate"
  echo "$out" | head -1 | grep -q ": ok: 2 scene(s), $((views * 11)) cell(s)$" ||
    fail "the cell count leaves packages out: $(echo "$out" | head -1), $views views x 11 labels"
  [ ! -s "$tmp/note" ] || fail "a note for a config that leaves nothing out: $(cat "$tmp/note")"
  "$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/out" 2>"$tmp/err" || { cat "$tmp/err"; fail "run"; }
  a=$(hard_rows "$tmp/out/point/figures.csv" c)
  [ "$(cut -d, -f1,2 <<<"$a" | sort -u | wc -l)" -eq "$views" ] || fail "the C nsm's figures cover $views views"
  for l in glsl pcf1; do
    b=$(hard_rows "$tmp/out/point/figures.csv" $l)
    [ "$a" = "$b" ] || { diff <(echo "$a") <(echo "$b") | head -20; fail "$l differs from the C nsm under a point light"; }
  done
  q() { sqlite3 "$tmp/out/shadowlab.db" "$1"; }
  [ "$(q "SELECT count(*) FROM cells")" -eq $((views * 11)) ] || fail "cells stored: $(q "SELECT count(*) FROM cells")"
  bad=$(q "SELECT label || ' ' || scene || '/' || viewpoint || ': ' || violations FROM cells WHERE violations > 0")
  [ -z "$bad" ] || fail "violations beside the packages: $bad"
  [ "$(q "SELECT count(*) FROM cells WHERE nonfinite > 0")" -eq 0 ] || fail "values not finite"
  # the packages run per face as the C methods do: the same faces per view
  f=$(q "SELECT group_concat(faces) FROM (SELECT faces FROM cells WHERE label = 'c' ORDER BY scene, viewpoint)")
  for l in glsl pcf vsm evsm; do
    g=$(q "SELECT group_concat(faces) FROM (SELECT faces FROM cells WHERE label = '$l' ORDER BY scene, viewpoint)")
    [ "$f" = "$g" ] || fail "$l ran on faces $g, the C nsm on $f"
  done
  [ "$(q "SELECT min(faces) FROM cells WHERE label = 'vsm'")" -gt 0 ] || fail "vsm ran on no face"
  # the faces' visibility merged: each view's mean |v - t| small and not 0
  # (a face's visibility lost reads as 0: most of the lit pixels' share)
  for l in pcf vsm evsm; do
    w=$(awk -F, -v l=$l '$6 == l && $7 == "image" && $8 == "soft_mae" { print $10 }' "$tmp/out/point/figures.csv")
    [ "$(echo "$w" | wc -l)" -eq "$views" ] || fail "$l: soft_mae of $views views: $w"
    echo "$w" | awk '!($1 > 0 && $1 < 30) { exit 1 }' || fail "$l: soft_mae under the point light: $w"
  done
  # a label that cannot run under a point light: named, never dropped unsaid
  "$bin" validate "$tmp/c.yaml" -D 'methods[1]={label: glsl, method: nsm_glsl, partitions: 2}' >/dev/null 2>"$tmp/note" ||
    fail "validate with cascades and no list"
  grep -q "scene 'room' has a point light .*leaves out glsl (runs cascades" "$tmp/note" ||
    fail "no note naming the cascades label left out: $(cat "$tmp/note")"
  out=$("$bin" validate "$tmp/c.yaml" -D 'methods[1]={label: glsl, method: nsm_glsl, partitions: 2}' \
        -D 'scenes[0].methods=[c, glsl]' 2>&1); rc=$?
  [ $rc -eq 2 ] && echo "$out" | grep -q "scenes\[0\]\.methods.*scene 'room' has a point light but method 'nsm_glsl' (label glsl) runs cascades" ||
    fail "a listed cascades label under a point light: rc $rc: $out"
  echo "ok point: $views views x 11 labels; $(echo "$a" | wc -l) figure rows equal"
  ;;
nonfinite)
  # tests/techniques: a lookup returning NaN, -inf or +inf on the map's left
  # half, and an rgba16f map holding +inf in its first 64 columns
  cat >"$tmp/c.yaml" <<YAML
name: nonfinite
techniques: [$PWD/tests/techniques]
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 128, height: 128}]
map_sizes: [256]
methods:
  - {label: nsm, method: nsm_glsl}
  - {label: nan, method: nonfinite, value: 0}
  - {label: ninf, method: nonfinite, value: 1}
  - {label: map, method: inf_map}
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/c.yaml" --no-cache -o "$tmp/out" >"$tmp/o" 2>"$tmp/e" || { cat "$tmp/e"; fail "run"; }
  db="$tmp/out/shadowlab.db"
  nf() { sqlite3 "$db" "SELECT nonfinite FROM cells WHERE label = '$1'"; }
  [ "$(nf nsm)" = 0 ] || fail "nsm_glsl has $(nf nsm) values not finite"
  # the lookup's: every PFL pixel on the left half, and no other
  for l in nan ninf; do
    n=$(nf $l); pfl=$(sqlite3 "$db" "SELECT n_pfl FROM cells WHERE label = '$l'")
    [ "$n" -gt 0 ] && [ "$n" -lt "$pfl" ] || fail "$l: $n values not finite of $pfl PFL pixels"
    # a result, not a shadow: uncertain, and not among the wrong pixels
    unc=$(sqlite3 "$db" "SELECT count FROM figures f JOIN cells c USING (cell_id) WHERE c.label = '$l' AND region = 'image' AND figure = 'uncertain'")
    [ "$unc" = "$n" ] || fail "$l: $unc uncertain pixels, $n not finite"
    grep -q "^$l .*NON-FINITE: $n value(s) in 1 cell(s)" "$tmp/o" || { cat "$tmp/o"; fail "the summary does not flag $l"; }
    grep -q "NON-FINITE: primitives/side map 256 '$l': $n value" "$tmp/e" || { cat "$tmp/e"; fail "no NON-FINITE line for $l"; }
  done
  [ "$(nf nan)" = "$(nf ninf)" ] || fail "NaN and -inf counted apart: $(nf nan) vs $(nf ninf)"
  # the map's: 64 columns of a 256² map (no guard band)
  [ "$(nf map)" = 16384 ] || fail "inf_map: $(nf map) texels not finite, not 64 x 256"
  grep -q "^nsm .*NON-FINITE" "$tmp/o" && fail "the summary flags nsm_glsl"
  grep -q "NON-FINITE: 256²: $(nf nan) value(s)" "$tmp/out/nonfinite/table.md" ||
    fail "table.md has no NON-FINITE note"
  # check: the store against its own baseline passes (it holds the counts);
  # against one without them (written before the counter, or holding 0) fails
  "$bin" check "$db" --baseline "$tmp/b.yaml" --update >/dev/null 2>&1 || fail "check --update"
  grep -q "nonfinite: $(nf nan)" "$tmp/b.yaml" || fail "the baseline does not hold the count"
  "$bin" check "$db" --baseline "$tmp/b.yaml" --exact >/dev/null || fail "check against its own baseline"
  sed 's/, nonfinite: [0-9]*//' "$tmp/b.yaml" >"$tmp/old.yaml"
  sed 's/nonfinite: [0-9]*/nonfinite: 0/' "$tmp/b.yaml" >"$tmp/zero.yaml"
  for b in old zero; do
    out=$("$bin" check "$db" --baseline "$tmp/$b.yaml" --format md); rc=$?
    [ $rc -eq 1 ] || { echo "$out"; fail "check against the $b baseline: exit $rc, not 1"; }
    echo "$out" | grep -q "nonfinite" || { echo "$out"; fail "check's table does not name nonfinite"; }
  done
  # the fractional figures are figures: the pivot takes leaking and
  # over_dark, and their sum is soft_mae (the non-finite pixels left out)
  "$bin" table "$db" --figure leaking --rows label --cols map_size --format csv >"$tmp/leak.csv" 2>&1 ||
    { cat "$tmp/leak.csv"; fail "table --figure leaking"; }
  grep -q '^nsm,[0-9.]*$' "$tmp/leak.csv" || { cat "$tmp/leak.csv"; fail "no leaking row for nsm"; }
  bad=$(sqlite3 "$db" "SELECT c.label FROM cells c JOIN figures m ON m.cell_id = c.cell_id AND m.figure = 'soft_mae'
                       JOIN figures l ON l.cell_id = c.cell_id AND l.figure = 'leaking'
                       JOIN figures o ON o.cell_id = c.cell_id AND o.figure = 'over_dark'
                       WHERE abs(l.percent + o.percent - m.percent) > 1e-9 OR m.percent IS NULL")
  [ -z "$bad" ] || fail "leaking + over_dark != soft_mae: $bad"
  echo "ok nonfinite: NaN $(nf nan), -inf $(nf ninf) pixels; $(nf map) map texels"
  ;;
trace)
  cat >"$tmp/c.yaml" <<'YAML'
name: trace
scenes:
  - {scene: primitives, viewpoints: [side, against]}
  - {scene: room}
viewports: [{width: 256, height: 256}]
map_sizes: [512]
methods:
  - {label: vsm, method: vsm}
  - {label: vsm_rt, method: vsm_rt}
  - {label: msm, method: msm}
  - {label: msm_rt, method: msm_rt}
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/out" 2>"$tmp/err" || { cat "$tmp/err"; fail "run"; }
  q() { sqlite3 "$tmp/out/shadowlab.db" "$1"; }
  bad=$(q "SELECT label || ' ' || scene || '/' || viewpoint || ': ' || violations FROM cells WHERE violations > 0")
  [ -z "$bad" ] || fail "traced pixels against the truth: $bad"
  for p in vsm msm; do
    n=$(q "SELECT count(*) FROM cells a JOIN cells b USING (scene, viewpoint, map_size)
           WHERE a.label = '$p' AND b.label = '${p}_rt'")
    [ "$n" -ge 3 ] || fail "$p and ${p}_rt side by side in $n views"
    worse=$(q "SELECT scene || '/' || viewpoint || ': ' || b.n_wrong_image || ' > ' || a.n_wrong_image
               FROM cells a JOIN cells b USING (scene, viewpoint, map_size)
               WHERE a.label = '$p' AND b.label = '${p}_rt' AND b.n_wrong_image > a.n_wrong_image")
    [ -z "$worse" ] || fail "${p}_rt has more wrong pixels than $p: $worse"
    off=$(q "SELECT scene || '/' || viewpoint || ': ' || rays || ' rays, ' || n_pfl || ' PFL' FROM cells
             WHERE label = '${p}_rt' AND NOT (rays > 0 AND rays < n_pfl)")
    [ -z "$off" ] || fail "${p}_rt traced none or all: $off"
    [ "$(q "SELECT count(*) FROM cells WHERE label = '$p' AND rays > 0")" -eq 0 ] || fail "$p traced"
    echo "  $(q "SELECT '${p}: ' || sum(a.n_wrong_image) || ' wrong, ${p}_rt: ' || sum(b.n_wrong_image) ||
                 ' wrong, ' || sum(b.rays) || ' rays of ' || sum(b.n_pfl) || ' PFL pixels'
                 FROM cells a JOIN cells b USING (scene, viewpoint, map_size)
                 WHERE a.label = '$p' AND b.label = '${p}_rt'")"
  done
  # the pivot's rays per PFL pixel (% of raytrace's): each view's share, averaged
  want=$(q "SELECT printf('%.4f', avg(100.0 * rays / n_pfl)) FROM cells WHERE label = 'vsm_rt' AND scene = 'primitives'")
  got=$("$bin" table "$tmp/out/shadowlab.db" --figure rays --of pfl --rows label --cols scene --where label=vsm_rt \
        --where scene=primitives --format csv | awk -F, 'NR == 2 { printf "%.4f", $2 }')
  [ -n "$got" ] && [ "$got" = "$want" ] || fail "table --figure rays --of pfl gives '$got', the cells $want"
  "$bin" table "$tmp/out/shadowlab.db" --figure ms_method --of pfl >/dev/null 2>&1 && fail "a time per PFL pixel"
  col=$(head -1 "$tmp/out/trace/costs.csv" | tr , '\n' | grep -nx rays | cut -d: -f1)
  [ -n "$col" ] || fail "costs.csv has no rays column"
  awk -F, -v c="$col" 'NR > 1 && $0 ~ /vsm_rt/ && $c > 0 { ok = 1 } END { exit !ok }' "$tmp/out/trace/costs.csv" ||
    fail "costs.csv holds no rays of vsm_rt"
  echo "ok trace"
  ;;
hard_classes)
  cat >"$tmp/c.yaml" <<'YAML'
name: hardfrac
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 256, height: 256}]
map_sizes: [1024]
methods:
  - {label: vsm, method: vsm}
  - {label: evsm, method: evsm}
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/out" || fail "run"
  db="$tmp/out/shadowlab.db"
  fig() { sqlite3 "$db" "SELECT f.$3 FROM figures f JOIN cells c USING (cell_id) WHERE c.label = '$1' AND f.figure = '$2'"; }
  for l in vsm evsm; do
    [ "$(sqlite3 "$db" "SELECT frac FROM cells WHERE label = '$l'")" = 1 ] || fail "$l: not a frac cell"
    [ "$(fig $l soft_truth_penumbra count)" = 0 ] || fail "$l: truth pixels in penumbra under a directional light"
    [ "$(fig $l soft_class_right count)" = "$(fig $l soft_within_005 count)" ] ||
      fail "$l: class right $(fig $l soft_class_right count) != within 0.05 $(fig $l soft_within_005 count)"
    awk -v p="$(fig $l soft_class_right percent)" 'BEGIN { exit !(p > 90) }' ||
      fail "$l: class right $(fig $l soft_class_right percent) %"
  done
  md="$tmp/out/hardfrac/table.md"
  grep -q "rea light" "$md" && fail "table.md says area light under a directional light"
  [ "$(grep -c "^Directional light: the visibility against the light's 0/1 truth over the PFL pixels" "$md")" = 2 ] ||
    fail "table.md's soft tables do not name the directional light"
  grep -q "within ε = 0.05 of 1" "$md" || fail "table.md does not state the classes' tolerance"
  "$bin" table "$db" --format latex >"$tmp/t.tex" || fail "table --format latex"
  grep -q "rea light" "$tmp/t.tex" && fail "the LaTeX says area light under a directional light"
  grep -q "Directional light: the visibility against the light's 0/" "$tmp/t.tex" ||
    fail "the LaTeX's soft captions do not name the directional light"
  grep -q "directional light, per method and shadow-map size: the visibility against its 0/" \
    "$tmp/out/hardfrac/table-detail.tex" ||
    fail "table-detail.tex does not name the directional light"
  echo "ok hard_classes: class right vsm $(fig vsm soft_class_right percent) %, evsm $(fig evsm soft_class_right percent) %"
  ;;
rules)
  # issue 49: a technique.yaml over its limit says the limit in its unit
  # (64 KiB, not "0 MiB"); one symlink rule: the package folder, its
  # technique.yaml and a shader that are links are each refused (exit 2,
  # named), while a folder holding packages may be a link
  cat >"$tmp/c.yaml" <<'YAML'
name: rules
techniques: [pk]
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64]
methods:
  - {label: copied, method: my_pcf}
YAML
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e" || { cat "$tmp/e"; fail "the plain copy does not validate"; }
  cp -r "$tmp/pk/my_pcf" "$tmp/orig"
  yes '# padding to push technique.yaml over 64 KiB' | head -c 70000 >>"$tmp/pk/my_pcf/technique.yaml"
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/e"; fail "technique.yaml over 64 KiB: exit $rc, not 2"; }
  grep -q "pk/my_pcf/technique.yaml: file of [0-9]* bytes: at most 64 KiB are read" "$tmp/e" ||
    { cat "$tmp/e"; fail "the size message"; }
  echo "ok size: $(head -1 "$tmp/e")"
  rm -rf "$tmp/pk/my_pcf"
  # the package folder a link to a package kept elsewhere
  ln -s "$tmp/orig" "$tmp/pk/my_pcf"
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] || { cat "$tmp/e"; fail "a linked package folder: exit $rc, not 2"; }
  grep -q "pk/my_pcf: the package folder is a symbolic link: refused" "$tmp/e" || { cat "$tmp/e"; fail "folder link not named"; }
  echo "ok folder link: $(head -1 "$tmp/e")"
  rm "$tmp/pk/my_pcf" && mkdir "$tmp/pk/my_pcf" && cp -r "$tmp/orig/." "$tmp/pk/my_pcf/"
  # technique.yaml a link
  mv "$tmp/pk/my_pcf/technique.yaml" "$tmp/t.yaml" && ln -s "$tmp/t.yaml" "$tmp/pk/my_pcf/technique.yaml"
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] && grep -q "pk/my_pcf/technique.yaml: a symbolic link: refused" "$tmp/e" ||
    { cat "$tmp/e"; fail "a linked technique.yaml: exit $rc"; }
  rm "$tmp/pk/my_pcf/technique.yaml" && mv "$tmp/t.yaml" "$tmp/pk/my_pcf/technique.yaml"
  # a shader a link
  mv "$tmp/pk/my_pcf/lookup.glsl" "$tmp/l.glsl" && ln -s "$tmp/l.glsl" "$tmp/pk/my_pcf/lookup.glsl"
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e"; rc=$?
  [ $rc -eq 2 ] && grep -q "lookup.glsl is a symbolic link (refused" "$tmp/e" || { cat "$tmp/e"; fail "a linked shader: exit $rc"; }
  rm "$tmp/pk/my_pcf/lookup.glsl" && mv "$tmp/l.glsl" "$tmp/pk/my_pcf/lookup.glsl"
  # the folder holding packages may be a link
  mv "$tmp/pk" "$tmp/pk_real" && ln -s "$tmp/pk_real" "$tmp/pk"
  "$bin" validate "$tmp/c.yaml" >"$tmp/o" 2>"$tmp/e" || { cat "$tmp/e"; fail "a linked folder of packages is refused"; }
  echo "ok links"
  ;;
*) fail "unknown case $case_" ;;
esac
