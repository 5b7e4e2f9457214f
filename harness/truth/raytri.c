/*
 * raytri.c — see raytri.h. Edges count as inside (closed triangles), so a ray
 * through a shared edge hits at least one of the two triangles.
 */
#include "raytri.h"
#include <math.h>

#define SUB(r, a, b) do { (r)[0] = (a)[0] - (b)[0]; (r)[1] = (a)[1] - (b)[1]; (r)[2] = (a)[2] - (b)[2]; } while (0)
#define CROSS(r, a, b) do { (r)[0] = (a)[1] * (b)[2] - (a)[2] * (b)[1]; \
                            (r)[1] = (a)[2] * (b)[0] - (a)[0] * (b)[2]; \
                            (r)[2] = (a)[0] * (b)[1] - (a)[1] * (b)[0]; } while (0)
#define DOT(a, b) ((a)[0] * (b)[0] + (a)[1] * (b)[1] + (a)[2] * (b)[2])

int sl_ray_tri_d(const double o[3], const double dir[3], const double a[3], const double b[3],
                 const double c[3], double tmin, double *t)
{
    double e1[3], e2[3], pv[3], tv[3], qv[3];
    SUB(e1, b, a);
    SUB(e2, c, a);
    CROSS(pv, dir, e2);
    double det = DOT(e1, pv);
    if (det == 0.0)
        return 0;
    double inv = 1.0 / det;
    SUB(tv, o, a);
    double u = DOT(tv, pv) * inv;
    if (u < 0.0 || u > 1.0)
        return 0;
    CROSS(qv, tv, e1);
    double v = DOT(dir, qv) * inv;
    if (v < 0.0 || u + v > 1.0)
        return 0;
    double tt = DOT(e2, qv) * inv;
    if (!(tt > tmin))
        return 0;
    *t = tt;
    return 1;
}

/* fmax and fmin for arguments that are never -0 (distances, magnitudes):
 * the same value, NaN arguments passed over as those do, without the libm
 * call GCC emits for them (fmax must honour NaNs; the sure test made twelve
 * such calls per triangle, more than its arithmetic). */
static inline double max_of(double x, double y)
{
    return x != x ? y : y != y ? x : x > y ? x : y;
}

static inline double min_of(double x, double y)
{
    return x != x ? y : y != y ? x : x < y ? x : y;
}

static double seg_dist(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3];
    SUB(ab, b, a);
    SUB(ap, p, a);
    double l2 = DOT(ab, ab);
    double s = l2 > 0.0 ? DOT(ap, ab) / l2 : 0.0;
    if (s < 0.0) s = 0.0;
    if (s > 1.0) s = 1.0;
    double q[3] = {a[0] + s * ab[0] - p[0], a[1] + s * ab[1] - p[1], a[2] + s * ab[2] - p[2]};
    return sqrt(DOT(q, q));
}

double sl_point_tri_edge_dist_d(const double p[3], const double a[3], const double b[3],
                                const double c[3])
{
    return min_of(seg_dist(p, a, b), min_of(seg_dist(p, b, c), seg_dist(p, c, a)));
}

/* The distance with the plane's normal n = (b - a) x (c - a) given (the
 * sure tests have it already): the same operations as computing it here. */
