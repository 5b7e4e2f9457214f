/*
 * softmc.c — see softmc.h.
 *
 * Invariants. A ray is traced in texture space from its start A (toward the
 * light) to its end B (the pixel's q'); along the projected segment, with
 * parameter s in [0, 1], the inverse depth is linear (perspective), so depth
 * d(s) = 1 / (ia + s (ib - ia)) increases monotonically from the light to
 * the pixel. A texel blocks the ray when some depth of the ray over that
 * texel lies in [near, far] of the texel (far = +inf with one layer).
 * "May hit" tests (hierarchical search, shortcuts) widen that interval by a
 * relative EPS on each side, the linear search samples points with the exact
 * test: so every sample hit is also found by the hierarchical search, and no
 * shortcut proves more than the hierarchical search would find.
 * Third layer (3.4): a sample between the layers that the camera sees
 * (eye_sees) takes the state FREE instead of being a hit, and a change into
 * or out of FREE is a hit unless the camera sees its other end too. A
 * search that meets no sample between the layers takes the same samples and
 * refinements with two layers and with three, so a ray blocked with three
 * layers is blocked with two: three layers never give less light.
 */
#include "softmc.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <omp.h>
#include "util.h"

#define EPS 0x1p-20
#define ITER_CAP_PER_TEXEL 64
/* Third layer: a point is seen by the camera when it lies in front of the
 * planes of the surfaces of its nearest pixels by more than this times its
 * distance from the camera (eye_sees says why). */
#define EYE_MARGIN 1e-4

void sl_softmc_defaults(const struct sl_softmc_desc *in, struct sl_softmc_desc *out)
{
    *out = *in;
    if (out->grid <= 0) out->grid = 3;
    if (out->layers <= 0) out->layers = 2;
    if (out->class_iters <= 0) out->class_iters = 2;
    if (out->step_texels <= 0.0) out->step_texels = 4.0;
    out->refine = out->refine == 0 ? 4 : out->refine < 0 ? 0 : out->refine;
    if (out->bias_scale <= 0.0) out->bias_scale = 1.0;
    if (out->ndl_min <= 0.0) out->ndl_min = 0.1;
    if (out->blur_radius > 0 && out->blur_sigma <= 0.0) out->blur_sigma = 0.5 * out->blur_radius;
    if (out->blur_depth_k <= 0.0) out->blur_depth_k = 1.0;
}

static int log2i(int x)
{
    int n = 0;
    while ((1 << (n + 1)) <= x)
        n++;
    return n;
}

/* ---- per-pixel context ------------------------------------------------- */

struct ctx {
    const struct sl_softmap *m;
    const struct sl_softmap_nbuf *nb;
    const struct sl_view *v;
    struct sl_softmc_desc o;
    int S, two, eye;                 /* eye: the camera's G-buffer is the third layer */
    double L;                        /* depth of the light's plane */
    struct sl_softmap_texel global;   /* the whole map */
    double cam[3];                   /* the camera's position */
    double clip[4][4];               /* proj x view, column-major as cglm's */
};

/* Per-thread counters, summed at the end (integer sums: any order). */
struct counts {
    uint64_t unlit, lit, umbra, endpoint, rays, backface, region, searched, hit, lookups, lk_search, capped;
    uint64_t eye_tests, eye_seen, eye_outside;
};

static inline int clampi(int x, int hi)
{
    return x < 0 ? 0 : x > hi ? hi : x;
}

/* The window of side 2^level at corner (i, j), clamped to the map: a corner
 * left of or below the map gives the window at 0, a superset of the part
 * inside. With one layer the far layer is "infinitely deep". */
static inline struct sl_softmap_texel fetch(const struct ctx *c, int level, int i, int j)
{
    const int S = c->S;
    struct sl_softmap_texel t =
        c->nb->t[((size_t)level * (size_t)S + (size_t)clampi(j, S - 1)) * (size_t)S + (size_t)clampi(i, S - 1)];
    if (!c->two)
        t.far_min = t.far_max = INFINITY;
    return t;
}

/* Extremes over the texels that the continuous rectangle [u0, u1] x [v0, v1]
 * touches, in at most 4 fetches: squares of side 2^n, n = floor(log2(longer
 * side)), at the two ends of each axis (a superset on the shorter axis). */
static struct sl_softmap_texel query_rect(const struct ctx *c, double u0, double v0, double u1, double v1,
                                         uint64_t *lookups)
{
    const int S = c->S;
    int i0 = clampi((int)floor(fmin(u0, u1)), S - 1), i1 = clampi((int)floor(fmax(u0, u1)), S - 1);
    int j0 = clampi((int)floor(fmin(v0, v1)), S - 1), j1 = clampi((int)floor(fmax(v0, v1)), S - 1);
    int wx = i1 - i0 + 1, wy = j1 - j0 + 1;
    int n = log2i(wx > wy ? wx : wy), side = 1 << n;
    int xs[2] = {i0, i1 - side + 1}, ys[2] = {j0, j1 - side + 1};
    int nx = wx > side ? 2 : 1, ny = wy > side ? 2 : 1;
    struct sl_softmap_texel r = fetch(c, n, xs[0], ys[0]);
    (*lookups)++;
    for (int a = 0; a < nx; a++)
        for (int b = 0; b < ny; b++) {
            if (a == 0 && b == 0)
                continue;
            struct sl_softmap_texel t = fetch(c, n, xs[a], ys[b]);
            sl_softmap_texel_merge(&r, &t);
            (*lookups)++;
        }
    return r;
}

