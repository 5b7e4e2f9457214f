/*
 * conservative.c — conservative shadow maps, exact by construction:
 * bgsm (a pixel it calls lit is lit), sgsm (a pixel it calls shadowed is
 * shadowed) and csm (both, the rest traced: its image is the truth).
 * After Morais 2015 (BGSM, SGSM, CSMa) and Hertel et al. 2009.
 *
 * The layers (harness/glsl/cons_*.glsl) store per texel a bound on depth:
 * BGSM the lowest depth over the texel of every triangle that touches it
 * (and BGSM2 the same without the triangle BGSM kept there); SGSM the
 * highest depth over the texel of any triangle that covers all of it. Why
 * the answers are exact, and the choices that make them so:
 *
 * - Coverage is decided per texel by an exact square-triangle test in double
 *   precision, with a margin of SL_CONS_EPS_TEXELS (1/128 texel) in the
 *   conservative direction. Float rounding of a point's or a vertex's map
 *   position is below 2e-3 texels even on 16384^2 maps, so a triangle that
 *   touches the pixel's light ray touches the texel the CPU computes for the
 *   pixel (BGSM), and a texel SGSM calls covered has the pixel's ray inside
 *   the triangle by a margin Embree resolves (SGSM).
 * - Depth is conservative over the whole texel, not only at its centre: the
 *   plane's minimum (maximum) over the texel's corners, clamped by the
 *   triangle's nearest (farthest) vertex, so steep, nearly edge-on triangles
 *   never produce extreme values; then SL_CONS_EPS_DEPTH (2^-18) further in
 *   the conservative direction, some thirty times the float error of a depth.
 * - Nothing is culled in these layers: Embree culls nothing, and an open
 *   one-sided surface facing the light is a real occluder.
 * - The receiver's own triangle is in the map, and nearest at its own texel
 *   wherever nothing else is above it. Policy: when BGSM's triangle at the
 *   texel is the pixel's own (the truth ignores it: the own-triangle filter
 *   of harness/truth.c), or a ray-triangle test in double precision shows
 *   the pixel's ray missing it by a margin (1e-5 of the coordinates, far
 *   above float error; or crossing its plane before half of tnear, where
 *   Embree does not look), the second layer decides instead. A coplanar
 *   neighbour (ground grids) is handled by the same test. Anything less sure
 *   leaves the pixel undecided, never wrongly lit.
 * - SGSM's triangle must be in front of the pixel by more than twice the
 *   truth's tnear (plus 2^-20), so Embree, which starts rays at tnear, meets
 *   it too.
 * csm traces its undecided pixels with the truth's own rays
 * (sl_rt_trace), so its image equals the truth pixel for pixel.
 * - Under an area light taken as a point at its centre the frame is a
 *   perspective frustum from that point (lightfit.c). Every argument above
 *   carries over: a pixel's ray to the point projects to the pixel's own
 *   texel, window depth is monotone in depth along the ray and affine across
 *   a triangle in window space, the ray-triangle tests use the ray to the
 *   point and stop where the truth's ray stops, and the depth margin for
 *   tnear is converted with the local scale (sl_frame_world_per_depth).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include "method.h"
#include "raytri.h"
#include "truth.h"
#include "util.h"

/* 1 when the pixel's shadow ray surely misses triangle t (or cannot reach
 * it within Embree's [tnear, inf)), 0 when it may hit. */
static int surely_misses(const struct sl_method_args *a, const float p[3], uint32_t t)
{
    const struct sl_scene *s = a->scene;
    const uint32_t *ix = s->idx + 3 * (size_t)t;
    float toward[3], tmax;
    sl_frame_toward(a->frame, p, toward, &tmax);
    return sl_shadow_ray_tri_sure(p, toward, tmax, sl_rt_tnear(p), s->pos + 3 * ix[0], s->pos + 3 * ix[1],
                                  s->pos + 3 * ix[2]) < 0;
}

enum { V_LIT = 1, V_SHADOW = 2 };

/* What the layers say of one PFL pixel: V_LIT if BGSM proves it lit,
 * V_SHADOW if SGSM proves it shadowed, 0 if neither; tests counted. */
