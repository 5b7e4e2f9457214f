#!/usr/bin/env python3
"""An independent renderer of Primitives' shadows, for `shadowlab grade`.

It shares no code with shadowlab: it reads the scene's numbers (scenes/
primitives.yaml, copied below: the camera of a viewpoint, the light, the
objects), intersects each pixel's primary ray with the objects as exact
shapes (a plane, a sphere, a capped cylinder, a pyramid's triangles, a torus
by sphere tracing its distance function) and answers each hit's shadow with
a second ray toward the light, the way an engine's ray-traced shadow pass
would. shadowlab's truth is traced against the tessellated meshes, so the
two disagree where a curved silhouette and its 32-sided stand-in differ:
what a grade should find.

Writes, in the conventions doc/grade.md lists:
  OUT/visibility.png  16-bit grey + alpha: 65535 lit, 0 shadowed; alpha 0
                      where the ray hits nothing within the near..far range
  OUT/depth.pfm       linear depth (eye-space distance along the view axis),
                      float, NaN where nothing was hit
Rows top-down in the PNG (as every image file), pixel centres at x + 0.5.

    python3 examples/primitives_shadows.py --viewpoint side --size 256x256 -o /tmp/eng
    shadowlab grade --scene primitives --viewpoint side --viewport 256x256 \
        --image /tmp/eng/visibility.png --depth /tmp/eng/depth.pfm --label numpy-rt
"""
import argparse
import math
import os
import struct
import zlib

import numpy as np

# scenes/primitives.yaml, as its numbers stand
LIGHT_DIR = np.array([0.528542, -0.376004, 0.761095])  # the direction light travels
VIEWPOINTS = {
    "side": dict(position=[35, 50, -43], direction=[-1, -1.2, 1], fov=60, near=20, far=250),
    "with": dict(position=[-28, 38, -40], direction=[0.4, -0.7, 0.6], fov=60, near=20, far=250),
    "against": dict(position=[31, 54, 38], direction=[-0.4, -0.7, -0.5], fov=60, near=20, far=250),
}
PLANE_HALF = 300.0
SPHERE = (np.array([-14.0, 5.0, -10.0]), 5.0)
CYL = (np.array([-6.0, 0.0, 4.0]), 3.0, 12.0)          # base centre, radius, height
PYR = (np.array([8.0, 0.0, 4.0]), 10.0, 10.0)          # base centre, base side, height
TORUS = (np.array([6.0, 1.5, -14.0]), 6.0, 1.5)         # centre, major, minor radius
EPS = 1e-3


def norm(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def hit_plane(o, d):
    t = np.where(np.abs(d[:, 1]) > 1e-12, -o[:, 1] / np.where(d[:, 1] == 0, 1, d[:, 1]), np.inf)
    p = o + d * t[:, None]
    ok = (t > EPS) & (np.abs(p[:, 0]) <= PLANE_HALF) & (np.abs(p[:, 2]) <= PLANE_HALF)
    return np.where(ok, t, np.inf)


def hit_sphere(o, d):
    c, r = SPHERE
    oc = o - c
    b = np.einsum("ij,ij->i", oc, d)
    cc = np.einsum("ij,ij->i", oc, oc) - r * r
    disc = b * b - cc
    s = np.sqrt(np.maximum(disc, 0))
    t0, t1 = -b - s, -b + s
    t = np.where(t0 > EPS, t0, np.where(t1 > EPS, t1, np.inf))
    return np.where(disc >= 0, t, np.inf)


def hit_cylinder(o, d):
    c, r, h = CYL
    ox, oz = o[:, 0] - c[0], o[:, 2] - c[2]
    a = d[:, 0] ** 2 + d[:, 2] ** 2
    b = ox * d[:, 0] + oz * d[:, 2]
    cc = ox * ox + oz * oz - r * r
    disc = b * b - a * cc
    s = np.sqrt(np.maximum(disc, 0))
    best = np.full(len(o), np.inf)
    for sign in (-1, 1):
        t = (-b + sign * s) / np.where(a > 1e-12, a, 1)
        y = o[:, 1] + t * d[:, 1]
        ok = (disc >= 0) & (a > 1e-12) & (t > EPS) & (y >= c[1]) & (y <= c[1] + h)
        best = np.where(ok & (t < best), t, best)
    for yc in (c[1], c[1] + h):  # the caps
        t = (yc - o[:, 1]) / np.where(np.abs(d[:, 1]) > 1e-12, d[:, 1], 1)
        px, pz = o[:, 0] + t * d[:, 0] - c[0], o[:, 2] + t * d[:, 2] - c[2]
        ok = (np.abs(d[:, 1]) > 1e-12) & (t > EPS) & (px * px + pz * pz <= r * r)
        best = np.where(ok & (t < best), t, best)
    return best


def pyramid_triangles():
    c, base, h = PYR
    s = base / 2
    a, b = c + [-s, 0, s], c + [s, 0, s]
    cc, e = c + [s, 0, -s], c + [-s, 0, -s]
    t = c + [0, h, 0]
    return [(a, b, t), (b, cc, t), (cc, e, t), (e, a, t), (a, e, cc), (a, cc, b)]


def hit_triangle(o, d, v0, v1, v2):  # Moller-Trumbore
    e1, e2 = v1 - v0, v2 - v0
    p = np.cross(d, e2)
    det = p @ e1
    inv = 1.0 / np.where(np.abs(det) > 1e-12, det, 1)
    tv = o - v0
    u = np.einsum("ij,ij->i", tv, p) * inv
    q = np.cross(tv, e1)
    v = np.einsum("ij,ij->i", d, q) * inv
    t = (q @ e2) * inv
    ok = (np.abs(det) > 1e-12) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > EPS)
    return np.where(ok, t, np.inf)


