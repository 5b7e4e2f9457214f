#!/usr/bin/env bash
# doc::adding_a_format — doc/layout.md's "Adding a format" stays true to the
# code:
# - its ```c block that opens the emitter's file is, byte for byte,
#   tests/example_emitter/emit_tsv.c, which test_emit builds with the
#   project's flags and runs (emit::example_tsv): the doc's code compiles
#   and works;
# - its declaration and table lines have the form emit.h's and emit.c's
#   lines have, and the example is not in the shipped table;
# - every emitter file the doc's table names exists and is in sl_store.
# Usage: doc_adding_a_format.sh   (run from the source tree)
set -u
doc=doc/layout.md
src=tests/example_emitter/emit_tsv.c
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "doc::adding_a_format: $*" >&2; fail=1; }

awk -v dir="$tmp" '
  /^```/ { if (inb) { inb = 0; close(f); next }
           if ($0 == "```c") { n++; f = sprintf("%s/%02d.c", dir, n); inb = 1; printf "" > f }
           next }
  inb { print > f }' "$doc"
file=$(grep -l '^ \* emit_tsv\.c — ' "$tmp"/*.c 2>/dev/null | head -1)
if [ -z "$file" ]; then
    bad "no \`\`\`c block opening with ' * emit_tsv.c — '"
elif ! diff -u "$src" "$file" >"$tmp/diff"; then
    bad "the emitter's code in $doc differs from $src:"
    cat "$tmp/diff" >&2
fi
grep -qx 'int sl_emit_tsv(FILE \*f, const struct sl_tab \*t, const struct sl_emit_opts \*o);' "$tmp"/*.c ||
    bad "no declaration line for sl_emit_tsv"
grep -qx '    {"tsv", sl_emit_tsv},' "$tmp"/*.c || bad "no table line for sl_emit_tsv"
grep -qx 'int sl_emit_md(FILE \*f, const struct sl_tab \*t, const struct sl_emit_opts \*o);' harness/results/emit.h ||
    bad "emit.h: its declarations changed form"
grep -qx '    {"md", sl_emit_md},' harness/results/emit.c || bad "emit.c: its table lines changed form"
grep -q 'sl_emit_tsv' harness/results/emit.c harness/results/emit.h && bad "the example is in the shipped table"
for f in $(grep -o 'harness/results/emit_[a-z]*\.c' "$doc" | sort -u); do
    [ -f "$f" ] || bad "$doc names $f, which does not exist"
    grep -q "$f" CMakeLists.txt || bad "$f is not in CMakeLists.txt"
done
[ "$fail" = 0 ] && echo "doc::adding_a_format: ok"
exit "$fail"
