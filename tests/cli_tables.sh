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
#           motion.tex, two pivots' LaTeX (one transposed, 120 rows paged
#           into floats of a page each) and the plain `table --format latex`
#           (also --figures all) and --summary compile in a one-column and a
#           two-column article with booktabs alone: 0 errors, no overfull
#           box, no float taller than the page, no longtable, no
#           \resizebox/\scalebox (exit 77 without pdflatex)
#   paper   issue 47: the Moderno study (configs/moderno-2011.yaml, two
#           scenes at 64x64 and maps of 64 and 128) as a paper takes it:
#           table.tex, table-detail.tex and two pivots compile in a
#           one-column and a two-column article, 0 errors, 0 overfull boxes;
#           every \label unique (two pivots that differ only in --of, --agg
#           or --where too); no caption holds an internal id (a figure's or
#           a counter's name, "at most N values") or a label that has a
#           display name; every table's first column holds display names
#           only; an exact 0 is "0", a value under 0.01 keeps two
#           significant digits; a pivot whose entries are all 0 is a
#           sentence (exit 77 without pdflatex)
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
  [ "$(grep -c '\\begin{table\*}' "$tmp/s.tex")" -eq 4 ] && grep -q 'label nsm\\_front' "$tmp/s.tex" &&
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
  # 120 rows are floats of a page each (34 rows), not one taller than the page
  "$bin" table "$tmp/m/shadowlab.db" --rows label --cols viewpoint --figure wrong --of count --agg sum \
    --format latex >"$tmp/p1.tex" 2>"$tmp/p1.err" || fail "p1"
  grep -q 'transposed' "$tmp/p1.err" && [ "$(grep -c 'begin{table\*}' "$tmp/p1.tex")" -eq 4 ] &&
    [ "$(grep -c '(continued)}' "$tmp/p1.tex")" -eq 3 ] && [ "$(grep -c '\\label{' "$tmp/p1.tex")" -eq 1 ] ||
    fail "p1 not transposed into 4 floats of one label: $(grep -c 'begin{table' "$tmp/p1.tex")"
  "$bin" table "$db" --rows viewpoint --cols region --figure wrong_caught --of count --agg sum --format latex \
    >"$tmp/p2.tex" 2>"$tmp/p2.err" || fail "p2"
  # the plain tables (one float per cell; every figure: wider than the line, split by regions)
  "$bin" table "$db" --format latex >"$tmp/t1.tex" 2>&1 || fail "t1"
  "$bin" table "$db" --format latex --figures all >"$tmp/t2.tex" 2>&1 || fail "t2"
  "$bin" table "$db" --summary wrong,light_incorrect --format latex >"$tmp/t3.tex" 2>&1 || fail "t3"
  cp "$dir/table.tex" "$dir/table-detail.tex" "$tmp/m/motion_tex/motion.tex" "$tmp/"
  for cls in article twocolumn; do
    opt=; [ "$cls" = twocolumn ] && opt='[twocolumn]'
    cat >"$tmp/doc-$cls.tex" <<TEX
