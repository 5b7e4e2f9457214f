#!/usr/bin/env bash
# hard::threads — the hard cases give the same counts with one llvmpipe
# thread and one Embree/OpenMP thread (LP_NUM_THREADS=1, threads: 1) as with
# the defaults: `shadowlab check` of the second run against a baseline written
# from the first, counts exact (same machine). LP_NUM_THREADS is read when the
# GL context is made, hence two processes.
set -u
bin=${1:?usage: hard_threads.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
body='scenes:
  - {scene: hard/grazing_89_99}
  - {scene: hard/slivers}
  - {scene: hard/tiny}
  - {scene: hard/tjunction}
  - {scene: hard/nonmanifold}
  - {scene: hard/leaves}
viewports: [{width: 256, height: 256}]
map_sizes: [512, 2048]
methods:
  - {label: nsm, method: nsm}
  - {label: chain, method: chain}
  - {label: bgsm, method: bgsm}
  - {label: sgsm_adj, method: sgsm_adj}
  - {label: csm_adj, method: csm_adj}
  - {label: hertel, method: hertel}
outputs: {overlays: false}'
printf 'name: threads\n%s\n' "$body" >"$tmp/many.yaml"
printf 'name: threads\n%s\nthreads: 1\n' "$body" >"$tmp/one.yaml"
"$bin" run "$tmp/many.yaml" --out "$tmp/a" --no-cache >"$tmp/a.out" 2>&1 || { cat "$tmp/a.out"; exit 1; }
LP_NUM_THREADS=1 "$bin" run "$tmp/one.yaml" --out "$tmp/b" --no-cache >"$tmp/b.out" 2>&1 || { cat "$tmp/b.out"; exit 1; }
grep -q "lp_num_threads: 1$" "$tmp/b/threads/run.yaml" ||
  { echo "FAIL the second run does not record LP_NUM_THREADS=1"; cat "$tmp/b/threads/run.yaml"; exit 1; }
"$bin" check "$tmp/a/shadowlab.db" --baseline "$tmp/base.yaml" --update 2>/dev/null || exit 1
sed -i 's/^counts: .*/counts: exact/' "$tmp/base.yaml"
"$bin" check "$tmp/b/shadowlab.db" --baseline "$tmp/base.yaml" --rows 20 >"$tmp/check.out"; rc=$?
tail -3 "$tmp/check.out"
[ $rc -eq 0 ] || { cat "$tmp/check.out"; echo "FAIL counts differ between 1 and 2 threads"; exit 1; }
grep -q " 0 moved" "$tmp/check.out" || { echo "FAIL something moved"; exit 1; }
echo "hard::threads passed"
