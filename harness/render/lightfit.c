/*
 * lightfit.c — see lightfit.h. Invariant: every receiver and every triangle
 * able to shadow one lies inside the box (tests/test_lightfit.c checks it).
 */
#define _DEFAULT_SOURCE
#include "lightfit.h"
#include <cglm/clipspace/ortho_rh_zo.h>
#include <cglm/clipspace/persp_rh_zo.h>
#include <assert.h>
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* A view from eye looking along dir. */
static void view_along(const float eye_in[3], const float dir[3], mat4 view)
{
    vec3 eye = {eye_in[0], eye_in[1], eye_in[2]}, d, up = {0, 1, 0};
    glm_vec3_copy((float *)dir, d);
    /* any up not parallel to the light: the axis least aligned with it */
    float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]);
    if (ay >= ax && ay >= az) {
        up[1] = 0.0f;
        if (ax <= az) up[0] = 1.0f; else up[2] = 1.0f;
    }
    glm_look(eye, d, up, view);
}

void sl_light_view(const float dir[3], mat4 view)
{
    const float origin[3] = {0.0f, 0.0f, 0.0f};
    view_along(origin, dir, view);
}

static void to_light(const mat4 view, const float p[3], float out[3])
{
    vec4 w, c;
    sl_point4(p, w);   /* one 16-byte store (frame.h): perf put a third of the fit on the stall */
    glm_mat4_mulv((vec4 *)view, w, c);
    out[0] = c[0];
    out[1] = c[1];
    out[2] = -c[2];   /* depth grows away from the light */
}

/* An area light as a point at its centre: a perspective frustum from the
 * centre along the light's normal. Across the axis it bounds the receivers'
 * tangents x/d, y/d (every receiver is on the emitting side, d > 0: the
 * G-buffer's classes say so) up to SL_POINT_MAX_TAN: one perspective map
 * cannot reach the light's own plane (receivers there need an infinite
 * field of view, and spread over a wide one the texels grow without bound),
 * so receivers more than atan(8) = 82.9 degrees off the axis in x or y are
 * left outside the map (counted in n_outside): the exact methods decide
 * them by tracing, the others read the map's border (a cube map would be
 * the full answer). Its far plane is twice the farthest receiver's depth
 * (below), its near plane the nearest receiver or the nearest point of a
 * caster whose tangents overlap theirs (a shadow ray runs from the receiver
 * to the centre, so its tangents stay the receiver's and its depth falls
 * toward 0: only such triangles, between the light and the receiver, can
 * block it).
 *
 * The conservative layers' exact per-texel tests need window coordinates
 * with float precision to spare. A triangle with a vertex closer to the
 * light's plane than far / 4096 (or behind it), or beyond a guard band of
 * one frustum width on each side (NDC beyond +-3), is "unmapped": listed
 * here, tested on the CPU by every method that claims light from those
 * layers, and dropped by their geometry shaders, which use looser bounds
 * (w < far / 8192, NDC beyond +-5) so that float rounding between this fit
 * and the GPU never loses a triangle from both. A triangle wholly behind
 * the plane, wholly beyond every receiver, or (in front) projecting outside
 * the receivers' tangents cannot block a receiver's ray and is ignored.
 * The near plane comes down to the nearest mapped caster or receiver, and
 * to the nearest point of an unmapped caster inside the receivers' pyramid
 * (pyramid_min_depth: the only part that can block their rays), never below
 * far / 4096: window depth is about 1 - near / d, so at depth d its float
 * steps are d / near * 2^-24 of d; with near / d >= 1/2048 that is at worst
 * 2^-13 of the depth, enough to tell surfaces apart. The plain layers clip
 * what lies nearer (only within far / 4096 of the light); the conservative
 * ones list it (above). */
#define SL_POINT_MAX_TAN 8.0f
#define SL_POINT_WMIN_DIV 4096.0f
#define SL_POINT_GUARD_CPU 3.0f
#define SL_POINT_GUARD_GPU 5.0f

/* ---- blocks: the fit on several threads, bit for bit the serial fit ----
 * The loops over pixels and over triangles run in blocks whose bounds
 * depend on the input's size only, never on the thread count; each block
 * fills a slot of its own, and the slots are combined in block order on
 * one thread. Every combination is exact: counts are integers; a least
 * (greatest) value is kept with the serial loop's own strict test
 * (`if (x < lo) lo = x`), which keeps the first of equal values in loop
 * order (+0 before a later -0) and passes NaN over: taken per block, then
 * over the blocks in order, it keeps the very value the serial loop keeps.
 * The lists of unmapped triangles are joined in block order, so they stay
 * in triangle order. Nothing is summed in floating point. */
#define FIT_BLOCKS 256          /* at most: the slots live on the stack */
#define FIT_PX_MIN 32768        /* pixels per block, at least */
#define FIT_TRI_MIN 2048        /* triangles per block, at least */

struct fit_blocks {
    size_t n, len;
    int nb;
};

static struct fit_blocks fit_blocks(size_t n, size_t min_len)
{
    size_t len = (n + FIT_BLOCKS - 1) / FIT_BLOCKS;
    if (len < min_len)
        len = min_len;
    struct fit_blocks b = {n, len, (int)((n + len - 1) / len)};
    return b;
}

static size_t blk_end(const struct fit_blocks *b, int i)
{
    size_t e = (size_t)(i + 1) * b->len;
    return e < b->n ? e : b->n;
}

static int fit_threads(int threads)
{
    return threads > 0 ? threads : omp_get_max_threads();
}

/* a block of pixels: bounds and counts */
struct px_acc {
    float lo[3], hi[3];
    uint32_t in, out;
};

