#!/usr/bin/env bash
# doc::define_examples — every -D example of `shadowlab run --help`, of the
# README and of doc/guide.md's "Overrides" validates against
# configs/default.yaml (exit 0): an example a reader copies works on the
# config the project ships. Each example alone, then each source's all together.
# Usage: doc_defines.sh SHADOWLAB_BINARY   (run from the source tree)
set -u
bin=${1:?usage: doc_defines.sh path/to/shadowlab}
fail=0
# -D 'quoted' or -D word, as a shell would take it (quotes dropped)
# (a placeholder such as KEY=VALUE is no example: keys are lower case)
examples() { grep -oE -- "-D ('[a-z_][^']*'|[a-z_][^ '\`]*)" | sed -E "s/^-D '?//; s/'\$//"; }
check() {  # source, examples on stdin
  local src=$1 n=0 all=()
  while IFS= read -r kv; do
    [ -n "$kv" ] || continue
    n=$((n + 1)); all+=(-D "$kv")
    out=$("$bin" validate configs/default.yaml -D "$kv" 2>&1 >/dev/null); rc=$?
    [ "$rc" -eq 0 ] || { echo "FAIL $src: -D '$kv' exits $rc on configs/default.yaml: $out"; fail=1; }
  done
  [ "$n" -ge 2 ] || { echo "FAIL $src: $n -D example(s) found, want at least 2"; fail=1; return; }
  "$bin" validate configs/default.yaml "${all[@]}" >/dev/null 2>&1 ||
    { echo "FAIL $src: its examples together: ${all[*]}"; fail=1; }
  echo "ok $src: $n example(s)"
}
check "run --help" < <("$bin" run --help 2>&1 | examples)
check README.md < <(grep -- '-D ' README.md | examples)
# the guide's Overrides paragraph (its example wraps over lines): the span
# after "the value in YAML:", not the refused one it quotes after
check doc/guide.md < <(awk '/^\*\*Overrides\.\*\*/, /^$/' doc/guide.md | tr '\n' ' ' |
  sed -E 's/.*the value in YAML: `([^`]*)`.*/\1/; s/-D +/-D /g' | examples)
[ "$fail" -eq 0 ] && echo "PASS doc::define_examples"
exit "$fail"
