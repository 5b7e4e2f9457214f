#!/usr/bin/env bash
# tables::* (shell) — issue 37, "Tables a paper takes": `shadowlab table
# --rows/--cols/--figure` and the run's LaTeX.
#   pivot   a tiny run; the pivot label x map_size of wrong (% of pixels) in
#           md, csv, json and latex: each entry the mean over the views that
#           awk computes from the run's figures.csv; --agg sum of counts, max;
#           --where label=a --where label=b keeps both labels; a label with
#           '_' escaped in LaTeX, thin-space thousands separators;
#           json parses; bad keys/aggregates exit 2
#   latex   the run's table.tex and table-detail.tex, a motion run's
#           motion.tex, two pivots' LaTeX (one transposed into a longtable) and
#           the plain `table --format latex` (also --figures all) and --summary
#           compile in a plain article with booktabs and longtable: 0 errors,
#           no overfull box, no float taller than the page, no
#           \resizebox/\scalebox (exit 77 without pdflatex)
set -u
bin=${1:?usage: cli_tables.sh path/to/shadowlab CASE}
case_=${2:?case}
tmp=$(mktemp -d)
trap '[ -n "${KEEP:-}" ] && echo "kept $tmp" || rm -rf "$tmp"' EXIT
fail() { echo "FAIL $*"; exit 1; }

# 2 views x 2 map sizes x 3 labels = 12 cells, seconds to run; a label as a
# user writes it, with a character LaTeX must escape
cat >"$tmp/tiny.yaml" <<'YAML'
name: tiny_tables
scenes: [{scene: primitives, viewpoints: [side, with]}]
viewports: [{width: 64, height: 64}]
map_sizes: [64, 128]
contours: [2, 4]
methods:
  - {label: nsm, method: nsm}
  - {label: nsm_front, method: nsm, self_shadow: front_faces}
  - {label: csm, method: csm}
outputs: {overlays: false}
YAML
"$bin" run "$tmp/tiny.yaml" -q -o "$tmp/r" >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; fail "run"; }
db=$tmp/r/shadowlab.db
dir=$tmp/r/tiny_tables
[ -s "$dir/figures.csv" ] && [ -s "$dir/table.tex" ] && [ -s "$dir/table-detail.tex" ] || fail "run's tables missing"

# awk over figures.csv (no field before `machine` holds a comma): the mean
# (or sum/max) of column col of figure fig in region image per label,map
ref() {  # fig col agg
  awk -F, -v fig="$1" -v col="$2" -v agg="$3" 'NR > 1 && $7 == "image" && $8 == fig {
      k = $6 "," $4; v = $col + 0; n[k]++; s[k] += v; if (!(k in m) || v > m[k]) m[k] = v }
    END { for (k in n) printf "%s,%.6f\n", k, agg == "sum" ? s[k] : agg == "max" ? m[k] : s[k] / n[k] }' \
    "$dir/figures.csv" | sort
}
# the pivot's CSV (label,64,128) as label,map,value lines
long() { awk -F, 'NR == 1 { for (i = 2; i <= NF; i++) c[i] = $i; next }
                  { for (i = 2; i <= NF; i++) if ($i != "") printf "%s,%s,%.6f\n", $1, c[i], $i }' | sort; }
same() {  # two label,map,value lists, values within tolerance
  join -t, -j1 <(awk -F, '{print $1 "|" $2 "," $3}' "$1" | sort) <(awk -F, '{print $1 "|" $2 "," $3}' "$2" | sort) |
    awk -F, -v tol="$3" -v want="$(wc -l <"$1")" '{ d = $2 - $3; if (d < 0) d = -d; if (d > tol) bad++; n++ }
      END { exit !(n == want && n > 0 && !bad) }'
}

case $case_ in
pivot)
  # mean of wrong's percentage (figures.csv keeps 4 decimals)
  "$bin" table "$db" --rows label --cols map_size --figure wrong --format csv >"$tmp/p.csv" || fail "pivot csv"
  head -1 "$tmp/p.csv" | grep -qx 'label,64,128' || fail "csv header: $(head -1 "$tmp/p.csv")"
  [ "$(wc -l <"$tmp/p.csv")" -eq 4 ] || fail "csv has $(wc -l <"$tmp/p.csv") lines, want 1 + 3 labels"
  ref wrong 10 mean >"$tmp/ref.txt"
  long <"$tmp/p.csv" >"$tmp/got.txt"
  same "$tmp/ref.txt" "$tmp/got.txt" 0.0001 || { paste -d' ' "$tmp/ref.txt" "$tmp/got.txt"; fail "pivot mean != awk mean"; }
  # sum and max of the counts: exact
  "$bin" table "$db" --figure wrong --of count --agg sum --format csv | long >"$tmp/got.txt" || fail "sum"
  ref wrong 9 sum >"$tmp/ref.txt"
  same "$tmp/ref.txt" "$tmp/got.txt" 0 || fail "pivot sum != awk sum"
  "$bin" table "$db" --figure light --of count --agg max --format csv | long >"$tmp/got.txt" || fail "max"
  ref light 9 max >"$tmp/ref.txt"
  same "$tmp/ref.txt" "$tmp/got.txt" 0 || fail "pivot max != awk max"
  # json: the same numbers, and parses
  "$bin" table "$db" --rows label --cols map_size --figure wrong --format json >"$tmp/p.json" || fail "json"
  python3 - "$tmp/p.json" "$tmp/p.csv" <<'PY' || fail "json differs from csv"