/* "May hit" tests: a ray portion with depths [dlo, dhi] against bounds. */
static inline int may_hit(double dlo, double dhi, const struct sl_softmap_texel *t)
{
    return dhi * (1.0 + EPS) >= (double)t->near_min && dlo * (1.0 - EPS) <= (double)t->far_max;
}

/* ---- rays in texture space --------------------------------------------- */

struct tray {
    double ax, ay, bx, by;   /* start (toward the light) and end (the pixel's q'), texels */
    double ia, ib;           /* inverse depths there */
};

static inline double ray_depth(const struct tray *r, double s)
{
    return 1.0 / (r->ia + s * (r->ib - r->ia));
}

/* Parameter at which the ray reaches a depth (unclamped). */
static inline double ray_param(const struct tray *r, double depth)
{
    return (1.0 / depth - r->ia) / (r->ib - r->ia);
}

/* The part [s0, s1] as a ray of its own (texture position and inverse depth
 * are both linear in s). */
static struct tray ray_sub(const struct tray *r, double s0, double s1)
{
    struct tray o;
    o.ax = r->ax + s0 * (r->bx - r->ax);
    o.ay = r->ay + s0 * (r->by - r->ay);
    o.bx = r->ax + s1 * (r->bx - r->ax);
    o.by = r->ay + s1 * (r->by - r->ay);
    o.ia = r->ia + s0 * (r->ib - r->ia);
    o.ib = r->ia + s1 * (r->ib - r->ia);
    return o;
}

/* Clip the segment to the map's square [0, S]^2 (Liang-Barsky); 0 when
 * nothing of it is inside. Outside the map nothing occludes: the frame holds
 * every ray of a fitted view, so this only trims rounding (or the rays of
 * points beyond a capped fov). */
static int ray_clip(const struct tray *r, double S, double *s0, double *s1)
{
    double lo = 0.0, hi = 1.0;
    const double p[2] = {r->ax, r->ay}, dd[2] = {r->bx - r->ax, r->by - r->ay};
    for (int k = 0; k < 2; k++) {
        if (dd[k] == 0.0) {
            if (p[k] < 0.0 || p[k] > S)
                return 0;
            continue;
        }
        double t0 = (0.0 - p[k]) / dd[k], t1 = (S - p[k]) / dd[k];
        if (t0 > t1) { double x = t0; t0 = t1; t1 = x; }
        if (t0 > lo) lo = t0;
        if (t1 < hi) hi = t1;
    }
    *s0 = lo;
    *s1 = hi;
    return lo <= hi;
}

/* Algorithm 2: hierarchical search through the N-buffer. The stepping s is
 * the searched part of the ray; the current window (side 2^n) holds the
 * texel the ray is in at s and extends forward along the ray. Where the
 * ray's depths in the window cannot reach [near_min, far_max] the stepping
 * jumps to the window's exit and the level goes up one; where they can, the
 * stepping advances to the depth near_min (nothing in the window is nearer)
 * and the level goes down one; a "may hit" at level 0 is a hit. */
static int search_hier(const struct ctx *c, const struct tray *r, uint64_t *lookups, uint64_t *capped)
{
    const int S = c->S;
    const double du = r->bx - r->ax, dv = r->by - r->ay;
    /* initial level: one window holding the projection of the whole ray */
    int ix0 = clampi((int)floor(fmin(r->ax, r->bx)), S - 1), ix1 = clampi((int)floor(fmax(r->ax, r->bx)), S - 1);
    int iy0 = clampi((int)floor(fmin(r->ay, r->by)), S - 1), iy1 = clampi((int)floor(fmax(r->ay, r->by)), S - 1);
    int ext = ix1 - ix0 > iy1 - iy0 ? ix1 - ix0 + 1 : iy1 - iy0 + 1;
    int n0 = log2i(ext);
    if ((1 << n0) < ext)
        n0++;
    struct sl_softmap_texel t = fetch(c, n0, ix0, iy0);
    (*lookups)++;
    double s = 0.0;
    if (!may_hit(ray_depth(r, 0.0), ray_depth(r, 1.0), &t))
        return 0;
    if (n0 == 0)
        return 1;
    /* initial stepping: where the ray reaches the plane at z_near_min */
    if ((double)t.near_min > ray_depth(r, 0.0)) {
        double sn = ray_param(r, (double)t.near_min / (1.0 + EPS));
        s = sn > 1.0 ? 1.0 : sn > 0.0 ? sn : 0.0;
    }
    int n = n0 - 1;
    const long cap = (long)ITER_CAP_PER_TEXEL * (long)(ext + 1) * (long)c->nb->levels;
    for (long it = 0; it < cap; it++) {
        const double px = r->ax + s * du, py = r->ay + s * dv;
        /* the texel the ray enters at s: moving toward lower coordinates, a
         * point on a texel edge belongs to the texel below the edge */
        int ix = du >= 0.0 ? (int)floor(px) : (int)ceil(px) - 1;
        int iy = dv >= 0.0 ? (int)floor(py) : (int)ceil(py) - 1;
        const int side = 1 << n;
        int x0 = du >= 0.0 ? ix : ix - side + 1;
        int y0 = dv >= 0.0 ? iy : iy - side + 1;
        double se = 1.0;
        if (du > 0.0) se = fmin(se, ((double)(x0 + side) - r->ax) / du);
        else if (du < 0.0) se = fmin(se, ((double)x0 - r->ax) / du);
        if (dv > 0.0) se = fmin(se, ((double)(y0 + side) - r->ay) / dv);
        else if (dv < 0.0) se = fmin(se, ((double)y0 - r->ay) / dv);
        if (!(se > s))
            se = fmin(1.0, s + 1e-12);   /* rounding on an edge: always move on */
        t = fetch(c, n, x0, y0);
        (*lookups)++;
        const double dlo = ray_depth(r, s), dhi = ray_depth(r, se);
        if (may_hit(dlo, dhi, &t)) {
            if (n == 0)
                return 1;
            if ((double)t.near_min > dlo) {
                double sn = ray_param(r, (double)t.near_min / (1.0 + EPS));
                if (sn > s)
                    s = sn < se ? sn : se;
            }
            n--;
        } else {
            if (se >= 1.0)
                return 0;
            s = se;
            if (n < n0)
                n++;   /* ascend: Curtis finds it saves long runs at level 0 */
        }
    }
    (*capped)++;
    return 1;   /* never seen; the conservative answer */
}

