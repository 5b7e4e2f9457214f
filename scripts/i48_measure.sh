#!/bin/sh
# i48_measure.sh — the measurements behind doc/methods.md's "Primitives'
# contours" and "Hertel's rays and wrong pixels" paragraphs (issue 48,
# items 4 and 5). Each study is an ordinary config run by build/shadowlab;
# nothing here changes a scene or a method, only the labels, contours and
# set-up the run is given. Usage:
#   scripts/i48_measure.sh OUT_DIR [contours|hertel|kinds] [-D KEY=VALUE]...
# the -D overrides go to `shadowlab run` as they are (e.g. -D name=hertel-sphere
# -D 'methods[1].light_frame={fit: sphere}').
set -eu
out=${1:?usage: i48_measure.sh OUT_DIR [contours|hertel|kinds]}
what=${2:-contours}
shift; [ $# -gt 0 ] && shift
bin=$(realpath "${SHADOWLAB:-build/shadowlab}")
mkdir -p "$out"
case $what in
contours)
    # Primitives as configs/default.yaml, every self-shadow policy NSM has,
    # for NSM and coherence-4, contours drawn from each label's own image
    # (raytrace: the truth's). Wrong hints: shadowlab table DB --rows label
    # --cols viewpoint --figure hinted_light_wrong (hinted_shadow_wrong)
    # --of count --agg sum --where region=image --where map_size=1024.
    for from in own nsm; do
        cat > "$out/prim-$from.yaml" <<YAML
name: prim-$from
scenes:
  - {scene: primitives, viewpoints: [side, with, against]}
viewports:
  - {width: 1024, height: 1024}
map_sizes: [1024, 2048]
contours: [2, 4, 6]
contour_from: $from
methods:
  - {label: raytrace, method: raytrace}
  - {label: nsm, method: nsm, self_shadow: front_faces}
  - {label: nsm_none, method: nsm, self_shadow: none}
  - {label: nsm_const1, method: nsm, self_shadow: constant, bias: 1}
  - {label: nsm_const2, method: nsm, self_shadow: constant, bias: 2}
  - {label: nsm_slope, method: nsm, self_shadow: slope, bias: 0, slope: 1}
  - {label: nsm_tid, method: nsm, self_shadow: triangle_id}
  - {label: coherence4, method: coherence, texels: 4}
  - {label: coh4_none, method: coherence, texels: 4, self_shadow: none}
  - {label: coh4_const1, method: coherence, texels: 4, self_shadow: constant, bias: 1}
  - {label: coh4_const2, method: coherence, texels: 4, self_shadow: constant, bias: 2}
  - {label: coh4_slope, method: coherence, texels: 4, self_shadow: slope, bias: 0, slope: 1}
  - {label: coh4_tid, method: coherence, texels: 4, self_shadow: triangle_id}
outputs: {tables: true, overlays: false}
repetitions: {warmup: 0, runs: 1}
YAML
        nice -n 10 "$bin" run "$out/prim-$from.yaml" -o "$out" -q "$@"
    done ;;
hertel)
    # Hertel's own set-up: a 1280 x 1024 view port, a 1K map, the Morais
    # scenes; hertel beside hertel_exact and the full trace.
    cat > "$out/hertel.yaml" <<YAML
name: hertel-setup
scenes:
  - {scene: bench, viewpoints: [side, with, against]}
  - {scene: trees, viewpoints: [side, with, against]}
  - {scene: flowers, viewpoints: [side, with, against]}
  - {scene: primitives, viewpoints: [side, with, against]}
viewports:
  - {width: 1280, height: 1024}
map_sizes: [1024]
contours: [2]
methods:
  - {label: raytrace, method: raytrace}
  - {label: hertel, method: hertel}
  - {label: hertel_exact, method: hertel_exact}
  - {label: bgsm, method: bgsm}
outputs: {tables: true, overlays: false, exr: true, aliasing: true}
repetitions: {warmup: 0, runs: 1}
YAML
    nice -n 10 "$bin" run "$out/hertel.yaml" -o "$out" -q "$@" ;;
kinds)
    # NSM's error kinds per mesh (scripts/i48_kinds.py OUT/nsm-kinds/exr):
    # the validation set's nine views at 1024 x 1024 with the 2048² map,
    # then the same with the trees' leaf cards one-sided (a copy of the
    # scenes under OUT/sc, tree_a and tree_b two_sided: false).
    rm -rf "$out/sc" && cp -r scenes "$out/sc"
    sed -i 's/two_sided: true/two_sided: false/' "$out/sc/bench.yaml"
    for v in "nsm-kinds bench trees flowers" "nsm-kinds-one-sided sc/bench.yaml sc/trees.yaml sc/flowers.yaml"; do
        set -- $v
        cat > "$out/$1.yaml" <<YAML
name: $1
scenes: [{scene: $2}, {scene: $3}, {scene: $4}]
viewports: [{width: 1024, height: 1024}]
map_sizes: [2048]
contours: [2]
methods:
  - {label: nsm, method: nsm, self_shadow: front_faces}
outputs: {tables: false, overlays: false, exr: true}
repetitions: {warmup: 0, runs: 1}
YAML
        (cd "$out" && nice -n 10 "$bin" run "$1.yaml" -o . -q)
    done ;;
*) echo "i48_measure.sh: unknown study '$what' (contours, hertel or kinds)" >&2; exit 2 ;;
esac
