/*
 * softtruth.c — see softtruth.h.
 *
 * Estimator: the light's rectangle is cut into n x n equal cells (strata);
 * sample k (cell k mod n, k div n) is one jittered point in its cell, y_k = 1
 * when it is visible (softtruth.h), and V = (1/N) sum y_k with N = n^2. This
 * is unbiased for the visible fraction of the area: each cell is 1/N of it
 * and y_k is unbiased for its cell's visible fraction.
 *
 * Standard error, and why this one: with one sample per stratum the
 * variance of V, (1/N^2) sum sigma_k^2, cannot be estimated stratum by
 * stratum. The binomial sqrt(V (1 - V) / N) bounds it, but stratification
 * is exactly what makes the truth cheap: across a straight occluder edge only
 * the ~n cells the edge crosses vary, so the true error falls as N^-3/4
 * while the binomial bound falls as N^-1/2 and overstates it 5x at n = 32
 * (RMS over curtis_box's penumbra; tests/test_softtruth.c measures both).
 * We use the classic collapsed-strata estimator instead: the cells of each row are grouped in adjacent pairs
 * (the last three form one group when n is odd), and for a group G of m
 * cells m/(m-1) sum_G (y - mean_G y)^2 estimates sum_G sigma^2 plus the
 * spread of the cells' means within G — never less in expectation, so the
 * estimate is conservative, and tight where neighbouring cells have nearly
 * the same visible fraction (everywhere but at an edge): measured 1.6x the
 * RMS error, 1.9x the mean absolute error at n = 4 .. 32. For 0/1 samples
 * and m <= 3 a group contributes exactly 1 when it holds both a visible and
 * a hidden sample, 0 otherwise, so
 *     stderr = sqrt(number of mixed groups) / N.
 * A pixel with all samples equal (fully lit, umbra) gets 0: no sample of
 * any group disagreed. n >= 2 so that every group has two cells.
 *
 * Packets: 16 consecutive samples of one pixel (cells in row order, so
 * neighbouring cells of the grid) per tile of 16 rays (one to four packets of the device's
 * native width, packet.h), all from the same origin toward nearby points: coherent. Pixels are independent and each one's counts are
 * integers summed in sample order, so the result does not depend on the
 * thread count or schedule.
 */
#include "softtruth.h"
#include <math.h>
#include <omp.h>
#include <string.h>
#include "arealight.h"
#include "packet.h"
#include "util.h"

int sl_soft_truth_side(int samples_per_side)
{
    return samples_per_side == 0 ? SL_SOFT_TRUTH_SIDE_DEFAULT : samples_per_side;
}

static const char *light_name(int type)
{
    switch (type) {
    case SL_LIGHT_DIRECTIONAL: return "directional";
    case SL_LIGHT_SPOT:        return "spot";
    case SL_LIGHT_POINT:       return "point";
    case SL_LIGHT_AREA:        return "area";
    default:                   return "unknown";
    }
}

struct pixel_out {
    uint32_t visible;   /* samples visible */
    uint32_t mixed;     /* groups holding a visible and a hidden sample */
    uint32_t rays;      /* samples traced */
};

/* All N = n^2 samples of pixel i at (x, y). */
static void trace_pixel(const struct sl_rt *rt, struct RTCIntersectContext *ctx, const struct sl_area *a,
                        const struct sl_view *v, size_t i, uint32_t x, uint32_t y, uint32_t n,
                        uint32_t seed, struct pixel_out *o)
{
    const uint32_t N = n * n, half = n / 2;
    const float *pf = v->pos + 3 * i;
    const double p[3] = {pf[0], pf[1], pf[2]};
    const double nrm[3] = {v->nrm[3 * i], v->nrm[3 * i + 1], v->nrm[3 * i + 2]};
    const float tnear = sl_rt_tnear(pf);
    uint32_t visible = 0, mixed = 0, rays = 0;
    uint32_t group = UINT32_MAX;   /* current group of cells, numbered in sample order */
    unsigned seen = 0;             /* bit 0: a hidden sample in it, bit 1: a visible one */
    const int shift = rt->shift;
    for (uint32_t k0 = 0; k0 < N; k0 += 16) {
        /* 16 lanes in packets of the device's width, every lane written
         * (packet.h): a sample past N or facing away is a dead lane */
        struct sl_rt_tile t;
        int any = 0;
        sl_tile_kill_all(&t, shift);
        for (int l = 0; l < 16; l++) {
            const uint32_t k = k0 + (uint32_t)l;
            if (k >= N)
                continue;
            double u, w, q[3], dq[3];
            sl_area_jitter(x, y, k, n, seed, &u, &w);
            sl_area_point(a, u, w, q);
            for (int c = 0; c < 3; c++)
                dq[c] = q[c] - p[c];
            const double front = nrm[0] * dq[0] + nrm[1] * dq[1] + nrm[2] * dq[2];
            const double emit = -(a->n[0] * dq[0] + a->n[1] * dq[1] + a->n[2] * dq[2]);
            if (!(front > 0.0 && emit > 0.0))
                continue;
            const double dist = sqrt(dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2]);
            const float qf[3] = {(float)q[0], (float)q[1], (float)q[2]};
            const float dir[3] = {(float)(dq[0] / dist), (float)(dq[1] / dist), (float)(dq[2] / dist)};
            sl_tile_ray(&t, shift, l, pf, dir, tnear, (float)dist - sl_rt_tnear(qf), v->tri[i]);
            any = 1;
        }
        if (any)
            sl_rt_occluded_tile(rt, ctx, &t);
        for (int l = 0; l < 16 && k0 + (uint32_t)l < N; l++) {
            const uint32_t k = k0 + (uint32_t)l, cx = k % n, cy = k / n;
            const uint32_t g = cy * half + (cx / 2 < half - 1 ? cx / 2 : half - 1);
            if (g != group) {
                mixed += seen == 3u;
                group = g;
                seen = 0;
            }
            /* an occluded ray comes back with tfar = -inf */
            const int vis = t.valid[l] && !sl_tile_occluded(&t, shift, l);
            seen |= vis ? 2u : 1u;
            visible += (uint32_t)vis;
            rays += (uint32_t)(t.valid[l] != 0);
        }
    }
    mixed += seen == 3u;
    o->visible = visible;
    o->mixed = mixed;
    o->rays = rays;
}

