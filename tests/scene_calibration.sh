#!/usr/bin/env bash
# scene::calibration_square, scene::calibration_wide — issue 38: the Bench,
# Trees and Flowers scenes cast the shadow the theses measured. A truth-only
# run (the raytrace method alone, one map size: the truth does not depend on
# it) of the published views; each view's figures from the store, against
# the thesis's within the band of scenes/CALIBRATION.md:
#   shadow % of PFL  (n_truth_shadow / n_pfl)            within +-15% relative
#   PnFL % of pixels (n_pnfl / all pixels)                within +-1 point
#   Moderno's shadow (n_truth_shadow + n_pnfl) / pixels   within +-15% relative
# Morais 2015 Tables 4-6 (seed 000) give the first two for three views at
# 512x512, 1024x1024 and 1920x1080; Moderno 2011's appendix (seed 003, the
# "Whole Image" rows, truth = defined-lit - wrongly-lit + wrongly-shadowed)
# the third for all nine views at 1024x1024, its shadow counting the pixels
# that face away from the light. Case square: 512x512 and 1024x1024; case
# wide: 1920x1080, whose aspect moves the thesis's own figures.
#
# A row marked "known" (6 of 27 since issue 48) is one outside its
# band that CALIBRATION.md explains: printed, and failing if it comes
# inside, so the mark is dropped with it. Every other row must be inside,
# or the test fails.
set -u
bin=${1:?usage: scene_calibration.sh path/to/shadowlab square|wide|boundaries|trees_only|validation}
case=${2:?usage: scene_calibration.sh path/to/shadowlab square|wide|boundaries|trees_only|validation}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

# boundary figures outside 1.5x that CALIBRATION.md ties to a statement of
# the theses ("Issue 48", the fit's residuals): scene/view/figure
known_boundaries='bench/side/nw bench/with/nw trees/with/nw trees/side/nw flowers/side/c2 flowers/against/c2 flowers/with/c2'
# scene view viewport figure thesis [known]
# figure: sh (shadow % of PFL), pn (PnFL % of pixels), mo (Moderno's shadow %)
targets_square='
trees   side    512x512   sh 35.55
trees   side    512x512   pn 0.00
flowers against 512x512   sh 47.01
flowers against 512x512   pn 5.78
bench   against 512x512   sh 40.97
bench   against 512x512   pn 2.38
trees   side    1024x1024 sh 35.55
trees   side    1024x1024 pn 0.00
flowers against 1024x1024 sh 47.01
flowers against 1024x1024 pn 5.79
bench   against 1024x1024 sh 40.97
bench   against 1024x1024 pn 2.38
bench   side    1024x1024 mo 30.75
bench   with    1024x1024 mo 35.08 known
bench   against 1024x1024 mo 42.38
trees   with    1024x1024 mo 37.50 known
trees   side    1024x1024 mo 35.55
trees   against 1024x1024 mo 40.25
flowers side    1024x1024 mo 39.08 known
flowers against 1024x1024 mo 50.39
flowers with    1024x1024 mo 41.80 known
'
# Table 4's 1920x1080 percentages (36.62 / 63.38) are Table 6's, copied: its
# own counts give 753160 / 2073445 = 36.32% (CALIBRATION.md, "Table 4")
targets_wide='
trees   side    1920x1080 sh 36.32 known
trees   side    1920x1080 pn 0.01
flowers against 1920x1080 sh 30.25 known
flowers against 1920x1080 pn 3.26
bench   against 1920x1080 sh 36.62
bench   against 1920x1080 pn 1.34
'
case $case in
trees_only)
    # Moderno 4.1: in the Trees views "only the shadows of the trees will be
    # seen": their truth is the same with every prop as with the ground and
    # the two trees alone (CALIBRATION.md, T3)
    exec python3 scripts/bench_calibration.py --build "$(dirname "$bin")" --viewport 512x512 treesonly ;;
validation)
    # issue 48, item 3: the validation table in CALIBRATION.md is what the
    # current scenes give (figures never fitted; it cannot go stale)
    exec python3 scripts/calibration_validation.py --build "$bin" check scenes/CALIBRATION.md ;;
boundaries)
    # issue 48, item 2: the fitting set's boundary figures, Moderno 2011's
    # appendix with the 1024^2 map (report/theses/moderno-2011-scenes.csv):
    # NSM's 2 px contour pixels (c2) and wrong pixels (nw) in each of the
    # nine views at 1024x1024, within 1.5x of the thesis's either way; a
    # view in $known_boundaries is printed, and fails if it comes inside
    cat >"$tmp/b.yaml" <<YAML