static int decide(const struct sl_method_args *a, size_t i, int use_bgsm, int use_sgsm,
                  enum sl_layer_id sgsm_layer, uint64_t *lookups, uint64_t *tests)
{
    const struct sl_light_frame *f = a->frame;
    const struct sl_view *v = a->view;
    const float *p = v->pos + 3 * i;
    float u, w, z;
    sl_frame_project(f, p, &u, &w, &z);
    uint32_t k = sl_frame_texel(f, u, w);
    int r = 0;
    if (!sl_frame_inside(f, u, w))
        return 0;   /* outside a point light's map: the layers say nothing */
    if (use_sgsm) {
        const struct sl_depth_layer *sg = &f->layer[sgsm_layer];
        (*lookups)++;
        const size_t ks = sl_layer_at(sg, k, i);   /* a layer may be gathered per pixel (frame.h) */
        float m = (float)(2.0 * sl_rt_tnear(p) / sl_frame_world_per_depth(f, z)) + 0x1p-20f;
        if (sg->id[ks] && sg->id[ks] != v->tri[i] && sg->depth[ks] < z - m)
            r |= V_SHADOW;
    }
    if (use_bgsm) {
        const struct sl_depth_layer *b1 = &f->layer[SL_LAYER_BGSM], *b2 = &f->layer[SL_LAYER_BGSM2];
        (*lookups)++;
        const size_t k1 = sl_layer_at(b1, k, i);
        const uint32_t id1 = b1->id[k1] & ~SL_FULL;
        if (b1->depth[k1] > z) {
            r |= V_LIT;
        } else if (id1) {
            int skip = id1 == v->tri[i];
            if (!skip) {
                (*tests)++;
                skip = surely_misses(a, p, id1 - 1);
            }
            if (skip) {
                (*lookups)++;
                if (b2->depth[sl_layer_at(b2, k, i)] > z)
                    r |= V_LIT;
            }
        }
        /* the layers know nothing of casters reaching behind a point light */
        if ((r & V_LIT) && !sl_method_unmapped_missed(a, p, v->tri[i], tests))
            r &= ~V_LIT;
    }
    return r;
}

enum mode { M_BGSM, M_SGSM, M_CSM };

static enum sl_err run_mode(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                            enum mode mode, enum sl_layer_id sgsm_layer, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const long n = (long)v->w * v->h;
    uint8_t *undecided = NULL;
    if (mode == M_CSM && !(undecided = sl_calloc((size_t)n, 1)))
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "csm mask");
    uint64_t lookups = 0, tests = 0, conflicts = 0;
    double t0 = sl_now();
#pragma omp parallel for num_threads(a->threads) schedule(dynamic, 4096) reduction(+ : lookups, tests, conflicts)
    for (long i = 0; i < n; i++) {
        if (sl_verdict_fixed(v, (size_t)i, out))
            continue;
        const uint64_t tests_before = tests;
        int r = decide(a, (size_t)i, mode != M_SGSM, mode != M_BGSM, sgsm_layer, &lookups, &tests);
        out->tests[i] = (uint8_t)(tests - tests_before > 255 ? 255 : tests - tests_before);
        out->how[i] = SL_HOW_MAP;
        if (r == (V_LIT | V_SHADOW)) {
            conflicts++;       /* impossible if both layers are right; trace it */
            r = 0;
        }
        if (r == V_LIT)
            out->v[i] = SL_V_LIT;
        else if (r == V_SHADOW)
            out->v[i] = SL_V_SHADOW;
        else if (mode == M_BGSM)
            out->v[i] = SL_V_SHADOW;            /* not proved lit */
        else if (mode == M_SGSM)
            out->v[i] = SL_V_LIT;               /* not proved shadowed */
        else {
            out->v[i] = SL_V_UNCERTAIN;
            undecided[i] = 1;
        }
    }
    c->ms_method += 1e3 * (sl_now() - t0);
    c->lookups += lookups;
    c->tri_tests += tests;
    enum sl_err e = SL_OK;
    if (mode == M_CSM)
        e = sl_method_trace_left(a, undecided, NULL, out, c, d);
    if (!e && conflicts)
        e = sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL,
                    "%llu pixels proved both lit and shadowed: a conservative layer is wrong",
                    (unsigned long long)conflicts);
    free(undecided);
    return e;
}