static void px_acc_init(struct px_acc *a)
{
    for (int k = 0; k < 3; k++) {
        a->lo[k] = FLT_MAX;
        a->hi[k] = -FLT_MAX;
    }
    a->in = a->out = 0;
}

static inline void px_acc_take(struct px_acc *a, const float t[3])
{
    for (int k = 0; k < 3; k++) {
        if (t[k] < a->lo[k]) a->lo[k] = t[k];
        if (t[k] > a->hi[k]) a->hi[k] = t[k];
    }
    a->in++;
}

static void px_acc_join(struct px_acc *all, const struct px_acc *a, int nb)
{
    px_acc_init(all);
    for (int b = 0; b < nb; b++) {
        for (int k = 0; k < 3; k++) {
            if (a[b].lo[k] < all->lo[k]) all->lo[k] = a[b].lo[k];
            if (a[b].hi[k] > all->hi[k]) all->hi[k] = a[b].hi[k];
        }
        all->in += a[b].in;
        all->out += a[b].out;
    }
}

/* a block of triangles: the least depth, casters, unmapped ones */
struct tri_acc {
    float near;
    uint32_t casters, n_un, cap;
    uint32_t *un;
    int oom;
};

static void tri_acc_init(struct tri_acc *a)
{
    memset(a, 0, sizeof *a);
    a->near = FLT_MAX;
}

static void tri_acc_unmapped(struct tri_acc *a, uint32_t t)
{
    if (a->n_un == a->cap && !a->oom) {
        uint32_t *g = realloc(a->un, (a->cap ? 2u * a->cap : 8u) * sizeof *g);
        if (g) {
            a->un = g;
            a->cap = a->cap ? 2u * a->cap : 8u;
        } else {
            /* counted but not listed: every conservative lit claim is withheld */
            a->oom = 1;
            free(a->un);
            a->un = NULL;
        }
    }
    if (!a->oom)
        a->un[a->n_un] = t;
    a->n_un++;
}

/* The blocks' results in block order: near from `near` down, the casters
 * and unmapped triangles into out (the list NULL with the count kept when
 * a block or the joined list had no memory, as lightfit.h says). */
static float tri_acc_join(struct tri_acc *a, int nb, float near, struct sl_light_box *out)
{
    uint32_t n_un = 0;
    int oom = 0;
    for (int b = 0; b < nb; b++) {
        if (a[b].near < near)
            near = a[b].near;
        out->n_casters += a[b].casters;
        n_un += a[b].n_un;
        oom |= a[b].oom;
    }
    uint32_t *list = n_un && !oom ? malloc(n_un * sizeof *list) : NULL;
    for (int b = 0, at = 0; b < nb; b++) {
        if (list && a[b].n_un) {
            memcpy(list + at, a[b].un, a[b].n_un * sizeof *list);
            at += (int)a[b].n_un;
        }
        free(a[b].un);
    }
    out->n_unmapped = n_un;
    out->unmapped = list;
    return near;
}

/* The least depth of the part of triangle t inside the pyramid of
 * tangents lo..hi in front of the light (x/d in [lo0, hi0], y/d in
 * [lo1, hi1], d >= 0), light space, double; FLT_MAX when no part is
 * inside. Sutherland-Hodgman against the five planes through the eye. */
static float pyramid_min_depth(const struct sl_scene *s, uint32_t t, const mat4 view, const float lo[2],
                               const float hi[2])
{
    double poly[2][9][3];
    int np = 3, cur = 0;
    for (int k = 0; k < 3; k++) {
        float q[3];
        to_light(view, s->pos + 3 * s->idx[3 * t + k], q);
        for (int j = 0; j < 3; j++)
            poly[0][k][j] = q[j];
    }
    /* plane p: a.x + b.y + c.d >= 0 */
    const double pl[5][3] = {{1, 0, -(double)lo[0]}, {-1, 0, hi[0]}, {0, 1, -(double)lo[1]}, {0, -1, hi[1]},
                             {0, 0, 1}};
    for (int p = 0; p < 5 && np > 0; p++) {
        int nn = 0;
        for (int k = 0; k < np; k++) {
            const double *a = poly[cur][k], *b = poly[cur][(k + 1) % np];
            double fa = pl[p][0] * a[0] + pl[p][1] * a[1] + pl[p][2] * a[2];
            double fb = pl[p][0] * b[0] + pl[p][1] * b[1] + pl[p][2] * b[2];
            if (fa >= 0.0)
                memcpy(poly[!cur][nn++], a, sizeof poly[0][0]);
            if ((fa >= 0.0) != (fb >= 0.0)) {
                double u = fa / (fa - fb);
                for (int j = 0; j < 3; j++)
                    poly[!cur][nn][j] = a[j] + u * (b[j] - a[j]);
                nn++;
            }
        }
        np = nn;
        cur = !cur;
    }
    double dmin = FLT_MAX;
    for (int k = 0; k < np; k++)
        dmin = poly[cur][k][2] < dmin ? poly[cur][k][2] : dmin;
    return (float)dmin;
}

/* fit_points' receivers, pixels [i0, i1): for each of its nf frames, the
 * tangents and depths of the PFL pixels it selects (mask NULL: every one),
 * into a[f * FIT_BLOCKS] */
#define FIT_FRAMES 6

