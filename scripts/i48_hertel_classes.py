#!/usr/bin/env python3
"""i48_hertel_classes.py — where `hertel`'s wrong pixels lie, from the EXR
layers a run with outputs.exr writes (scripts/i48_measure.sh OUT hertel).

For each cell with wrong pixels it reads the hertel, hertel_exact and bgsm
EXR files of the same scene, view and map (oiiotool --dumpdata; the half
channels hold the codes) and counts the wrong pixels by: error kind (said
lit / said shadowed), how hertel decided them (map, confirm, traced),
BGSM's verdict there (lit: the map-lit rule; uncertain: a covered texel),
how hertel_exact decided them (confirm: the stored triangle is hit; traced:
another triangle), the Chebyshev distance in pixels to the nearest change
of the truth's state (lit against shadowed or PnFL), whether a PnFL pixel
(the object's own terminator: a silhouette edge seen from the light) lies
within 2 pixels, and the texel's size in pixels (the aliasing layer's m).
Usage: scripts/i48_hertel_classes.py EXR_DIR
"""
import collections
import glob
import os
import re
import subprocess
import sys

CH = ("aliasing", "contour", "error", "how", "truth", "verdict")
HOW = {0: "none", 1: "pnfl", 2: "map", 3: "hint", 4: "confirm", 5: "confirm_adj", 6: "correct", 7: "traced",
       8: "fallback"}


def layers(path):
    out = subprocess.run(["oiiotool", "--dumpdata", path], check=True, capture_output=True, text=True).stdout
    head = out.split("\n", 1)[0]
    m = re.search(r": (\d+) x (\d+), (\d+) channel", head)
    w, h = int(m.group(1)), int(m.group(2))
    names = re.search(r"channel list: (.*)", subprocess.run(["oiiotool", "--info", "-v", path], check=True,
                                                            capture_output=True, text=True).stdout).group(1)
    order = [c.split(" ")[0] for c in names.split(", ")]
    idx = {c: order.index(c) for c in CH}
    lay = {c: bytearray(w * h) for c in CH}
    for line in out.splitlines()[1:]:
        p = line.find("Pixel (")
        if p < 0:
            continue
        xy, vals = line[p + 7:].split("):")
        x, y = (int(t) for t in xy.split(","))
        v = vals.split()
        i = y * w + x
        for c in CH:
            lay[c][i] = int(float(v[idx[c]]))
    return w, h, lay


def main():
    d = sys.argv[1] if len(sys.argv) > 1 else "."
    total = collections.Counter()
    for path in sorted(glob.glob(os.path.join(d, "*-hertel.exr"))):
        base = path[:-len("-hertel.exr")]
        w, h, L = layers(path)
        wrong = [i for i in range(w * h) if L["error"][i] in (1, 2)]
        if not wrong:
            print(f"{os.path.basename(base)}: 0 wrong")
            continue
        _, _, B = layers(base + "-bgsm.exr")
        _, _, X = layers(base + "-hertel_exact.exr")
        t = L["truth"]
        c = collections.Counter()
        for i in wrong:
            x, y = i % w, i // w
            kind = "said_lit" if L["error"][i] == 1 else "said_shadowed"
            c[kind] += 1
            c["hertel_how=" + HOW[L["how"][i]]] += 1
            c["bgsm=" + {1: "lit", 2: "shadowed", 3: "uncertain"}.get(B["verdict"][i], "?")] += 1
            c["exact_how=" + HOW[X["how"][i]]] += 1
            own = 1 if t[i] == 2 else 0
            dist = 9
            pnfl = False
            for r in range(1, 9):
                for yy in range(max(0, y - r), min(h, y + r + 1)):
                    for xx in range(max(0, x - r), min(w, x + r + 1)):
                        s = t[yy * w + xx]
                        if s != 0 and (1 if s == 2 else 0) != own:
                            dist = min(dist, max(abs(xx - x), abs(yy - y)))
                        if s == 1 and max(abs(xx - x), abs(yy - y)) <= 2:
                            pnfl = True
                if dist <= r:
                    break
            c["truth_change_within=" + ("1px" if dist <= 1 else "2px" if dist <= 2 else "3-8px" if dist <= 8
                                        else ">8px")] += 1
            c["pnfl_within_2px" if pnfl else "no_pnfl_within_2px"] += 1
            m = L["aliasing"][i]
            if not m:  # the run wrote no aliasing layer (outputs.aliasing false) or m is undefined here
                c["texel_px=n/a"] += 1
            else:
                texel = 2 ** ((m - 128) / 8)
                c["texel_px=" + ("<1" if texel < 1 else "1-2" if texel < 2 else ">=2")] += 1
        print(f"{os.path.basename(base)}: {len(wrong)} wrong: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
        total.update(c)
    print("all: " + ", ".join(f"{k} {v}" for k, v in sorted(total.items())))


if __name__ == "__main__":
    main()