\\documentclass$opt{article}
\\usepackage{booktabs}
\\begin{document}
\\input{table.tex}
\\input{table-detail.tex}
\\input{motion.tex}
\\input{p1.tex}
\\input{p2.tex}
\\clearpage
\\input{t1.tex}
\\clearpage
\\input{t2.tex}
\\clearpage
\\input{t3.tex}
\\end{document}
TEX
    (cd "$tmp" && pdflatex -interaction=nonstopmode "doc-$cls.tex" >/dev/null 2>&1 &&
      pdflatex -interaction=nonstopmode "doc-$cls.tex" >/dev/null 2>&1)
    log=$tmp/doc-$cls.log
    [ -s "$tmp/doc-$cls.pdf" ] || { grep -A3 '^!' "$log" | head -20; fail "pdflatex ($cls)"; }
    errs=$(grep -c '^!' "$log"); over=$(grep -c 'Overfull' "$log")
    [ "$errs" -eq 0 ] || { grep -A3 '^!' "$log" | head; fail "$errs LaTeX errors ($cls)"; }
    [ "$over" -eq 0 ] || { grep -A2 'Overfull' "$log" | head; fail "$over overfull boxes ($cls)"; }
    ! grep -q 'Float too large' "$log" || fail "a float taller than the page ($cls)"
  done
  ! grep -qE 'resizebox|scalebox' "$tmp"/table.tex "$tmp"/table-detail.tex "$tmp"/motion.tex "$tmp"/p?.tex "$tmp"/t?.tex ||
    fail "a table is scaled"
  ! grep -q 'longtable' "$tmp"/table.tex "$tmp"/table-detail.tex "$tmp"/motion.tex "$tmp"/p?.tex "$tmp"/t?.tex ||
    fail "a longtable (a two-column class refuses it)"
  [ "$(grep -c '\\begin{table\*}' "$tmp/table.tex")" -le 6 ] || fail "table.tex has more than a handful of floats"
  grep -q 'nsm\\_front' "$tmp/table.tex" && grep -q 'nsm\\_snap' "$tmp/motion.tex" || fail "labels not escaped"
  echo "PASS tables::latex"
  ;;
paper)
  command -v pdflatex >/dev/null || { echo "SKIP: no pdflatex (apt-get install texlive-latex-recommended)"; exit 77; }
  # the shipped study, small: 2 scenes x 3 viewpoints x 2 maps x 10 labels
  src=$(cd "$(dirname "$0")/.." && pwd)
  "$bin" run "$src/configs/moderno-2011.yaml" -q -o "$tmp/mo" -D 'viewports=[{width: 64, height: 64}]' \
    -D 'map_sizes=[64,128]' -D 'scenes=[{scene: primitives}, {scene: bench}]' -D outputs.overlays=false \
    >"$tmp/mo.out" 2>&1 || { cat "$tmp/mo.out"; fail "moderno run"; }
  mdb=$tmp/mo/shadowlab.db
  cp "$tmp/mo/moderno-2011/table.tex" "$tmp/mo/moderno-2011/table-detail.tex" "$tmp/"
  # two pivots that differ only in --agg, one in --where: three labels
  "$bin" table "$mdb" --rows label --cols viewpoint --figure wrong --format latex >"$tmp/q1.tex" 2>/dev/null || fail "q1"
  "$bin" table "$mdb" --rows label --cols viewpoint --figure wrong --agg max --format latex >"$tmp/q2.tex" 2>/dev/null ||
    fail "q2"
  "$bin" table "$mdb" --rows label --cols viewpoint --figure wrong --where scene=bench --format latex >"$tmp/q3.tex" \
    2>/dev/null || fail "q3"
  # a pivot of zeros: the undecided pixels of the methods that decide every pixel
  "$bin" table "$mdb" --figure uncertain --where label=nsm --where label=chain --format latex >"$tmp/q4.tex" ||
    fail "q4"
  grep -q 'every entry is 0, a sentence instead of a table' "$tmp/q4.tex" && ! grep -q 'begin{table' "$tmp/q4.tex" &&
    grep -q 'is 0 for every method and shadow-map size' "$tmp/q4.tex" || fail "a table of zeros: $(cat "$tmp/q4.tex")"
  all="$tmp/table.tex $tmp/table-detail.tex $tmp/q1.tex $tmp/q2.tex $tmp/q3.tex $tmp/q4.tex"
  # every \label once
  # shellcheck disable=SC2086
  dup=$(grep -ho '\\label{[^}]*}' $all | sort | uniq -d)
  [ -z "$dup" ] || fail "labels used twice: $dup"
  # shellcheck disable=SC2086
  [ "$(grep -ho '\\label{[^}]*}' $all | wc -l)" -ge 20 ] || fail "too few labels"
  # captions and sentences: no internal id, no label that has a display
  # name (each of the study's 10 labels has one: its own `display:` or its
  # method's) once the display names are taken out; every row named by a
  # display name
  # shellcheck disable=SC2086
  python3 - "$mdb" $all <<'PY' || fail "captions or row names"
