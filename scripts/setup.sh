#!/usr/bin/env bash
# scripts/setup.sh — one command from a fresh Debian 12 machine to results.
#
#   scripts/setup.sh run [CONFIG]   install, build, run an experiment (default: configs/default.yaml)
#   scripts/setup.sh test           install, build, run the whole test suite through ctest
#   scripts/setup.sh build          install and build only
#
# Installs only the Debian packages that are missing (as root, or through
# sudo): `run` and `build` what building and running shadowlab needs (every
# verb, report's plots included), `test` that and the tools only the tests
# and CI use (cmocka, the sqlite3 shell, Chromium, TeX Live, Slurm and munge,
# clang). `run` and `build` configure with -DSL_TESTS=OFF.
# Other distributions: the same packages by name and the plain cmake
# commands, doc/guide.md#installing.
set -euo pipefail
cd "$(dirname "$0")/.."

# What building and running shadowlab needs, by name.
RUN_PACKAGES=(
  build-essential cmake pkg-config git
  libosmesa6-dev        # OpenGL 4.5 core without a window (llvmpipe)
  libegl-dev            # EGL (libglvnd): the GL context on GPU machines and where OSMesa is gone
  libegl-mesa0          # Mesa's EGL vendor (llvmpipe, surfaceless or the software device)
  libembree-dev         # ray tracing: the ground truth
  glslang-dev           # technique packages' shaders compiled at validate, without GL (harness/render/techcheck.h)
  libopenimageio-dev    # images (overlays)
  fonts-dejavu-core     # the overlays' legend text (drawn without text when missing)
  libopenexr-dev        # OpenImageIO's CMake package asks for OpenEXR
  openimageio-tools     # ... and checks that its tools (iconvert, ...) exist
  libdeflate-dev        # the overlay sheets' PNG compressor (harness/base/image_sheet.cpp)
  libfreetype-dev       # the overlay sheets' glyphs, without OpenImageIO (harness/base/image_sheet.cpp)
  zlib1g-dev            # the store's cell digests (CRC-32); overlay::png_chunks reads the sheets' PNG
  libunistring-dev      # LaTeX text: UTF-8 decoding and Unicode decomposition (harness/results/emit_tex.c)
  libcglm-dev           # vector math
  libcyaml-dev libyaml-dev  # configs
  libassimp-dev         # model files
  assimp-testmodels     # third-party models the model scenes (configs/models.yaml) and tests load
  libsqlite3-dev        # results store
  gnuplot-nox           # the report's plots (shadowlab report)
)
# What only the tests and CI add.
TEST_PACKAGES=(
  libcmocka-dev         # the unit tests (CMake asks for it only when SL_TESTS is on)
  sqlite3               # the store from the shell (tests: cli::hostile, cli::report)
  chromium              # the report's rendering test (cli::report)
  texlive-latex-recommended lmodern  # pdflatex, booktabs, fonts: report --latex compiles (cli::report)
  slurm-wlm munge       # the Slurm job-array test (slurm::array); `shadowlab submit` needs only sbatch
  clang                 # the libFuzzer entries (-DSL_FUZZ=ON, fuzz/; CI's fuzz step) ...
  libclang-rt-14-dev    # ... whose libFuzzer and sanitizer runtimes clang only recommends
  python3-numpy         # grade::example: the independent renderer of examples/ (doc/grade.md)
)

mode=${1:-run}
case $mode in
  run|build) PACKAGES=("${RUN_PACKAGES[@]}") ;;
  test)      PACKAGES=("${RUN_PACKAGES[@]}" "${TEST_PACKAGES[@]}") ;;
  *)         echo "usage: scripts/setup.sh run [CONFIG] | test | build" >&2; exit 2 ;;
esac

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
# the tests are built for `test` only: `run` and `build` need no cmocka
tests=OFF
[ "$mode" = test ] && tests=ON
# SL_CMAKE_ARGS: extra configure flags (CI passes -DSL_WERROR=ON)
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSL_TESTS=$tests ${SL_CMAKE_ARGS:-} >/dev/null
cmake --build build -j "$jobs"

case $mode in
  run)   shift || true; exec build/shadowlab run "${1:-configs/default.yaml}" ;;
  # the tests run $jobs at a time, one per core: OpenMP's idle threads wait
  # passively, so one test's spinning workers do not take another's core
  test)  cd build && OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} exec ctest --output-on-failure -j "$jobs" ;;
  build) ;;
esac
