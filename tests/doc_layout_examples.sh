#!/usr/bin/env bash
# doc::layout_examples — the "Adding things" examples of doc/layout.md
# compile: each ```c block there opens with a comment naming a file of the
# tree and the line it goes after,
#   /* into FILE after: LINE */
# and the test puts the block's other lines after that line (LINE must be
# in FILE exactly once; a macro line's trailing blanks and backslash aside) in a copy of FILE beside copies of the blocks'
# other files, then compiles every changed .c file with the flags the
# build gives it (compile_commands.json). So "a new setting is one line and
# its field" or "a new parameter is one line" stays true of the code.
# Usage: doc_layout_examples.sh BUILD_DIR   (run from the source tree)
set -u
build=${1:?usage: doc_layout_examples.sh BUILD_DIR}
doc=doc/layout.md
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "doc::layout_examples: $*" >&2; fail=1; }
[ -f "$build/compile_commands.json" ] || { bad "no $build/compile_commands.json (configure the build again)"; exit 1; }
# every ```c block of the "Adding things" section: tmp/blocks/N
mkdir -p "$tmp/blocks" "$tmp/src"
awk -v dir="$tmp/blocks" '
  /^## / { on = ($0 ~ /^## Adding things/) }
  on && /^```/ { if (inb) { inb = 0; close(f); next }
                 if ($0 == "```c") { n++; f = sprintf("%s/%02d", dir, n); inb = 1; printf "" > f }
                 next }
  inb { print > f }' "$doc"
n=$(ls "$tmp/blocks" | wc -l)
[ "$n" -ge 3 ] || bad "$n example blocks in $doc's 'Adding things', want at least 3"
changed=()
for b in "$tmp"/blocks/*; do
  head=$(head -n 1 "$b")
  file=$(echo "$head" | sed -nE 's|^/\* into ([^ ]+) after: (.*) \*/$|\1|p')
  after=$(echo "$head" | sed -nE 's|^/\* into ([^ ]+) after: (.*) \*/$|\2|p')
  if [ -z "$file" ] || [ -z "$after" ]; then bad "block $(basename "$b"): no '/* into FILE after: LINE */' first line"; continue; fi
  [ -f "$file" ] || { bad "block $(basename "$b"): no file $file"; continue; }
  copy="$tmp/src/$file"
  mkdir -p "$(dirname "$copy")"
  [ -f "$copy" ] || cp "$file" "$copy"
  # LINE as written, a macro line's trailing blanks and backslash aside
  hits=$(awk -v line="$after" '{ s = $0; sub(/[ \t]*\\?$/, "", s) } s == line { n++ } END { print n + 0 }' "$copy")
  [ "$hits" = 1 ] || { bad "$file: the line '$after' is there $hits times, want once"; continue; }
  tail -n +2 "$b" > "$tmp/ins"
  awk -v line="$after" -v ins="$tmp/ins" '{ print; s = $0; sub(/[ \t]*\\?$/, "", s) }
       s == line { while ((getline l < ins) > 0) print l; close(ins) }' "$copy" > "$copy.new" && mv "$copy.new" "$copy"
  changed+=("$file")
done
# compile each changed .c (a changed header: the .c files beside it that the blocks name)
for f in $(printf '%s\n' "${changed[@]}" | sort -u); do
  case "$f" in *.c) ;; *) continue ;; esac
  cmd=$(python3 - "$build/compile_commands.json" "$PWD/$f" "$tmp/src/$f" "$tmp/obj.o" <<'PY'
import json, shlex, sys
db, src, copy, obj = sys.argv[1:5]
for e in json.load(open(db)):
    if e["file"] == src:
        args = shlex.split(e["command"])
        out = []
        skip = False
        for a in args:
            if skip: skip = False; out.append(obj); continue
            if a == "-o": skip = True; out.append(a); continue
            out.append(copy if a == src else a)
        # the copy's own folder first: its changed headers are found before the tree's
        import os
        out.insert(1, "-I" + os.path.dirname(copy))
        print(shlex.join(out)); break
PY
)
  [ -n "$cmd" ] || { bad "$f: not in compile_commands.json"; continue; }
  if (cd "$build" && eval "$cmd") >"$tmp/log" 2>&1; then
    echo "ok $f with the example compiles"
  else
    bad "$f with the example does not compile:"; cat "$tmp/log" >&2
  fi
done
[ "$fail" = 0 ] && echo "doc::layout_examples: ok ($n blocks)"
exit "$fail"