import csv, json, sys
j = json.load(open(sys.argv[1]))
rows = list(csv.reader(open(sys.argv[2])))
assert j["columns"] == rows[0][1:], (j["columns"], rows[0])
assert [r["row"] for r in j["table"]] == [r[0] for r in rows[1:]]
for r, c in zip(j["table"], rows[1:]):
    for v, w, n in zip(r["values"], c[1:], r["n"]):
        assert abs(v - float(w)) < 1e-6 and n == 2, (v, w, n)
assert j["agg"] == "mean" and j["unit"] == "% of pixels" and j["where"] == {"region": "image"}
PY
  # md: the same numbers to 2 decimals
  "$bin" table "$db" --figure wrong --format md >"$tmp/p.md" || fail "md"
  grep -q '^| label \\ map_size | 64² | 128² |$' "$tmp/p.md" || fail "md header"
  want=$(awk -F, '$1 == "csm" { printf "| csm | %.2f | %.2f |", $2, $3 }' "$tmp/p.csv")
  grep -qxF "$want" "$tmp/p.md" || fail "md row, want '$want'"
  # --where: a key given twice keeps either value
  "$bin" table "$db" --figure wrong --where label=nsm --where label=csm --format csv >"$tmp/w.csv" || fail "where"
  [ "$(cut -d, -f1 "$tmp/w.csv" | tr '\n' ' ')" = "label nsm csm " ] || fail "where: $(cat "$tmp/w.csv")"
  "$bin" table "$db" --figure wrong --where label=nsm --where map_size=64 --format csv >"$tmp/w.csv" || fail "where 2"
  [ "$(cat "$tmp/w.csv" | tr '\n' ' ')" = "label,64 $(grep '^nsm,' "$tmp/p.csv" | cut -d, -f2 | sed 's/^/nsm,/') " ] ||
    fail "where label and map: $(cat "$tmp/w.csv")"
  # region as columns: the contours and the image, image last
  "$bin" table "$db" --cols region --figure wrong_caught --format csv | head -1 | grep -qx 'label,2px,4px,image' ||
    fail "region columns"
  # LaTeX: escaped display names, thin spaces, booktabs, no scaling
  "$bin" table "$db" --figure pixels --agg sum --format latex >"$tmp/p.tex" 2>"$tmp/p.err" || fail "latex"
  grep -q '^nsm\\_front & ' "$tmp/p.tex" || fail "latex label not escaped"
  # display names: a label that is its method's name prints the method's own
  # (nsm: NSM, csm: CSMa), any other label itself; md, csv and json keep labels
  grep -q '^NSM & ' "$tmp/p.tex" && grep -q '^CSMa & ' "$tmp/p.tex" || fail "latex rows are not the display names"
  grep -q '^| csm |' "$tmp/p.md" || fail "md rows are not the labels"
  # `display:` in the config: the filled-in config keeps it (quoted), LaTeX escapes it
  "$bin" validate "$tmp/tiny.yaml" -D 'methods[1].display=Front faces & 50%' >"$tmp/v.txt" || fail "validate display"
  grep -qF '{label: nsm_front, method: nsm, display: "Front faces & 50%"' "$tmp/v.txt" || fail "display not in the filled-in config"
  "$bin" validate "$tmp/tiny.yaml" -D "methods[1].display=$(printf 'x%.0s' $(seq 60))" >/dev/null 2>"$tmp/v.err"; rc=$?
  [ $rc -eq 2 ] && grep -q 'methods\[1\]\.display' "$tmp/v.err" || fail "a too-long display: rc $rc, $(cat "$tmp/v.err")"
  "$bin" run "$tmp/tiny.yaml" -q -o "$tmp/rd" -D 'methods[1].display=Front faces & 50%' --cells 0:4 >/dev/null 2>&1 ||
    fail "run with a display"
  "$bin" table "$tmp/rd/shadowlab.db" --figure wrong --format latex | grep -q '^Front faces \\& 50\\% & ' ||
    fail "the config's display not in LaTeX: $("$bin" table "$tmp/rd/shadowlab.db" --figure wrong --format latex | grep ' & ' | head -3)"
  grep -qE ' & [0-9]{1,3}\\,[0-9]{3}' "$tmp/p.tex" || fail "no thin-space thousands separator"
  grep -q '\\toprule' "$tmp/p.tex" && ! grep -qE 'resizebox|scalebox' "$tmp/p.tex" || fail "latex not booktabs/scaled"
  [ ! -s "$tmp/p.err" ] || fail "a two-column table said: $(cat "$tmp/p.err")"
  # usage errors
  for bad in "--rows nope" "--agg mode" "--where colour=red" "--figure nope" "--rows label --cols label" \
             "--figure ms_method --of pixels" "--format json --label nsm"; do
    # shellcheck disable=SC2086
    "$bin" table "$db" $bad >/dev/null 2>&1; rc=$?
    [ "$rc" -eq 2 ] || fail "table $bad: exit $rc, want 2"
  done
  # --label a,b (or repeated) keeps those labels; --summary of several figures and labels
  "$bin" table "$db" --label nsm,csm --format csv | cut -d, -f6 | sed 1d | sort -u | tr '\n' ' ' | grep -qx 'csm nsm ' ||
    fail "--label nsm,csm"
  "$bin" table "$db" --label nsm --label csm --format csv | cut -d, -f6 | sed 1d | sort -u | tr '\n' ' ' |
    grep -qx 'csm nsm ' || fail "--label repeated"
  "$bin" table "$db" --summary wrong,light_incorrect --label nsm,nsm_front --format csv >"$tmp/s.csv" || fail "summary csv"
  [ "$(grep -c '^figure,label,' "$tmp/s.csv")" -eq 1 ] && [ "$(grep -c ',average,' "$tmp/s.csv")" -eq 4 ] &&
    grep -q '^light_incorrect,nsm_front,average,' "$tmp/s.csv" || fail "summary of 2 figures x 2 labels: $(cat "$tmp/s.csv")"
  "$bin" table "$db" --summary wrong --summary light_incorrect --label nsm,nsm_front --format latex >"$tmp/s.tex" ||
    fail "summary latex"
  [ "$(grep -c '\\begin{table}' "$tmp/s.tex")" -eq 4 ] && grep -q 'label nsm\\_front' "$tmp/s.tex" &&
    grep -q '\\toprule' "$tmp/s.tex" && ! grep -qE 'resizebox|scalebox' "$tmp/s.tex" || fail "summary latex: $(cat "$tmp/s.tex")"
  "$bin" table "$db" --summary wrong,pixels >/dev/null 2>&1; [ $? -eq 2 ] || fail "--summary of a count"
  "$bin" table "$db" --summary wrong,nope >/dev/null 2>&1; [ $? -eq 2 ] || fail "--summary of an unknown figure"
  # the existing table keeps its options
  "$bin" table "$db" --label nsm --format csv | head -1 | grep -q '^scene,viewpoint,viewport,map_size' ||
    fail "plain table changed"
  echo "PASS tables::pivot"
  ;;