def hit_pyramid(o, d):
    best = np.full(len(o), np.inf)
    for tri in pyramid_triangles():
        best = np.minimum(best, hit_triangle(o, d, *tri))
    return best


def torus_sdf(p):
    c, R, r = TORUS
    q = p - c
    xz = np.sqrt(q[:, 0] ** 2 + q[:, 2] ** 2) - R
    return np.sqrt(xz * xz + q[:, 1] ** 2) - r


def hit_torus(o, d):
    c, R, r = TORUS
    # bounding sphere first, then sphere tracing inside it
    oc = o - c
    b = np.einsum("ij,ij->i", oc, d)
    disc = b * b - (np.einsum("ij,ij->i", oc, oc) - (R + r) ** 2)
    live = disc > 0
    t = np.where(live, np.maximum(-b - np.sqrt(np.maximum(disc, 0)), EPS), np.inf)
    tmax = np.where(live, -b + np.sqrt(np.maximum(disc, 0)), -np.inf)
    out = np.full(len(o), np.inf)
    for _ in range(200):
        idx = np.nonzero(live)[0]
        if idx.size == 0:
            break
        dist = torus_sdf(o[idx] + d[idx] * t[idx, None])
        hit = dist < 1e-5
        out[idx[hit]] = t[idx[hit]]
        t[idx] += np.where(hit, 0, dist)
        live[idx[hit | (t[idx] > tmax[idx])]] = False
    return out


def nearest(o, d):
    ts = np.stack([hit_plane(o, d), hit_sphere(o, d), hit_cylinder(o, d), hit_pyramid(o, d), hit_torus(o, d)])
    return ts.min(axis=0)


def png16_grey_alpha(path, w, h, grey, alpha):
    """16-bit grey + alpha PNG (colour type 4), rows top-down, big-endian."""
    px = np.empty((h, w, 2), dtype=">u2")
    px[..., 0], px[..., 1] = grey, alpha
    raw = b"".join(b"\0" + px[y].tobytes() for y in range(h))

    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 4, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 6)))
        f.write(chunk(b"IEND", b""))


def pfm(path, w, h, rows_top_down):
    """Portable float map, one channel: rows bottom-up, little-endian."""
    with open(path, "wb") as f:
        f.write(b"Pf\n%d %d\n-1.0\n" % (w, h))
        f.write(np.ascontiguousarray(rows_top_down[::-1], dtype="<f4").tobytes())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--viewpoint", default="side", choices=sorted(VIEWPOINTS))
    ap.add_argument("--size", default="256x256")
    ap.add_argument("-o", "--out", default=".")
    a = ap.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    vp = VIEWPOINTS[a.viewpoint]
    eye = np.array(vp["position"], float)
    f = norm(np.array(vp["direction"], float))
    right = norm(np.cross(f, [0.0, 1.0, 0.0]))
    up = np.cross(right, f)
    th = math.tan(math.radians(vp["fov"]) / 2)
    # pixel centres at half-integers; row 0 at the top
    xs = (2 * (np.arange(w) + 0.5) / w - 1) * th * (w / h)
    ys = (1 - 2 * (np.arange(h) + 0.5) / h) * th
    X, Y = np.meshgrid(xs, ys)
    d = norm(f + X.reshape(-1, 1) * right + Y.reshape(-1, 1) * up)
    o = np.broadcast_to(eye, d.shape).copy()
    t = nearest(o, d)
    p = o + d * t[:, None]
    z = (p - eye) @ f  # linear depth: along the view axis
    seen = np.isfinite(t) & (z >= vp["near"]) & (z <= vp["far"])
    # the shadow ray: from the hit toward the light (against its travel)
    to_light = np.broadcast_to(-norm(LIGHT_DIR), d.shape)
    ts = nearest(p + to_light * 1e-2, to_light)
    lit = ~np.isfinite(ts)
    vis = np.where(seen & lit, 65535, 0).reshape(h, w)
    alpha = np.where(seen, 65535, 0).reshape(h, w)
    os.makedirs(a.out, exist_ok=True)
    png16_grey_alpha(os.path.join(a.out, "visibility.png"), w, h, vis, alpha)
    pfm(os.path.join(a.out, "depth.pfm"), w, h, np.where(seen, z, np.nan).reshape(h, w))
    print("%s: %d x %d, %.1f %% of the surface pixels lit" % (a.out, w, h, 100 * lit[seen].mean()))


if __name__ == "__main__":
    main()
