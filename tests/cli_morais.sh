#!/usr/bin/env bash
# cli::morais — Morais 2015's tables from a real run (issue 38): two of his
# cases (Against-Flowers, Side-Trees) at his 512x512 viewport and a 512²
# map, his methods and Hertel's, then `report --latex`. On the page, read
# back from report.md: every method's light + shadow (his base) is the
# case's PFL and its percentages add to 100; a conservative method's
# uncertain split adds up to the traced pixels the store holds (sqlite3)
# and its correct/incorrect rows to PFL; his printed row follows ours; the
# Hertel table's traced count is the store's. report.tex compiles without
# an overfull box. Numbers are read, never expected: the scenes may change.
set -u
bin=${1:?usage: cli_morais.sh path/to/shadowlab}
command -v sqlite3 >/dev/null || { echo "SKIP sqlite3 is not installed"; exit 77; }
command -v python3 >/dev/null || { echo "SKIP python3 is not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/m.yaml" <<'YAML'
name: m
scenes:
  - {scene: flowers, viewpoints: [against]}
  - {scene: trees, viewpoints: [side]}
viewports: [{width: 512, height: 512}]
map_sizes: [512]
contours: [2]
methods:
  - {label: nsm, method: nsm, self_shadow: front_faces}
  - {label: bgsm, method: bgsm}
  - {label: csm, method: csm}
  - {label: csm_adj, method: csm_adj}
  - {label: hertel, method: hertel}
repetitions: {warmup: 0, runs: 1}
YAML
"$bin" run "$tmp/m.yaml" --out "$tmp/res" --no-cache >"$tmp/run.out" 2>&1 || { cat "$tmp/run.out"; echo "FAIL run"; exit 1; }
db="$tmp/res/shadowlab.db"
"$bin" report "$db" -o "$tmp/rep" --latex >"$tmp/rep.out" 2>&1 || { cat "$tmp/rep.out"; echo "FAIL report"; exit 1; }
# the store's traced pixels per (scene, label), whole image
sqlite3 -separator ' ' "$db" "SELECT scene, label, count FROM figures WHERE region = 'image' AND figure = 'traced'" \
  >"$tmp/traced.txt"
python3 - "$tmp/rep/report.md" "$tmp/traced.txt" <<'PY' || exit 1
import re, sys
md = open(sys.argv[1], encoding='utf-8').read()
traced = {}
for line in open(sys.argv[2]):
    scene, label, n = line.split()
    traced[(scene, label)] = int(n)
fails = passes = 0
def check(cond, what):
    global fails, passes
    if cond:
        passes += 1
    else:
        fails += 1
        print('FAIL', what)
cases = {'Against-Flowers': ('flowers', 5, 8), 'Side-Trees': ('trees', 4, 7)}
# the pages his List of Tables prints (report/theses/morais-2015.csv)
page = {4: 46, 5: 47, 7: 50, 8: 51, 10: 55, 11: 57, 19: 73, 20: 74, 22: 79, 23: 80}
cell = re.compile(r'^(\d+) \(([\d.]+)%\)')
def table(title):
    i = md.find('**' + title + '**')
    if i < 0:
        return None
    rows, key = [], None
    for line in md[i:].split('\n')[1:]:
        if line.startswith('|'):
            f = [x.strip() for x in line.strip('|').split('|')]
            rows.append(f)
        elif rows:
            break
    return rows[2:]   # header and rule
for name, (scene, truth_t, first) in cases.items():
    prefix = name + (' (worst case)' if scene == 'flowers' else ' (best case)')
    t = table(prefix + ": the truth's pixels (Morais 2015 Table %d, p. %d)" % (truth_t, page[truth_t]))
    check(t is not None, prefix + ': no Table %d' % truth_t)
    if t is None:
        continue
    pfl = int(cell.match(t[0][2]).group(1))
    check(t[0][0] == 'PFL' and t[0][1] == 'ours' and t[1][1] == 'thesis', prefix + ': truth rows')
    for label, off, csm in (('nsm', 0, 0), ('bgsm', 3, 0), ('csm', 12, 1), ('csm_adj', 15, 1)):
        num = first + off
        t = table(re.sub(r'\s+', ' ', '%s: %s (label %s), Morais 2015 Table %d, p. %d' % (
            prefix, {'nsm': 'NSM', 'bgsm': 'BGSM', 'csm': 'CSMa (CSM without adjacency)',
                     'csm_adj': 'CSMA (CSM with adjacency)'}[label], label.replace('_', '\\_'), num, page[num])))
        check(t is not None, '%s: no Table %d' % (prefix, num))
        if t is None:
            continue
        ours = {}
        kind = None
        for r in t:
            if r[1]:
                kind = r[1]
            if r[2] == 'ours':
                m = cell.match(r[3])
                ours[kind] = (int(m.group(1)), float(m.group(2)))
            check(r[2] in ('ours', 'thesis'), 'Table %d: row source %r' % (num, r[2]))
        # his row under each of ours, at his viewport and map
        check(len(t) == 12 and all(t[k][2] == 'thesis' and cell.match(t[k][3]) for k in range(1, 12, 2)),
              'Table %d: a thesis row under each of ours' % num)
        lc, li = ours['Light – Correct'][0], ours['Light – Incorrect'][0]
        sc, si = ours['Shadow – Correct'][0], ours['Shadow – Incorrect'][0]
        check(lc + li + sc + si == pfl, 'Table %d: correct + incorrect = PFL (%d)' % (num, pfl))
        check(abs(ours['Light – Correct'][1] + ours['Light – Incorrect'][1] - 100.0) <= 0.011 or lc + li == 0,
              'Table %d: light correct + incorrect = 100%%' % num)
        if not csm:
            (l, lp), (s, sp) = ours['Pixels in Light'], ours['Pixels in Shadow']
            check(l + s == pfl, 'Table %d: light %d + shadow %d = PFL %d (PnFL left out)' % (num, l, s, pfl))
            check(abs(lp + sp - 100.0) <= 0.011, 'Table %d: light %% + shadow %% = 100' % num)
            check(l == lc + li and s == sc + si, 'Table %d: light and shadow split into correct/incorrect' % num)
        else:
            lu, su = ours['Light – Uncertain'][0], ours['Shadow – Uncertain'][0]
            check(lu + su == traced[(scene, label)],
                  'Table %d: uncertain %d + %d = traced %d (store)' % (num, lu, su, traced[(scene, label)]))
            check(li == 0 and si == 0, 'Table %d: %s is exact' % (num, label))
    t = table(prefix + ": Hertel 2009's classification, as published (hertel) and exact (hertel\\_exact)")
    check(t is not None and int(cell.match(t[0][2]).group(1)) == traced[(scene, 'hertel')],
          prefix + ": Hertel's traced pixels are the store's")
check('**Hertel 2009 Table 2: ' in md, 'no Hertel 2009 Table 2')
print('%d passed, %d failed' % (passes, fails))
sys.exit(1 if fails else 0)
PY
# the Bench scenes' validation paragraph (report/fidelity.c, issue 48): its
# count, median and share within 2x recomputed here from the store and the
# thesis's file, Tables 7-24's Incorrect and Uncertain counts of >= 100 px
python3 - "$tmp/rep/report.md" "$db" report/theses/morais-2015.csv <<'PY' || exit 1
import csv, re, sqlite3, statistics, sys
md = open(sys.argv[1], encoding='utf-8').read()
f = {}
for s, v, m, lab, fig, n in sqlite3.connect(sys.argv[2]).execute(
        "SELECT scene, viewpoint, map_size, label, figure, count FROM figures WHERE region = 'image'"):
    f.setdefault((s, v, m, lab), {})[fig] = n
rs, rb = [], []
BOUNDARY = {('nsm', 'light_incorrect'), ('nsm', 'shadow_incorrect'), ('bgsm', 'shadow_incorrect'),
            ('csm', 'light_uncertain'), ('csm_adj', 'light_uncertain')}
for r in csv.DictReader(ln for ln in open(sys.argv[3], encoding='utf-8') if not ln.startswith('#')):
    row = r['row']
    if not (7 <= int(r['table']) <= 24 and r['width'] == '512' and r['height'] == '512' and int(r['count']) >= 100
            and row in ('light_incorrect', 'shadow_incorrect', 'light_uncertain', 'shadow_uncertain')):
        continue
    g = f.get((r['scene'], r['viewpoint'], int(r['map_size']), r['method']))
    if g is None:
        continue
    o = g.get(row, 0) if row.endswith('incorrect') else g.get('traced_shadow', 0) if row == 'shadow_uncertain' \
        else g.get('traced', 0) - g.get('traced_shadow', 0)
    rs.append(o / int(r['count']))
    if (r['method'], row) in BOUNDARY:
        rb.append(rs[-1])
m = re.search(r'at 512×512, (\d+) of Morais 2015.s Tables 7-24 .*?median ([\d.]+), (\d+)% within 2×', md, re.S)
if not m or not rs:
    sys.exit('FAIL the validation paragraph is missing (%d counts expected)' % len(rs))
want = (len(rs), '%.2f' % statistics.median(rs), '%.0f' % (100.0 * sum(0.5 <= x <= 2 for x in rs) / len(rs)))
got = (int(m.group(1)), m.group(2), m.group(3))
print('validation paragraph: %s, recomputed %s' % (got, want))
mb = re.search(r'Of them, the (\d+) counts set by the shadow boundary .*?median ([\d.]+), (\d+)% within 2×', md, re.S)
wantb = (len(rb), '%.2f' % statistics.median(rb), '%.0f' % (100.0 * sum(0.5 <= x <= 2 for x in rb) / len(rb))) \
    if rb else None
gotb = (int(mb.group(1)), mb.group(2), mb.group(3)) if mb else None
print('boundary counts: %s, recomputed %s' % (gotb, wantb))
sys.exit(0 if got == want and gotb == wantb and rb else 1)
PY
# in the HTML every thesis row is set back (grey), no row of ours is
python3 - "$tmp/rep/report.html" <<'PY' || { echo "FAIL thesis rows not set back in the HTML"; exit 1; }
import re, sys
rows = re.findall(r'<tr( class="[^"]*")?>(.*?)</tr>', open(sys.argv[1]).read(), re.S)
src = [('muted' in (c or ''), re.findall(r'<td class="k">(thesis|ours)</td>', r)) for c, r in rows]
src = [(m, s[0]) for m, s in src if s]
bad = [s for m, s in src if m != (s == 'thesis')]
print('%d ours/thesis rows, %d muted, %d wrong' % (len(src), sum(m for m, s in src), len(bad)))
sys.exit(1 if bad or sum(m for m, s in src) < 50 else 0)
PY
if command -v pdflatex >/dev/null; then
  (cd "$tmp/rep" && for pass in 1 2; do pdflatex -interaction=nonstopmode -halt-on-error report.tex >/dev/null 2>&1 || exit 1; done) ||
    { grep -A3 '^!' "$tmp/rep/report.log" | head; echo "FAIL pdflatex report.tex"; exit 1; }
  if grep -q 'Overfull \\hbox' "$tmp/rep/report.log"; then grep -A2 'Overfull' "$tmp/rep/report.log" | head; echo "FAIL Overfull hbox"; exit 1; fi
  echo "report.tex: compiled, nothing overfull"
else
  echo "pdflatex not installed: report.tex not compiled"
fi
