/*
 * raytrace.c — every PFL pixel traced with Embree: the reference method,
 * for the cost columns. It uses the truth's own rays (sl_rt_trace), so its
 * image is the truth; what it measures is what exactness costs without any
 * shadow map.
 */
#include "method.h"
#include "truth.h"
#include "util.h"

static unsigned rt_needs(const struct sl_method_params *p) { (void)p; return 0; }

static enum sl_err rt_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                          struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    size_t n = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < n; i++)
        sl_verdict_fixed(v, i, out);
    return sl_method_trace_left(a, NULL, NULL, out, c, d);
}

const struct sl_method sl_method_raytrace = {
    .cite = "wald2014embree",
    .name = "raytrace", .display = "Ray tracing", .beside = "morais-2015", .summary = "every PFL pixel traced with Embree (the reference, for costs)",
    .exact = SL_EXACT_LIT | SL_EXACT_SHADOW, .needs = rt_needs, .run = rt_run,
};
