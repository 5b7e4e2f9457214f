#!/usr/bin/env bash
# layout::flow — the code's rooms follow the data flow (doc/layout.md):
# every quoted #include of a stage resolves in that stage or a stage before
# it (the CMake libraries enforce it at build time; this names the file and
# the header when an arrow runs back up); only the command line (main.c and
# harness/cli/, the last room: it includes from every stage) prints to
# stderr, never a library stage. The graph between files (below) has no
# cycle and at most 2 arrows against the flow, each allowed by name. No
# line caps: a file's size is a smell, not a rule (a file is split where a
# concept ends, never to meet a count).
set -u
start=$PWD
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
# ---- the file graph ----
# Nodes: every .c/.h/.cpp of a stage. Arrows: a file -> the file each quoted
# #include resolves to (its own folder first, as the compiler looks, then
# the stages); a .c -> the .c that defines a non-static function it calls.
# Calls come from nm on the build's objects (build/CMakeFiles/<lib>.dir/
# <source>.o: the source's defined T symbols against its undefined U ones),
# not from ctags or grep: nm sees what the compiler made of the code (calls
# through macros such as page.c's html_text, no static functions, nothing in
# comments or #if 0), and names each symbol's one defining object, where a
# text scan would have to guess which of two files' same-named functions a
# call means. It needs a build: without the objects the test fails rather
# than pass on includes alone.
# A header gets no arrow to its .c (a call already runs .c -> .c), so a
# folder's shared internal header (report_int.h) does not fold the folder
# into one cycle; the cycles left are real: two files that need each other.
# A cycle between files fails (its files and arrows printed), except a .c
# with its own .h (foo.c, foo.h: one module). An arrow against the flow (a
# file of an earlier stage including or calling a later stage's file) must
# be on this list ("from>to"), at most 2, each with why it is allowed (the
# include check above stays strict, so only a call can be allowed here):
#   (none: no arrow runs against the flow)
back_allowed=()
# Cycles tolerated for a while (entries: a cycle's files sorted, separated
# by ";"), each printed as PENDING on every run; an entry whose cycle is
# gone fails. None now (store.c <-> integrity.c was broken by moving
# sl_store_verify into store.c).
cycles_pending=""
export cycles_pending
build=""
for d in "$start" "$start/.." "build"; do   # ctest runs this in <build>/tests
  [ -f "$d/CMakeCache.txt" ] && { build=$d; break; }
done
if [ -z "$build" ] || [ -z "$(find "$build/CMakeFiles/" -path '*.dir/*' -name '*.o' 2>/dev/null | head -1)" ]; then
  echo "FAIL no build objects (build/CMakeFiles/*.dir/**.o) for the call graph: build first"; exit 1
