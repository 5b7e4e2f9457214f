#!/usr/bin/env bash
# cli::report — `shadowlab report` end to end: run a tiny study of both
# theses' methods (with the chain, overlays on), write the report, render
# report.html with headless Chromium and check the screenshot is not blank
# (OpenImageIO stats), that every file the HTML and the Markdown reference
# exists, that each table has its .tex, that the page needs no network; then
# the refusals: missing, empty, foreign and cell-less databases, no gnuplot,
# a damaged or missing thesis data file, and a failing gnuplot, which must
# leave the earlier report untouched.
# Also: every anchor resolves and the contents reach the views
# (report_anchors.py), plots kept as .dat/.gp/.pdf, --self-contained refers
# to nothing outside itself and renders alone, --latex compiles with
# pdflatex without an overfull box, table --figures and the terminal's rows.
# Skips (77) only when Chromium is not installed.
set -u
bin=${1:?usage: cli_report.sh path/to/shadowlab}
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
  echo "SKIP chromium is not installed (Debian: apt-get install chromium)"; exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0; passes=0
ok()   { passes=$((passes + 1)); }
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
refuse() {  # refuse WHAT EXPECTED_TEXT command...
  local what=$1 text=$2; shift 2
  "$@" >"$tmp/r.out" 2>"$tmp/r.err"; local rc=$?
  if [ "$rc" -ne 2 ]; then fail "$what: exit $rc, wanted 2"; return; fi
  [ "$(wc -l <"$tmp/r.err")" -eq 1 ] || { fail "$what: not one line:"; cat "$tmp/r.err"; return; }
  grep -q -i -- "$text" "$tmp/r.err" && ok || { fail "$what: message lacks '$text':"; cat "$tmp/r.err"; }
}

cat >"$tmp/mini.yaml" <<'YAML'
name: mini
scenes:
  - {scene: primitives, viewpoints: [side, with]}
  - {scene: curtis_box, viewpoints: [above]}
viewports: [{width: 96, height: 96}]
map_sizes: [256, 512]
contours: [2, 4]
methods:
  - {label: nsm, method: nsm, self_shadow: front_faces}
  - {label: coherence4, method: coherence, texels: 4}
  - {label: chain, method: chain, finish: trace}
  - {label: chain_lit, method: chain, finish: lit}
  - {label: csm_adj, method: csm_adj}
  - {label: raytrace, method: raytrace}
  - {label: point, method: hard_point}
  - {label: mc, method: soft_mc, grid: 2}
