#!/usr/bin/env bash
# doc::adding_a_method — doc/adding-a-method.md stays true to the code:
# - its ```c block that opens the method's file is, byte for byte,
#   tests/example_method/pcf3.c, which test_example_method builds with the
#   project's flags and runs (example_method::*): the doc's code compiles
#   and works;
# - its registry lines have the form registry.c's lines have (an extern
#   declaration and a table entry), and the parameter its config uses is
#   one the method declares;
# - the fast-path rules it cites are named in method.h.
# Usage: doc_adding_a_method.sh   (run from the source tree)
set -u
doc=doc/adding-a-method.md
src=tests/example_method/pcf3.c
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "doc::adding_a_method: $*" >&2; fail=1; }

# every ```c block of the doc: tmp/N.c
awk -v dir="$tmp" '
  /^```/ { if (inb) { inb = 0; close(f); next }
           if ($0 == "```c") { n++; f = sprintf("%s/%02d.c", dir, n); inb = 1; printf "" > f }
           else skip = !skip
           next }
  inb { print > f }' "$doc"
file=$(grep -l '^ \* pcf3\.c — ' "$tmp"/*.c 2>/dev/null | head -1)
if [ -z "$file" ]; then
    bad "no \`\`\`c block opening with ' * pcf3.c — '"
elif ! diff -u "$src" "$file" >"$tmp/diff"; then
    bad "the method's code in $doc differs from $src:"
    cat "$tmp/diff" >&2
fi

# the registry lines, in the form registry.c uses
reg=$(grep -l 'sl_method_pcf3' "$tmp"/*.c | grep -v "$file" | head -1)
if [ -z "$reg" ]; then
    bad "no \`\`\`c block with the registry lines"
else
    grep -qx 'extern const struct sl_method sl_method_pcf3;' "$reg" || bad "no extern line for sl_method_pcf3"
    grep -qx '    &sl_method_pcf3,' "$reg" || bad "no table line for sl_method_pcf3"
    grep -qx 'extern const struct sl_method sl_method_nsm;' methods/registry.c || bad "registry.c: its extern lines changed form"
    grep -qx '    &sl_method_nsm,' methods/registry.c || bad "registry.c: its table lines changed form"
fi
grep -q 'sl_method_pcf3' methods/registry.c && bad "the example is in the shipped registry"

# the config's parameter, and the names the doc cites from method.h and frame.h
grep -q 'method: pcf3, bias: ' "$doc" || bad "no config entry 'method: pcf3, bias: ...'"
grep -q 'SL_PARAM_FLOAT_DECL("bias",' "$src" || bad "pcf3.c does not declare its parameter bias"
for name in sl_method_fast at_pixel looks look_parts sl_method_configure sl_method_param SL_METHOD_PARAMS sl_layer_at; do
    grep -q "$name" methods/method.h || bad "method.h does not name $name"
done
for name in SL_LOOK_REACH SL_GUARD_TEXELS sl_frame_pcf_lit; do
    grep -q "$name" harness/render/frame.h || bad "frame.h does not name $name"
done
[ "$fail" = 0 ] && echo "doc::adding_a_method: ok"
exit "$fail"
