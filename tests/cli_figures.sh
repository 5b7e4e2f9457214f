#!/usr/bin/env bash
# figures::aliasing_on_demand — issue 38: the aliasing error m is computed
# only where a study asks for it. A run of nsm alone stores no aliasing
# figure (outputs.aliasing auto: no method reads m); the same run with
# outputs.aliasing=true stores them, and its other figures are the same.
set -u
bin=${1:?usage: cli_figures.sh path/to/shadowlab}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }
cat >"$tmp/c.yaml" <<'YAML'
name: fig
scenes: [{scene: primitives, viewpoints: [side]}]
viewports: [{width: 96, height: 96}]
map_sizes: [128]
methods: [{label: nsm, method: nsm}]
outputs: {overlays: false}
YAML
"$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/a" || fail "run"
"$bin" run "$tmp/c.yaml" --no-cache -q -o "$tmp/b" -D outputs.aliasing=true || fail "run with aliasing"
# the aliasing figures (score/figrec.h, SL_ALIAS_FIGURES): px_m_*, wrong_m_*, m_*
is_m="(figure LIKE 'px\_m\_%' ESCAPE '\' OR figure LIKE 'wrong\_m\_%' ESCAPE '\' OR figure LIKE 'm\_%' ESCAPE '\')"
n() { sqlite3 "$1" "SELECT count(*) FROM figures WHERE $is_m"; }
rest() { sqlite3 "$1" "SELECT region, figure, count FROM figures WHERE NOT $is_m ORDER BY 1, 2"; }
[ "$(n "$tmp/a/shadowlab.db")" -eq 0 ] || fail "aliasing figures stored though no method reads them"
[ "$(n "$tmp/b/shadowlab.db")" -gt 0 ] || fail "outputs.aliasing=true stored no aliasing figure"
[ "$(rest "$tmp/a/shadowlab.db")" = "$(rest "$tmp/b/shadowlab.db")" ] || fail "the other figures moved"
grep -q 'aliasing: false' "$tmp/a/fig/config.yaml" || fail "config.yaml does not say aliasing: false"
echo "ok: $(n "$tmp/b/shadowlab.db") aliasing figure rows only when asked"
# figures.csv holds every figure the store holds for its cells, the
# aliasing figures included (region, figure, count the same, row for row)
for r in a b; do
    csv=$tmp/$r/fig/figures.csv
    [ -s "$csv" ] || fail "no $csv"
    want=$(sqlite3 -separator , "$tmp/$r/shadowlab.db" "SELECT region, figure, count FROM figures" | sort)
    got=$(tail -n +2 "$csv" | cut -d, -f7-9 | sort)
    [ "$want" = "$got" ] || fail "$r: figures.csv differs from the store: $(diff <(echo "$want") <(echo "$got") | head -5)"
done
grep -q ',wrong_m_' "$tmp/b/fig/figures.csv" || fail "figures.csv lacks the aliasing figures"
echo "ok: figures.csv holds the store's $(tail -n +2 "$tmp/b/fig/figures.csv" | wc -l) figure rows"