/* ---- the third layer: the camera's G-buffer (3.4) ---------------------- */

/* The inverse of sl_softmap_project: the world point at continuous texel
 * (u, v) and linear depth z. */
static void unproject(const struct sl_softmap *m, double u, double v, double z, double out[3])
{
    const double k = 2.0 * m->tan_half * z / (double)m->size;
    const double x = (u - 0.5 * (double)m->size) * k, y = (v - 0.5 * (double)m->size) * k;
    for (int a = 0; a < 3; a++)
        out[a] = m->eye[a] + x * m->right[a] + y * m->up[a] + z * m->fwd[a];
}

enum eye { EYE_HIDDEN, EYE_SEEN, EYE_OUTSIDE };

/* Whether the camera sees the world point x, i.e. x is nearer to the camera
 * than the surfaces the G-buffer holds where x projects: then x is empty
 * space (the camera looks through it), not inside a solid, and a ray there
 * is not blocked.
 * The surface at a pixel is taken as the plane of its triangle (position
 * and face normal, turned toward the camera), not the single depth at the
 * pixel's centre: x falls anywhere inside a pixel, and across half a pixel
 * a surface seen at an angle can change depth by as much as a ray's end
 * stands off its own receiver (the bias, about one map texel, see below),
 * so the centre's depth would call a ray's last samples hidden or seen by
 * where they fall in the pixel. With the camera on the plane's front side, "in front of the
 * plane" is "nearer than the plane along x's line of sight".
 * x must be in front of the planes of all 4 pixels whose centres surround
 * its projection (background pixels, where the camera saw nothing up to the
 * far plane, constrain nothing): at a silhouette or a crease one of them
 * holds the nearer surface, so an edge falls back to two layers rather than
 * leak light.
 * Margin: EYE_MARGIN x the distance from the camera, along the normal. It
 * sits between two measured sizes (softbox, softmix, soft_wuson, 256x192
 * views): the G-buffer's float, GPU-interpolated positions lie off their
 * triangle's plane by ~1e-8 of the distance (99.9% below 2e-7), so 1e-4 is
 * far above that noise; a ray's end q' stands off its own receiver, along
 * the normal, by about sqrt(2) z tan(fov/2) / size (eq. 3.2's bias), i.e.
 * 1.5e-3 (1st percentile) to 3e-3 (median) of the distance at a 512^2
 * map, half that at 1024^2, so the margin stays several times below it up
 * to 2048^2 and a receiver's own surface does not hide its rays' last
 * samples. A point within the margin keeps the two-layer answer.
 * Outside the view frustum (behind the camera, off the image, nearer than
 * the near plane or beyond the far plane, where geometry is clipped) the
 * G-buffer says nothing about x: EYE_OUTSIDE, and the caller keeps the
 * two-layer answer (an occluder), so the third layer only ever removes
 * intersections the camera shows to be empty. */
