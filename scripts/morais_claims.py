#!/usr/bin/env python3
"""The Morais 2015 and Hertel 2009 claims, counted in a Morais study's store.

    build/shadowlab run configs/morais-2015.yaml -o OUT
    scripts/morais_claims.py OUT/shadowlab.db

Prints, over every cell of the study (all scenes, viewpoints, viewports and
map sizes; whole image): the exactness claims (BGSM's lit pixels lit in
truth, SGSM's shadowed pixels shadowed, CSMa/CSMA exact, violations), the
adjacency claim (CSMA traces no more than CSMa, per view and map), and
Hertel's (rays traced as a share of PFL, wrong pixels, ray step against a
full trace). The closing notes of issue 38 quote these lines; the report's
Morais section shows the same counts per case, beside the thesis's.
"""
import sqlite3
import sys


def main(path):
    db = sqlite3.connect(path)

    def pct(a, b):
        return f"{100.0 * a / b:.2f}%" if b else "-"

    def fig(label, figure, where=""):
        """sum of a whole-image figure over the label's cells, and the cells"""
        q = ("SELECT coalesce(sum(f.count), 0), count(*) FROM figures f JOIN cells c USING (cell_id) "
             "WHERE f.label = ? AND f.region = 'image' AND f.figure = ? " + where)
        return db.execute(q, (label, figure)).fetchone()

    def cells(label, col, where=""):
        return db.execute(f"SELECT coalesce(sum({col}), 0), count(*) FROM cells WHERE label = ? {where}",
                          (label,)).fetchone()

    n, k = fig("bgsm", "light_incorrect")
    print(f"BGSM said lit, shadowed in truth: {n} pixels over {k} cells")
    for lab in ("sgsm", "sgsm_adj"):
        n, k = fig(lab, "shadow_incorrect")
        print(f"{lab} said shadowed, lit in truth: {n} pixels over {k} cells")
    for lab in ("csm", "csm_adj", "hertel_exact", "raytrace"):
        w, k = cells(lab, "n_wrong_image")
        v, _ = cells(lab, "violations")
        print(f"{lab}: {w} wrong pixels, {v} violations over {k} cells")
    v, k = db.execute("SELECT sum(violations), count(*) FROM cells").fetchone()
    print(f"all labels: {v} violations over {k} cells")

    rows = db.execute(
        "SELECT a.rays, b.rays FROM cells a JOIN cells b USING (scene, viewpoint, vw, vh, map_size) "
        "WHERE a.label = 'csm' AND b.label = 'csm_adj'").fetchall()
    fewer = sum(1 for a, b in rows if b < a)
    same = sum(1 for a, b in rows if b == a)
    more = sum(1 for a, b in rows if b > a)
    print(f"CSMA traces fewer rays than CSMa in {fewer} of {len(rows)} (view, viewport, map) keys, "
          f"as many in {same}, more in {more}; rays {sum(b for _, b in rows):,} against {sum(a for a, _ in rows):,}")

    def traced(label, where=""):
        """the label's traced pixels as a share of its PFL, and both counts"""
        t, k = fig(label, "traced", where)
        p, _ = fig(label, "pfl", where)
        return pct(t, p), t, p, k

    share, t, p, k = traced("hertel")
    print(f"hertel traces {share} of PFL ({t:,} of {p:,}) over {k} cells")
    for m in sorted(r[0] for r in db.execute("SELECT DISTINCT map_size FROM cells")):
        print(f"  map {m}^2: {traced('hertel', f'AND c.map_size = {int(m)}')[0]}")
    print(f"hertel_exact traces {traced('hertel_exact')[0]} of PFL")
    w, _ = cells("hertel", "n_wrong_image")
    px, _ = fig("hertel", "pixels")
    li, _ = fig("hertel", "light_incorrect")
    si, _ = fig("hertel", "shadow_incorrect")
    nw, _ = cells("nsm", "n_wrong_image")
    print(f"hertel: {w:,} wrong pixels of {px:,} ({li:,} said lit, {si:,} said shadowed); "
          f"NSM {nw:,} ({nw / max(w, 1):.0f}x)")
    hs, _ = cells("hertel", "ms_ray_step")
    rs, _ = cells("raytrace", "ms_ray_step")
    hm, _ = cells("hertel", "ms_method")
    rm, _ = cells("raytrace", "ms_method")
    print(f"ray step: hertel {hs / 1000:.1f} s, raytrace {rs / 1000:.1f} s ({pct(hs, rs)}); "
          f"per-pixel work (method ms): hertel {hm / 1000:.1f} s, raytrace {rm / 1000:.1f} s ({hm / rm if rm else 0:.2f}x)")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: morais_claims.py STORE.db")
    main(sys.argv[1])