static void point_px(const struct sl_view *v, int nf, const mat4 *view, const uint8_t *mask, const uint8_t *values,
                     size_t i0, size_t i1, struct px_acc *a)
{
    /* the matrices and the bounds in locals: written through `a`, they
     * would be reloaded for every pixel (a may alias the views); the same
     * arithmetic, so the same bits */
    mat4 V[FIT_FRAMES];
    memcpy(V, view, (size_t)nf * sizeof *V);
    struct px_acc l[FIT_FRAMES];
    for (int f = 0; f < nf; f++)
        px_acc_init(&l[f]);
    for (size_t i = i0; i < i1; i++) {
        if (v->cls[i] != SL_C_PFL)
            continue;
        for (int f = 0; f < nf; f++) {
            if (mask && mask[i] != values[f])
                continue;
            float q[3];
            to_light(V[f], v->pos + 3 * i, q);
            if (!(q[2] > 0.0f)) {
                /* behind the frame's plane: none under an area light or a
                 * spot (sl_point_faces); left outside for a caller whose
                 * selected pixels are not all in front */
                l[f].out++;
                continue;
            }
            float t[3] = {q[0] / q[2], q[1] / q[2], q[2]};
            if (!(fabsf(t[0]) <= SL_POINT_MAX_TAN && fabsf(t[1]) <= SL_POINT_MAX_TAN)) {
                l[f].out++;
                continue;
            }
            px_acc_take(&l[f], t);
        }
    }
    for (int f = 0; f < nf; f++)
        a[(size_t)f * FIT_BLOCKS] = l[f];
}

/* fit_point's casters, triangles [t0, t1), against the receivers'
 * pyramid lo..hi (tangents; depth up to hi[2]) */
static void point_tri(const struct sl_scene *s, const mat4 view, const float lo[3], const float hi[3], float dmin,
                      uint32_t t0, uint32_t t1, struct tri_acc *a)
{
    tri_acc_init(a);
    for (uint32_t t = t0; t < t1; t++) {
        int behind = 0, close = 0, outside = 0;
        float dlo = FLT_MAX, dhi = -FLT_MAX, xlo = FLT_MAX, xhi = -FLT_MAX, ylo = FLT_MAX, yhi = -FLT_MAX;
        for (int k = 0; k < 3; k++) {
            float q[3];
            to_light(view, s->pos + 3 * s->idx[3 * t + k], q);
            float d = q[2];
            behind |= !(d > 0.0f);
            close |= !(d >= dmin);
            dlo = fminf(dlo, d);
            dhi = fmaxf(dhi, d);
            if (d > 0.0f) {
                float tt[2] = {q[0] / d, q[1] / d};
                xlo = fminf(xlo, tt[0]);
                xhi = fmaxf(xhi, tt[0]);
                ylo = fminf(ylo, tt[1]);
                yhi = fmaxf(yhi, tt[1]);
                for (int j = 0; j < 2; j++) {
                    float ndc = 2.0f * (tt[j] - lo[j]) / (hi[j] - lo[j]) - 1.0f;
                    outside |= !(fabsf(ndc) <= SL_POINT_GUARD_CPU);
                }
            }
        }
        if (!(dhi > 0.0f) || dlo > hi[2])
            continue;   /* wholly behind the light, or beyond every receiver */
        if (!behind && (xhi < lo[0] || xlo > hi[0] || yhi < lo[1] || ylo > hi[1]))
            continue;   /* in front, projecting beside every receiver */
        a->casters++;
        if (close || outside) {
            tri_acc_unmapped(a, t);
            /* The plain layers still draw it, GL clipping it at the near
             * plane: the near plane comes down to the nearest point of its
             * part that can block a receiver's ray (inside the receivers'
             * pyramid), so a caster crossing the light's plane (a lamp's
             * pole beside a spot) keeps that part in those layers. Not to
             * its dlo: a floor crossing a cube face's plane reaches depth 0
             * only far outside the face's receivers' tangents, and would
             * pull every face's near plane to dmin for nothing. */
            float dc = pyramid_min_depth(s, t, view, lo, hi);
            if (dc < a->near)
                a->near = dc;
            continue;
        }
        if (dlo < a->near)
            a->near = dlo;
    }
}

/* nf frames from the light at c, frame f along axes[f] over the pixels
 * with mask[i] == values[f] (mask NULL: every PFL pixel), into outs[f]
 * (zeroed): each exactly as fitted alone, but every pass over the pixels
 * and over the triangles made once for all of them (a point light's six
 * cube faces: one read of the G-buffer instead of six, and two parallel
 * regions instead of twelve — at each region's end a thread waits for the
 * others, spinning). */
