#!/usr/bin/env bash
# layout::flow — the code's rooms follow the data flow (doc/layout.md):
# every quoted #include of a stage resolves in that stage or a stage before
# it (the CMake libraries enforce it at build time; this names the file and
# the header when an arrow runs back up); only main.c prints to stderr; no
# .c file over 1,000 lines and run.c at most 800.
set -u
cd "$(dirname "$0")/.."
order=(harness/base harness/scene harness/render harness/truth methods harness/score harness/results report harness)
fail=0
for i in "${!order[@]}"; do
  dir=${order[$i]}
  allowed=("${order[@]:0:$((i + 1))}")
  for f in "$dir"/*.[ch] "$dir"/*.cpp; do
    [ -f "$f" ] || continue
    for h in $(grep -oE '^#include "[^"]+"' "$f" | sed 's/#include "//; s/"$//'); do
      ok=0
      for a in "${allowed[@]}"; do [ -f "$a/$h" ] && ok=1; done
      [ -f "build/$h" ] && ok=1   # generated
      if [ $ok -eq 0 ]; then echo "FAIL $f includes \"$h\", which is not in $dir or a stage before it"; fail=1; fi
    done
  done
done
hits=$(grep -rln 'fprintf(stderr' harness methods report | grep -v '^harness/main\.c$')
if [ -n "$hits" ]; then echo "FAIL library code prints to stderr: $hits"; fail=1; fi
while read -r n f; do
  [ "$f" = total ] && continue
  if [ "$n" -gt 1000 ]; then echo "FAIL $f has $n lines (> 1000)"; fail=1; fi
done < <(find harness methods report -name '*.c' -o -name '*.cpp' | xargs wc -l)
n=$(wc -l < harness/run.c)
if [ "$n" -gt 800 ]; then echo "FAIL harness/run.c has $n lines (> 800)"; fail=1; fi
c=$(find harness -maxdepth 1 -name '*.c' | sort | tr '\n' ' ')
[ $fail -eq 0 ] && echo "ok: includes follow the flow; driver files: $c"
exit $fail