latex)
  command -v pdflatex >/dev/null || { echo "SKIP: no pdflatex (apt-get install texlive-latex-recommended)"; exit 77; }
  # a short motion run: the first frames of the orbit and the sun path
  cat >"$tmp/motion.yaml" <<'YAML'
name: motion_tex
scenes: [{scene: primitives_motion, paths: [orbit, sun]}]
viewports: [{width: 64, height: 64}]
map_sizes: [128]
contours: [2]
methods:
  - {label: nsm, method: nsm}
  - {label: nsm_snap, method: nsm, light_frame: {fit: sphere, snap: true}}
outputs: {overlays: false}
YAML
  "$bin" run "$tmp/motion.yaml" -q -o "$tmp/m" >"$tmp/m.out" 2>&1 || { cat "$tmp/m.out"; fail "motion run"; }
  [ -s "$tmp/m/motion_tex/motion.tex" ] || fail "no motion.tex"
  # pivots: the motion run's 120 frames as columns do not fit: transposed, and
  # 120 rows are a longtable, not a float taller than the page
  "$bin" table "$tmp/m/shadowlab.db" --rows label --cols viewpoint --figure wrong --of count --agg sum \
    --format latex >"$tmp/p1.tex" 2>"$tmp/p1.err" || fail "p1"
  grep -q 'transposed' "$tmp/p1.err" && grep -q 'begin{longtable}' "$tmp/p1.tex" || fail "p1 not a transposed longtable"
  "$bin" table "$db" --rows viewpoint --cols region --figure wrong_caught --of count --agg sum --format latex \
    >"$tmp/p2.tex" 2>"$tmp/p2.err" || fail "p2"
  # the plain tables (one float per cell; every figure: wider than the line, split by regions)
  "$bin" table "$db" --format latex >"$tmp/t1.tex" 2>&1 || fail "t1"
  "$bin" table "$db" --format latex --figures all >"$tmp/t2.tex" 2>&1 || fail "t2"
  "$bin" table "$db" --summary wrong,light_incorrect --format latex >"$tmp/t3.tex" 2>&1 || fail "t3"
  cp "$dir/table.tex" "$dir/table-detail.tex" "$tmp/m/motion_tex/motion.tex" "$tmp/"
  cat >"$tmp/doc.tex" <<'TEX'
