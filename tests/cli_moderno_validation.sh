#!/usr/bin/env bash
# cli::moderno_validation — the report's validation of the Bench scenes
# against Moderno 2011 (report/fidelity.c, sl_report_fidelity_scenes; issue
# 48). Two studies, each run and then `report`ed: scripts/
# calibration_validation.py's own (CONFIG_MODERNO: the nine views at
# 1024x1024 with the 2048² map, NSM and the chain with the rest lit; 3 s),
# and three of its views (trees/side, bench/with, flowers/with: one per
# scene, each a case of Table 15), whose report names the other six as not
# measured. On the page, read back from report.md: every row of the
# appendix's table, its summary line (median, within 2x, dominant kind) and
# Table 15 with its order line equal what the script counts from the same
# store (its moderno_views, moderno_summary and table15_cases, which write
# scenes/CALIBRATION.md's table). Numbers are recomputed, never expected:
# the scenes may change.
set -u
bin=${1:?usage: cli_moderno_validation.sh path/to/shadowlab}
command -v python3 >/dev/null || { echo "SKIP python3 is not installed"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 -c 'import sys; sys.path.insert(0, "scripts"); import calibration_validation as cv
sys.stdout.write(cv.CONFIG_MODERNO)' >"$tmp/all.yaml" || { echo "FAIL scripts/calibration_validation.py"; exit 1; }
cat >"$tmp/three.yaml" <<'YAML'
name: three
scenes:
  - {scene: trees, viewpoints: [side]}
  - {scene: bench, viewpoints: [with]}
  - {scene: flowers, viewpoints: [with]}
viewports: [{width: 1024, height: 1024}]
map_sizes: [2048]
contours: [2, 6]
methods:
  - {label: nsm, method: nsm, self_shadow: front_faces}
  - {label: chain_lit, method: chain, finish: lit}
outputs: {tables: false, overlays: false}
repetitions: {warmup: 0, runs: 1}
YAML
for study in all three; do
echo "== $study"
"$bin" run "$tmp/$study.yaml" --out "$tmp/$study" --no-cache -q >"$tmp/run.out" 2>&1 ||
  { cat "$tmp/run.out"; echo "FAIL run $study"; exit 1; }
db="$tmp/$study/shadowlab.db"
"$bin" report "$db" -o "$tmp/rep-$study" >"$tmp/rep.out" 2>&1 || { cat "$tmp/rep.out"; echo "FAIL report $study"; exit 1; }
python3 - "$tmp/rep-$study/report.md" "$db" "$study" <<'PY' || exit 1
import re, sqlite3, sys
sys.path.insert(0, 'scripts')
import calibration_validation as cv
md = open(sys.argv[1], encoding='utf-8').read()
db = sqlite3.connect(sys.argv[2])
fo = {r: cv.figs(db, r) for r in ('image', '2px', '6px')}
fails = passes = 0
def check(cond, what):
    global fails, passes
    if cond:
        passes += 1
    else:
        fails += 1
        print('FAIL', what)
def table(title):
    i = md.find('**' + title + '**')
    if i < 0:
        return None
    rows = []
    for line in md[i:].split('\n')[1:]:
        if line.startswith('|'):
            rows.append([x.strip() for x in line.strip('|').split('|')])
        elif rows:
            break
    return rows[2:]   # header and rule
def unmd(s):
    return s.replace('\\', '')
# the appendix's views
views = cv.moderno_views(fo)
nviews = {'all': 9, 'three': 3}[sys.argv[3]]
check(len(views) == nviews, 'the script counts %d views of the store, not %d' % (len(views), nviews))
t = table("Bench, Trees and Flowers, 1024×1024, 2048² map: NSM (label nsm) against Moderno 2011's appendix")
check(t is not None, 'no appendix table in the report')
t = t or []
check(len(t) == len(views), 'the report has %d views, the script %d' % (len(t), len(views)))
for r, (s, v, oc2, tc2, onw, tnw, ko, (oli, osi), kt, (tli, tsi)) in zip(t, views):
    want = ['%s / %s' % (s, v), str(oc2), str(tc2), '%.2f' % (oc2 / tc2), str(onw), str(tnw), '%.2f' % (onw / tnw),
            '%s (%d / %d)' % (ko, oli, osi), '%s (%d / %d)' % (kt, tli, tsi)]
    got = [unmd(x) for x in r[:1] + r[2:]]
    check(got == want, '%s / %s: report %s, script %s' % (s, v, got, want))
    print('%-16s report %s' % ('%s / %s' % (s, v), ' | '.join(got)))
med, within, nr, match, nv = cv.moderno_summary(views)
m = re.search(r"Moderno 2011's appendix, 2048² map: ratios median ([\d.]+), (\d+) of (\d+) within 2×; dominant kind "
              r"as the thesis in (\d+) of (\d+) views\.(?: Not measured \(.*?\): ([^\n]*)\.)?\n", md)
check(m is not None, 'no summary line for the appendix')
if m:
    got = (m.group(1), int(m.group(2)), int(m.group(3)), int(m.group(4)), int(m.group(5)))
    want = ('%.2f' % med, within, nr, match, nv)
    check(got == want, 'summary: report %s, script %s' % (got, want))
    print('summary          report %s, script %s' % (got, want))
    ran = {'%s / %s' % (w[0], w[1]) for w in views}
    rest = sorted('%s / %s' % k for k in cv.appendix(2048) if '%s / %s' % k not in ran)
    named = sorted(m.group(6).split(', ')) if m.group(6) else []
    check(named == rest, 'not measured: %s, expected %s' % (named, rest))
# Table 15
cases = cv.table15_cases(fo)
check(len(cases) == 3 and all(c[4] is not None for c in cases), 'the script measures not every case of Table 15')
t = table("Moderno 2011 Table 15 (2048² map): the chain with the uncertain pixels left lit (label chain\\_lit), "
          "wrong % of the contour's pixels")
check(t is not None, 'no Table 15 in the report')
t = t or []
check(len(t) == len(cases), 'Table 15: the report has %d cases, the script %d' % (len(t), len(cases)))
for r, (case, s, v, px, pct, tv) in zip(t, cases):
    want = [case, '%s / %s' % (s, v), '%d px' % px, '%.2f' % pct, '%.2f' % tv]
    check(r == want, 'Table 15 %s: report %s, script %s' % (case, r, want))
    print('Table 15 %-7s report %s' % (case, ' | '.join(r)))
got = [c[4] for c in cases]
want = 'Table 15\'s order best \\< average \\< worst: %s (%s).' % (
    'as the thesis' if got[0] < got[1] < got[2] else 'not as the thesis', ' / '.join('%.2f' % x for x in got))
check(want in md, 'no order line %r' % want)
print('%d passed, %d failed' % (passes, fails))
sys.exit(1 if fails else 0)
PY
done
