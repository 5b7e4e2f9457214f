#!/usr/bin/env python3
"""i48_morais_tears.py -- Morais 2015's SGSM wrongly lit pixels (Tables 7-24,
512x512) with and without adjacency, ours beside the thesis's, per case and
map (issue 48, item 3: why the conservative maps' uncertain counts sit at
0.17-0.34x the thesis's). SGSM shrinks each triangle on its own and tears a
mesh along its shared edges; SGSM with adjacency keeps the shared edges
(Morais, chapter 4), so what adjacency removes is the tears' share. Last,
the shrunk band (SGSM's wrongly lit, with and without adjacency) over the
enlarged band on the same boundary (CSMa's lit-side uncertain), ours and
the thesis's: both move every edge by the same lambda (eq. 21).

  scripts/i48_morais_tears.py [--build build] OUT_DIR

Runs scripts/calibration_validation.py's Morais study into OUT_DIR.
"""
import argparse
import importlib.util
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("out")
    a = ap.parse_args()
    spec = importlib.util.spec_from_file_location("cv", os.path.join(HERE, "calibration_validation.py"))
    cv = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cv)
    os.makedirs(a.out, exist_ok=True)
    db = cv.run(os.path.abspath(os.path.join(a.build, "shadowlab")), cv.CONFIG_MORAIS, a.out, "m")
    fm = {vp: cv.figs(db, "image", vp) for vp in cv.VIEWPORTS}
    db.close()
    th = {}
    for t, s, v, m, meth, row, n, vp in cv.thesis_rows():
        if vp == "512x512" and ((row == "light_incorrect" and meth in ("sgsm", "sgsm_adj")) or
                                (row == "light_uncertain" and meth == "csm")):
            th[(s, v, m, meth)] = n
    fm = fm["512x512"]
    print("| case | map | SGSM ours | thesis | ratio | with adjacency ours | thesis | ratio "
          "| adjacency keeps, ours | thesis | shrunk / enlarged band, ours (adjacency) | thesis (adjacency) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|")
    for (s, v, m, meth) in sorted(k for k in th if k[3] == "sgsm"):
        o, t = fm[(s, v, m, "sgsm")]["light_incorrect"], th[(s, v, m, "sgsm")]
        oa, ta = fm[(s, v, m, "sgsm_adj")]["light_incorrect"], th.get((s, v, m, "sgsm_adj"))
        if ta is None:
            continue
        lo = cv.ours_morais(fm[(s, v, m, "csm")], "light_uncertain")
        lt = th.get((s, v, m, "csm"))
        band = f"{o / lo:.2f} ({oa / lo:.2f}) | {t / lt:.2f} ({ta / lt:.2f})" if lt else "- | -"
        print(f"| {s} / {v} | {m}² | {o} | {t} | {o / t:.2f} | {oa} | {ta} | {oa / ta:.2f} | "
              f"{oa / o:.2f} | {ta / t:.2f} | {band} |")


if __name__ == "__main__":
    main()
