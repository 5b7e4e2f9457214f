/*
 * raytrace.c — every PFL pixel traced with Embree: the reference method,
 * for the cost columns. It uses the truth's own rays (sl_rt_trace), so its
 * image is the truth; what it measures is what exactness costs without any
 * shadow map.
 */
#include <stdlib.h>
#include "method.h"
#include "truth.h"
#include "util.h"

static unsigned rt_needs(const struct sl_method_params *p) { (void)p; return 0; }

static enum sl_err rt_configure(struct sl_method_params *p, struct sl_diag *d)
{
    (void)d;
    p->set = 0;
    return SL_OK;
}

static enum sl_err rt_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                          struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    size_t n = (size_t)v->w * (size_t)v->h;
    uint8_t *traced = sl_calloc(n, 1);
    if (!traced)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "raytrace buffer");
    double t0 = sl_now();
    uint64_t rays = 0;
    enum sl_err e = sl_rt_trace(a->rt, a->scene, v, NULL, traced, &rays, NULL, d);
    for (size_t i = 0; !e && i < n; i++) {
        if (v->cls[i] == SL_C_BACKGROUND) {
            out->v[i] = SL_V_NONE;
            out->how[i] = SL_HOW_NONE;
        } else if (v->cls[i] == SL_C_PNFL) {
            out->v[i] = SL_V_SHADOW;
            out->how[i] = SL_HOW_PNFL;
        } else {
            out->v[i] = traced[i] == SL_T_SHADOW ? SL_V_SHADOW : SL_V_LIT;
            out->how[i] = SL_HOW_TRACED;
        }
    }
    double ms = 1e3 * (sl_now() - t0);
    c->ms_method += ms;
    c->ms_trace += ms;
    c->rays += rays;
    free(traced);
    return e;
}

const struct sl_method sl_method_raytrace = {
    .name = "raytrace", .summary = "every PFL pixel traced with Embree (the reference, for costs)",
    .exact = SL_EXACT_LIT | SL_EXACT_SHADOW, .needs = rt_needs, .configure = rt_configure, .run = rt_run,
};
