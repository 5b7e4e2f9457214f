/*
 * nsm.c — normal shadow mapping: one nearest-texel depth comparison per PFL
 * pixel, PnFL pixels shadowed by definition.
 *
 * The lookup runs on the CPU over the G-buffer positions read back from GL:
 * the same float math a fragment shader would do (project, take the texel
 * whose square holds the point, compare depths), but deterministic across
 * thread counts and shared with every later method that reads texels.
 *
 * Self-shadow policies (parameter self_shadow):
 * - front_faces (default: what Moderno 2011 used, "front face culling to
 *   prevent self shadowing"): the map holds back faces only; no bias.
 * - none: plain comparison, lit iff depth <= stored depth.
 * - constant: lit iff depth - bias * texel <= stored, bias in texels
 *   (multiples of one texel's world size; default 1).
 * - slope: offset = texel * (bias + slope * min(tan a, 10)) with a the angle
 *   between the normal and the light (defaults bias 0, slope 1): a plane
 *   tilted by a changes depth by texel * tan a across one texel, and the
 *   stored sample is at most half a texel diagonal away; the clamp keeps
 *   grazing receivers from pushing shadows off their casters entirely.
 * - triangle_id (Hertel 2009): lit when the texel stores the pixel's own
 *   triangle, otherwise the plain comparison.
 * Biases are expressed in texels so that a config keeps its meaning across
 * scene scales and map sizes.
 */
#include <math.h>
#include <omp.h>
#include "method.h"
#include "util.h"

static int policy_of(const struct sl_method_params *p)
{
    return (int)sl_method_param(p, "self_shadow");
}

static unsigned nsm_needs(const struct sl_method_params *p)
{
    return policy_of(p) == SL_SELF_FRONT_FACES ? SL_NEED(SL_LAYER_DEPTH_ID_BACK)
                                               : SL_NEED(SL_LAYER_DEPTH_ID);
}

static const struct sl_param nsm_params[] = {SL_SELF_SHADOW_DECL, SL_DEPTH_BIAS_DECLS};

/* bias applies to the constant and slope policies, slope to slope alone;
 * bias defaults to 1 texel under constant and to 0 under slope (the slope
 * term carries it). */
enum sl_err sl_self_shadow_configure(struct sl_method_params *p, struct sl_diag *d)
{
    struct sl_params *s = &p->values;
    int policy = policy_of(p);
    int uses_bias = policy == SL_SELF_CONSTANT || policy == SL_SELF_SLOPE;
    int uses_slope = policy == SL_SELF_SLOPE;
    char when[96];
    snprintf(when, sizeof when, "self_shadow constant or slope, not %s", sl_self_shadow_name(policy));
    enum sl_err e = SL_OK;
    if (!uses_bias)
        e = sl_params_off(s, "bias", when, d);
    snprintf(when, sizeof when, "self_shadow slope, not %s", sl_self_shadow_name(policy));
    if (!e && !uses_slope)
        e = sl_params_off(s, "slope", when, d);
    if (e)
        return e;
    if (!sl_params_given(s, "bias"))
        sl_params_derive(s, "bias", policy == SL_SELF_CONSTANT ? 1.0 : 0.0);
    if (!uses_slope)
        sl_params_derive(s, "slope", 0.0);
    return SL_OK;
}

void sl_self_test_of(const struct sl_method_args *a, struct sl_self_test *t)
{
    const struct sl_light_frame *f = a->frame;
    const int policy = policy_of(a->params);
    const float texel_z = f->texel_world / f->depth_range;
    const float *Ld = a->scene->light_dir;
    t->policy = policy;
    t->persp = f->box.persp;
    t->bias_texels = (policy == SL_SELF_CONSTANT || policy == SL_SELF_SLOPE) ? (float)sl_method_param(a->params, "bias") : 0.0f;
    t->slope_texels = policy == SL_SELF_SLOPE ? (float)sl_method_param(a->params, "slope") : 0.0f;
    t->bias = t->bias_texels * texel_z;
    t->slope = t->slope_texels * texel_z;
    t->toward[0] = -Ld[0], t->toward[1] = -Ld[1], t->toward[2] = -Ld[2];
}

