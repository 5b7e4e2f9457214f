/*
 * zpart.c — z-partitioned shadow maps (seed 004, section 4.3.2 via its
 * appendix B; after Lloyd et al. and Tadamura et al.): k maps of the
 * configured size, one per slice of the view's depth, each over a light
 * box fitted to what the camera sees in its slice plus that slice's
 * casters (lightfit.h, sl_light_fit_slice: the existing fit, per slice).
 * A pixel is looked up in the map of the slice its view depth falls in,
 * with NSM's lookup and self-shadow policy (the NSM method itself is run
 * per slice on a copy of the view in which the other slices' pixels are
 * background, so the two cannot drift apart: k = 1 is NSM pixel for pixel).
 *
 * Split planes: eq. 62's iterative form with lambda (1 = eq. 63, the
 * logarithmic split; 0 = uniform). n and f are the least and greatest view
 * depths of the visible pixels, not the camera's near and far planes: the
 * thesis splits the view frustum, but a config's near plane often lies far
 * in front of the nearest surface (Moderno's scenes: near 20), and slices
 * in front of every surface would be maps spent on nothing. The tightest
 * range is the choice that gives every slice receivers.
 *
 * Invariants: every visible pixel lies in exactly one slice (slice[]);
 * each slice's box holds its receivers and casters (tests/test_zpart.c).
 * The maps are rendered here (the method owns them: the frame builder
 * renders one frame per view and map size), so ms_method includes the k
 * fits, renders and readbacks besides the lookups; a slice without a PFL
 * pixel gets no map. With warp lispsm each slice's map is a LiSPSM frame
 * (lightfit.h, sl_light_fit_lispsm, with the slice's planes as z_n and
 * z_f). Directional lights only (an area light taken as a
 * point would need a perspective fit per slice: not done).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "lightfit.h"
#include "method.h"
#include "shadowmap.h"
#include "util.h"
#include "zpart.h"

extern const struct sl_method sl_method_nsm;

#define ZPART_MAX 8

static unsigned zpart_needs(const struct sl_method_params *p)
{
    (void)p;
    return 0;   /* no layer of the cell's frame: it renders its own */
}

static const struct sl_param zpart_params[] = {
    SL_SELF_SHADOW_DECL,
    SL_DEPTH_BIAS_DECLS,
    SL_PARAM_INT_DECL("partitions", 4, 1, ZPART_MAX, "", "shadow maps over the view's depth slices"),
    SL_PARAM_FLOAT_DECL("lambda", 0.5, 0, 1, "", "split planes, 0 uniform .. 1 logarithmic (seed 004 eq. 62)"),
    SL_PARAM_CHOICE_DECL("warp", 0, "each slice's map uniform (orthographic) or lispsm (Wimmer et al. 2004)",
                         "uniform", "lispsm"),
};

static enum sl_err zpart_configure(struct sl_method_params *p, struct sl_diag *d)
{
    enum sl_err e = sl_method_nsm.configure(p, d);
    if (e)
        return e;
    int policy = (int)sl_method_param(p, "self_shadow");
    if (sl_method_param(p, "warp") != 0 && (policy == SL_SELF_CONSTANT || policy == SL_SELF_SLOPE))
        return sl_fail(d, SL_E_METHOD, NULL, 0, "self_shadow",
                       "warp lispsm takes self_shadow front_faces, none or triangle_id: a depth bias in "
                       "texels assumes a uniform map");
    return SL_OK;
}

/* The slice of view depth z among planes[0..k]: the last i with planes[i] <= z. */
static int slice_of(const double *planes, int k, double z)
{
    int i = 0;
    while (i + 1 < k && z >= planes[i + 1])
        i++;
    return i;
}

void sl_zpart_slices(const struct sl_view *v, int k, double lambda, double *planes, uint8_t *slice)
{
    float zmin, zmax;
    sl_view_depth_range(v, &zmin, &zmax);
    sl_zsplit_iterative(zmin, zmax, k, lambda, planes);
    size_t n = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < n; i++)
        slice[i] = v->cls[i] == SL_C_BACKGROUND ? 255 : (uint8_t)slice_of(planes, k, sl_view_depth(v, v->pos + 3 * i));
}

/* A frame for box b at map size `size`, as the driver builds the cell's. */
static void frame_for(const struct sl_scene *s, const struct sl_light_box *b, int size, struct sl_light_frame *f)
{
    memset(f, 0, sizeof *f);
    f->size = size;
    memcpy(f->dir, s->light_dir, sizeof f->dir);
    f->box = *b;
    f->texel_world = fmaxf(b->hi[0] - b->lo[0], b->hi[1] - b->lo[1]) / (float)size;
    f->depth_range = b->hi[2] - b->lo[2];
}

