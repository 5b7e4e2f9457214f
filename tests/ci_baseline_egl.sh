#!/usr/bin/env bash
# ci::baseline_egl — the CI experiment through the EGL backend (on this
# machine Mesa's software device or surfaceless, llvmpipe) against the same
# committed baseline as ci::baseline, which was measured through OSMesa:
# counts must agree exactly on the same machine. Skips (77) only when this
# build has no EGL backend.
set -u
bin=${1:?usage: ci_baseline_egl.sh path/to/shadowlab BACKENDS}
backends=${2:-}
case ";$backends;" in *";egl;"*) ;; *) echo "EGL backend not built (backends: $backends)"; exit 77 ;; esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Leak-checked under LeakSanitizer like every run: glegl.c keeps Mesa's EGL
# vendor library mapped (RTLD_NODELETE), so what it holds for the life of the
# process stays reachable instead of showing as an unknown module.
"$bin" run configs/ci.yaml --gl egl --out "$tmp" --no-cache >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; exit 1; }
# the run says which backend and EGL device it used
grep -m1 '^gl_backend: egl ' "$tmp"/*/run.yaml || { echo "run.yaml lacks 'gl_backend: egl ...'"; exit 1; }
"$bin" check "$tmp/shadowlab.db" --baseline tests/baselines/ci.yaml --rows 60
