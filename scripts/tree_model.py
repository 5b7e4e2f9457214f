#!/usr/bin/env python3
"""tree_model.py -- scenes/models/tree_cards.obj, the Bench scene's tree: a
trunk and a crown of leaf cards with gaps between them (issue 48, item 1;
scenes/CALIBRATION.md, "The trees' crowns").

  scripts/tree_model.py write [OUT.obj]    the model (default: the one in scenes/models)
  scripts/tree_model.py gaps [OBJ]         the share of the crown's outline, seen
                                           along the Bench light, that no leaf covers

The model is 1 unit tall, standing on the origin; a scene file scales, turns
and moves it with `transform` (scale [w, h, d] for a tree h tall). It keeps
the triangle budget of harness/scene/gen.c's sl_gen_tree (1,024: a 16-sided
closed trunk of 64 triangles and 960 leaf triangles) and its crown's
ellipsoid (radii 0.30 / 0.28 / 0.30, centred 0.66 up), so the theses' total
(55,026 triangles for the whole Bench scene) is kept. What differs is the
crown: sl_gen_tree scatters 960 leaves of circumradius 0.05-0.08 through the
ellipsoid, about nine layers deep along the light, so a crown casts one
solid shadow; here 480 square cards (two triangles each) of side 0.036 sit
in 40 clusters of 12 (a cluster 0.075 across its radius, a twig's leaves),
so light passes between the clusters and between the cards of one.

Why cards of that size. The theses say the trees "are constituted by big
triangles" (Moderno 4.1, Morais 5.1): a card is 0.036 of the tree's height,
2 units on a 57-unit tree, its shadow tens of pixels across in the Trees
views, where a petal is a few pixels. The size and the clustering set how
much light the crown lets through (`gaps`): one layer of cards on average,
so about half the outline is leaf and the rest sunflecks.

Deterministic: the seed below, Python's random (Mersenne Twister, the same
sequence on every platform for random() and the functions used here).
"""
import math
import os
import random
import sys

SEED = 48
CLUSTERS, CARDS, CARD = 40, 12, 0.036
CLUSTER_R = 0.075
CTR, RAD = (0.0, 0.66, 0.0), (0.30, 0.28, 0.30)
TRUNK_R, TRUNK_H, SIDES = 0.035, 0.62, 16
LIGHT = (0.744, -0.408, 0.527)   # scenes/bench.yaml's light, travelling
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "scenes", "models", "tree_cards.obj")


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def in_ball(rng):
    while True:
        p = tuple(rng.uniform(-1, 1) for _ in range(3))
        if sum(x * x for x in p) <= 1:
            return p


def model():
    """(vertices, triangles): the trunk first, then the cards"""
    V, T = [], []
    # trunk: a closed 16-sided prism, its caps fans about their centres
    base = len(V)
    for y in (0.0, TRUNK_H):
        for k in range(SIDES):
            a = 2 * math.pi * k / SIDES
            V.append((TRUNK_R * math.cos(a), y, TRUNK_R * math.sin(a)))
    V.append((0.0, 0.0, 0.0))
    V.append((0.0, TRUNK_H, 0.0))
    cb, ct = base + 2 * SIDES, base + 2 * SIDES + 1
    for k in range(SIDES):
        b0, b1 = base + k, base + (k + 1) % SIDES
        t0, t1 = b0 + SIDES, b1 + SIDES
        T += [(b0, t1, b1), (b0, t0, t1), (cb, b0, b1), (ct, t1, t0)]
    rng = random.Random(SEED)
    for _ in range(CLUSTERS):
        # a cluster's centre inside the ellipsoid shrunk by the cluster's radius
        q = in_ball(rng)
        c = tuple(CTR[k] + q[k] * (RAD[k] - CLUSTER_R) for k in range(3))
        for _ in range(CARDS):
            q = in_ball(rng)
            p = tuple(c[k] + q[k] * CLUSTER_R for k in range(3))
            n = unit(in_ball(rng))
            h = (1.0, 0.0, 0.0) if abs(n[0]) < 0.6 else (0.0, 1.0, 0.0)
            u = unit(cross(n, h))
            v = cross(n, u)
            th = rng.uniform(0, 2 * math.pi)
            eu = tuple(math.cos(th) * u[k] + math.sin(th) * v[k] for k in range(3))
            ev = tuple(-math.sin(th) * u[k] + math.cos(th) * v[k] for k in range(3))
            i = len(V)
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                V.append(tuple(p[k] + 0.5 * CARD * (su * eu[k] + sv * ev[k]) for k in range(3)))
            T += [(i, i + 1, i + 2), (i, i + 2, i + 3)]
    return V, T


