/*
 * common.c — what several methods share: tracing the pixels the maps leave
 * undecided, with the truth's own rays (harness/truth.c), so a traced pixel
 * gets, ray for ray, the truth's answer.
 */
#include <stdlib.h>
#include "method.h"
#include "truth.h"
#include "util.h"

enum sl_err sl_method_trace_left(const struct sl_method_args *a, const uint8_t *left, const float *tfar,
                                 struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    size_t n = (size_t)v->w * (size_t)v->h;
    uint8_t *traced = sl_calloc(n, 1);
    if (!traced)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "traced pixels");
    double t0 = sl_now();
    uint64_t rays = 0;
    enum sl_err e = sl_rt_trace_until(a->rt, a->scene, v, left, tfar, traced, &rays, NULL, d);
    for (size_t i = 0; !e && i < n; i++)
        if (!left || left[i]) {
            if (v->cls[i] != SL_C_PFL)
                continue;
            out->v[i] = traced[i] == SL_T_SHADOW ? SL_V_SHADOW : SL_V_LIT;
            out->how[i] = SL_HOW_TRACED;
        }
    double ms = 1e3 * (sl_now() - t0);
    c->rays += rays;
    c->ms_trace += ms;
    c->ms_method += ms;
    free(traced);
    return e;
}
