/*
 * hertel.c — Hertel, Hormann and Westermann 2009, "A hybrid GPU rendering
 * pipeline for alias-free hard shadows" (seed 002), as two methods that
 * share one per-pixel loop:
 *
 * `hertel`, as published (section 4.2). No exactness is promised: what the
 * classification gets wrong shows as wrong pixels, not as violations.
 * - A pixel is lit when nothing is stored at its texel or the stored depth
 *   lies beyond its own (section 4).
 * - In a texel the stored triangle covers fully (BGSM's SL_FULL mark), the
 *   stored depth decides: lit when the pixel's depth is at or before it,
 *   shadowed when beyond it. No ray, no triangle test.
 * - Self-shadowing, by triangle id as the paper does it: "by simply
 *   comparing the ID that was read from the shadow map with the ID of the
 *   triangle the view sample belongs to, self shadowing can be detected and
 *   pixels with false shadowing can be eliminated" (section 4.2; no depth
 *   bias). Ours: a fully covered texel storing the pixel's own triangle
 *   lights the pixel. The seed is silent on an own triangle stored at a
 *   partially covered texel; there the paper's decision is the exact test
 *   of the pixel's ray against the stored triangle, which its own triangle
 *   can never pass, so nothing false is eliminated and the pixel stays
 *   "uncertain" and is traced (calling it lit would be a claim the paper
 *   does not make). The seed is also silent on a depth equal to the stored
 *   one ("greater (or smaller)"): a fully covered texel lights it (at or
 *   before), as a shadow-map comparison does; elsewhere the strict
 *   comparison of `hertel_exact` is kept and the pixel goes on to the
 *   triangle test.
 * - In a partially covered texel the pixel's ray is tested against the
 *   stored triangle, by id: a sure hit shadows it; otherwise it is traced,
 *   with the ray cut at the stored depth (RT_opt): nothing nearer to the
 *   light than the stored conservative depth touches the texel.
 * Where ours departs from the paper for want of its setting: the stored
 * depth decides a fully covered texel only where the light frame holds
 * every caster of the pixel's ray (a directional light always; a point
 * light's face leaves out triangles reaching behind the light, see
 * sl_method_unmapped_missed, and pixels outside the frustum read a border
 * texel); there the pixel takes `hertel_exact`'s path. The paper's single
 * map holds those casters; ours cannot, and a verdict from a map lacking
 * them would be an error of our frame, not of the paper's method.
 *
 * `hertel_exact`, exact by construction (the image equals the truth):
 * - Lit as above when nothing is stored or the stored depth lies beyond.
 * - Otherwise, fully covered or not, the stored triangle test (a sure hit
 *   shadows) and else a ray cut at the stored depth. The own triangle is
 *   never trusted: another triangle nearer than the pixel can hide behind
 *   the own triangle's conservative depth, and a fully covered texel's
 *   stored depth is only the lowest over the texel, not the triangle's
 *   depth at the pixel. On the Morais study it traces 97.8% of the PFL
 *   pixels (the own triangle is stored almost everywhere), `hertel` 3.5%
 *   (doc/methods.md, "Hertel 2009").
 *
 * Both read the conservative map of BGSM (shared with bgsm and csm; the
 * enlargement and the per-texel tests are those of the other conservative
 * layers, see conservative.c: the edges move by half the texel diagonal
 * plus a margin rather than Hertel's full diagonal, and the exact square
 * test in the fragment shader stands for his barycentric distance test,
 * full coverage included, with a 1/128-texel margin).
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

/* One loop for both: `paper` set, fully covered texels are decided by the
 * stored depth (hertel); clear, every pixel not lit by the map is tested
 * and traced (hertel_exact). */
static enum sl_err h_run_any(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                             struct sl_diag *d, int paper)
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
        /* Hertel 4.2: a fully covered texel decides by its stored depth,
         * its own triangle stored meaning self-shadowing, hence lit */
        if (paper && clear && (L->id[k] & SL_FULL)) {
            out->v[i] = id == v->tri[i] || z <= L->depth[k] ? SL_V_LIT : SL_V_SHADOW;
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

static enum sl_err h_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                         struct sl_diag *d)
{
    return h_run_any(a, out, c, d, 1);
}

static enum sl_err h_run_exact(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                               struct sl_diag *d)
{
    return h_run_any(a, out, c, d, 0);
}

const struct sl_method sl_method_hertel = {
    .cite = "hertel2009",
    .name = "hertel", .display = "Hertel 2009", .family = "hertel-2009", .beside = "morais-2015", .summary = "Hertel 2009 as published: fully covered texels decided by the stored depth "
                                 "(own triangle: lit), the rest by the stored-triangle test and rays cut at the "
                                 "stored depth",
    .exact = 0, .needs = h_needs, .run = h_run,
};

const struct sl_method sl_method_hertel_exact = {
    .cite = "hertel2009",
    .name = "hertel_exact", .display = "Hertel 2009, exact", .family = "hertel-2009", .beside = "morais-2015", .summary = "Hertel 2009 made exact: every pixel the map does not light gets the "
                                       "stored-triangle test, then a ray cut at the stored depth",
    .exact = SL_EXACT_LIT | SL_EXACT_SHADOW, .needs = h_needs, .run = h_run_exact,
};