enum sl_err sl_soft_truth(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                          int samples_per_side, uint32_t seed, float *visible, float *stderr_out,
                          struct sl_soft_truth_stats *st, struct sl_diag *d)
{
    if (!rt || !s || !v || !visible)
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_soft_truth: NULL argument");
    const int side = sl_soft_truth_side(samples_per_side);
    if (side < 2 || side > SL_SOFT_TRUTH_SIDE_MAX)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "samples_per_side",
                       "%d samples per side: must be 2 .. %d (0 = %d)", samples_per_side,
                       SL_SOFT_TRUTH_SIDE_MAX, SL_SOFT_TRUTH_SIDE_DEFAULT);
    if (s->light.type != SL_LIGHT_AREA)
        return sl_fail(d, SL_E_SCENE, s->path[0] ? s->path : NULL, 0, "light.type",
                       "the soft-shadow truth needs an area light; scene '%s' has a %s light", s->name,
                       light_name(s->light.type));
    struct sl_area a;
    sl_area_of(&s->light, &a);
    /* scene files refuse these; scenes made in code may not */
    if (!(a.w > 0.0 && a.h > 0.0 && isfinite(a.w) && isfinite(a.h)) || !isfinite(a.ex[0] + a.ex[1] + a.ex[2]) ||
        !isfinite(a.ey[0] + a.ey[1] + a.ey[2]) || !isfinite(a.c[0] + a.c[1] + a.c[2]))
        return sl_fail(d, SL_E_SCENE, s->path[0] ? s->path : NULL, 0, "light",
                       "scene '%s': degenerate area light (size %g x %g, or normal and up not independent)",
                       s->name, a.w, a.h);

    const double t0 = sl_now();
    const uint32_t n = (uint32_t)side, N = n * n;
    const size_t npix = (size_t)v->w * (size_t)v->h;
    const int threads = rt->threads > 0 ? rt->threads : omp_get_max_threads();
    uint64_t rays = 0, pixels = 0, lit = 0, umbra = 0;
#pragma omp parallel num_threads(threads) reduction(+ : rays, pixels, lit, umbra)
    {
        sl_rt_thread_init();
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        /* a pixel is N rays: small chunks keep the two cores even */
#pragma omp for schedule(dynamic, 8)
        for (size_t i = 0; i < npix; i++) {
            if (v->tri[i] == 0) {
                visible[i] = 0.0f;
                if (stderr_out)
                    stderr_out[i] = 0.0f;
                continue;
            }
            struct pixel_out o;
            trace_pixel(rt, &ctx, &a, v, i, (uint32_t)(i % (size_t)v->w), (uint32_t)(i / (size_t)v->w), n, seed,
                        &o);
            visible[i] = (float)((double)o.visible / (double)N);
            if (stderr_out)
                stderr_out[i] = (float)(sqrt((double)o.mixed) / (double)N);
            pixels++;
            lit += o.visible == N;
            umbra += o.visible == 0;
            rays += o.rays;
        }
    }
    if (st) {
        memset(st, 0, sizeof *st);
        st->side = side;
        st->seed = seed;
        st->pixels = pixels;
        st->lit = lit;
        st->umbra = umbra;
        st->rays = rays;
        st->ms_trace = 1e3 * (sl_now() - t0);
    }
    enum RTCError err = rtcGetDeviceError(rt->device);
    if (err != RTC_ERROR_NONE)
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "Embree trace failed (error %d)", (int)err);
    return SL_OK;
}
