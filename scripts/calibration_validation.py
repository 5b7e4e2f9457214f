#!/usr/bin/env python3
"""calibration_validation.py -- the validation table of scenes/CALIBRATION.md
(issue 48, item 3): the scenes' figures that the calibration never fitted,
ours beside the theses'.

  scripts/calibration_validation.py [--build build] table
      run the validation study on the current scenes and print the table
  scripts/calibration_validation.py [--build build] check CALIBRATION.md
      the same, compared with the table between the file's markers; exit 1
      if they differ (the test scene::calibration_validation)
  scripts/calibration_validation.py [--build build] write CALIBRATION.md
      the same, written between the markers

The validation set (CALIBRATION.md, "the split"):
- Morais 2015, Tables 7-24 (report/theses/morais-2015.csv), the three cases
  at 512x512, 1024x1024 and 1920x1080 with maps 512^2 to 4096^2: every
  Light/Shadow - Incorrect and Light/Shadow - Uncertain count the thesis
  prints as at least 100 pixels, ours / thesis; counted as report/morais.c
  counts them (the whole image; uncertain = the pixels a label traced,
  split by the truth).
- Moderno 2011's appendix with the 2048^2 map (report/theses/
  moderno-2011-scenes.csv), nine views at 1024x1024: NSM's 2 px contour and
  wrong pixels, ours / thesis, and its dominant error kind (said lit but
  shadowed in truth, or said shadowed but lit).
- Moderno 2011's Table 15 (2048^2; report/theses/moderno-2011-table15.csv):
  the chain with the rest left lit, wrong % of the contour's pixels, in the
  thesis's best case (Trees/side, 6 px), average (Bench/with, 2 px) and
  worst (Flowers/with, 2 px); the thesis's order best < average < worst.
The report's fidelity section prints the same figures for any study that
has their cells (report/fidelity.c); moderno_views and table15_cases below
are the counting that cli::moderno_validation checks it against.
The runs are deterministic (counts do not depend on threads or machine), so
the table is the scenes' and can be checked.
"""
import argparse
import csv
import os
import sqlite3
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..")
BEGIN, END = "<!-- validation:begin -->", "<!-- validation:end -->"
CASES = [("trees", "side"), ("flowers", "against"), ("bench", "against")]
BOUNDARY = (("nsm", "light_incorrect"), ("nsm", "shadow_incorrect"), ("bgsm", "shadow_incorrect"),
            ("csm", "light_uncertain"), ("csm_adj", "light_uncertain"))
VIEWPORTS = ("512x512", "1024x1024", "1920x1080")
ROWS = ("light_incorrect", "shadow_incorrect", "light_uncertain", "shadow_uncertain")
THESES = os.path.join(ROOT, "report", "theses")

CONFIG_MORAIS = """name: validation-morais
scenes: [{scene: trees, viewpoints: [side]}, {scene: flowers, viewpoints: [against]},
         {scene: bench, viewpoints: [against]}]
viewports: [{width: 512, height: 512}, {width: 1024, height: 1024}, {width: 1920, height: 1080}]
map_sizes: [512, 1024, 2048, 4096]
methods:
  - {label: nsm, method: nsm, self_shadow: front_faces}
  - {label: bgsm, method: bgsm}
  - {label: sgsm, method: sgsm}
  - {label: sgsm_adj, method: sgsm_adj}
  - {label: csm, method: csm}
  - {label: csm_adj, method: csm_adj}
outputs: {tables: false, overlays: false}
repetitions: {warmup: 0, runs: 1}
"""
CONFIG_MODERNO = """name: validation-moderno
scenes: [{scene: bench}, {scene: trees}, {scene: flowers}]
viewports: [{width: 1024, height: 1024}]
map_sizes: [2048]
contours: [2, 4, 6]
methods:
  - {label: nsm, method: nsm, self_shadow: front_faces}
  - {label: chain_lit, method: chain, finish: lit}
outputs: {tables: false, overlays: false}
repetitions: {warmup: 0, runs: 1}
"""


def thesis_rows():
    out = []
    with open(os.path.join(THESES, "morais-2015.csv")) as f:
        for r in csv.DictReader(ln for ln in f if not ln.startswith("#")):
            if 7 <= int(r["table"]) <= 24 and r["row"] in ROWS and int(r["count"]) >= 100:
                out.append((int(r["table"]), r["scene"], r["viewpoint"], int(r["map_size"]), r["method"],
                            r["row"], int(r["count"]), f'{r["width"]}x{r["height"]}'))
    return out


def appendix(map_size):
    out = {}
    with open(os.path.join(THESES, "moderno-2011-scenes.csv")) as f:
        for r in csv.DictReader(ln for ln in f if not ln.startswith("#")):
            if int(r["map_size"]) == map_size:
                out[(r["scene"], r["viewpoint"])] = {k: int(v) for k, v in r.items()
                                                     if k.startswith(("c2", "img"))}
    return out