name: boundaries
scenes: [{scene: bench}, {scene: trees}, {scene: flowers}]
viewports: [{width: 1024, height: 1024}]
map_sizes: [1024]
contours: [2]
methods: [{label: nsm, method: nsm, self_shadow: front_faces}]
outputs: {tables: false, overlays: false}
repetitions: {warmup: 0, runs: 1}
YAML
    "$bin" run "$tmp/b.yaml" --no-cache -q -o "$tmp/b" || { echo "FAIL run"; exit 1; }
    checked=0
    while IFS=, read -r _ _ scene view map l2w l2 s2w s2 ilw il isw is _; do
        case $scene in bench|trees|flowers) ;; *) continue ;; esac
        [ "$map" = 1024 ] || continue
        ours=$(sqlite3 -separator ' ' "$tmp/b/shadowlab.db" "SELECT
              sum(CASE WHEN region = '2px' AND figure = 'pixels' THEN count END),
              sum(CASE WHEN region = 'image' AND figure IN ('light_incorrect', 'shadow_incorrect') THEN count END)
              FROM figures WHERE scene = '$scene' AND viewpoint = '$view'")
        set -- $ours
        [ $# -eq 2 ] || { echo "FAIL $scene/$view: no cell"; fail=1; continue; }
        for f in "c2 $1 $((l2 + s2))" "nw $2 $((ilw + isw))"; do
            set -- $f
            v=$(awk -v o="$2" -v t="$3" 'BEGIN { r = o / t; printf "%s %.2f", (r >= 1 / 1.5 && r <= 1.5 ? "in" : "out"), r }')
            set -- $1 $2 $3 $v
            line=$(printf '%-8s %-8s %s ours %7d thesis %7d ratio %s' "$scene" "$view" "$1" "$2" "$3" "$5")
            k=" $known_boundaries "
            if [ "$4" = in ] && [ "${k#* $scene/$view/$1 }" != "$k" ]; then
                echo "FAIL  $line: inside 1.5x though marked known"; fail=1
            elif [ "$4" = in ]; then echo "ok    $line"
            elif [ "${k#* $scene/$view/$1 }" != "$k" ]; then echo "known $line (scenes/CALIBRATION.md)"
            else echo "FAIL  $line"; fail=1
            fi
            checked=$((checked + 1))
        done
    done < <(grep -v '^#' report/theses/moderno-2011-scenes.csv)
    [ "$checked" -eq 18 ] || { echo "FAIL $checked of 18 figures checked"; exit 1; }
    exit $fail ;;
square) targets=$targets_square
        viewports='[{width: 512, height: 512}, {width: 1024, height: 1024}]'
        scenes='[{scene: bench}, {scene: trees}, {scene: flowers}]' ;;
wide)   targets=$targets_wide
        viewports='[{width: 1920, height: 1080}]'
        scenes='[{scene: bench, viewpoints: [against]}, {scene: trees, viewpoints: [side]}, {scene: flowers, viewpoints: [against]}]' ;;
*) echo "unknown case '$case' (square, wide, boundaries, trees_only, validation)"; exit 2 ;;
esac
cat >"$tmp/c.yaml" <<YAML
name: calibration
scenes: $scenes
viewports: $viewports
map_sizes: [512]
methods: [{label: raytrace, method: raytrace}]
outputs: {tables: false, overlays: false}
repetitions: {warmup: 0, runs: 1}
YAML
"$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/out" || { echo "FAIL run"; exit 1; }
db=$tmp/out/shadowlab.db
checked=0
while read -r scene view vp fig thesis known; do
    [ -n "$scene" ] || continue
    row=$(sqlite3 -separator ' ' "$db" "SELECT n_pfl, n_pnfl, n_background, n_truth_shadow FROM cells
          WHERE scene='$scene' AND viewpoint='$view' AND viewport='$vp' AND label='raytrace'")
    [ -n "$row" ] || { echo "FAIL $scene/$view $vp: no cell in the store"; fail=1; continue; }
    verdict=$(echo "$row" | awk -v fig="$fig" -v t="$thesis" '{
        pfl = $1; pnfl = $2; all = $1 + $2 + $3; sh = $4
        if (fig == "sh") { v = 100 * sh / pfl; band = 0.15 * t }
        else if (fig == "pn") { v = 100 * pnfl / all; band = 1.0 }
        else { v = 100 * (sh + pnfl) / all; band = 0.15 * t }
        d = v - t; if (d < 0) d = -d
        printf "%s %.2f %.2f\n", (d <= band ? "in" : "out"), v, band }')
    set -- $verdict
    line=$(printf '%-8s %-8s %-10s %s ours %6.2f thesis %6.2f +-%.2f' "$scene" "$view" "$vp" "$fig" "$2" "$thesis" "$3")
    if [ "$1" = in ] && [ "$known" = known ]; then
        echo "FAIL  $line: inside its band though marked known (drop the mark, update CALIBRATION.md)"; fail=1
    elif [ "$1" = in ]; then
        echo "ok    $line"
    elif [ "$known" = known ]; then
        echo "known $line (outside its band; scenes/CALIBRATION.md)"
    else
        echo "FAIL  $line"; fail=1
    fi
    checked=$((checked + 1))
done <<<"$targets"
[ "$checked" -gt 0 ] || { echo "FAIL nothing checked"; exit 1; }
exit $fail