float sl_self_offset(const struct sl_self_test *t, const struct sl_light_frame *f, const float pos[3],
                     const float nrm[3], float z)
{
    float off = t->bias, sl = t->slope, toward[3] = {t->toward[0], t->toward[1], t->toward[2]};
    if (t->persp && (t->bias_texels > 0.0f || t->slope_texels > 0.0f)) {
        float tz = (float)(sl_frame_texel_world_at(f, z) / sl_frame_world_per_depth(f, z)), tmax;
        off = t->bias_texels * tz;
        sl = t->slope_texels * tz;
        sl_frame_toward(f, pos, toward, &tmax);
    }
    if (sl > 0.0f) {
        float cosa = nrm[0] * toward[0] + nrm[1] * toward[1] + nrm[2] * toward[2];
        float tana = sqrtf(fmaxf(0.0f, 1.0f - cosa * cosa)) / cosa;
        off += sl * fminf(tana, 10.0f);
    }
    return off;
}

static enum sl_err nsm_run(const struct sl_method_args *a, struct sl_verdicts *out,
                           struct sl_cost *c, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_light_frame *f = a->frame;
    const int policy = policy_of(a->params);
    const enum sl_layer_id L = policy == SL_SELF_FRONT_FACES ? SL_LAYER_DEPTH_ID_BACK
                                                             : SL_LAYER_DEPTH_ID;
    if (!(f->have & SL_NEED(L)))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "nsm: layer %d not rendered", (int)L);
    const float *depth = f->layer[L].depth;
    const uint32_t *id = f->layer[L].id;
    /* offsets in window depth units: world units / depth range (a point
     * light's frustum: per pixel, with the texel's size and the depth's
     * scale at the pixel's depth, and the slope toward the light point) */
    struct sl_self_test t;
    sl_self_test_of(a, &t);
    const long n = (long)v->w * v->h;
    /* no offset to compute (front_faces, none, or a zero bias): the one
     * comparison, without the per-pixel tests of the general path below;
     * bias == 0.0f is false for a NaN bias, which keeps the general path's
     * answer then too */
    const int plain = (policy == SL_SELF_FRONT_FACES || policy == SL_SELF_NONE) && t.bias == 0.0f && t.slope == 0.0f;
    uint64_t lookups = 0;
    /* the plain test made by the driver already, with every pixel's
     * lookup (frame.h: sl_frame_look; its time charged here below) */
    const struct sl_frame_look *look = plain ? sl_frame_look_of(f, L, v->serial, (size_t)n) : NULL;
    double t0 = sl_now();
    /* rows, not tiles: 32x32 tiles measured no faster here (the 1024² and
     * 1920x1080 frames' rows already read nearby texels of 2048² and 4096²
     * maps; perf samples of this loop within noise of the row walk) */
#pragma omp parallel for num_threads(a->threads) schedule(static) reduction(+ : lookups)
    for (long i = 0; i < n; i++) {
        if (sl_verdict_fixed(v, (size_t)i, out))
            continue;
        lookups++;
        out->how[i] = SL_HOW_MAP;
        if (look) {
            out->v[i] = (look->px[i].k & SL_LOOK_SHADOW) ? SL_V_SHADOW : SL_V_LIT;
            continue;
        }
        float u, w, z;
        sl_frame_project(f, v->pos + 3 * i, &u, &w, &z);
        uint32_t k = sl_frame_texel(f, u, w);
        if (plain) {
            out->v[i] = z <= depth[k] ? SL_V_LIT : SL_V_SHADOW;
            continue;
        }
        const float off = sl_self_offset(&t, f, v->pos + 3 * i, v->nrm + 3 * i, z);
        int lit;
        if (policy == SL_SELF_TRIANGLE_ID && id[k] == v->tri[i])
            lit = 1;
        else
            lit = z - off <= depth[k];
        out->v[i] = lit ? SL_V_LIT : SL_V_SHADOW;
    }
    c->ms_method += 1e3 * (sl_now() - t0) + (look ? look->ms : 0.0);
    c->lookups += lookups;
    return SL_OK;
}

const struct sl_method sl_method_nsm = {
    .cite = "williams1978",
    .name = "nsm", .display = "NSM", .beside = "moderno-2011 morais-2015",
    .summary = "normal shadow mapping (self_shadow: front_faces|none|constant|slope|triangle_id)",
    SL_METHOD_PARAMS(nsm_params),
    .needs = nsm_needs,
    .configure = sl_self_shadow_configure,
    .run = nsm_run,
    .fast = {.looks = SL_NEED(SL_LAYER_DEPTH_ID_BACK)},
};