def table15(map_size):
    """Table 15's cases at one map size: [(case, scene, view, contour, label, thesis %)], as in the file"""
    with open(os.path.join(THESES, "moderno-2011-table15.csv")) as f:
        return [(r["case"], r["scene"], r["viewpoint"], int(r["contour"]), r["label"], float(r["percent"]))
                for r in csv.DictReader(ln for ln in f if not ln.startswith("#")) if int(r["map_size"]) == map_size]


def run(binary, text, d, name):
    with open(f"{d}/{name}.yaml", "w") as f:
        f.write(text)
    r = subprocess.run([binary, "run", f"{d}/{name}.yaml", "-o", f"{d}/{name}", "--no-cache", "-q"],
                       capture_output=True, text=True)
    if r.returncode:
        sys.exit(f"shadowlab run failed:\n{r.stdout}{r.stderr}")
    return sqlite3.connect(f"{d}/{name}/shadowlab.db")


def figs(db, region="image", viewport=None):
    """{(scene, view, map, label): {figure: count}} in one region (and one
    viewport, "WxH"; None: the store's only one)"""
    out = {}
    q = "SELECT scene, viewpoint, map_size, label, figure, count FROM figures WHERE region = ?"
    args = (region,)
    if viewport:
        q, args = q + " AND viewport = ?", (region, viewport)
    for s, v, m, lab, fig, n in db.execute(q, args):
        out.setdefault((s, v, m, lab), {})[fig] = n
    return out


def ours_morais(f, row):
    if row == "light_incorrect":
        return f.get("light_incorrect", 0)
    if row == "shadow_incorrect":
        return f.get("shadow_incorrect", 0)
    if row == "shadow_uncertain":
        return f.get("traced_shadow", 0)
    return f.get("traced", 0) - f.get("traced_shadow", 0)


def fmt_ratio(x):
    return f"{x:.2f}"


def moderno_views(fo, map_size=2048):
    """The appendix's views at map_size that the study's NSM cell (label nsm,
    1024x1024) measures, sorted: (scene, view, ours c2, thesis c2, ours wrong,
    thesis wrong, ours kind, ours lit / shadow wrong, thesis kind, its lit /
    shadow wrong); fo = {region: figs(db, region)}"""
    out = []
    for (s, v), t in sorted(appendix(map_size).items()):
        im, c2 = fo["image"].get((s, v, map_size, "nsm")), fo["2px"].get((s, v, map_size, "nsm"))
        if im is None or c2 is None:
            continue
        li, si = im.get("light_incorrect", 0), im.get("shadow_incorrect", 0)
        ko = "lit" if li >= si else "shadow"
        kt = "lit" if t["img_lit_wrong"] >= t["img_shadow_wrong"] else "shadow"
        out.append((s, v, c2["pixels"], t["c2_lit"] + t["c2_shadow"], li + si,
                    t["img_lit_wrong"] + t["img_shadow_wrong"], ko, (li, si), kt,
                    (t["img_lit_wrong"], t["img_shadow_wrong"])))
    return out


def moderno_summary(views):
    """(median of the ratios, within 2x, ratios, kind as the thesis, views)"""
    rs = [x for w in views for x in (w[2] / w[3], w[4] / w[5])]
    return (statistics.median(rs), sum(0.5 <= x <= 2 for x in rs), len(rs),
            sum(w[6] == w[8] for w in views), len(views))


def table15_cases(fo, map_size=2048):
    """Table 15's cases: (case, scene, view, contour, ours % or None, thesis %)"""
    out = []
    for case, s, v, px, label, tv in table15(map_size):
        f = fo.get(f"{px}px", {}).get((s, v, map_size, label))
        pct = None if not f or not f.get("pixels") else \
            100.0 * (f.get("light_incorrect", 0) + f.get("shadow_incorrect", 0)) / f["pixels"]
        out.append((case, s, v, px, pct, tv))
    return out


