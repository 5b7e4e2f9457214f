/*
 * soft.c — methods for scenes with an area light (Curtis 2009). They return
 * a visible fraction of the light per pixel (out->vis, 0..1), scored against
 * the area truth (softtruth.h) by the soft figures (softfig.h).
 *
 * hard_point: the hard-shadow approximation of an area light — the light as
 * a point at its centre, each pixel lit (1) or not (0) by one exact Embree
 * ray. Its error against the area truth is what any hard-shadow method makes
 * under this light before adding errors of its own (aliasing): the
 * penumbra it cannot have.
 */
#include <math.h>
#include <omp.h>
#include <string.h>
#include <embree3/rtcore.h>
#include "arealight.h"
#include "method.h"
#include "truth.h"
#include "util.h"

static unsigned point_needs(const struct sl_method_params *p) { (void)p; return 0; }

static enum sl_err point_configure(struct sl_method_params *p, struct sl_diag *d)
{
    (void)d;
    p->set = 0;
    return SL_OK;
}

static enum sl_err point_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                             struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    if (a->scene->light.type != SL_LIGHT_AREA || !out->vis)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "method", "hard_point needs an area light");
    struct sl_area ar;
    sl_area_of(&a->scene->light, &ar);
    double t0 = sl_now();
    long np = (long)v->w * v->h;
    uint64_t rays = 0;
#pragma omp parallel for schedule(dynamic, 1024) reduction(+ : rays) num_threads(a->threads > 0 ? a->threads : omp_get_max_threads())
    for (long i = 0; i < np; i++) {
        out->v[i] = SL_V_NONE;
        out->how[i] = SL_HOW_NONE;
        out->vis[i] = 0.0f;
        if (!v->tri[i])
            continue;
        const float *p = v->pos + 3 * i, *n = v->nrm + 3 * i;
        double to[3], dist2 = 0, facing = 0, emitting = 0;
        for (int k = 0; k < 3; k++) {
            to[k] = ar.c[k] - p[k];
            dist2 += to[k] * to[k];
            facing += n[k] * to[k];
            emitting -= ar.n[k] * to[k];
        }
        out->how[i] = SL_HOW_TRACED;
        /* facing away from the centre, or behind the light: no light */
        if (!(facing > 0.0 && emitting > 0.0)) {
            out->v[i] = SL_V_SHADOW;
            continue;
        }
        double dist = sqrt(dist2);
        struct RTCRay r;
        memset(&r, 0, sizeof r);
        r.org_x = p[0];
        r.org_y = p[1];
        r.org_z = p[2];
        r.dir_x = (float)(to[0] / dist);
        r.dir_y = (float)(to[1] / dist);
        r.dir_z = (float)(to[2] / dist);
        r.tnear = sl_rt_tnear(p);
        /* stop short of the light as the area truth does (softtruth.c) */
        float q[3] = {(float)ar.c[0], (float)ar.c[1], (float)ar.c[2]};
        r.tfar = (float)dist - sl_rt_tnear(q);
        r.mask = 0xffffffffu;
        r.id = v->tri[i];   /* the own-triangle filter's key */
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        rtcOccluded1(a->rt->scene, &ctx, &r);
        rays++;
        int lit = r.tfar >= 0.0f;   /* Embree sets tfar = -inf when occluded */
        out->vis[i] = lit ? 1.0f : 0.0f;
        out->v[i] = lit ? SL_V_LIT : SL_V_SHADOW;
    }
    c->rays = rays;
    c->ms_trace = c->ms_method = 1e3 * (sl_now() - t0);
    return SL_OK;
}

const struct sl_method sl_method_hard_point = {
    .name = "hard_point",
    .summary = "area light as a point at its centre, one exact ray per pixel: the hard-shadow approximation",
    .lights = SL_LIGHTS_AREA,
    .needs = point_needs,
    .configure = point_configure,
    .run = point_run,
};
