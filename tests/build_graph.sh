#!/usr/bin/env bash
# build::graph BUILD — the build refuses an arrow that runs against the
# flow: the report's objects compile with the store's read API in reach
# (graph_report_allowed) and fail, each for its missing header, when they
# include one of the scene, the renderer, the truth or the methods.
set -u
build=${1:?usage: build_graph.sh BUILD}
fail=0
out=$(cmake --build "$build" --target graph_report_allowed 2>&1) ||
  { echo "$out" | tail -5; echo "FAIL the report cannot include the store's read API"; fail=1; }
for h in view truth scene method lightframe; do
  if out=$(cmake --build "$build" --target graph_report_$h 2>&1); then
    echo "FAIL the report compiles with #include \"$h.h\" in reach"; fail=1
  elif ! echo "$out" | grep -q "$h\.h: No such file"; then
    echo "$out" | tail -5; echo "FAIL graph_report_$h failed, but not for want of $h.h"; fail=1
  else
    echo "ok: $h.h is out of the report's reach"
  fi
done
exit $fail