static enum eye eye_sees(const struct ctx *c, const double x[3])
{
    const struct sl_view *v = c->v;
    double h[4];
    for (int r = 0; r < 4; r++)
        h[r] = c->clip[0][r] * x[0] + c->clip[1][r] * x[1] + c->clip[2][r] * x[2] + c->clip[3][r];
    /* GL clip space, z in [-w, w] (gbuffer.c: GL_NEGATIVE_ONE_TO_ONE) */
    if (!(h[3] > 0.0) || !(fabs(h[0]) <= h[3]) || !(fabs(h[1]) <= h[3]) || !(fabs(h[2]) <= h[3]))
        return EYE_OUTSIDE;
    /* continuous pixel coordinates with pixel centres at integers */
    const double px = (0.5 * h[0] / h[3] + 0.5) * (double)v->w - 0.5;
    const double py = (0.5 * h[1] / h[3] + 0.5) * (double)v->h - 0.5;
    const int i0 = (int)floor(px), j0 = (int)floor(py);
    const double dc[3] = {x[0] - c->cam[0], x[1] - c->cam[1], x[2] - c->cam[2]};
    const double margin = EYE_MARGIN * sqrt(dc[0] * dc[0] + dc[1] * dc[1] + dc[2] * dc[2]);
    for (int dj = 0; dj < 2; dj++)
        for (int di = 0; di < 2; di++) {
            const size_t i = (size_t)clampi(j0 + dj, v->h - 1) * (size_t)v->w + (size_t)clampi(i0 + di, v->w - 1);
            if (!v->tri[i])
                continue;
            const float *p = v->pos + 3 * i, *n = v->nrm + 3 * i;
            const double off = (x[0] - (double)p[0]) * (double)n[0] + (x[1] - (double)p[1]) * (double)n[1] +
                               (x[2] - (double)p[2]) * (double)n[2];
            if (!(off > margin))
                return EYE_HIDDEN;
        }
    return EYE_SEEN;
}

/* The eye test of a point, counted: seen (1) or not (0). */
static int eye_free(const struct ctx *c, const double x[3], struct counts *k)
{
    const enum eye e = eye_sees(c, x);
    k->eye_tests++;
    k->eye_seen += e == EYE_SEEN;
    k->eye_outside += e == EYE_OUTSIDE;
    return e == EYE_SEEN;
}

/* ---- linear search ----------------------------------------------------- */

/* FREE: between the layers, but seen by the camera (third layer only). */
enum state { FRONT, BEHIND, BOTH, BETWEEN, FREE };

/* A point sample of the ray: its texel, position, depth and state (exact
 * tests). */
struct sample {
    int i, j;
    double u, v, d;
    float near, far;
    enum state st;
};

static struct sample sample_at(const struct ctx *c, const struct tray *r, double s, uint64_t *lookups,
                               struct counts *k)
{
    struct sample o;
    const double px = r->ax + s * (r->bx - r->ax), py = r->ay + s * (r->by - r->ay);
    o.i = clampi((int)floor(px), c->S - 1);
    o.j = clampi((int)floor(py), c->S - 1);
    o.u = px;
    o.v = py;
    struct sl_softmap_texel t = fetch(c, 0, o.i, o.j);
    (*lookups)++;
    o.near = t.near_min;
    o.far = t.far_max;
    o.d = ray_depth(r, s);
    const int front = o.d < (double)o.near, behind = o.d > (double)o.far;
    o.st = front && behind ? BOTH : front ? FRONT : behind ? BEHIND : BETWEEN;
    if (o.st == BETWEEN && c->eye) {
        double x[3];
        unproject(c->m, px, py, o.d, x);
        if (eye_free(c, x, k))
            o.st = FREE;
    }
    return o;
}

/* Third layer: a change between FREE and a state outside the layers
 * (FRONT, BEHIND, BOTH: empty space as the light sees it) is a way out of
 * the hull only if the camera sees the samples outside too; otherwise it is
 * a hit, the two-layer answer. Between two texels the layers cannot tell a
 * surface that runs on (a leaf crossed at a texel's edge: "in front" on one
 * side, "between" just under it on the other; or, with the leaf's depth
 * varying inside a texel, "in front" on both sides) from a step in depth (a
 * ray that slips under a horn from the side); the camera can: it sees both
 * sides of the crossing only when no surface it sees parts them. The
 * samples are the ends of the linear step (a, d) and of the refined change
 * (b, c; b keeps a's state): all of them outside the layers must be seen
 * (tests/scenes/softmix.yaml's leaf leaked light through texel edges until
 * all four were asked). */
static int free_change_blocked(const struct ctx *c, const struct sample *const s[4], struct counts *k)
{
    int any = 0;
    for (int n = 0; n < 4; n++)
        any |= s[n]->st == FREE;
    if (!any)
        return 0;
    for (int n = 0; n < 4; n++) {
        /* b is a copy of a until the refinement moves it (and c of d) */
        if (s[n]->st == FREE || (n > 0 && s[n]->u == s[n - 1]->u && s[n]->v == s[n - 1]->v &&
                                 s[n]->d == s[n - 1]->d))
            continue;
        double x[3];
        unproject(c->m, s[n]->u, s[n]->v, s[n]->d, x);
        if (!eye_free(c, x, k))
            return 1;
    }
    return 0;
}

/* Two samples in one texel: the ray's depths between them run from a.d to
 * b.d over the same [near, far], so a crossing shows without a sample
 * inside (a zero-thickness leaf has near = far: no point is ever
 * "between", yet the ray goes through it). */
static int crossed(const struct sample *a, const struct sample *b)
{
    return a->i == b->i && a->j == b->j && a->near <= a->far && a->d <= (double)a->far && b->d >= (double)a->near;
}

