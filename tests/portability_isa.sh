#!/usr/bin/env bash
# portability::isa_figures — the same study traced by Embree's SSE4.2, AVX2
# and native kernels (SHADOWLAB_EMBREE_CONFIG=isa=..., so every CPU CI may
# get runs all three) gives figures.csv byte for byte (its machine column
# aside: git SHA and config hash are the same by construction, and the file
# holds no time). The study traces every way the program traces: the truth
# under a directional light and under an area light taken as a point, the
# methods that trace a subset (raytrace, chain, csm, hertel_exact,
# hard_point) and the area light's soft truth (soft_mc), at a viewport that
# is no multiple of 4 so that the edge tiles hold dead lanes.
#
# It also checks the packet width each run says it used (run.yaml,
# embree_packets): 4 under SSE4.2, 8 under AVX2 — the device's native width
# (harness/truth/packet.h) — and that a SHADOWLAB_EMBREE_CONFIG Embree does
# not document is refused (exit 2) before anything is written, by run and by
# bench.
#
# On the code before packet.h (16-wide packets with unwritten lanes) the
# forced runs abort in Embree's assertions (exit 134), so this test fails
# there.
set -u
bin=${1:?usage: portability_isa.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
cat >"$tmp/isa.yaml" <<'EOF'
name: isa
scenes:
  - {scene: primitives, viewpoints: [side, against]}
  - {scene: curtis_box, viewpoints: [above]}
viewports: [{width: 250, height: 198}]
map_sizes: [512]
contours: [2, 4]
methods:
  - {label: nsm, method: nsm}
  - {label: chain, method: chain, finish: trace}
  - {label: csm, method: csm}
  - {label: hertel_exact, method: hertel_exact}
  - {label: raytrace, method: raytrace}
  - {label: hard_point, method: hard_point}
  - {label: mc_3x3, method: soft_mc}
area_samples: 16
outputs: {tables: true, overlays: false}
repetitions: {warmup: 0, runs: 1}
EOF

# figures.csv without its last column (machine: host/CPU/ISA)
strip() { sed 's/,[^,]*$//' "$1"; }

run_isa() { # run_isa NAME [ENV=VALUE]
    local name=$1
    shift
    env "$@" "$bin" run "$tmp/isa.yaml" --out "$tmp/$name" --no-cache -q >"$tmp/$name.log" 2>&1
    local rc=$?
    if [ $rc != 0 ]; then
        echo "FAIL: $name: run exited $rc ($*):"
        tail -5 "$tmp/$name.log"
        fails=1
        return 1
    fi
    echo "ok: $name: $(grep -E '^embree' "$tmp/$name/isa/run.yaml" | tr '\n' ' ')"
}

run_isa native SHADOWLAB_EMBREE_CONFIG=
run_isa sse42 SHADOWLAB_EMBREE_CONFIG=isa=sse4.2
run_isa avx2 SHADOWLAB_EMBREE_CONFIG=isa=avx2
for isa in native sse42 avx2; do
    [ -f "$tmp/$isa/isa/figures.csv" ] || { echo "FAIL: $isa: no figures.csv"; fails=1; }
done
if [ -f "$tmp/native/isa/figures.csv" ]; then
    rows=$(wc -l <"$tmp/native/isa/figures.csv")
    [ "$rows" -gt 1000 ] || { echo "FAIL: native figures.csv has $rows rows"; fails=1; }
    for isa in sse42 avx2; do
        [ -f "$tmp/$isa/isa/figures.csv" ] || continue
        if cmp -s <(strip "$tmp/native/isa/figures.csv") <(strip "$tmp/$isa/isa/figures.csv"); then
            echo "ok: $isa: figures.csv the same as native ($rows rows)"
        else
            echo "FAIL: $isa: figures.csv differs from native:"
            diff <(strip "$tmp/native/isa/figures.csv") <(strip "$tmp/$isa/isa/figures.csv") | head -10
            fails=1
        fi
    done
fi

# the width follows the ISA Embree runs
want_packets() { # want_packets NAME N CONFIG
    local got
    got=$(sed -n 's/^embree_packets: //p' "$tmp/$1/isa/run.yaml" 2>/dev/null)
    [ "$got" = "$2" ] && grep -qx "embree_config: $3" "$tmp/$1/isa/run.yaml" ||
        { echo "FAIL: $1: embree_packets '$got' (want $2), embree_config (want $3)"; fails=1; }
}
want_packets sse42 4 isa=sse4.2
want_packets avx2 8 isa=avx2
want_packets native "$(sed -n 's/^embree_packets: //p' "$tmp/native/isa/run.yaml")" "(unset)"

# a config Embree would misread is refused before anything is written
for bad in isa=avx-2 isa=AVX2 nonsense=1 isa ",isa=avx2"; do
    SHADOWLAB_EMBREE_CONFIG=$bad "$bin" run "$tmp/isa.yaml" --out "$tmp/bad" --no-cache -q >"$tmp/bad.log" 2>&1
    rc=$?
    if [ $rc != 2 ] || ! grep -q "SHADOWLAB_EMBREE_CONFIG" "$tmp/bad.log" || [ -e "$tmp/bad" ]; then
        echo "FAIL: SHADOWLAB_EMBREE_CONFIG='$bad': exit $rc (want 2, naming the variable, nothing written):"
        cat "$tmp/bad.log"
        fails=1
    else
        echo "ok: SHADOWLAB_EMBREE_CONFIG='$bad' refused: $(head -1 "$tmp/bad.log")"
    fi
done
# ... by bench too, before any stage
SHADOWLAB_EMBREE_CONFIG=isa=avx-2 "$bin" bench --only truth --reps 1 >"$tmp/bench.log" 2>&1
rc=$?
if [ $rc != 2 ] || ! grep -q "SHADOWLAB_EMBREE_CONFIG" "$tmp/bench.log"; then
    echo "FAIL: bench with SHADOWLAB_EMBREE_CONFIG='isa=avx-2': exit $rc (want 2):"
    cat "$tmp/bench.log"
    fails=1
else
    echo "ok: bench refuses SHADOWLAB_EMBREE_CONFIG='isa=avx-2': $(head -1 "$tmp/bench.log")"
fi
exit $fails