static void fit_points(const struct sl_scene *s, const struct sl_view *v, const float c[3], int nf,
                       const float (*axes)[3], const uint8_t *mask, const uint8_t *values, int size, int guard,
                       int threads, struct sl_light_box *const *outs)
{
    mat4 views[FIT_FRAMES];
    for (int f = 0; f < nf; f++) {
        struct sl_light_box *out = outs[f];
        view_along(c, axes[f], out->view);
        out->persp = 1;
        memcpy(out->eye, c, sizeof out->eye);
        memcpy(views[f], out->view, sizeof views[f]);
    }
    threads = fit_threads(threads);
    const struct fit_blocks pb = fit_blocks((size_t)v->w * (size_t)v->h, FIT_PX_MIN);
    static_assert(FIT_FRAMES * FIT_BLOCKS * sizeof(struct px_acc) <= 65536, "the blocks' slots live on the stack");
    struct px_acc pa[FIT_FRAMES * FIT_BLOCKS];
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && pb.nb > 1)
    for (int b = 0; b < pb.nb; b++)
        point_px(v, nf, (const mat4 *)views, mask, values, (size_t)b * pb.len, blk_end(&pb, b), pa + b);
    float lo[FIT_FRAMES][3], hi[FIT_FRAMES][3], far[FIT_FRAMES], dmin[FIT_FRAMES];
    for (int f = 0; f < nf; f++) {
        struct sl_light_box *out = outs[f];
        struct px_acc all;
        px_acc_join(&all, pa + (size_t)f * FIT_BLOCKS, pb.nb);
        memcpy(lo[f], all.lo, sizeof lo[f]);
        memcpy(hi[f], all.hi, sizeof hi[f]);
        out->n_receivers += all.in;
        out->n_outside += all.out;
        if (out->n_receivers == 0) {
            /* nothing lit inside: no lookup will be trusted; any valid frustum */
            lo[f][0] = lo[f][1] = -1.0f;
            hi[f][0] = hi[f][1] = 1.0f;
            lo[f][2] = hi[f][2] = 1.0f;
        }
        /* tangents: 1e-4 of the extent, at least 1e-6 absolute */
        for (int k = 0; k < 2; k++) {
            float m = fmaxf(1e-4f * (hi[f][k] - lo[f][k]), 1e-6f);
            lo[f][k] -= m;
            hi[f][k] += m;
        }
        /* a cube face's guard band (sl_light_fit_face): `guard` texels of the
         * final map on each side beyond the receivers, widened before the
         * casters are chosen so the band's casters count toward the near plane
         * as the receivers' do: the band's texels hold the geometry there, not
         * a clipped or empty border */
        if (guard > 0 && size > 2 * guard && out->n_receivers > 0)
            for (int k = 0; k < 2; k++) {
                float t = (hi[f][k] - lo[f][k]) / (float)(size - 2 * guard);
                lo[f][k] -= (float)guard * t;
                hi[f][k] += (float)guard * t;
            }
        /* far at twice the farthest receiver: window depth 1 - z there is then
         * about near / (2 d), clear of the cleared 1 by many float steps (a 1e-4
         * margin, as the box has, would be near/d * 1e-4: below one step when
         * near is small); the precision of depth barely depends on far */
        far[f] = 2.0f * hi[f][2];
        dmin[f] = far[f] / SL_POINT_WMIN_DIV;
    }
    const struct fit_blocks tb = fit_blocks(s->nt, FIT_TRI_MIN);
    struct tri_acc ta[FIT_FRAMES * FIT_BLOCKS];
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && tb.nb > 1)
    for (int b = 0; b < tb.nb; b++)
        for (int f = 0; f < nf; f++)
            point_tri(s, views[f], lo[f], hi[f], dmin[f], (uint32_t)((size_t)b * tb.len), (uint32_t)blk_end(&tb, b),
                      &ta[(size_t)f * FIT_BLOCKS + (size_t)b]);
    for (int f = 0; f < nf; f++) {
        struct sl_light_box *out = outs[f];
        float near = tri_acc_join(ta + (size_t)f * FIT_BLOCKS, tb.nb, lo[f][2], out);
        near = fmaxf(near * (1.0f - 1e-4f), dmin[f]);
        lo[f][2] = near;
        hi[f][2] = far[f];
        memcpy(out->lo, lo[f], sizeof lo[f]);
        memcpy(out->hi, hi[f], sizeof hi[f]);
        out->wmin = dmin[f] * 0.5f;
        out->guard = SL_POINT_GUARD_GPU;
        glm_frustum_rh_zo(lo[f][0] * near, hi[f][0] * near, lo[f][1] * near, hi[f][1] * near, near, far[f],
                          out->proj);
        glm_mat4_mul(out->proj, out->view, out->vp);
    }
}

static void fit_point(const struct sl_scene *s, const struct sl_view *v, const float c[3], const float axis[3],
                      const uint8_t *mask, uint8_t value, int size, int guard, int threads,
                      struct sl_light_box *out)
{
    const float ax[1][3] = {{axis[0], axis[1], axis[2]}};
    fit_points(s, v, c, 1, ax, mask, &value, size, guard, threads, &out);
}

/* fit_dir's receivers, pixels [i0, i1), in light space */
static void dir_px(const struct sl_view *v, const mat4 view, const uint8_t *mask, uint8_t value, size_t i0,
                   size_t i1, struct px_acc *a)
{
    mat4 V;   /* locals, as in point_px */
    memcpy(V, view, sizeof V);
    struct px_acc l;
    px_acc_init(&l);
    for (size_t i = i0; i < i1; i++) {
        if (v->cls[i] != SL_C_PFL || (mask && mask[i] != value))
            continue;
        float q[3];
        to_light(V, v->pos + 3 * i, q);
        px_acc_take(&l, q);
    }
    *a = l;
}

/* the scene's vertices [i0, i1), in light space */
static void dir_vtx(const struct sl_scene *s, const mat4 view, size_t i0, size_t i1, struct px_acc *a)
{
    px_acc_init(a);
    for (size_t i = i0; i < i1; i++) {
        float q[3];
        to_light(view, s->pos + 3 * i, q);
        px_acc_take(a, q);
    }
}

/* fit_dir's casters, triangles [t0, t1): over the receivers' cross-section
 * lo..hi, not wholly beyond the farthest receiver */