/* 3.3: linear steps along the ray, both ends included; between two
 * samples whose states differ, binary refinement (refine halvings) keeps
 * the half whose ends still differ, then the linear search resumes at the
 * farther sample. Curtis refines transitions to "in front" and from
 * "behind"; we refine every change, which includes those and also "in
 * front" -> "behind" (a thin occluder stepped over), and end each
 * refinement with the one-texel crossing test above. With one layer the
 * states are only "in front" and "between": nothing to refine.
 * Steps: each is the shorter of step_texels in the map and the depth step
 * dd, 1/N of the whole ray's depth range with N = its length / step_texels
 * (at most about 2N samples). The caller passes dd of the whole ray, so a
 * shortened ray keeps the sampling density of the full one.
 * Steps even in the map alone put almost every sample near the light: the
 * inverse depth is what is linear in the map, so in a wide frustum a ray
 * runs through the depths of the occluders (and of its end) in its last few
 * texels (softmix.yaml, 150 degrees: 31% of the pixels differed from the
 * hierarchical search; 6% with the depth steps added).
 * Third layer: FREE is one more state, so a ray entering or leaving the
 * camera's empty space is refined like any other change, and the refined
 * change must pass free_change_blocked. The one-texel crossing test stays:
 * within one texel the depth runs past near (or far) there, i.e. through
 * the surface the light sees (or its back), whatever the camera sees of
 * the points beside it. */
static int search_linear(const struct ctx *c, const struct tray *r, double dd, uint64_t *lookups,
                         struct counts *k)
{
    const double len = fmax(fabs(r->bx - r->ax), fabs(r->by - r->ay));
    const int n = len > c->o.step_texels ? (int)ceil(len / c->o.step_texels) : 1;
    const double ds = 1.0 / (double)n;
    struct sample prev = sample_at(c, r, 0.0, lookups, k);
    if (prev.st == BETWEEN)
        return 1;
    /* each step ends a texture step or a depth step: at most this many */
    const double cap = (double)n + ceil((ray_depth(r, 1.0) - prev.d) / dd) + 1.0;
    double sp = 0.0;
    for (int it = 0; sp < 1.0; it++) {
        double s = fmin(sp + ds, ray_param(r, prev.d + dd));
        if (!(s > sp) || s > 1.0 || (double)it >= cap)
            s = 1.0;
        const struct sample cur = sample_at(c, r, s, lookups, k);
        if (cur.st == BETWEEN)
            return 1;
        if (cur.st != prev.st) {
            double lo = sp, hi = s;
            struct sample slo = prev, shi = cur;
            for (int j = 0; j < c->o.refine; j++) {
                const double mid = 0.5 * (lo + hi);
                const struct sample sm = sample_at(c, r, mid, lookups, k);
                if (sm.st == BETWEEN)
                    return 1;
                if (sm.st != slo.st) {
                    hi = mid;
                    shi = sm;
                } else {
                    lo = mid;
                    slo = sm;
                }
            }
            if (c->two && crossed(&slo, &shi))
                return 1;
            if (c->eye) {
                const struct sample *const ends[4] = {&prev, &slo, &shi, &cur};
                if (free_change_blocked(c, ends, k))
                    return 1;
            }
        }
        prev = cur;
        sp = s;
    }
    return 0;
}

/* Narrow [s0, s1] of a ray running from depth L to ze to the part with
 * depths in [ds, de]; 0 when nothing is left. */
static int shorten(const struct tray *r, double L, double ze, double ds, double de, double *s0, double *s1)
{
    if (ds > L)
        *s0 = fmax(*s0, ray_param(r, ds));
    if (de < ze)
        *s1 = fmin(*s1, ray_param(r, de));
    return *s0 <= *s1;
}

/* The continuous texture-space box of every ray from the light to apex qe
 * (depth ze) where deeper than D: the projection of the cross-section of the
 * pyramid over the light at depth D, and of the apex (Curtis fig. 3.7,
 * eq. 3.3: the box's side is n (z - D) / (D (z - n)) of the map). */
static void region_at(const struct ctx *c, const double qe[3], double ze, double D, double bb[4])
{
    const struct sl_softmap *m = c->m;
    if (D <= c->L) {
        bb[0] = bb[1] = 0.0;
        bb[2] = bb[3] = (double)c->S;
        return;
    }
    double u, v, z;
    sl_softmap_project(m, qe, &u, &v, &z);
    bb[0] = bb[2] = u;
    bb[1] = bb[3] = v;
    const double f = (ze - D) / (ze - c->L);
    for (int k = 0; k < 4; k++) {
        double p[3], x[3];
        sl_area_point(&m->area, (double)(k & 1), (double)(k >> 1), p);
        for (int a = 0; a < 3; a++)
            x[a] = qe[a] + (p[a] - qe[a]) * f;
        sl_softmap_project(m, x, &u, &v, &z);
        bb[0] = fmin(bb[0], u);
        bb[1] = fmin(bb[1], v);
        bb[2] = fmax(bb[2], u);
        bb[3] = fmax(bb[3], v);
    }
}

