#!/usr/bin/env bash
# layout::flow — the code's rooms follow the data flow (doc/layout.md):
# every quoted #include of a stage resolves in that stage or a stage before
# it (the CMake libraries enforce it at build time; this names the file and
# the header when an arrow runs back up); only the command line (main.c and
# harness/cli/, the last room: it includes from every stage) prints to
# stderr, never a library stage. No
# line caps: a file's size is a smell, not a rule (a file is split where a
# concept ends, never to meet a count).
set -u
cd "$(dirname "$0")/.."
order=(harness/base harness/scene harness/render harness/truth methods harness/score harness/plan harness/results report harness/run harness/cluster harness/bench harness/cli harness)
fail=0
for i in "${!order[@]}"; do
  dir=${order[$i]}
  allowed=("${order[@]:0:$((i + 1))}")
  for f in "$dir"/*.[ch] "$dir"/*.cpp; do
    [ -f "$f" ] || continue
    # main.c, the program's entry, is checked below against every stage
    [ "$f" = harness/main.c ] && continue
    for h in $(grep -oE '^#include "[^"]+"' "$f" | sed 's/#include "//; s/"$//'); do
      ok=0
      for a in "${allowed[@]}"; do [ -f "$a/$h" ] && ok=1; done
      [ -f "build/$h" ] && ok=1   # generated
      if [ $ok -eq 0 ]; then echo "FAIL $f includes \"$h\", which is not in $dir or a stage before it"; fail=1; fi
    done
  done
done
# main.c, the program's entry, sits above every stage (the CLI included)
for f in harness/main.c; do
  for h in $(grep -oE '^#include "[^"]+"' "$f" | sed 's/#include "//; s/"$//'); do
    ok=0
    for a in "${order[@]}"; do [ -f "$a/$h" ] && ok=1; done
    [ -f "build/$h" ] && ok=1
    if [ $ok -eq 0 ]; then echo "FAIL $f includes \"$h\", which is in no stage"; fail=1; fi
  done
done
hits=$(grep -rln 'fprintf(stderr' harness methods report | grep -vE '^harness/(main\.c$|cli/)')
if [ -n "$hits" ]; then echo "FAIL library code prints to stderr: $hits"; fail=1; fi
c=$(find harness -maxdepth 1 -name '*.c' | sort | tr '\n' ' ')
[ $fail -eq 0 ] && echo "ok: includes follow the flow; driver files: $c"
exit $fail