outputs: {tables: true, overlays: true, overlay_contour: 2}
repetitions: {warmup: 0, runs: 2}
area_samples: 4
YAML
"$bin" run "$tmp/mini.yaml" --out "$tmp/res" --no-cache >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; echo "FAIL run"; exit 1; }
db="$tmp/res/shadowlab.db"
# one overlay recorded but gone: listed on the page, not an error
gone=$(ls "$tmp"/res/mini/overlays/*.png | head -1)
rm -f "$gone"

# ---- the report, in the default folder ----
if "$bin" report "$db" >"$tmp/report.out" 2>&1; then ok; else cat "$tmp/report.out"; fail "report exited $?"; fi
rep="$tmp/res/report"
html="$rep/report.html"; md="$rep/report.md"
[ -s "$html" ] && [ -s "$md" ] && ok || fail "report.html or report.md missing"
# the area-light scene's cells get Curtis's table, with both soft labels
grep -q "soft shadows (area lights), Curtis 2009" "$md" && grep -q "^| mc | 256² | " "$md" &&
  grep -q "^| point | 256² | " "$md" && ok || fail "no soft-shadow table for the area-light cells"
grep -q "$(basename "$gone")" "$html" && ok || fail "the missing overlay is not listed"
# the thesis studies keep their sections (issue 37 item 3: they appear where the theses' own methods ran)
# a section with nothing to show is left out (issue 47): at 96 x 96 no
# datum of Moderno's 1024 x 1024 tables is measured, so no fidelity section
if grep -q "fidelity to Moderno 2011" "$md" || grep -q "not measured |" "$md"; then fail "a fidelity section of nothing measured"; else ok; fi
for want in "### mini: tables in Moderno 2011's layout" \
            "### mini: tables in Morais 2015's layout" "### mini: the chain's steps per scene" \
            "Thesis sections, from the methods that ran: Moderno 2011's tables, Morais 2015's tables, Curtis 2009's"; do
  grep -q -F "$want" "$md" && ok || fail "the thesis study lost '$want'"
done
ls -a "$rep" | grep -q staging && fail "a staging folder was left" || ok

# every local reference exists (HTML src/href, Markdown links and images)
refs=$(grep -o -E '(src|href)="[^"#][^"]*"' "$html" | sed -E 's/^(src|href)="//; s/"$//' | sort -u)
n=0
for r in $refs; do
  n=$((n + 1))
  case "$r" in *://*) fail "external reference $r"; continue ;; esac
  [ -s "$rep/$r" ] || fail "report.html references $r, which is not there"
done
[ "$n" -ge 40 ] && ok || fail "only $n references in report.html"
for r in $(grep -o -E '\]\([^)#][^)]*\)' "$md" | sed -E 's/^\]\(//; s/\)$//' | sort -u); do
  [ -s "$rep/$r" ] || fail "report.md references $r, which is not there"
done
grep -q 'plots/mini-chain-primitives.svg' "$html" && ok || fail "no chain plot"
grep -q 'plots/mini-accuracy-time.svg' "$html" && grep -q 'plots/mini-accuracy-rays.svg' "$html" && ok || fail "no accuracy plots"
grep -q 'overlays/mini/' "$html" && ok || fail "no overlay shown"
# issue 47: the wrong pixels against the map size on a log2 axis, one line a
# method named by its display name, and their spread across the 3 views as
# box plots with n; text at least 8.5 pt printed (a 900 px SVG at 15 px,
# shrunk to A4's 703 px line: 8.8 pt; the PDF at 9 pt), legends beside the data
grep -q 'plots/mini-maps.svg' "$html" && grep -q 'plots/mini-spread.svg' "$html" && ok || fail "no maps or spread plot"
grep -q '^set logscale x 2$' "$rep/plots/mini-maps.gp" && grep -q "title 'NSM'" "$rep/plots/mini-maps.gp" &&
  grep -q "'256²' 256, '512²' 512" "$rep/plots/mini-maps.gp" && ok || fail "maps plot: not log2 or no display names"
[ "$(grep -c 'with boxplot' "$rep/plots/mini-spread.gp")" -ge 5 ] && grep -q "'NSM (n = 3)' 1" "$rep/plots/mini-spread.gp" &&
  ok || fail "spread plot: no box per method with its n"
for gp in "$rep"/plots/mini-maps.gp "$rep"/plots/mini-accuracy-time.gp; do
  grep -q "font 'sans,15'" "$gp" && grep -q "pdfcairo .* font 'sans,9'" "$gp" && grep -q 'set key at screen 0.58' "$gp" &&
    grep -q 'set rmargin at screen 0.56' "$gp" && ok || fail "$gp: fonts under 8.5 pt printed, or the key on the data"
done
# one LaTeX file per table
ntab=$(grep -c -E '<table[ >]' "$html"); ntex=$(grep -o 'href="tex/[^"]*"' "$html" | sort -u | wc -l)
[ "$ntab" -gt 10 ] && [ "$ntab" -eq "$ntex" ] && ok || fail "$ntab tables but $ntex .tex links"
grep -q '\\toprule' "$rep"/tex/mini-costs.tex && ok || fail "tex is not booktabs"
# offline: no loaded scripts (the gallery's filter is inline), no stylesheet links, no remote fonts
grep -q -i -E '<script[^>]* src=|<link |@import|url\(|https?://' "$html" && fail "the page reaches outside itself" || ok
# every plot kept as data + script beside its SVG, and a PDF where gnuplot has pdfcairo
pdf=0; gnuplot -e 'set terminal pdfcairo' </dev/null >/dev/null 2>&1 && pdf=1
for svg in "$rep"/plots/*.svg; do
  b=${svg%.svg}
  [ -s "$b.dat" ] && [ -s "$b.gp" ] && ok || fail "$svg has no .dat/.gp beside it"
  [ "$pdf" -eq 0 ] || [ -s "$b.pdf" ] && ok || fail "$svg has no .pdf beside it"
done
# the kept script redraws its plot by itself
(cd "$rep/plots" && gnuplot -e "out='svg'" mini-accuracy-time.gp) >/dev/null 2>&1 && ok || fail "mini-accuracy-time.gp does not redraw"
# the two-panel accuracy plot counts the undecided pixels, and the page says how
grep -q 'undecided pixels' "$rep/plots/mini-accuracy-time.gp" && grep -q 'Pareto front (wrong + undecided)' \
  "$rep/plots/mini-accuracy-time.gp" && ok || fail "accuracy plot without its undecided panel"
# every anchor resolves, the contents reach the views
python3 "$(dirname "$0")/report_anchors.py" "$html" && ok || fail "anchors of report.html"
# the summary comes first: the first plot precedes the first thesis table
first_plot=$(grep -n -m1 'plots/mini-accuracy-time.svg' "$html" | cut -d: -f1)
first_thesis=$(grep -n -m1 'Moderno 2011 Table 5' "$html" | cut -d: -f1)
[ -n "$first_plot" ] && [ -n "$first_thesis" ] && [ "$first_plot" -lt "$first_thesis" ] && ok ||
  fail "the plots do not come before the tables"
for want in 'Moderno 2011 Table 5' 'Moderno 2011 Tables 17/18' 'Moderno 2011 Table 23' 'as in Morais 2015 Tables 7-24' \
            'as in Morais 2015 Tables 25-30' 'Pareto front' 'carry the comparison to a GPU' 'Run 1: config' 'llvmpipe'; do
  grep -q "$want" "$html" && ok || fail "no '$want' in the page"
done

# ---- headless Chromium renders it ----
shot="$tmp/shot.png"
timeout 120 "$chromium" --headless=new --no-sandbox --disable-gpu --hide-scrollbars \
  --user-data-dir="$tmp/chrome" --screenshot="$shot" --window-size=1280,2000 "file://$html" >"$tmp/chrome.out" 2>&1
if [ -s "$shot" ]; then ok; else cat "$tmp/chrome.out"; fail "chromium wrote no screenshot"; fi
stats=$( (oiiotool --stats "$shot" || iinfo --stats "$shot") 2>/dev/null)
sd=$(echo "$stats" | sed -n 's/.*StdDev: *//p' | head -1 | tr ' ' '\n' | grep -E '^[0-9.]+$' | sort -g | tail -1)
if [ -n "$sd" ] && awk -v s="$sd" 'BEGIN { exit !(s > 5.0) }'; then ok; else echo "$stats"; fail "blank screenshot (stddev ${sd:-?})"; fi
echo "$stats" | grep -q 'Constant: Yes' && fail "screenshot is one colour" || ok

# ---- --self-contained: one file, nothing outside it ----
"$bin" report "$db" --out "$tmp/one" --self-contained >/dev/null 2>&1 && [ -s "$tmp/one/report.html" ] && ok ||
  fail "report --self-contained"
python3 "$(dirname "$0")/report_anchors.py" "$tmp/one/report.html" --self-contained && ok || fail "self-contained page"
grep -q -i -E '<script[^>]* src=|<link |@import|url\(' "$tmp/one/report.html" && fail "self-contained page loads something" || ok
# moved alone, it still shows its images: copy it where nothing is beside it
mkdir -p "$tmp/alone" && cp "$tmp/one/report.html" "$tmp/alone/" || fail "copy"
timeout 120 "$chromium" --headless=new --no-sandbox --disable-gpu --hide-scrollbars \
  --user-data-dir="$tmp/chrome2" --screenshot="$tmp/one.png" --window-size=1280,2000 "file://$tmp/alone/report.html" \
  >"$tmp/chrome2.out" 2>&1
st1=$( (oiiotool --stats "$tmp/one.png" || iinfo --stats "$tmp/one.png") 2>/dev/null)
sd1=$(echo "$st1" | sed -n 's/.*StdDev: *//p' | head -1 | tr ' ' '\n' | grep -E '^[0-9.]+$' | sort -g | tail -1)
if [ -n "$sd1" ] && awk -v s="$sd1" 'BEGIN { exit !(s > 5.0) }'; then ok; else fail "blank self-contained screenshot (stddev ${sd1:-?})"; fi

# ---- --latex: report.tex compiles with pdflatex, nothing overfull ----
"$bin" report "$db" --out "$tmp/tex" --latex >/dev/null 2>&1 && [ -s "$tmp/tex/report.tex" ] && ok || fail "report --latex"
if command -v pdflatex >/dev/null; then
  (cd "$tmp/tex" && for pass in 1 2; do pdflatex -interaction=nonstopmode -halt-on-error report.tex >/dev/null 2>&1 || exit 1; done) &&
    [ -s "$tmp/tex/report.pdf" ] && ok || { grep -A3 '^!' "$tmp/tex/report.log" | head; fail "pdflatex report.tex"; }
  grep -q 'Overfull \\hbox' "$tmp/tex/report.log" && { grep -A2 'Overfull' "$tmp/tex/report.log" | head; fail "Overfull hbox"; } || ok
  ! grep -q 'Float too large' "$tmp/tex/report.log" && ok || fail "a report table taller than the page"
  # fitted, never scaled: a wide table is stacked, wrapped or split
  ! grep -lE 'resizebox|scalebox' "$tmp/tex/report.tex" "$tmp"/tex/tex/*.tex && ok || fail "a report table is scaled"
  grep -q 'includegraphics.*plots/mini-accuracy-time.pdf' "$tmp/tex/report.tex" && ok || fail "report.tex lacks the plots"
else
  fail "pdflatex is not installed (Debian: apt-get install texlive-latex-recommended; scripts/setup.sh does)"
fi

# ---- tables: LaTeX without a heading, --figures, the terminal's produced rows ----
"$bin" table "$db" --format latex --label nsm >"$tmp/t.tex" 2>&1 && ! grep -q '\\section' "$tmp/t.tex" && ok ||
  fail "table --format latex writes a heading"
"$bin" table "$db" --format latex --label nsm --figures wrong,light_incorrect >"$tmp/f.tex" 2>&1 &&
  [ "$(grep -c -E '^(wrong|light\\_incorrect) & ' "$tmp/f.tex")" -eq "$(grep -c '^\\begin{tabular}' "$tmp/f.tex" | awk '{print 2*$1}')" ] &&
  ! grep -q '^pixels & ' "$tmp/f.tex" && ok || fail "table --figures"
refuse "unknown figure" "'bogus'" "$bin" table "$db" --figures wrong,bogus
"$bin" table "$db" --label nsm >"$tmp/t.md" 2>&1
grep -q '^| hinted |' "$tmp/t.md" && fail "the terminal's nsm table prints hinted (0, not produced)" || ok
grep -q '^| hinted |' "$tmp/res/mini/table.md" && ok || fail "table.md lost the rows nsm does not produce"
grep -q '^| wrong |' "$tmp/t.md" && ok || fail "the terminal's table lost wrong"

# ---- --out elsewhere ----
"$bin" report "$db" --out "$tmp/elsewhere" >/dev/null 2>&1 && [ -s "$tmp/elsewhere/report.html" ] && ok ||
  fail "report --out"

# ---- refusals: exit 2, one line naming the problem, nothing written ----
refuse "missing db" "no such results store" "$bin" report "$tmp/nope.db" --out "$tmp/x1"
: >"$tmp/empty.db"
refuse "empty file" "empty file" "$bin" report "$tmp/empty.db" --out "$tmp/x2"
echo "not a database" >"$tmp/text.db"
refuse "foreign file" "text.db" "$bin" report "$tmp/text.db" --out "$tmp/x3"
# an empty store: the schema of a real one, no rows (readers open read-only
# and no longer initialise a store)
{ sqlite3 "$db" .schema | grep -v '^CREATE TABLE sqlite_'
  echo "PRAGMA user_version = $(sqlite3 "$db" 'PRAGMA user_version');"; } | sqlite3 "$tmp/store.db"
refuse "store without cells" "no cells" "$bin" report "$tmp/store.db" --out "$tmp/x4"
refuse "no gnuplot" "gnuplot" env PATH=/nonexistent "$bin" report "$db" --out "$tmp/x5"
# a damaged or missing thesis data file (report/theses.h; SHADOWLAB_THESES in
# front of the source tree's report/theses/): the file, line and column named
mkdir -p "$tmp/theses"
cp report/theses/*.csv "$tmp/theses/"
ln=$(grep -n -m1 '^16,,side,1024,2,nsm,pixels,11000,$' "$tmp/theses/moderno-2011.csv" | cut -d: -f1)
sed -i "${ln}s/,11000,/,11x00,/" "$tmp/theses/moderno-2011.csv"
refuse "damaged thesis file" "theses/moderno-2011.csv:$ln: 'value': '11x00' is not a count" \
  env SHADOWLAB_THESES="$tmp/theses" "$bin" report "$db" --out "$tmp/x6"
cp report/theses/moderno-2011.csv "$tmp/theses/"
rm "$tmp/theses/morais-2015-times.csv"
refuse "missing thesis file" "theses/morais-2015-times.csv: cannot open" \
  env SHADOWLAB_THESES="$tmp/theses" "$bin" report "$db" --out "$tmp/x7"
# these two stop once the folder is made (a section reads the file on first
# use): it is left empty, its staging folder removed
for x in x6 x7; do [ -z "$(ls -A "$tmp/$x")" ] && ok || fail "refused report $x left files in $tmp/$x"; done
for x in x1 x2 x3 x4 x5; do [ -e "$tmp/$x" ] && fail "refused report $x still wrote $tmp/$x"; done
"$bin" report >/dev/null 2>"$tmp/r.err"; rc=$?
[ "$rc" -eq 2 ] && head -1 "$tmp/r.err" | grep -q "missing RESULTS_DB" && ok || fail "usage: exit $rc"

# a gnuplot that fails: error, and the report already there is untouched
mkdir -p "$tmp/fakebin"
printf '#!/bin/sh\ncat >/dev/null\necho "line 1: fake error" >&2\nexit 1\n' >"$tmp/fakebin/gnuplot"
chmod +x "$tmp/fakebin/gnuplot"
before=$(cd "$rep" && find . -type f | sort | xargs md5sum)
refuse "failing gnuplot" "gnuplot failed" env PATH="$tmp/fakebin:$PATH" "$bin" report "$db"
after=$(cd "$rep" && find . -type f | sort | xargs md5sum)
[ "$before" = "$after" ] && ok || fail "a failed report changed the earlier one"

echo "$passes passed, $fails failed"
[ "$fails" -eq 0 ]