/* Sample s of pixel (x, y): a point of the jittered grid, or the light's
 * centre for every ray when desc.centre is set (the light as a point). */
static void sample_uv(const struct ctx *c, int x, int y, int s, int r, double *su, double *sv)
{
    if (c->o.centre) {
        *su = *sv = 0.5;
        return;
    }
    sl_area_jitter((uint32_t)x, (uint32_t)y, (uint32_t)s, (uint32_t)r, c->o.seed, su, sv);
}

/* The fraction of the pixel's rays that leave its surface on the front
 * side (3.7's first case blocks the others): no lookups. */
static float front_facing(const struct ctx *c, int x, int y, const double q[3], const double nr[3])
{
    const int r = c->o.grid, nrays = r * r;
    int front = 0;
    for (int s = 0; s < nrays; s++) {
        double su, sv, p[3];
        sample_uv(c, x, y, s, r, &su, &sv);
        sl_area_point(&c->m->area, su, sv, p);
        front += nr[0] * (p[0] - q[0]) + nr[1] * (p[1] - q[1]) + nr[2] * (p[2] - q[2]) > 0.0;
    }
    return (float)front / (float)nrays;
}

/* One pixel: its visible fraction. */
static float pixel(const struct ctx *c, int x, int y, size_t i, struct counts *k)
{
    const struct sl_softmap *m = c->m;
    const struct sl_area *a = &m->area;
    const double q[3] = {c->v->pos[3 * i], c->v->pos[3 * i + 1], c->v->pos[3 * i + 2]};
    const double nr[3] = {c->v->nrm[3 * i], c->v->nrm[3 * i + 1], c->v->nrm[3 * i + 2]};
    const double rel[3] = {q[0] - a->c[0], q[1] - a->c[1], q[2] - a->c[2]};
    if (!(rel[0] * a->n[0] + rel[1] * a->n[1] + rel[2] * a->n[2] > 0.0)) {
        k->unlit++;   /* on or behind the light's plane: the light emits on one side */
        return 0.0f;
    }
    double qu, qv, z;
    sl_softmap_project(m, q, &qu, &qv, &z);
    /* eq. 3.2, n.l toward the light's centre, limited below */
    double rl = sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
    double ndl = -(nr[0] * rel[0] + nr[1] * rel[1] + nr[2] * rel[2]) / rl;
    if (ndl < c->o.ndl_min)
        ndl = c->o.ndl_min;
    double bias = c->o.bias_scale * 1.4142135623730951 * z * m->tan_half / ((double)c->S * ndl);
    /* the shared end q': no closer to the light than halfway, so that a ray
     * always has depth to run through */
    double ze = z - bias;
    if (ze < c->L + 0.5 * (z - c->L))
        ze = c->L + 0.5 * (z - c->L);
    double qe[3];
    for (int a3 = 0; a3 < 3; a3++)
        qe[a3] = m->eye[a3] + (q[a3] - m->eye[a3]) * (ze / z);
    double eu, ev, ez;
    sl_softmap_project(m, qe, &eu, &ev, &ez);

    /* 3.6: bounds over the region every ray crosses, refined (eq. 3.3) */
    struct sl_softmap_texel Q = c->global;
    double Dreg = c->L;                                  /* Q holds for depths >= Dreg */
    double D = fmax(c->L, (double)Q.near_min);           /* nothing can be hit nearer */
    if (!c->o.no_classify) {
        for (int it = 0; it < c->o.class_iters && (double)Q.near_min <= ze * (1.0 + EPS); it++) {
            double bb[4];
            region_at(c, qe, ze, D, bb);
            Q = query_rect(c, bb[0], bb[1], bb[2], bb[3], &k->lookups);
            Dreg = D;
            D = fmax(D, (double)Q.near_min);
        }
        if ((double)Q.near_min > ze * (1.0 + EPS) || (double)Q.far_max < Dreg * (1.0 - EPS)) {
            /* no layer can block a ray; the back-face rule still does */
            k->lit++;
            return front_facing(c, x, y, q, nr);
        }
        /* with the third layer a ray between the layers may pass (3.6: the
         * umbra test "becomes invalid when using three depth maps") */
        const double dh = fmax((double)Q.near_max, Dreg);
        const int umbra = !c->eye && (c->o.curtis_umbra ? (double)Q.near_max <= ze
                                                        : dh <= ze && (double)Q.far_min >= dh);
        if (umbra) {
            k->umbra++;
            return 0.0f;
        }
    }
    /* 3.7: the end of every ray inside a solid: one lookup, all rays;
     * with the third layer, not where the camera sees the end (in front of
     * its own receiver: the hollows of 3.4 are what it is for) */
    if (!c->o.no_accel) {
        struct sl_softmap_texel t = fetch(c, 0, (int)floor(eu), (int)floor(ev));
        k->lookups++;
        if (may_hit(ze, ze, &t) && !(c->eye && eye_free(c, qe, k))) {
            k->endpoint++;
            return 0.0f;
        }
    }

    const int r = c->o.grid, nrays = r * r;
    int visible = 0;
    for (int s = 0; s < nrays; s++) {
        double su, sv, p[3];
        sample_uv(c, x, y, s, r, &su, &sv);
        sl_area_point(a, su, sv, p);
        k->rays++;
        /* 3.7: leaving the surface on its back side */
        if (nr[0] * (p[0] - q[0]) + nr[1] * (p[1] - q[1]) + nr[2] * (p[2] - q[2]) <= 0.0) {
            k->backface++;
            continue;
        }
        double pu, pv, pz;
        sl_softmap_project(m, p, &pu, &pv, &pz);
        struct tray ray = {pu, pv, eu, ev, 1.0 / c->L, 1.0 / ze};
        double s0, s1;
        if (!ray_clip(&ray, (double)c->S, &s0, &s1)) {
            visible++;
            continue;
        }
        if (!c->o.no_accel) {
            /* shorten to the depths that can hold a hit, z_near_min to
             * z_far_max of the pixel's region; then the ray's own region
             * (the box of its projection) may prove it lit, or shorten it
             * again */
            double ds = D / (1.0 + EPS), de = fmin(ze, (double)Q.far_max / (1.0 - EPS));
            int lit = !shorten(&ray, c->L, ze, ds, de, &s0, &s1);
            if (!lit) {
                struct tray sub = ray_sub(&ray, s0, s1);
                struct sl_softmap_texel t = query_rect(c, sub.ax, sub.ay, sub.bx, sub.by, &k->lookups);
                lit = !may_hit(ray_depth(&sub, 0.0), ray_depth(&sub, 1.0), &t) ||
                      !shorten(&ray, c->L, ze, (double)t.near_min / (1.0 + EPS),
                               (double)t.far_max / (1.0 - EPS), &s0, &s1);
            }
            if (lit) {
                k->region++;
                visible++;
                continue;
            }
        }
        struct tray sub = ray_sub(&ray, s0, s1);
        uint64_t lk = 0;
        int hit;
        if (c->o.search == SL_SOFTMC_LINEAR) {
            /* the depth step of the whole ray, whatever was cut off */
            const double len = fmax(fabs(ray.bx - ray.ax), fabs(ray.by - ray.ay));
            const double n = len > c->o.step_texels ? ceil(len / c->o.step_texels) : 1.0;
            hit = search_linear(c, &sub, (ze - c->L) / n, &lk, k);
        } else
            hit = search_hier(c, &sub, &lk, &k->capped);
        k->lookups += lk;
        k->lk_search += lk;
        k->searched++;
        k->hit += (uint64_t)hit;
        visible += !hit;
    }
    return (float)visible / (float)nrays;
}