fi
objs=$(mktemp)
trap 'rm -f "$objs"' EXIT
find "$build/CMakeFiles/" -path '*.dir/*' -name '*.o' | while read -r o; do
  src=${o#*.dir/}; src=${src%.o}
  [ -f "$src" ] || continue
  # an object a target no longer builds (a file moved to another library)
  # stays in a reused build folder: only those the target's build.make names
  tdir=${o%%.dir/*}.dir
  grep -qF "${o#"$tdir"/}" "$tdir/build.make" 2>/dev/null || continue
  nm --defined-only -g "$o" | awk -v s="$src" '$2 == "T" { print "T", s, $3 }'
  nm -u "$o" | awk -v s="$src" '{ print "U", s, $NF }'
done | sort -u > "$objs"
python3 - "$objs" "${#back_allowed[@]}" "${back_allowed[@]}" "${order[@]}" <<'PY' || fail=1
import os, re, sys
objs, nallow = sys.argv[1], int(sys.argv[2])
allow = set(sys.argv[3:3 + nallow])
order = sys.argv[3 + nallow:]
stage, files = {}, []
for i, d in enumerate(order):
    for f in sorted(os.listdir(d)):
        p = os.path.join(d, f)
        if os.path.isfile(p) and re.search(r'\.(c|h|cpp)$', f):
            stage[p] = i
            files.append(p)
edges = {}   # (a, b) -> why
for f in files:
    for line in open(f, errors='replace'):
        m = re.match(r'#include "([^"]+)"', line)
        if not m:
            continue
        h = m.group(1)
        for d in [os.path.dirname(f)] + order:
            p = os.path.normpath(os.path.join(d, h))
            if p in stage:
                edges.setdefault((f, p), 'includes "%s"' % h)
                break
defs, uses = {}, []
for line in open(objs):
    k, src, sym = line.split()
    if src not in stage:
        continue
    if k == 'T':
        defs[sym] = src
    else:
        uses.append((src, sym))
for src, sym in uses:
    d = defs.get(sym)
    if d and d != src:
        edges.setdefault((src, d), 'calls %s' % sym)
if not defs:
    print('FAIL nm found no function of a stage in the objects'); sys.exit(1)
out = {f: [] for f in files}
for a, b in edges:
    out[a].append(b)
# Tarjan's strongly connected components, iteratively
index, low, onstack, st, sccs, n = {}, {}, set(), [], [], 0
for root in files:
    if root in index:
        continue
    work = [(root, 0)]
    while work:
        v, i = work.pop()
        if i == 0:
            index[v] = low[v] = n; n += 1; st.append(v); onstack.add(v)
        if i < len(out[v]):
            work.append((v, i + 1))
            w = out[v][i]
            if w not in index:
                work.append((w, 0))
            elif w in onstack:
                low[v] = min(low[v], index[w])
            continue
        if low[v] == index[v]:
            c = []
            while True:
                w = st.pop(); onstack.discard(w); c.append(w)
                if w == v:
                    break
            sccs.append(sorted(c))
        if work:
            u = work[-1][0]
            low[u] = min(low[u], low[v])
pending = {p for p in os.environ.get('cycles_pending', '').split(';') if p}
bad = 0
for c in sccs:
    if len(c) < 2:
        continue
    stems = {os.path.splitext(x)[0] for x in c}
    if len(c) == 2 and len(stems) == 1:
        continue   # foo.c and its own foo.h
    if ' '.join(c) in pending:
        pending.discard(' '.join(c))
        print('PENDING cycle between files (to break in its own folder): ' + ' '.join(c))
    else:
        bad = 1
        print('FAIL cycle between files: ' + ' '.join(c))
    for (a, b), why in sorted(edges.items()):
        if a in c and b in c:
            print('  %s -> %s (%s)' % (a, b, why))
for p in sorted(pending):
    print('FAIL pending cycle no longer found, remove it from cycles_pending: ' + p); bad = 1
back = sorted((a, b, why) for (a, b), why in edges.items() if stage[a] < stage[b])
for a, b, why in back:
    ok = ('%s>%s' % (a, b)) in allow
    print('%s arrow against the flow: %s -> %s (%s)%s' % ('ok' if ok else 'FAIL', a, b, why,
          ', allowed' if ok else ', not on the allowed list'))
    bad |= not ok
if len(back) > 2 or len(allow) > 2:
    print('FAIL %d arrows against the flow (%d allowed): at most 2' % (len(back), len(allow))); bad = 1
ncalls = sum(1 for w in edges.values() if w.startswith('calls'))
print('file graph: %d files, %d arrows (%d calls), %d against the flow' % (len(files), len(edges), ncalls, len(back)))
sys.exit(bad)
PY
c=$(find harness -maxdepth 1 -name '*.c' | sort | tr '\n' ' ')
# the harness's top holds the program's entry (main.c), not a stage's code
nc=$(find harness -maxdepth 1 -name '*.c' | wc -l)
if [ "$nc" -gt 3 ]; then echo "FAIL harness/ holds $nc .c files (at most 3; a stage's code goes in its folder): $c"; fail=1; fi
[ $fail -eq 0 ] && echo "ok: includes and calls follow the flow; driver files: $c"
exit $fail