static inline double point_tri_dist_n(const double p[3], const double a[3], const double b[3], const double c[3],
                                      const double n[3])
{
    double ap[3];
    double nn = DOT(n, n);
    SUB(ap, p, a);
    double h = DOT(ap, n) / nn;
    double q[3] = {p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
    double plane = fabs(h) * sqrt(nn);
    /* inside test of the projection by barycentric signs */
    double c0[3], c1[3], c2[3], qa[3], qb[3], qc[3], ba[3], cb[3], ac[3];
    SUB(qa, q, a); SUB(qb, q, b); SUB(qc, q, c);
    SUB(ba, b, a); SUB(cb, c, b); SUB(ac, a, c);
    CROSS(c0, ba, qa); CROSS(c1, cb, qb); CROSS(c2, ac, qc);
    if (DOT(c0, n) >= 0.0 && DOT(c1, n) >= 0.0 && DOT(c2, n) >= 0.0)
        return plane;
    double e = sl_point_tri_edge_dist_d(q, a, b, c);
    return sqrt(plane * plane + e * e);
}

double sl_point_tri_dist_d(const double p[3], const double a[3], const double b[3],
                           const double c[3])
{
    double e1[3], e2[3], n[3];
    SUB(e1, b, a);
    SUB(e2, c, a);
    CROSS(n, e1, e2);
    return point_tri_dist_n(p, a, b, c, n);
}

/* The set-up both sure tests share: the triangle and ray in double, the
 * plane's unit-free normal n and |n|, and mag, the coordinates' size. */
struct sure_in {
    double a[3], b[3], c[3], o[3], dir[3], n[3], nn, mag;
};

static inline void sure_setup(struct sure_in *s, const float p[3], const float toward[3], const float af[3],
                              const float bf[3], const float cf[3])
{
    double e1[3], e2[3], mag = 0.0;
    for (int k = 0; k < 3; k++) {
        s->a[k] = af[k];
        s->b[k] = bf[k];
        s->c[k] = cf[k];
        s->o[k] = p[k];
        s->dir[k] = (double)toward[k];
        mag = max_of(mag, max_of(fabs(s->o[k]), max_of(fabs(s->a[k]), max_of(fabs(s->b[k]), fabs(s->c[k])))));
    }
    SUB(e1, s->b, s->a);
    SUB(e2, s->c, s->a);
    CROSS(s->n, e1, e2);
    s->nn = sqrt(DOT(s->n, s->n));
    s->mag = mag;
}

int sl_shadow_ray_tri_sure(const float p[3], const float toward[3], float tmax, float tnear, const float af[3],
                           const float bf[3], const float cf[3])
{
    struct sure_in s;
    sure_setup(&s, p, toward, af, bf, cf);
    const double *a = s.a, *b = s.b, *c = s.c, *o = s.o, *dir = s.dir, *n = s.n, nn = s.nn;
    if (!(nn > 0.0))
        return 0;
    double den = DOT(n, dir) / nn;
    if (fabs(den) < 1e-9)
        return 0;                              /* grazing: too close to call */
    double ao[3];
    SUB(ao, a, o);
    double th = DOT(n, ao) / nn / den;
    if (th < 0.5 * (double)tnear)
        return -1;                             /* behind, or before Embree starts looking */
    double q[3] = {o[0] + th * dir[0], o[1] + th * dir[1], o[2] + th * dir[2]};
    double margin = 1e-5 * (s.mag + 1.0);
    if (th > (double)tmax + margin)
        return -1;                             /* beyond the ray's end: behind a point light */
    if (sl_point_tri_dist_d(q, a, b, c) > margin)
        return -1;
    /* inside: by how much (distance to the boundary, with the sign of the
     * barycentric test) */
    double t;
    if (th > 2.0 * (double)tnear && th < (double)tmax - margin && sl_ray_tri_d(o, dir, a, b, c, 0.0, &t) &&
        sl_point_tri_edge_dist_d(q, a, b, c) > margin)
        return 1;
    return 0;
}

/* The same conditions as sl_shadow_ray_tri_sure's +1, each computed from
 * the same values by the same expressions (so to the same bits), but
 * ordered cheapest and most often failing first: a +1 needs every one of
 * them, and none has a side effect, so their order cannot change the
 * answer. Most rays a method tests miss the triangle by far, and the
 * Moller-Trumbore test (two cross products and a division) rejects them
 * before the point-triangle distance (three segment distances, each with a
 * division and a square root) that the sure test pays first; of those it
 * keeps, the edge distance drops the ones within the margin of an edge
 * before the distance to the triangle, which reuses the normal. */
int sl_shadow_ray_tri_hit(const float p[3], const float toward[3], float tmax, float tnear, const float af[3],
                          const float bf[3], const float cf[3])
{
    struct sure_in s;
    sure_setup(&s, p, toward, af, bf, cf);
    const double *a = s.a, *b = s.b, *c = s.c, *o = s.o, *dir = s.dir, *n = s.n, nn = s.nn;
    double t;
    if (!(nn > 0.0) || !sl_ray_tri_d(o, dir, a, b, c, 0.0, &t))
        return 0;
    double den = DOT(n, dir) / nn;
    if (fabs(den) < 1e-9)
        return 0;
    double ao[3];
    SUB(ao, a, o);
    double th = DOT(n, ao) / nn / den;
    double margin = 1e-5 * (s.mag + 1.0);
    if (th < 0.5 * (double)tnear || th > (double)tmax + margin || !(th > 2.0 * (double)tnear) ||
        !(th < (double)tmax - margin))
        return 0;
    double q[3] = {o[0] + th * dir[0], o[1] + th * dir[1], o[2] + th * dir[2]};
    return sl_point_tri_edge_dist_d(q, a, b, c) > margin && !(point_tri_dist_n(q, a, b, c, n) > margin);
}