enum sl_err sl_softmc_run(const struct sl_softmap *m, const struct sl_view *v, const struct sl_softmc_desc *desc,
                          struct sl_softmc_result *out, struct sl_diag *d)
{
    const struct sl_softmap_nbuf *nb = m->nbuf;
    memset(out, 0, sizeof *out);
    struct ctx c;
    memset(&c, 0, sizeof c);
    sl_softmc_defaults(desc, &c.o);
    if (!nb || !nb->t || nb->size != m->size)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "N-buffer not built for this map");
    if (c.o.grid > 64 || c.o.layers > 3 || c.o.search < 0 || c.o.search > SL_SOFTMC_LINEAR)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL,
                       "soft_mc: grid %d (at most 64), layers %d (1, 2 or 3), search %d", c.o.grid, c.o.layers,
                       c.o.search);
    if (c.o.layers == 3 && c.o.search != SL_SOFTMC_LINEAR)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "soft_mc: layers 3 (the camera's depth, 3.4) needs the "
                       "linear search");
    c.m = m;
    c.nb = nb;
    c.v = v;
    c.S = m->size;
    c.two = c.o.layers >= 2;
    c.eye = c.o.layers == 3;
    if (c.eye) {
        /* the camera at -R^T t of view = [R | t]; clip = proj x view */
        for (int a = 0; a < 3; a++)
            c.cam[a] = -((double)v->view[a][0] * v->view[3][0] + (double)v->view[a][1] * v->view[3][1] +
                         (double)v->view[a][2] * v->view[3][2]);
        for (int col = 0; col < 4; col++)
            for (int row = 0; row < 4; row++) {
                double acc = 0.0;
                for (int k = 0; k < 4; k++)
                    acc += (double)v->proj[k][row] * (double)v->view[col][k];
                c.clip[col][row] = acc;
            }
    }
    c.L = m->light_depth;
    c.global = fetch(&c, nb->levels - 1, 0, 0);
    out->w = v->w;
    out->h = v->h;
    const size_t n = (size_t)v->w * (size_t)v->h;
    out->vis = sl_calloc(n, sizeof(float));
    if (!out->vis)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "soft_mc result %dx%d", v->w, v->h);
    const int threads = c.o.threads > 0 ? c.o.threads : omp_get_max_threads();
    struct counts tot;
    memset(&tot, 0, sizeof tot);
    uint64_t pixels = 0;
    double t0 = sl_now();