static void dir_tri(const struct sl_scene *s, const mat4 view, const float lo[3], const float hi[3], uint32_t t0,
                    uint32_t t1, struct tri_acc *a)
{
    tri_acc_init(a);
    for (uint32_t t = t0; t < t1; t++) {
        float tl[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, th[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
        for (int c = 0; c < 3; c++) {
            float q[3];
            to_light(view, s->pos + 3 * s->idx[3 * t + c], q);
            for (int k = 0; k < 3; k++) {
                if (q[k] < tl[k]) tl[k] = q[k];
                if (q[k] > th[k]) th[k] = q[k];
            }
        }
        if (th[0] < lo[0] || tl[0] > hi[0] || th[1] < lo[1] || tl[1] > hi[1] || tl[2] > hi[2])
            continue;
        a->casters++;
        if (tl[2] < a->near)
            a->near = tl[2];
    }
}

/* A directional light's box, fitted to the PFL pixels i with mask[i] ==
 * value (mask NULL: every one). */
static void fit_dir(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                    int threads, struct sl_light_box *out)
{
    sl_light_view(s->light_dir, out->view);
    threads = fit_threads(threads);
    const struct fit_blocks pb = fit_blocks((size_t)v->w * (size_t)v->h, FIT_PX_MIN);
    struct px_acc pa[FIT_BLOCKS], all;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && pb.nb > 1)
    for (int b = 0; b < pb.nb; b++)
        dir_px(v, out->view, mask, value, (size_t)b * pb.len, blk_end(&pb, b), &pa[b]);
    px_acc_join(&all, pa, pb.nb);
    out->n_receivers += all.in;
    if (out->n_receivers == 0) {
        /* nothing faces the light: no lookup will happen; fit the scene
         * (its bounds go on from the receivers' empty ones, as one loop) */
        const struct fit_blocks vb = fit_blocks(s->nv, FIT_PX_MIN);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && vb.nb > 1)
        for (int b = 0; b < vb.nb; b++)
            dir_vtx(s, out->view, (size_t)b * vb.len, blk_end(&vb, b), &pa[b]);
        px_acc_join(&all, pa, vb.nb);
    }
    float lo[3], hi[3];
    memcpy(lo, all.lo, sizeof lo);
    memcpy(hi, all.hi, sizeof hi);
    const struct fit_blocks tb = fit_blocks(s->nt, FIT_TRI_MIN);
    struct tri_acc ta[FIT_BLOCKS];
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && tb.nb > 1)
    for (int b = 0; b < tb.nb; b++)
        dir_tri(s, out->view, lo, hi, (uint32_t)((size_t)b * tb.len), (uint32_t)blk_end(&tb, b), &ta[b]);
    float near = tri_acc_join(ta, tb.nb, lo[2], out);
    lo[2] = near;
    /* Margins: 1e-4 of the extent (at least 1e-6 of the coordinates' size)
     * so points on the boundary are strictly inside after float rounding;
     * the depth margin also keeps the farthest receiver below the cleared 1. */
    for (int k = 0; k < 3; k++) {
        float ext = hi[k] - lo[k];
        float mag = fmaxf(fabsf(lo[k]), fabsf(hi[k]));
        float m = fmaxf(1e-4f * ext, 1e-6f * mag + 1e-6f);
        lo[k] -= m;
        hi[k] += m;
    }
    memcpy(out->lo, lo, sizeof lo);
    memcpy(out->hi, hi, sizeof hi);
    glm_ortho_rh_zo(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], out->proj);
    glm_mat4_mul(out->proj, out->view, out->vp);
}

/* ---- stabilised frames (lightfit.h, sl_light_fit_stable) ----
 * Kept apart from the tight fit above so either can change alone. The
 * sphere is centred on the frustum's corners' centroid (on its axis, at
 * (near + far) / 2), its radius the farthest corner's distance: not the
 * smallest enclosing sphere, but the usual engine choice and rigid with the
 * camera, which is what keeps the size fixed. */
/* the stable box's receivers, pixels [i0, i1): inside its square or not */
static void stable_px(const struct sl_view *v, const mat4 view, const float lo[2], const float hi[2], size_t i0,
                      size_t i1, struct px_acc *a)
{
    mat4 V;   /* locals, as in point_px */
    memcpy(V, view, sizeof V);
    const float x0 = lo[0], x1 = hi[0], y0 = lo[1], y1 = hi[1];
    uint32_t in = 0, out = 0;
    for (size_t i = i0; i < i1; i++) {
        if (v->cls[i] != SL_C_PFL)
            continue;
        float q[3];
        to_light(V, v->pos + 3 * i, q);
        if (q[0] >= x0 && q[0] <= x1 && q[1] >= y0 && q[1] <= y1)
            in++;
        else
            out++;
    }
    px_acc_init(a);
    a->in = in;
    a->out = out;
}

