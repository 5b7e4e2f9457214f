/*
 * method.c — the helpers of method.h that several methods share: tracing
 * the pixels the maps leave undecided with the truth's own rays
 * (harness/truth/truth.c), so a traced pixel gets, ray for ray, the truth's
 * answer. The table of methods and its lookups are in registry.c.
 */
#include <stdlib.h>
#include <string.h>
#include "method.h"
#include "raytri.h"
#include "truth.h"
#include "util.h"

void sl_method_params_init(const struct sl_method *m, struct sl_method_params *p)
{
    memset(p, 0, sizeof *p);
    sl_params_init(&p->values, m->params, m->nparams);
}

enum sl_err sl_method_configure(const struct sl_method *m, struct sl_method_params *p, struct sl_diag *d)
{
    return m->configure ? m->configure(p, d) : SL_OK;
}

int sl_method_unmapped_missed(const struct sl_method_args *a, const float p[3], uint32_t own, uint64_t *tests)
{
    const struct sl_light_box *b = &a->frame->box;
    if (!b->n_unmapped)
        return 1;
    if (!b->unmapped)
        return 0;   /* not listed (out of memory): nothing is claimed */
    const struct sl_scene *s = a->scene;
    float toward[3], tmax;
    sl_frame_toward(a->frame, p, toward, &tmax);
    for (uint32_t k = 0; k < b->n_unmapped; k++) {
        if (b->unmapped[k] + 1u == own)
            continue;   /* the truth ignores the pixel's own triangle */
        const uint32_t *ix = s->idx + 3 * (size_t)b->unmapped[k];
        (*tests)++;
        if (sl_shadow_ray_tri_sure(p, toward, tmax, sl_rt_tnear(p), s->pos + 3 * ix[0], s->pos + 3 * ix[1],
                                   s->pos + 3 * ix[2]) >= 0)
            return 0;
    }
    return 1;
}

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

void sl_verdicts_drop_frames(struct sl_verdicts *vd)
{
    for (int k = 0; k < vd->nown; k++) {
        sl_light_box_free(&vd->frames[k].box);
        sl_frame_free(&vd->frames[k]);
    }
    free(vd->frames);
    free(vd->slice);
    vd->frames = NULL;
    vd->slice = NULL;
    vd->nframes = vd->nown = 0;
}

enum sl_err sl_method_make_looks(struct sl_light_frame *f, int own_frame, const struct sl_view *v,
                                 const struct sl_method *m, unsigned needs, unsigned shared, int threads,
                                 struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    const size_t n = (size_t)v->w * (size_t)v->h;
    for (int l = 0; l < SL_LAYER_COUNT && !e; l++)
        if ((sl_method_looks(m) & needs & f->have & SL_NEED(l)) && !f->layer[l].per_pixel &&
            ((own_frame && (shared & SL_NEED(l))) || sl_frame_look_of(f, l, v->serial, n)))
            e = sl_frame_look(f, l, v, threads, sl_method_look_parts(m), d);
    return e;
}