enum sl_err sl_zpart_run_k(const struct sl_method_args *a, int k, double lambda, int lispsm,
                           struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_method_params *p = a->params;
    const char *who = lispsm && k == 1 ? "lispsm" : "zpart";
    if (!a->spass || !a->mesh)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "%s: no shadow-map pass to render its maps with", who);
    if (a->scene->light.type != SL_LIGHT_DIRECTIONAL)
        return sl_fail(d, SL_E_METHOD, NULL, 0, who, "%s needs a directional light", who);
    double t0 = sl_now();
    sl_verdicts_drop_frames(out);
    const size_t n = (size_t)v->w * (size_t)v->h;
    double planes[ZPART_MAX + 1];
    out->slice = malloc(n);
    out->frames = calloc((size_t)k, sizeof *out->frames);
    uint8_t *cls = malloc(n), *tv = malloc(2 * n);
    if (!out->slice || !out->frames || !cls || !tv) {
        free(cls);
        free(tv);
        sl_verdicts_drop_frames(out);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "%s: slices of %zu pixels", who, n);
    }
    out->nown = k;
    sl_zpart_slices(v, k, lambda, planes, out->slice);
    for (size_t i = 0; i < n; i++)
        sl_verdict_fixed(v, i, out);
    const unsigned needs = sl_method_nsm.needs(p);
    struct sl_verdicts tmp = *out;
    tmp.v = tv;
    tmp.how = tv + n;
    tmp.frames = NULL;
    tmp.nframes = tmp.nown = 0;
    tmp.slice = NULL;
    struct sl_view mv = *v;
    mv.cls = cls;
    enum sl_err e = SL_OK;
    for (int s = 0; s < k && !e; s++) {
        struct sl_light_box box;
        double nopt;
        if (lispsm)
            sl_light_fit_lispsm(a->scene, v, out->slice, (uint8_t)s, planes[s], planes[s + 1], &box, &nopt);
        else
            sl_light_fit_slice_mt(a->scene, v, out->slice, (uint8_t)s, &box, a->threads);
        if (box.n_receivers == 0)
            continue;   /* no PFL pixel here: no map (size 0 marks it) */
        frame_for(a->scene, &box, a->frame->size, &out->frames[s]);
        if ((e = sl_shadowmap_render(a->spass, a->mesh, &out->frames[s], needs, d)))
            break;
        /* the slice's map pass and readback are the cell's map and readback
         * stages (method.h), as the driver's layers are a C method's */
        for (int l = 0; l < SL_LAYER_COUNT; l++)
            if (out->frames[s].have & SL_NEED(l)) {
                c->ms_map += out->frames[s].layer[l].ms_render;
                c->ms_readback += out->frames[s].layer[l].ms_readback;
                c->gpu_map += out->frames[s].layer[l].ms_gpu;
            }
        for (size_t i = 0; i < n; i++)
            cls[i] = out->slice[i] == s ? v->cls[i] : (uint8_t)SL_C_BACKGROUND;
        struct sl_method_args na = *a;
        na.view = &mv;
        na.frame = &out->frames[s];
        struct sl_cost nc = {0};
        if ((e = sl_method_nsm.run(&na, &tmp, &nc, d)))
            break;
        for (size_t i = 0; i < n; i++)
            if (out->slice[i] == s && v->cls[i] == SL_C_PFL) {
                out->v[i] = tmp.v[i];
                out->how[i] = tmp.how[i];
            }
        c->lookups += nc.lookups;
        /* scoring needs the slice's box and size only (its m): the layers go now,
         * so k maps of the largest size are never held past the lookups */
        for (int l = 0; l < SL_LAYER_COUNT; l++) {
            free(out->frames[s].layer[l].depth);
            free(out->frames[s].layer[l].id);
            out->frames[s].layer[l].depth = NULL;
            out->frames[s].layer[l].id = NULL;
        }
        out->frames[s].have = 0;
    }
    free(cls);
    free(tv);
    if (e) {
        sl_verdicts_drop_frames(out);
        return e;
    }
    out->nframes = k;
    c->ms_method += 1e3 * (sl_now() - t0);
    return SL_OK;
}

static enum sl_err zpart_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                             struct sl_diag *d)
{
    const struct sl_method_params *p = a->params;
    return sl_zpart_run_k(a, (int)sl_method_param(p, "partitions"), (float)sl_method_param(p, "lambda"),
                          (int)sl_method_param(p, "warp"), out, c, d);
}

const struct sl_method sl_method_zpart = {
    .name = "zpart", .display = "z-partitioned SM", .family = "seed-004",
    .summary = "z-partitioned shadow maps: NSM over k view-depth slices (partitions 1..8, lambda 0..1, "
               "warp uniform|lispsm)",
    .lights = SL_LIGHTS_DIRECTIONAL,
    .figures = SL_FIGS_ALIASING,
    SL_METHOD_PARAMS(zpart_params),
    .needs = zpart_needs,
    .configure = zpart_configure,
    .run = zpart_run,
};