void sl_light_fit_stable_mt(const struct sl_scene *s, const struct sl_view *v, const struct sl_fit_opts *o, int size,
                            struct sl_light_box *out, int threads)
{
    if (o->fit != SL_FIT_SPHERE || s->light.type == SL_LIGHT_AREA) {
        sl_light_fit_mt(s, v, out, threads);
        return;
    }
    threads = fit_threads(threads);
    memset(out, 0, sizeof *out);
    sl_light_view(s->light_dir, out->view);
    const struct sl_viewpoint *vp = &s->vp[v->vp];
    const double aspect = (double)v->w / (double)v->h;
    const double hf = vp->zfar * tan(0.5 * vp->fov_deg * M_PI / 180.0), wf = hf * aspect;
    const double half_depth = 0.5 * ((double)vp->zfar - vp->znear);
    double radius = sqrt(half_depth * half_depth + hf * hf + wf * wf);
    radius = ceil(radius * 16.0) / 16.0;   /* bit-stable from view to view */
    float centre[3], c[3];
    for (int k = 0; k < 3; k++)
        centre[k] = (float)(vp->pos[k] + vp->dir[k] * 0.5 * ((double)vp->znear + vp->zfar));
    to_light(out->view, centre, c);
    const double texel = 2.0 * radius / (double)(size - 2);
    double cx = c[0], cy = c[1];
    if (o->snap) {
        cx = floor(cx / texel) * texel;
        cy = floor(cy / texel) * texel;
    }
    float lo[3], hi[3];
    lo[0] = (float)(cx - 0.5 * size * texel);
    hi[0] = (float)(cx + 0.5 * size * texel);
    lo[1] = (float)(cy - 0.5 * size * texel);
    hi[1] = (float)(cy + 0.5 * size * texel);
    /* along the light: the whole scene, with the tight fit's margins. Its
     * bounds by the strict test in blocks (above); fminf/fmaxf, as this
     * loop had them, differ from it only in the sign of a zero bound,
     * which the margin below takes away (+-0 - m = -m), so the box is the
     * same bit for bit. */
    const struct fit_blocks vb = fit_blocks(s->nv, FIT_PX_MIN);
    struct px_acc pa[FIT_BLOCKS], all;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && vb.nb > 1)
    for (int b = 0; b < vb.nb; b++)
        dir_vtx(s, out->view, (size_t)b * vb.len, blk_end(&vb, b), &pa[b]);
    px_acc_join(&all, pa, vb.nb);
    lo[2] = all.lo[2];
    hi[2] = all.hi[2];
    float ext = hi[2] - lo[2], mag = fmaxf(fabsf(lo[2]), fabsf(hi[2]));
    float m = fmaxf(1e-4f * ext, 1e-6f * mag + 1e-6f);
    lo[2] -= m;
    hi[2] += m;
    const struct fit_blocks pb = fit_blocks((size_t)v->w * (size_t)v->h, FIT_PX_MIN);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) if (threads > 1 && pb.nb > 1)
    for (int b = 0; b < pb.nb; b++)
        stable_px(v, out->view, lo, hi, (size_t)b * pb.len, blk_end(&pb, b), &pa[b]);
    px_acc_join(&all, pa, pb.nb);
    out->n_receivers += all.in;
    out->n_outside += all.out;
    out->n_casters = s->nt;
    memcpy(out->lo, lo, sizeof lo);
    memcpy(out->hi, hi, sizeof hi);
    glm_ortho_rh_zo(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], out->proj);
    glm_mat4_mul(out->proj, out->view, out->vp);
}

void sl_cube_faces(const float eye[3], const struct sl_view *v, uint8_t *face, int threads)
{
    const size_t n = (size_t)v->w * (size_t)v->h;
    threads = fit_threads(threads);
    /* each pixel's own face: no order to keep */
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1 && n > FIT_PX_MIN)
    for (size_t i = 0; i < n; i++)
        face[i] = (uint8_t)sl_cube_face_of(eye, v->pos + 3 * i);
}

/* A point light's view as one box (lightfit.h, sl_light_fit): the six
 * faces fitted without a guard band, their counts summed (unmapped
 * triangles are each face's own: none listed here), the matrices those of
 * the face with most receivers. The cube's own frames (harness/render/lightframe.c) are
 * fitted per map size, with their guard band. */
static void fit_cube_summary(const struct sl_scene *s, const struct sl_view *v, int threads,
                             struct sl_light_box *out)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    uint8_t *face = malloc(n ? n : 1);
    int best = -1;
    if (face)
        sl_cube_faces(s->light.pos, v, face, threads);
    struct sl_light_box bx[6], *bp[6];
    float axes[6][3];
    uint8_t values[6];
    for (int f = 0; f < 6; f++) {
        sl_cube_axis(f, axes[f]);
        values[f] = (uint8_t)f;
        memset(&bx[f], 0, sizeof bx[f]);
        bp[f] = &bx[f];
    }
    /* without the selection (no memory) every face sees every PFL pixel: the counts are then the faces' sums */
    fit_points(s, v, s->light.pos, 6, (const float(*)[3])axes, face, values, 0, 0, threads, bp);
    for (int f = 0; f < 6; f++) {
        const struct sl_light_box *b = &bx[f];
        uint32_t r = out->n_receivers, o = out->n_outside, c = out->n_casters;
        if (best < 0 || b->n_receivers > r) {
            memcpy(out->view, b->view, sizeof b->view);
            memcpy(out->proj, b->proj, sizeof b->proj);
            memcpy(out->vp, b->vp, sizeof b->vp);
            memcpy(out->lo, b->lo, sizeof b->lo);
            memcpy(out->hi, b->hi, sizeof b->hi);
            memcpy(out->eye, b->eye, sizeof b->eye);
            out->wmin = b->wmin;
            out->guard = b->guard;
            best = f;
        }
        out->n_receivers = r + b->n_receivers;
        out->n_outside = o + (face ? b->n_outside : 0);
        out->n_casters = c + b->n_casters;
        free(bx[f].unmapped);
    }
    out->persp = 1;
    free(face);
}

void sl_light_fit_mt(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out, int threads)
{
    memset(out, 0, sizeof *out);
    if (s->light.type == SL_LIGHT_AREA)
        fit_point(s, v, s->light.pos, s->light.normal, NULL, 0, 0, 0, threads, out);
    else if (s->light.type == SL_LIGHT_SPOT)
        fit_point(s, v, s->light.pos, s->light.dir, NULL, 0, 0, 0, threads, out);
    else if (s->light.type == SL_LIGHT_POINT)
        fit_cube_summary(s, v, threads, out);
    else
        fit_dir(s, v, NULL, 0, threads, out);
}

void sl_light_fit(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out)
{
    sl_light_fit_mt(s, v, out, 1);
}

