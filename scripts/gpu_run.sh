#!/usr/bin/env bash
# scripts/gpu_run.sh — the device checks on a lent GPU machine (doc/performance.md,
# "On a GPU"), run there by the device tool in the checkout's copy with `.gpu`
# carried: .gpu/deb holds the runtime libraries' Debian packages (apt-get
# download, see ../shared/PLATFORM.md), .gpu/bin the binary and its modules.
# Writes under $OUT: the CI config through EGL checked against the llvmpipe
# baseline, and the studies' wall and CPU times, each repeated.
set -u
out=${OUT:?}
for f in .gpu/deb/libegl1*.deb .gpu/deb/libglvnd0*.deb .gpu/deb/libopengl0*.deb .gpu/deb/libgl1*.deb \
         .gpu/deb/libglx0*.deb; do dpkg -x "$f" /; done
ldconfig
mkdir -p .gpu/root
for f in .gpu/deb/*.deb; do dpkg -x "$f" .gpu/root; done
export LD_LIBRARY_PATH=$PWD/.gpu/root/usr/lib/x86_64-linux-gnu:$PWD/.gpu/root/lib/x86_64-linux-gnu
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
export SHADOWLAB_SCENES=$PWD/scenes SHADOWLAB_TECHNIQUES=$PWD/techniques SHADOWLAB_MODULE_DIR=$PWD/.gpu/bin
bin=$PWD/.gpu/bin/shadowlab
t=$(mktemp -d)
{
  nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
  nproc; uptime
} >"$out/machine.txt" 2>&1
# 1. the CI config through EGL on the GPU against the llvmpipe baseline
"$bin" run configs/ci.yaml --gl egl --no-cache -o "$t/ci" >"$out/ci.txt" 2>&1
echo "run exit $?" >>"$out/ci.txt"
grep -h '^gl_' "$t"/ci/*/run.yaml >>"$out/ci.txt"
"$bin" check "$t/ci/shadowlab.db" --baseline tests/baselines/ci.yaml --rows 200 >>"$out/ci.txt" 2>&1
echo "check exit $?" >>"$out/ci.txt"
sqlite3 "$t/ci/shadowlab.db" "SELECT label, sum(violations) FROM cells GROUP BY label" >>"$out/ci.txt" 2>&1 || true
# 2. the studies' times (no overlay files: the sheets' font is not carried)
timed() {   # name, repeats, config, args...
  local name=$1 n=$2 cfg=$3; shift 3
  for i in $(seq "$n"); do
    rm -rf "$t/$name"
    TIMEFORMAT="$name run $i: %R s wall, %U+%S s CPU"
    { time "$bin" run "$cfg" --gl egl --no-cache -q -o "$t/$name" -D outputs.overlays=false "$@" >/dev/null ||
        echo "$name run $i failed"; } 2>>"$out/times.txt"
  done
  cp "$t/$name/$name"/costs.csv "$out/$name-costs.csv" 2>/dev/null || true
}
timed moderno-2011 3 configs/moderno-2011.yaml
timed morais-2015 2 configs/morais-2015.yaml
timed techniques 1 configs/techniques.yaml
grep -h '^gl_' "$t"/techniques/techniques/run.yaml >>"$out/times.txt" 2>/dev/null
cp "$t/techniques/techniques/figures.csv" "$out/techniques-figures.csv" 2>/dev/null || true
uptime >>"$out/times.txt"
