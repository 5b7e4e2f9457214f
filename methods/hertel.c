/*
 * hertel.c — Hertel, Hormann and Westermann 2009, "A hybrid GPU rendering
 * pipeline for alias-free hard shadows", exact by construction.
 *
 * Their pipeline, and where ours differs:
 * - A conservative shadow map holds per texel the nearest conservative depth
 *   and the id of its triangle, with a mark for texels the triangle covers
 *   fully (BGSM's layer, shared with bgsm and csm; the enlargement and the per-texel tests are
 *   those of the other conservative layers, see conservative.c: the edges
 *   move by half the texel diagonal plus a margin rather than Hertel's full
 *   diagonal, and the exact square test in the fragment shader stands for
 *   his barycentric distance test).
 * - A pixel is lit when nothing is stored at its texel or the stored depth
 *   lies beyond it: every occluder would have stored a nearer one.
 * - Otherwise the pixel's ray is tested against the stored triangle, by id,
 *   before any ray is traced (section 4.2): a sure hit shadows it.
 * - Self-shadowing: Hertel's id comparison calls a pixel lit when the
 *   stored triangle is its own. That is not exact (another triangle nearer
 *   than the pixel can hide behind the own triangle's conservative depth),
 *   so here the own triangle, and a stored triangle the ray does not surely
 *   hit, leave the pixel uncertain, fully covered or not.
 * - Uncertain pixels are traced with the truth's rays, cut short at the
 *   stored depth (his RT_opt): nothing nearer to the light than the stored
 *   conservative depth touches the texel, so a ray that reaches it unblocked
 *   is lit, and the answer is the full ray's.
 * The image equals the truth; what it costs is the point of measuring it.
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include "method.h"
#include "raytri.h"
#include "truth.h"
#include "util.h"

static unsigned h_needs(const struct sl_method_params *p) { (void)p; return SL_NEED(SL_LAYER_BGSM); }

/* How far the pixel's shadow ray runs before reaching window depth zs (the
 * stored depth, zs <= z, the pixel's), with room for rounding (2^-16 of
 * window depth) and the truth's tnear. Along a directional light depth falls
 * one for one with the distance; toward a point light, a ray from depth d
 * reaches depth d' after (1 - d'/d) of its length to the light (depth is 0
 * at the light), d and d' from the frustum's window depths. */
static float ray_to_depth(const struct sl_light_frame *f, const float p[3], float z, float zs)
{
    if (!f->box.persp)
        return (z - zs + 0x1p-16f) * f->depth_range + 4.0f * sl_rt_tnear(p);
    double d = sl_frame_depth_of(f, z), ds = sl_frame_depth_of(f, fmax(0.0, (double)zs - 0x1p-16));
    double len = 0.0;
    for (int k = 0; k < 3; k++)
        len += ((double)f->box.eye[k] - p[k]) * ((double)f->box.eye[k] - p[k]);
    double t = sqrt(len) * (1.0 - ds / d);
    return (float)(t * (1.0 + 0x1p-16)) + 4.0f * sl_rt_tnear(p);
}

static enum sl_err h_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                         struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_light_frame *f = a->frame;
    const struct sl_depth_layer *L = &f->layer[SL_LAYER_BGSM];
    const struct sl_scene *s = a->scene;
    const long n = (long)v->w * v->h;
    uint8_t *undecided = sl_calloc((size_t)n, 1);
    float *tfar = sl_calloc((size_t)n, sizeof(float));
    if (!undecided || !tfar) {
        free(undecided);
        free(tfar);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "hertel buffers");
    }
    uint64_t lookups = 0, tests = 0;
    double t0 = sl_now();
#pragma omp parallel for num_threads(a->threads) schedule(dynamic, 4096) reduction(+ : lookups, tests)
    for (long i = 0; i < n; i++) {
        if (sl_verdict_fixed(v, (size_t)i, out))
            continue;
        const float *p = v->pos + 3 * i;
        float u, w, z;
        sl_frame_project(f, p, &u, &w, &z);
        uint32_t k = sl_frame_texel(f, u, w);
        lookups++;
        uint32_t id = L->id[k] & ~SL_FULL;
        out->how[i] = SL_HOW_MAP;
        /* casters reaching behind a point light are not in the layer: only
         * a ray that surely misses them all may be called lit from it or cut
         * short at its depth */
        const uint64_t tests_before = tests;
        const int clear = sl_frame_inside(f, u, w) && sl_method_unmapped_missed(a, p, v->tri[i], &tests);
        out->tests[i] = (uint8_t)(tests - tests_before > 255 ? 255 : tests - tests_before);
        if (clear && (!id || L->depth[k] > z)) {
            out->v[i] = SL_V_LIT;
            continue;
        }
        if (id && id != v->tri[i] && sl_frame_inside(f, u, w) && (clear || L->depth[k] <= z)) {
            const uint32_t *ix = s->idx + 3 * (size_t)(id - 1);
            tests++;
            out->tests[i] = (uint8_t)(out->tests[i] < 255 ? out->tests[i] + 1 : 255);
            float toward[3], tmax;
            sl_frame_toward(f, p, toward, &tmax);
            if (sl_shadow_ray_tri_sure(p, toward, tmax, sl_rt_tnear(p), s->pos + 3 * ix[0], s->pos + 3 * ix[1],
                                       s->pos + 3 * ix[2]) > 0) {
                out->v[i] = SL_V_SHADOW;
                out->how[i] = SL_HOW_CONFIRM;
                continue;
            }
        }
        out->v[i] = SL_V_UNCERTAIN;
        undecided[i] = 1;
        /* RT_opt: from the pixel up to the stored depth, with room for
         * rounding and the truth's tnear */
        tfar[i] = clear && id ? ray_to_depth(f, p, z, L->depth[k]) : INFINITY;
    }
    c->ms_method += 1e3 * (sl_now() - t0);
    c->lookups += lookups;
    c->tri_tests += tests;
    enum sl_err e = sl_method_trace_left(a, undecided, tfar, out, c, d);
    free(undecided);
    free(tfar);
    return e;
}

const struct sl_method sl_method_hertel = {
    .name = "hertel", .summary = "Hertel 2009: conservative map + stored-triangle test + rays cut at the stored depth",
    .exact = SL_EXACT_LIT | SL_EXACT_SHADOW, .needs = h_needs, .run = h_run,
};