void sl_light_fit_stable(const struct sl_scene *s, const struct sl_view *v, const struct sl_fit_opts *o, int size,
                         struct sl_light_box *out)
{
    sl_light_fit_stable_mt(s, v, o, size, out, 1);
}

void sl_light_fit_persp(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const float axis[3],
                        const uint8_t *mask, uint8_t value, struct sl_light_box *out)
{
    memset(out, 0, sizeof *out);
    fit_point(s, v, eye, axis, mask, value, 0, 0, 1, out);
}

void sl_light_fit_face_mt(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const float axis[3],
                          const uint8_t *mask, uint8_t value, int size, int guard, struct sl_light_box *out,
                          int threads)
{
    memset(out, 0, sizeof *out);
    fit_point(s, v, eye, axis, mask, value, size, guard, threads, out);
}

void sl_light_fit_cube_mt(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const uint8_t *face,
                          int size, int guard, struct sl_light_box out[6], int threads)
{
    struct sl_light_box *bp[6];
    float axes[6][3];
    uint8_t values[6];
    for (int f = 0; f < 6; f++) {
        sl_cube_axis(f, axes[f]);
        values[f] = (uint8_t)f;
        memset(&out[f], 0, sizeof out[f]);
        bp[f] = &out[f];
    }
    fit_points(s, v, eye, 6, (const float(*)[3])axes, face, values, size, guard, threads, bp);
}

void sl_light_fit_face(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const float axis[3],
                       const uint8_t *mask, uint8_t value, int size, int guard, struct sl_light_box *out)
{
    sl_light_fit_face_mt(s, v, eye, axis, mask, value, size, guard, out, 1);
}

int sl_light_fit_slice_mt(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                          struct sl_light_box *out, int threads)
{
    memset(out, 0, sizeof *out);
    if (s->light.type == SL_LIGHT_AREA)
        return 0;
    fit_dir(s, v, mask, value, threads, out);
    return 1;
}

int sl_light_fit_slice(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                       struct sl_light_box *out)
{
    return sl_light_fit_slice_mt(s, v, mask, value, out, 1);
}

void sl_zsplit_closed(double n, double f, int k, double *planes)
{
    for (int i = 0; i <= k; i++)
        planes[i] = n * pow(f / n, (double)i / k);
    planes[0] = n;   /* exact ends, whatever pow rounds to */
    planes[k] = f;
}

void sl_zsplit_iterative(double n, double f, int k, double lambda, double *planes)
{
    /* eq. 62, from the far end down: f_k = f; n_i = f_(i-1) =
     * lambda n (f_i / n)^((i-1)/i) + (1 - lambda) f_i / alpha_i; n_1 = n.
     * alpha_i is defined in the thesis's section 4.3.2, outside the seed;
     * we take f_i / alpha_i = n + (f_i - n)(i - 1)/i, the uniform split of
     * [n, f_i] into i equal slices, so that lambda = 0 gives the uniform
     * split of [n, f] (the uniform counterpart of the log term, which is
     * the log split of [n, f_i] into i slices). */
    planes[k] = f;
    for (int i = k; i >= 2; i--) {
        double fi = planes[i];
        double lg = n * pow(fi / n, (double)(i - 1) / i);
        double un = n + (fi - n) * (double)(i - 1) / i;
        planes[i - 1] = lambda * lg + (1.0 - lambda) * un;
    }
    planes[0] = n;
}

void sl_view_depth_range(const struct sl_view *v, float *zmin, float *zmax)
{
    float lo = FLT_MAX, hi = 0.0f;
    size_t n = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < n; i++) {
        if (v->cls[i] == SL_C_BACKGROUND)
            continue;
        float z = sl_view_depth(v, v->pos + 3 * i);
        if (z < lo) lo = z;
        if (z > hi) hi = z;
    }
    if (!(lo <= hi)) {
        lo = 1.0f;
        hi = 2.0f;
    }
    *zmin = lo;
    *zmax = hi;
}

/* LiSPSM (Wimmer, Scherzer, Purgathofer 2004) for a directional light.
 * Light space: y toward the light, z the camera's view direction made
 * perpendicular to the light, x = y cross z. The warp is a perspective
 * along z from a centre C at n_opt in front of the body's near face,
 * under which light rays (parallel to y, at fixed z) stay parallel: the
 * map is then an orthographic view along -y of the warped space, and depth
 * -y/z_c keeps its order along every light ray, so NSM's comparison holds.
 * In clip space, with (x_c, y_c, z_c) relative to C:
 *   X = sx (x_c - ox z_c), Y = sy (1 - oy z_c), Z = sz (-y_c - oz z_c), W = z_c
 * i.e. NDC x = sx (x_c/z_c - ox), y = sy (1/z_c - oy), depth = sz (-y_c/z_c - oz),
 * fitted to the receivers' warped bounds; the depth's near end also to
 * every caster's highest point over the receivers' z range (the warped
 * depth -y/z_c of a point at height y is least at one end of that range).
 * C lies at the camera's x and y in light space (the paper's choice: the
 * warp is centred on the viewer). */