def table(binary):
    with tempfile.TemporaryDirectory() as d:
        dbm = run(binary, CONFIG_MORAIS, d, "m")
        fm = {vp: figs(dbm, "image", vp) for vp in VIEWPORTS}
        dbm.close()
        dbo = run(binary, CONFIG_MODERNO, d, "o")
        fo = {r: figs(dbo, r) for r in ("image", "2px", "4px", "6px")}
        dbo.close()
    L = []
    # ---- Morais Tables 7-24
    ratios, by, byvp = [], {}, {}
    for t, s, v, m, meth, row, n, vp in thesis_rows():
        x = ours_morais(fm[vp][(s, v, m, meth)], row) / n
        ratios.append(x)
        by.setdefault((meth, row), []).append(x)
        byvp.setdefault(vp, []).append(x)

    def summary(xs):
        return (f"{len(xs)} counts of at least 100 pixels; ours / thesis median "
                f"**{statistics.median(xs):.2f}**, **{100.0 * sum(0.5 <= x <= 2 for x in xs) / len(xs):.0f}%** "
                f"within 2x")
    L.append(f"Morais 2015, Tables 7-24, the three cases at 512x512, 1024x1024 and 1920x1080, maps 512²-4096²: "
             f"{summary(ratios)} (target: median in [0.67, 1.5], 75% within 2x). By viewport: "
             + "; ".join(f"{vp}: {summary(byvp[vp])}" for vp in VIEWPORTS if vp in byvp) + ".")
    L.append("")
    # the counts set by the shadow boundary and the map alone (NSM's errors,
    # BGSM's wrongly shadowed, CSM's lit-side uncertain band), apart from
    # those set by the conservative maps' construction: the shrunk map's
    # tears and band (SGSM's wrongly lit = CSM's shadow-side uncertain, with
    # and without adjacency) and the thesis's conservative maps' own errors,
    # which exact conservative maps do not make (0 here)
    bound = [x for (meth, row), xs in by.items() for x in xs
             if (meth, row) in BOUNDARY]
    L.append(f"Of them, the counts set by the shadow boundary and the map alone ({', '.join(f'{m} {r}' for m, r in BOUNDARY)}): "
             f"{summary(bound)}; the rest are the conservative maps' (the shrunk map's uncertain band and the "
             f"thesis's non-conservative errors).")
    L.append("")
    L.append("| method | row | counts | median ours / thesis | within 2x | min | max |")
    L.append("|---|---|---:|---:|---:|---:|---:|")
    for (meth, row), xs in sorted(by.items()):
        L.append(f"| {meth} | {row} | {len(xs)} | {statistics.median(xs):.2f} | "
                 f"{sum(0.5 <= x <= 2 for x in xs)} | {min(xs):.2f} | {max(xs):.2f} |")
    L.append("")
    # ---- Moderno's appendix, 2048^2
    L.append("Moderno 2011's appendix, 1024x1024, 2048² map, NSM (front faces culled): ours / thesis, and the "
             "dominant error kind (lit: said lit, shadowed in truth; shadow: said shadowed, lit in truth).")
    L.append("")
    L.append("| view | 2 px contour ours | thesis | ratio | NSM wrong ours | thesis | ratio | kind ours | thesis |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---|---|")
    views = moderno_views(fo)
    for s, v, oc2, tc2, onw, tnw, ko, (oli, osi), kt, (tli, tsi) in views:
        L.append(f"| {s} / {v} | {oc2} | {tc2} | {oc2 / tc2:.2f} | {onw} | {tnw} | {onw / tnw:.2f} | {ko} "
                 f"({oli} / {osi}) | {kt} ({tli} / {tsi}) |")
    med, within, nr, match, nv = moderno_summary(views)
    L.append("")
    L.append(f"Ratios: median {med:.2f}, {within} of {nr} within 2x; dominant kind as the thesis in "
             f"**{match} of {nv}** views.")
    L.append("")
    # ---- Table 15
    L.append("Moderno 2011, Table 15 (2048² map): the chain with the uncertain pixels left lit, wrong % of the "
             "contour's pixels.")
    L.append("")
    L.append("| case | view | contour | ours % | thesis % |")
    L.append("|---|---|---|---:|---:|")
    got = []
    for case, s, v, px, pct, tv in table15_cases(fo):
        got.append(pct)
        L.append(f"| {case} | {s} / {v} | {px} px | {pct:.2f} | {tv:.2f} |")
    order = got[0] < got[1] < got[2]
    L.append("")
    L.append(f"Order best < average < worst: {'as the thesis' if order else 'not as the thesis'} "
             f"({got[0]:.2f} / {got[1]:.2f} / {got[2]:.2f}).")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("what", choices=["table", "check", "write"])
    ap.add_argument("file", nargs="?")
    a = ap.parse_args()
    binary = os.path.abspath(a.build if a.build.endswith("shadowlab") else os.path.join(a.build, "shadowlab"))
    t = table(binary)
    if a.what == "table":
        sys.stdout.write(t)
        return
    if not a.file:
        sys.exit("check and write need the file (scenes/CALIBRATION.md)")
    with open(a.file) as f:
        doc = f.read()
    i, j = doc.find(BEGIN), doc.find(END)
    if i < 0 or j < i:
        sys.exit(f"{a.file}: no '{BEGIN}' ... '{END}' markers")
    have = doc[i + len(BEGIN):j].strip("\n") + "\n"
    if a.what == "check":
        if have == t:
            print(f"{a.file}: the validation table is what the current scenes give")
            return
        sys.stdout.write(f"{a.file}: the validation table differs from the current scenes'\n--- in the file\n"
                         f"{have}--- measured\n{t}")
        sys.exit(1)
    with open(a.file, "w") as f:
        f.write(doc[:i + len(BEGIN)] + "\n" + t + doc[j:])
    print(f"{a.file}: validation table written")


if __name__ == "__main__":
    main()
