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
 *
 * soft_mc: see below.
 */
#include <math.h>
#include <omp.h>
#include <string.h>
#include <embree3/rtcore.h>
#include "arealight.h"
#include "method.h"
#include "softmap.h"
#include "softmc.h"
#include "truth.h"
#include "util.h"

static unsigned point_needs(const struct sl_method_params *p) { (void)p; return 0; }

static enum sl_err point_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                             struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    if (a->scene->light.type != SL_LIGHT_AREA || !out->vis)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "method", "hard_point needs an area light");
    const struct sl_light *L = &a->scene->light;
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
        out->how[i] = SL_HOW_TRACED;
        float dir[3], tfar;
        /* facing away from the centre, or behind the light: no light */
        if (!sl_point_faces(L, p, n) || !sl_point_ray(L->pos, p, dir, &tfar)) {
            out->v[i] = SL_V_SHADOW;
            continue;
        }
        struct RTCRay r;
        memset(&r, 0, sizeof r);
        r.org_x = p[0];
        r.org_y = p[1];
        r.org_z = p[2];
        r.dir_x = dir[0];
        r.dir_y = dir[1];
        r.dir_z = dir[2];
        r.tnear = sl_rt_tnear(p);
        r.tfar = tfar;   /* stops short of the light as the area truth does (softtruth.c) */
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
    .cite = "curtis2009",
    .name = "hard_point", .display = "Hard shadows (point)", .family = "curtis-2009",
    .summary = "area light as a point at its centre, one exact ray per pixel: the hard-shadow approximation",
    .lights = SL_LIGHTS_AREA,
    .needs = point_needs,
    .run = point_run,
};

/*
 * soft_mc: Curtis 2009 (softmc.h) as a method. Parameters: grid (rays per
 * pixel = grid^2, default 3; Curtis uses 2 and 3), search (hierarchical or
 * linear), layers (2, default; 1: the single-layer variant; 3: near, far
 * and the camera's depth, 3.4), blur (the depth-sensitive screen-space
 * blur, default false). The search defaults to hierarchical with 1 or 2
 * layers and to linear with 3: the third layer decides points between the
 * layers, which only the linear search samples (softmc.h), so layers 3
 * with search hierarchical is refused rather than quietly run linear.
 * Its samples use the config's seed + 1, so they are never the very points
 * the area truth draws (same grid, same seed would cancel their errors).
 */
static unsigned mc_needs(const struct sl_method_params *p) { (void)p; return SL_NEED_SOFT; }

static const struct sl_param mc_params[] = {
    SL_PARAM_INT_DECL("grid", 3, 1, 16, "", "rays per pixel = grid x grid (jittered points on the light)"),
    SL_PARAM_CHOICE_DECL("search", 1, "the occluder search: linear (+ binary refinement) or hierarchical (N-buffer); "
                         "default hierarchical, linear under layers 3", "linear", "hierarchical"),
    SL_PARAM_INT_DECL("layers", 2, 1, 3, "", "1 (near only), 2 (near and far) or 3 (and the camera's depth)"),
    SL_PARAM_BOOL_DECL("blur", 0, "true: the depth-sensitive screen-space blur; false: none"),
};

/* layers 3 reads the camera's depth, which only the linear search can
 * use: search defaults to linear there, and hierarchical is refused */
static enum sl_err mc_configure(struct sl_method_params *p, struct sl_diag *d)
{
    struct sl_params *s = &p->values;
    int layers = (int)sl_params_get(s, "layers");
    if (!sl_params_given(s, "search"))
        sl_params_derive(s, "search", layers == 3 ? 0 : 1);
    if (layers == 3 && sl_params_get(s, "search") != 0)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "layers",
                       "layers 3 (the camera's depth as a third layer) needs search: linear; the hierarchical "
                       "search cannot use it");
    return SL_OK;
}

static enum sl_err mc_desc_run(const struct sl_method_args *a, const struct sl_softmc_desc *desc_in,
                               struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d);

static enum sl_err mc_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                          struct sl_diag *d)
{
    const struct sl_method_params *p = a->params;
    struct sl_softmc_desc desc = {
        .grid = (int)sl_method_param(p, "grid"), .seed = a->seed + 1u,
        .search = sl_method_param(p, "search") != 0 ? SL_SOFTMC_HIER : SL_SOFTMC_LINEAR,
        .layers = (int)sl_method_param(p, "layers"), .blur_radius = sl_method_param(p, "blur") != 0 ? 4 : 0,
        .threads = a->threads,
    };
    return mc_desc_run(a, &desc, out, c, d);
}

/* point_map: the hard shadow-map approximation of an area light — one ray
 * per pixel to the light's centre tested against the near layer alone,
 * which is a conventional shadow map from the centre (with Curtis's bias):
 * hard_point's answer plus the map's own aliasing. */
static enum sl_err pm_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                          struct sl_diag *d)
{
    struct sl_softmc_desc desc = {.grid = 1, .layers = 1, .centre = 1, .search = SL_SOFTMC_HIER,
                                  .threads = a->threads};
    return mc_desc_run(a, &desc, out, c, d);
}

static enum sl_err mc_desc_run(const struct sl_method_args *a, const struct sl_softmc_desc *desc_in,
                               struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d)
{
    if (!a->softmap || !a->softmap->nbuf || !out->vis)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, "method", "soft_mc without its layers");
    struct sl_softmc_desc desc = *desc_in;
    struct sl_softmc_result r;
    memset(&r, 0, sizeof r);
    double t0 = sl_now();
    enum sl_err e = sl_softmc_run(a->softmap, a->view, &desc, &r, d);
    if (!e) {
        const struct sl_view *v = a->view;
        const float *src = r.vis_blur ? r.vis_blur : r.vis;
        size_t np = (size_t)v->w * (size_t)v->h;
        for (size_t i = 0; i < np; i++) {
            out->vis[i] = src[i];
            out->v[i] = !v->tri[i] ? SL_V_NONE : src[i] >= 1.0f ? SL_V_LIT : src[i] <= 0.0f ? SL_V_SHADOW : SL_V_UNCERTAIN;
            out->how[i] = v->tri[i] ? SL_HOW_MAP : SL_HOW_NONE;
        }
        c->rays = r.st.rays;
        c->lookups = r.st.lookups;
        c->ms_trace = r.st.ms_trace;
    }
    c->ms_method = 1e3 * (sl_now() - t0);
    sl_softmc_result_free(&r);
    return e;
}

const struct sl_method sl_method_soft_mc = {
    .cite = "curtis2009",
    .name = "soft_mc", .display = "Monte Carlo soft shadows", .family = "curtis-2009",
    .summary = "Curtis 2009: rays to jittered points on an area light through near/far layers, or near/far + "
               "the camera's depth with layers 3 and linear search (grid, search, layers, blur)",
    .lights = SL_LIGHTS_AREA,
    SL_METHOD_PARAMS(mc_params),
    .needs = mc_needs,
    .configure = mc_configure,
    .run = mc_run,
};

const struct sl_method sl_method_point_map = {
    .cite = "curtis2009",
    .name = "point_map", .display = "Point-light map", .family = "curtis-2009",
    .summary = "area light as a point at its centre through a shadow map (soft_mc's near layer): the hard map approximation",
    .lights = SL_LIGHTS_AREA,
    .needs = mc_needs,
    .run = pm_run,
};
