/*
 * pcf3.c — percentage-closer filtering over the 3x3 texels around each
 * pixel's own, taken as a hard shadow: a PFL pixel is lit when at least 5
 * of the 9 texels light it. Parameter: bias (texels, default 1). It reads the
 * depth layer dense (a neighbour's texel: no fast path) and counts 9
 * lookups a pixel. The worked example of doc/adding-a-method.md.
 */
#include <omp.h>
#include "method.h"
#include "util.h"

static unsigned pcf3_needs(const struct sl_method_params *p)
{
    (void)p;
    return SL_NEED(SL_LAYER_DEPTH_ID);
}

/* its parameters: one line each (name, default, range, unit, doc) */
static const struct sl_param pcf3_params[] = {
    SL_PARAM_FLOAT_DECL("bias", 1, 0, 1000, "texels", "depth bias of the 9 comparisons"),
};

static enum sl_err pcf3_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                            struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_light_frame *f = a->frame;
    if (!(f->have & SL_NEED(SL_LAYER_DEPTH_ID)))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "pcf3: depth layer not rendered");
    const float *depth = f->layer[SL_LAYER_DEPTH_ID].depth;
    const float bias = (float)sl_method_param(a->params, "bias");
    const long n = (long)v->w * v->h;
    uint64_t lookups = 0;
    double t0 = sl_now();
#pragma omp parallel for num_threads(a->threads) schedule(static) reduction(+ : lookups)
    for (long i = 0; i < n; i++) {
        if (sl_verdict_fixed(v, (size_t)i, out))
            continue;
        float u, w, z;
        sl_frame_project(f, v->pos + 3 * i, &u, &w, &z);
        /* one texel's depth in window units: fixed for a directional
         * light, at the pixel's depth for a perspective frame */
        float texel_z = f->box.persp ? (float)(sl_frame_texel_world_at(f, z) / sl_frame_world_per_depth(f, z))
                                     : f->texel_world / f->depth_range;
        int lit = sl_frame_pcf_lit(depth, f->size, u, w, z - bias * texel_z, 9);
        lookups += 9;
        out->v[i] = lit >= 5 ? SL_V_LIT : SL_V_SHADOW;
        out->how[i] = SL_HOW_MAP;
    }
    c->ms_method += 1e3 * (sl_now() - t0);
    c->lookups += lookups;
    return SL_OK;
}

const struct sl_method sl_method_pcf3 = {
    .name = "pcf3", .summary = "3x3 percentage-closer filtering, lit when 5 of the 9 texels light the pixel",
    SL_METHOD_PARAMS(pcf3_params), .needs = pcf3_needs, .run = pcf3_run,
};