import re, sqlite3, sys
db, files = sys.argv[1], sys.argv[2:]
names = sqlite3.connect(db).execute(
    "select distinct label, display from cells where display != '' and display != label").fetchall()
assert len(names) == 10, names
tex = lambda s: s.replace("_", "\\_").replace("&", "\\&").replace("%", "\\%")
caps, rows = [], []
for f in files:
    t = open(f).read()
    caps += re.findall(r"\\caption\{(.*)\}\n", t)
    caps += re.findall(r"\\par\\noindent (.*)\\par\n", t)
    rows += [l.split(" & ")[0] for l in t.splitlines() if " & " in l and l.endswith("\\\\")
             and not l.startswith(("method &", " &", "\\"))]
assert len(caps) >= 20, len(caps)
for c in caps:
    bare = c
    for _, d in sorted(names, key=lambda n: -len(n[1])):
        bare = bare.replace(tex(d), "")
    for l, d in names:
        assert not re.search(r"(^|[^A-Za-z\\])" + re.escape(tex(l)) + r"([^A-Za-z_]|$)", bare), (l, c)
    # an internal id: a name with '_' (figures.h, softfig.h, cellcols.h), "at most N values"
    assert not re.search(r"[a-z]\\_[a-z]", c), c
    assert "at most" not in c and "ms\\_" not in c, c
displays = {tex(d) for _, d in names}
assert rows and all(r in displays or r.startswith("Scene") for r in rows if not r[0].isdigit() and
                    not r.startswith("$")), sorted(set(rows) - displays)[:5]
assert len([r for r in rows if r in displays]) >= 100, len(rows)
PY
  grep -q 'the mean over 2 scenes (primitives and bench) and 3 viewpoints (side, with and against), 6 values an entry; viewport 64\$\\times\$64; directional light; the whole image (study moderno-2011)' \
    "$tmp/table.tex" || fail "the summary's caption: $(grep -m1 caption "$tmp/table.tex")"
  # numbers: an exact 0 as 0 (the undecided pixels of NSM), never 0.00
  # shellcheck disable=SC2086
  ! grep -qE '(^| )0\.0+( |$)' $all || fail "a 0.00 in a table: $(grep -hE '(^| )0\.0+( |$)' $all | head -2)"
  grep -qE '^NSM & 0 & 0 \\\\$' "$tmp/table.tex" || fail "NSM's undecided pixels not 0: $(grep '^NSM' "$tmp/table.tex")"
  for cls in article twocolumn; do
    opt=; [ "$cls" = twocolumn ] && opt='[twocolumn]'
    cat >"$tmp/paper-$cls.tex" <<TEX
\\documentclass$opt{article}
\\usepackage{booktabs}
\\begin{document}
A paper's text.
\\input{table.tex}
\\input{q1.tex}
\\input{q2.tex}
\\input{q3.tex}
\\input{q4.tex}
\\clearpage
\\input{table-detail.tex}
\\end{document}
TEX
    (cd "$tmp" && pdflatex -interaction=nonstopmode "paper-$cls.tex" >/dev/null 2>&1 &&
      pdflatex -interaction=nonstopmode "paper-$cls.tex" >/dev/null 2>&1)
    log=$tmp/paper-$cls.log
    [ -s "$tmp/paper-$cls.pdf" ] || { grep -A3 '^!' "$log" | head -20; fail "pdflatex ($cls)"; }
    errs=$(grep -c '^!' "$log"); over=$(grep -c 'Overfull' "$log")
    [ "$errs" -eq 0 ] || { grep -A3 '^!' "$log" | head; fail "$errs LaTeX errors ($cls)"; }
    [ "$over" -eq 0 ] || { grep -A2 'Overfull' "$log" | head; fail "$over overfull boxes ($cls)"; }
    ! grep -qE 'Float too large|multiply defined' "$log" || fail "a float too large or a label twice ($cls)"
  done
  echo "PASS tables::paper"
  ;;
*) fail "unknown case $case_" ;;
esac