static unsigned needs_bgsm(const struct sl_method_params *p) { (void)p; return SL_NEED(SL_LAYER_BGSM) | SL_NEED(SL_LAYER_BGSM2); }
static unsigned needs_sgsm(const struct sl_method_params *p) { (void)p; return SL_NEED(SL_LAYER_SGSM); }
static unsigned needs_sgsm_adj(const struct sl_method_params *p) { (void)p; return SL_NEED(SL_LAYER_SGSM_ADJ) | SL_NEED_ADJACENCY; }
static unsigned needs_csm(const struct sl_method_params *p) { return needs_bgsm(p) | needs_sgsm(p); }
static unsigned needs_csm_adj(const struct sl_method_params *p) { return needs_bgsm(p) | needs_sgsm_adj(p); }
/* every layer these methods read, they read at the pixel's own texel only
 * (decide), through sl_layer_at: the driver may gather them per pixel */
#define CONS_AT_PIXEL (SL_NEED(SL_LAYER_BGSM) | SL_NEED(SL_LAYER_BGSM2) | SL_NEED(SL_LAYER_SGSM) | SL_NEED(SL_LAYER_SGSM_ADJ))

static enum sl_err run_bgsm(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_mode(a, o, c, M_BGSM, SL_LAYER_SGSM, d); }
static enum sl_err run_sgsm(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_mode(a, o, c, M_SGSM, SL_LAYER_SGSM, d); }
static enum sl_err run_sgsm_adj(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_mode(a, o, c, M_SGSM, SL_LAYER_SGSM_ADJ, d); }
static enum sl_err run_csm(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_mode(a, o, c, M_CSM, SL_LAYER_SGSM, d); }
static enum sl_err run_csm_adj(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_mode(a, o, c, M_CSM, SL_LAYER_SGSM_ADJ, d); }

const struct sl_method sl_method_bgsm = {
    .cite = "morais2015",
    .name = "bgsm", .display = "BGSM", .family = "morais-2015", .summary = "big-triangle (conservative) shadow map: its lit pixels are lit in truth",
    .exact = SL_EXACT_LIT, .needs = needs_bgsm, .run = run_bgsm,
    .fast = {.at_pixel = CONS_AT_PIXEL},
};
const struct sl_method sl_method_sgsm = {
    .cite = "morais2015",
    .name = "sgsm", .display = "SGSM", .family = "morais-2015", .summary = "small-triangle shadow map: its shadowed pixels are shadowed in truth",
    .exact = SL_EXACT_SHADOW, .needs = needs_sgsm, .run = run_sgsm,
    .fast = {.at_pixel = CONS_AT_PIXEL},
};
const struct sl_method sl_method_sgsm_adj = {
    .cite = "morais2015",
    .name = "sgsm_adj", .display = "SGSM + adjacency", .family = "morais-2015", .summary = "SGSM keeping edges between away-facing neighbours (Morais 2015 ch. 4)",
    .exact = SL_EXACT_SHADOW, .needs = needs_sgsm_adj, .run = run_sgsm_adj,
    .fast = {.at_pixel = CONS_AT_PIXEL},
};
const struct sl_method sl_method_csm = {
    .cite = "morais2015",
    .name = "csm", .display = "CSMa", .family = "morais-2015", .summary = "CSMa: lit by BGSM, shadowed by SGSM, the rest traced (Morais 2015)",
    .exact = SL_EXACT_LIT | SL_EXACT_SHADOW, .needs = needs_csm, .run = run_csm,
    .fast = {.at_pixel = CONS_AT_PIXEL},
};
const struct sl_method sl_method_csm_adj = {
    .cite = "morais2015",
    .name = "csm_adj", .display = "CSMA", .family = "morais-2015", .summary = "CSMA: lit by BGSM, shadowed by SGSM with adjacency, the rest traced",
    .exact = SL_EXACT_LIT | SL_EXACT_SHADOW, .needs = needs_csm_adj, .run = run_csm_adj,
    .fast = {.at_pixel = CONS_AT_PIXEL},
};