#pragma omp parallel num_threads(threads)
    {
        struct counts k;
        memset(&k, 0, sizeof k);
        uint64_t px = 0;
#pragma omp for schedule(dynamic, 2)
        for (int y = 0; y < v->h; y++)
            for (int x = 0; x < v->w; x++) {
                const size_t i = (size_t)y * (size_t)v->w + (size_t)x;
                if (!v->tri[i])
                    continue;
                px++;
                out->vis[i] = pixel(&c, x, y, i, &k);
            }
#pragma omp critical
        {
            pixels += px;
            tot.unlit += k.unlit; tot.lit += k.lit; tot.umbra += k.umbra; tot.endpoint += k.endpoint;
            tot.rays += k.rays; tot.backface += k.backface; tot.region += k.region;
            tot.searched += k.searched; tot.hit += k.hit; tot.lookups += k.lookups;
            tot.lk_search += k.lk_search; tot.capped += k.capped;
            tot.eye_tests += k.eye_tests; tot.eye_seen += k.eye_seen; tot.eye_outside += k.eye_outside;
        }
    }
    struct sl_softmc_stats *st = &out->st;
    st->ms_trace = 1e3 * (sl_now() - t0);
    st->pixels = pixels;
    st->px_unlit = tot.unlit;
    st->px_lit = tot.lit;
    st->px_umbra = tot.umbra;
    st->px_endpoint = tot.endpoint;
    st->rays = tot.rays;
    st->rays_backface = tot.backface;
    st->rays_region = tot.region;
    st->rays_searched = tot.searched;
    st->rays_hit = tot.hit;
    st->lookups = tot.lookups;
    st->lookups_search = tot.lk_search;
    st->capped = tot.capped;
    st->eye_tests = tot.eye_tests;
    st->eye_seen = tot.eye_seen;
    st->eye_outside = tot.eye_outside;
    if (c.o.blur_radius > 0) {
        out->vis_blur = sl_calloc(n, sizeof(float));
        if (!out->vis_blur) {
            sl_softmc_result_free(out);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "soft_mc blur %dx%d", v->w, v->h);
        }
        double t1 = sl_now();
        enum sl_err e = sl_softmc_blur(v, out->vis, out->vis_blur, c.o.blur_radius, c.o.blur_sigma,
                                       c.o.blur_depth_k, d);
        st->ms_blur = 1e3 * (sl_now() - t1);
        if (e) {
            sl_softmc_result_free(out);
            return e;
        }
    }
    return SL_OK;
}

/* ---- depth-sensitive blur ---------------------------------------------- */

/* One pass along x (dx = 1) or y (dx = 0): background pixels neither give
 * nor take; weights Gaussian / (1 + k |depth difference|), normalised. */
static void blur_pass(const struct sl_view *v, const float *eye, const float *in, float *out, int dx,
                      int radius, const double *g, double k)
{
    const int W = v->w, H = v->h;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const size_t i = (size_t)y * (size_t)W + (size_t)x;
            if (!v->tri[i]) {
                out[i] = 0.0f;
                continue;
            }
            double sw = 0.0, sv = 0.0;
            for (int o = -radius; o <= radius; o++) {
                int xx = dx ? x + o : x, yy = dx ? y : y + o;
                if (xx < 0 || yy < 0 || xx >= W || yy >= H)
                    continue;
                const size_t j = (size_t)yy * (size_t)W + (size_t)xx;
                if (!v->tri[j])
                    continue;
                double w = g[o < 0 ? -o : o] / (1.0 + k * fabs((double)eye[j] - (double)eye[i]));
                sw += w;
                sv += w * (double)in[j];
            }
            out[i] = (float)(sv / sw);   /* sw >= g[0] > 0: the centre counts */
        }
}

enum sl_err sl_softmc_blur(const struct sl_view *v, const float *in, float *out, int radius, double sigma,
                           double depth_k, struct sl_diag *d)
{
    const size_t n = (size_t)v->w * (size_t)v->h;
    if (radius <= 0) {
        memcpy(out, in, n * sizeof *out);
        return SL_OK;
    }
    if (sigma <= 0.0)
        sigma = 0.5 * radius;
    float *eye = sl_calloc(n, sizeof(float));
    float *tmp = sl_calloc(n, sizeof(float));
    double *g = sl_calloc((size_t)radius + 1, sizeof(double));
    if (!eye || !tmp || !g) {
        free(eye);
        free(tmp);
        free(g);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "blur %dx%d", v->w, v->h);
    }
    for (int o = 0; o <= radius; o++)
        g[o] = exp(-0.5 * (double)o * (double)o / (sigma * sigma));
    /* eye-space depth: the distance along the camera's axis */
    for (size_t i = 0; i < n; i++) {
        if (!v->tri[i])
            continue;
        const float *p = v->pos + 3 * i;
        eye[i] = -(v->view[0][2] * p[0] + v->view[1][2] * p[1] + v->view[2][2] * p[2] + v->view[3][2]);
    }
    blur_pass(v, eye, in, tmp, 1, radius, g, depth_k);
    blur_pass(v, eye, tmp, out, 0, radius, g, depth_k);
    free(eye);
    free(tmp);
    free(g);
    return SL_OK;
}

void sl_softmc_result_free(struct sl_softmc_result *r)
{
    if (!r)
        return;
    free(r->vis);
    free(r->vis_blur);
    r->vis = r->vis_blur = NULL;
}