int sl_light_fit_lispsm(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                        double zn, double zf, struct sl_light_box *out, double *nopt)
{
    *nopt = INFINITY;
    if (!sl_light_fit_slice(s, v, mask, value, out) || out->n_receivers == 0)
        return 0;
    /* camera: forward = -(third row of the view matrix), eye = -R^T t */
    double fw[3] = {-v->view[0][2], -v->view[1][2], -v->view[2][2]}, eye[3];
    for (int k = 0; k < 3; k++)
        eye[k] = -(v->view[k][0] * v->view[3][0] + v->view[k][1] * v->view[3][1] + v->view[k][2] * v->view[3][2]);
    double y[3] = {-s->light_dir[0], -s->light_dir[1], -s->light_dir[2]};
    double ly = sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    for (int k = 0; k < 3; k++)
        y[k] /= ly;
    double fy = fw[0] * y[0] + fw[1] * y[1] + fw[2] * y[2], z[3];
    for (int k = 0; k < 3; k++)
        z[k] = fw[k] - fy * y[k];
    double lz = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
    /* sin gamma, gamma the angle between the view and light directions */
    double sing = lz / sqrt(fw[0] * fw[0] + fw[1] * fw[1] + fw[2] * fw[2]);
    double n = (zn + sqrt(zn * zf)) / sing;
    *nopt = n;
    /* gamma -> 0: n_opt -> infinity and LiSPSM tends to the uniform map,
     * which it then is (the paper's fallback); 1e-3 keeps the warp's float
     * matrix well conditioned */
    if (!(sing > 1e-3) || !isfinite(n))
        return 0;
    for (int k = 0; k < 3; k++)
        z[k] /= lz;
    double x[3] = {y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]};
#define LDOT(a, p) ((a)[0] * (double)(p)[0] + (a)[1] * (double)(p)[1] + (a)[2] * (double)(p)[2])
    size_t np = (size_t)v->w * (size_t)v->h;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < np; i++) {
        if (v->cls[i] != SL_C_PFL || (mask && mask[i] != value))
            continue;
        const float *p = v->pos + 3 * i;
        double q[3] = {LDOT(x, p), LDOT(y, p), LDOT(z, p)};
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], q[k]);
            hi[k] = fmax(hi[k], q[k]);
        }
    }
    double d = hi[2] - lo[2];
    if (!(d > 0.0) || n > 1e4 * d)
        return 0;   /* a flat body along z, or a warp too weak to matter: uniform */
    double C[3] = {LDOT(x, eye), LDOT(y, eye), lo[2] - n};
    /* casters over the receivers' x, z cross-section, not wholly below the lowest receiver */
    double ytop = hi[1];
    for (uint32_t t = 0; t < s->nt; t++) {
        double tl[3] = {INFINITY, INFINITY, INFINITY}, th[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int c = 0; c < 3; c++) {
            const float *p = s->pos + 3 * s->idx[3 * t + c];
            double q[3] = {LDOT(x, p), LDOT(y, p), LDOT(z, p)};
            for (int k = 0; k < 3; k++) {
                tl[k] = fmin(tl[k], q[k]);
                th[k] = fmax(th[k], q[k]);
            }
        }
        if (th[0] < lo[0] || tl[0] > hi[0] || th[2] < lo[2] || tl[2] > hi[2] || th[1] < lo[1])
            continue;
        ytop = fmax(ytop, th[1]);
    }
    /* warped bounds: u = x_c/z_c, t = 1/z_c, h = -y_c/z_c over the receivers */
    double wl[3] = {INFINITY, INFINITY, INFINITY}, wh[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < np; i++) {
        if (v->cls[i] != SL_C_PFL || (mask && mask[i] != value))
            continue;
        const float *p = v->pos + 3 * i;
        double zc = LDOT(z, p) - C[2], w[3] = {(LDOT(x, p) - C[0]) / zc, 1.0 / zc, -(LDOT(y, p) - C[1]) / zc};
        for (int k = 0; k < 3; k++) {
            wl[k] = fmin(wl[k], w[k]);
            wh[k] = fmax(wh[k], w[k]);
        }
    }
#undef LDOT
    wl[2] = fmin(wl[2], fmin(-(ytop - C[1]) / n, -(ytop - C[1]) / (n + d)));
    for (int k = 0; k < 3; k++) {   /* the box's relative margins (above) */
        double m = fmax(1e-4 * (wh[k] - wl[k]), 1e-6 * fmax(fabs(wl[k]), fabs(wh[k])) + 1e-12);
        wl[k] -= m;
        wh[k] += m;
    }
    double sx = 2.0 / (wh[0] - wl[0]), ox = 0.5 * (wh[0] + wl[0]);
    double sy = 2.0 / (wh[1] - wl[1]), oy = 0.5 * (wh[1] + wl[1]);
    double sz = 1.0 / (wh[2] - wl[2]), oz = wl[2];
    /* rows of clip = A (q - C), q = (x.p, y.p, z.p): X = sx q_x - sx ox q_z, ... */
    double A[4][4] = {{sx, 0, -sx * ox, 0}, {0, 0, -sy * oy, sy}, {0, -sz, -sz * oz, 0}, {0, 0, 1, 0}};
    double R[3][3] = {{x[0], x[1], x[2]}, {y[0], y[1], y[2]}, {z[0], z[1], z[2]}};
    for (int r = 0; r < 4; r++) {
        double row[4] = {0, 0, 0, 0};
        for (int c = 0; c < 3; c++) {
            for (int k = 0; k < 3; k++)
                row[c] += A[r][k] * R[k][c];
        }
        /* the constant: A (-C) plus the homogeneous column of A */
        row[3] = A[r][3] - (A[r][0] * C[0] + A[r][1] * C[1] + A[r][2] * C[2]);
        for (int c = 0; c < 4; c++)
            out->vp[c][r] = (float)row[c];
    }
    /* view and proj are not a product that makes vp here: vp is the frame */
    glm_mat4_identity(out->view);
    glm_mat4_copy(out->vp, out->proj);
    for (int k = 0; k < 3; k++) {
        out->lo[k] = (float)wl[k];
        out->hi[k] = (float)wh[k];
    }
    return 1;
}
