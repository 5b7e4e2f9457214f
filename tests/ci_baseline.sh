#!/usr/bin/env bash
# ci::baseline — the CI experiment (configs/ci.yaml) against its committed
# baseline (tests/baselines/ci.yaml): exit 1 when a figure moved beyond its
# tolerance or an exactness invariant broke. The table of what moved is
# printed either way. To refresh the baseline deliberately, see doc/guide.md, "Refreshing a baseline".
# Arguments after the binary go to `check`: CI's platform matrix passes
# --exact (every count exactly, under another ISA or llvmpipe width too).
set -u
bin=${1:?usage: ci_baseline.sh path/to/shadowlab [check options]}
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" run configs/ci.yaml --out "$tmp" --no-cache >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; exit 1; }
"$bin" check "$tmp/shadowlab.db" --baseline tests/baselines/ci.yaml --rows 60 "$@"