def write(path):
    V, T = model()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write("# tree_cards.obj -- written by scripts/tree_model.py (seed %d): a tree 1 unit tall,\n"
                "# a 16-sided trunk and %d leaf cards in %d clusters; %d triangles. Open cards:\n"
                "# render two-sided (two_sided: true). scenes/CALIBRATION.md says why.\n"
                % (SEED, CLUSTERS * CARDS, CLUSTERS, len(T)))
        for v in V:
            f.write("v %.6f %.6f %.6f\n" % v)
        for t in T:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    print(f"{path}: {len(V)} vertices, {len(T)} triangles")


def read(path):
    V, T = [], []
    with open(path) as f:
        for ln in f:
            w = ln.split()
            if w and w[0] == "v":
                V.append(tuple(float(x) for x in w[1:4]))
            elif w and w[0] == "f":
                T.append(tuple(int(x.split("/")[0]) - 1 for x in w[1:4]))
    return V, T


def gaps(path, n=60):
    """Rays along the light through an n x n grid over the crown's outline
    (the ellipsoid's shadow outline, sampled on a plane across the light):
    the share of those inside the outline that hit no card."""
    V, T = read(path)
    L = unit(LIGHT)
    h = (1.0, 0.0, 0.0) if abs(L[0]) < 0.6 else (0.0, 1.0, 0.0)
    a = unit(cross(L, h))
    b = cross(L, a)
    leaf = [t for t in T if t[0] >= 2 * SIDES + 2]
    tris = [(V[i], V[j], V[k]) for i, j, k in leaf]
    R = max(RAD)
    inside = free = 0
    for gi in range(n):
        for gj in range(n):
            s, t = (2 * (gi + 0.5) / n - 1) * R, (2 * (gj + 0.5) / n - 1) * R
            o = tuple(CTR[k] + s * a[k] + t * b[k] - 2 * L[k] for k in range(3))
            # inside the outline: the ray meets the ellipsoid
            oc = tuple((o[k] - CTR[k]) / RAD[k] for k in range(3))
            d = tuple(L[k] / RAD[k] for k in range(3))
            A = sum(x * x for x in d)
            B = 2 * sum(oc[k] * d[k] for k in range(3))
            C = sum(x * x for x in oc) - 1
            if B * B - 4 * A * C < 0:
                continue
            inside += 1
            hit = False
            for p0, p1, p2 in tris:
                e1 = tuple(p1[k] - p0[k] for k in range(3))
                e2 = tuple(p2[k] - p0[k] for k in range(3))
                pv = cross(L, e2)
                det = sum(e1[k] * pv[k] for k in range(3))
                if abs(det) < 1e-12:
                    continue
                tv = tuple(o[k] - p0[k] for k in range(3))
                u = sum(tv[k] * pv[k] for k in range(3)) / det
                if u < 0 or u > 1:
                    continue
                qv = cross(tv, e1)
                v = sum(L[k] * qv[k] for k in range(3)) / det
                if v < 0 or u + v > 1:
                    continue
                if sum(e2[k] * qv[k] for k in range(3)) / det > 0:
                    hit = True
                    break
            free += not hit
    print(f"{path}: {free} of {inside} rays through the crown's outline hit no leaf "
          f"({100.0 * free / inside:.1f}% light through)")


def main():
    if len(sys.argv) < 2 or sys.argv[1] not in ("write", "gaps"):
        sys.exit(__doc__)
    path = sys.argv[2] if len(sys.argv) > 2 else OUT
    (write if sys.argv[1] == "write" else gaps)(path)


if __name__ == "__main__":
    main()