\documentclass{article}
\usepackage{booktabs,longtable}
\begin{document}
\input{table.tex}
\input{table-detail.tex}
\input{motion.tex}
\input{p1.tex}
\input{p2.tex}
\clearpage
\input{t1.tex}
\clearpage
\input{t2.tex}
\clearpage
\input{t3.tex}
\end{document}
TEX
  (cd "$tmp" && pdflatex -interaction=nonstopmode doc.tex >/dev/null 2>&1 && pdflatex -interaction=nonstopmode doc.tex >/dev/null 2>&1)
  [ -s "$tmp/doc.pdf" ] || { grep -A3 '^!' "$tmp/doc.log" | head -20; fail "pdflatex"; }
  errs=$(grep -c '^!' "$tmp/doc.log"); over=$(grep -c 'Overfull' "$tmp/doc.log")
  [ "$errs" -eq 0 ] || { grep -A3 '^!' "$tmp/doc.log" | head; fail "$errs LaTeX errors"; }
  [ "$over" -eq 0 ] || { grep -A2 'Overfull' "$tmp/doc.log" | head; fail "$over overfull boxes"; }
  ! grep -q 'Float too large' "$tmp/doc.log" || fail "a float taller than the page"
  ! grep -qE 'resizebox|scalebox' "$tmp"/table.tex "$tmp"/table-detail.tex "$tmp"/motion.tex "$tmp"/p?.tex "$tmp"/t?.tex ||
    fail "a table is scaled"
  grep -q 'longtable' "$tmp/table-detail.tex" && grep -q 'longtable' "$tmp/motion.tex" || fail "no longtable"
  [ "$(grep -c '\\begin{table}' "$tmp/table.tex")" -le 6 ] || fail "table.tex has more than a handful of floats"
  grep -q 'nsm\\_front' "$tmp/table.tex" && grep -q 'nsm\\_snap' "$tmp/motion.tex" || fail "labels not escaped"
  echo "PASS tables::latex"
  ;;
*) fail "unknown case $case_" ;;
esac
