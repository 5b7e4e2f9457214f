#!/usr/bin/python3
"""i48_kinds.py -- NSM's error kinds per mesh (issue 48, item 3: where the
excess of "said shadowed but lit" pixels lies), from the EXR layers of a run
with outputs.exr (scripts/i48_measure.sh OUT kinds): per cell, the whole
image and the 2 px contour, said lit wrongly / said shadowed wrongly, in
all and on each mesh (the `mesh` layer, named by the header's
shadowlab:mesh).

  scripts/i48_kinds.py OUT/nsm-kinds/exr [OUT/nsm-kinds-one-sided/exr ...]

Needs Debian's python3-openimageio and python3-numpy (/usr/bin/python3).
"""
import glob
import os
import re
import sys

import numpy as np
import OpenImageIO as oiio


def layers(path):
    inp = oiio.ImageInput.open(path)
    if not inp:
        sys.exit(f"{path}: {oiio.geterror()}")
    spec = inp.spec()
    names = list(spec.channelnames)
    px = inp.read_image(oiio.UINT)
    inp.close()
    legend = {int(a): b for a, b in re.findall(r"(\d+) (\w+)", spec.getattribute("shadowlab:mesh") or "")}
    return {n[5:]: px[:, :, names.index(n)].astype(np.int64) for n in names if n.startswith("code.")}, legend


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for d in sys.argv[1:]:
        print(f"# {d}")
        for path in sorted(glob.glob(os.path.join(d, "*.exr"))):
            L, legend = layers(path)
            err, mesh, cont = L["error"], L["mesh"], L["contour"]
            parts = []
            for region, m in (("image", np.ones_like(err, bool)), ("2 px", cont >= 1)):
                tot = [int(((err == k) & m).sum()) for k in (1, 2)]
                per = []
                for code in sorted(legend):
                    a = int(((err == 1) & m & (mesh == code)).sum())
                    b = int(((err == 2) & m & (mesh == code)).sum())
                    if code and a + b:
                        per.append(f"{legend[code]} {a}/{b}")
                parts.append(f"{region} lit/shadow {tot[0]}/{tot[1]}: " + ", ".join(per))
            print(os.path.basename(path)[:-4], "|", " | ".join(parts))


if __name__ == "__main__":
    main()
