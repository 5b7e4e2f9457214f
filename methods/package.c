/*
 * package.c — technique packages as methods (package.h).
 */
#include "package.h"
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "lightfit.h"
#include "techpass.h"
#include "util.h"
#include "zpart.h"

#define CASCADES_MAX 8

struct pkg {
    struct sl_method    m;
    struct sl_technique t;      /* the package (sources owned) */
    /* m's parameters: the package's own, in its order, then the cascades' */
    struct sl_param     decl[SL_TECH_MAX_PARAMS + 2];
    struct sl_techpass  pass;   /* its GL programs and maps, once prepared */
    int                 ready;
};

static enum sl_err pkg_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                           struct sl_diag *d);

/* The package a package method or its technique belongs to: the method and
 * the technique are members of one struct pkg (no table to search). */
static struct pkg *pkg_of_method(const struct sl_method *m)
{
    return m && m->run == pkg_run ? (struct pkg *)(void *)((char *)(void *)m - offsetof(struct pkg, m)) : NULL;
}
static struct pkg *pkg_of_tech(const struct sl_technique *t)
{
    return t ? (struct pkg *)(void *)((char *)(void *)t - offsetof(struct pkg, t)) : NULL;
}

static unsigned pkg_needs(const struct sl_method_params *p)
{
    (void)p;
    return SL_NEED_OWN_MAPS;   /* rendered in run (techpass.h), per face of a point light's cube */
}

/* The parameters a package entry may give beside its own: cascades
 * (partitions, lambda: the z-partitioning of zpart.c, seed 004 eq. 62).
 * partitions 1 (the default) is the cell's own light frame. */
static const struct sl_param cascade_params[2] = {
    SL_PARAM_INT_DECL("partitions", 1, 1, CASCADES_MAX, "",
                      "cascades: the package's maps over the view's depth slices (1: the cell's own frame)"),
    SL_PARAM_FLOAT_DECL("lambda", 0.5, 0, 1, "", "cascades' split planes, 0 uniform .. 1 logarithmic (seed 004 eq. 62)"),
};

static enum sl_err pkg_configure(struct sl_method_params *p, struct sl_diag *d)
{
    struct sl_params *s = &p->values;
    if (sl_params_get(s, "partitions") == 1) {
        if (sl_params_given(s, "lambda"))
            return sl_fail(d, SL_E_METHOD, NULL, 0, "lambda", "lambda splits cascades: give partitions 2 to %d",
                           CASCADES_MAX);
        return sl_params_off(s, "lambda", "cascades", d);
    }
    return SL_OK;
}

static enum sl_err pkg_ready(struct pkg *k, struct sl_diag *d)
{
    if (k->ready)
        return SL_OK;
    enum sl_err e = sl_techpass_init(&k->pass, &k->t, d);
    if (!e)
        k->ready = 1;
    return e;
}

/* The package over frame f for the pixels mask marks: maps, lookup, the
 * visibility of those pixels into vis; costs added. */
static enum sl_err pkg_frame(struct pkg *k, const struct sl_method_args *a, const struct sl_light_frame *f,
                             const uint8_t *mask, float *vis, struct sl_verdicts *out, struct sl_cost *c,
                             struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_params *tv = &a->params->values;   /* the package's come first */
    const struct sl_light *L = &a->scene->light;
    k->pass.light_width = L->type == SL_LIGHT_AREA ? fmaxf(L->size[0], L->size[1]) : 0.0f;
    k->pass.limits = (struct sl_techpass_limits){.stop = a->stop, .pass_seconds = a->pass_seconds};
    enum sl_err e = sl_techpass_render(&k->pass, a->mesh, f, tv, d);
    if (!e)
        e = sl_techpass_lookup(&k->pass, f, tv, v->pos, v->nrm, mask, v->w, v->h, vis, d);
    if (e)
        return e;
    const struct sl_techpass_costs *pc = &k->pass.costs;
    c->ms_map += pc->ms_map;
    c->ms_post += pc->ms_post;
    c->ms_readback += pc->ms_readback;
    c->gpu_map += pc->gpu_map;
    c->gpu_post += pc->gpu_post;
    c->gpu_lookup += pc->gpu_lookup;
    c->gl_passes = 1;
    c->ms_method += pc->ms_map + pc->ms_post + pc->ms_lookup + pc->ms_readback;
    c->lookups += pc->lookups;
    out->nonfinite += pc->map_nonfinite;
    return SL_OK;
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

/* Cascades: the view's depth split into p->partitions slices (zpart.h,
 * lambda between uniform and logarithmic), each slice's PFL pixels fitted
 * a tight light frame of the cell's map size and served by the package's
 * maps for it; the slices' frames go to scoring (vd->frames, slice) as
 * zpart's do, for the aliasing error m. Directional lights only (the fits
 * are orthographic). */
static enum sl_err pkg_cascades(struct pkg *k, const struct sl_method_args *a, uint8_t *mask,
                                struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const int n = (int)sl_method_param(a->params, "partitions");
    if (a->scene->light.type != SL_LIGHT_DIRECTIONAL)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "partitions", "%s: cascades need a directional light", k->t.name);
    size_t npx = (size_t)v->w * (size_t)v->h;
    double planes[CASCADES_MAX + 1];
    sl_verdicts_drop_frames(out);
    out->slice = malloc(npx);
    out->frames = calloc((size_t)n, sizeof *out->frames);
    float *part = malloc(npx * sizeof *part);
    if (!out->slice || !out->frames || !part) {
        free(part);
        sl_verdicts_drop_frames(out);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cascades of %zu pixels", npx);
    }
    out->nown = n;
    sl_zpart_slices(v, n, (float)sl_method_param(a->params, "lambda"), planes, out->slice);
    enum sl_err e = SL_OK;
    for (int s = 0; s < n && !e; s++) {
        struct sl_light_box box;
        sl_light_fit_slice_mt(a->scene, v, out->slice, (uint8_t)s, &box, a->threads);
        if (box.n_receivers == 0)
            continue;   /* no PFL pixel in the slice: no map (size 0 marks it) */
        frame_for(a->scene, &box, a->frame->size, &out->frames[s]);
        size_t any = 0;
        for (size_t i = 0; i < npx; i++)
            any += mask[i] = v->cls[i] == SL_C_PFL && out->slice[i] == s;
        if (!any)
            continue;
        if ((e = pkg_frame(k, a, &out->frames[s], mask, part, out, c, d)))
            break;
        for (size_t i = 0; i < npx; i++)
            if (mask[i])
                out->vis[i] = part[i];
    }
    free(part);
    if (e) {
        sl_verdicts_drop_frames(out);
        return e;
    }
    out->nframes = n;
    return SL_OK;
}

/* A hybrid (technique.yaml's `trace:`): the PFL pixels whose visibility
 * lies in [lo, hi] are traced with the truth's own rays (sl_method_trace_left,
 * as csm and hertel trace theirs: rays and time counted), and their
 * visibility becomes the ray's answer, 0 or 1. A visibility that is not
 * finite is in no band: it stays uncertain and counted. */
static enum sl_err pkg_trace(const struct sl_technique *t, const struct sl_method_args *a, struct sl_verdicts *out,
                             struct sl_cost *c, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    if (!a->rt)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "%s: `trace:` needs the truth's rays, which this caller "
                       "has not built", t->name);
    size_t npx = (size_t)v->w * (size_t)v->h, any = 0;
    uint8_t *left = malloc(npx);
    if (!left)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "traced band %dx%d", v->w, v->h);
    const float lo = (float)t->trace_lo, hi = (float)t->trace_hi;
    for (size_t i = 0; i < npx; i++) {
        left[i] = v->cls[i] == SL_C_PFL && out->vis[i] >= lo && out->vis[i] <= hi;
        any += left[i];
    }
    enum sl_err e = any ? sl_method_trace_left(a, left, NULL, out, c, d) : SL_OK;
    for (size_t i = 0; !e && i < npx; i++)
        if (left[i])
            out->vis[i] = out->v[i] == SL_V_LIT ? 1.0f : 0.0f;
    free(left);
    return e;
}

static enum sl_err pkg_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                           struct sl_diag *d)
{
    struct pkg *k = pkg_of_tech(a->params->tech);
    if (!k)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "a package method run without its package");
    if (!a->mesh)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "%s: a technique package needs the scene's GL mesh",
                       k->t.name);
    if (!out->vis)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "%s: no visibility buffer to write", k->t.name);
    enum sl_err e = pkg_ready(k, d);
    if (e)
        return e;
    const struct sl_view *v = a->view;
    size_t npx = (size_t)v->w * (size_t)v->h;
    uint8_t *mask = malloc(npx);
    if (!mask)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "lookup mask %dx%d", v->w, v->h);
    if (sl_method_param(a->params, "partitions") > 1) {
        e = pkg_cascades(k, a, mask, out, c, d);
    } else {
        for (size_t i = 0; i < npx; i++)
            mask[i] = v->cls[i] == SL_C_PFL;
        e = pkg_frame(k, a, a->frame, mask, out->vis, out, c, d);
    }
    free(mask);
    if (e)
        return e;
    const float thr = (float)k->t.threshold;
    for (size_t i = 0; i < npx; i++) {
        if (sl_verdict_fixed(v, i, out)) {
            out->vis[i] = 0.0f;
            continue;
        }
        /* NaN (a lookup not finite, techpass.h) is neither: uncertain */
        out->v[i] = out->vis[i] >= thr ? SL_V_LIT : out->vis[i] < thr ? SL_V_SHADOW : SL_V_UNCERTAIN;
        out->how[i] = SL_HOW_MAP;
    }
    out->has_vis = 1;
    return k->t.trace ? pkg_trace(&k->t, a, out, c, d) : SL_OK;
}

enum sl_err sl_packages_load(struct sl_packages *set, const char *const *config_dirs, int n, const char *rel_dir,
                             const char *const *c_names, struct sl_diag *d)
{
    char (*dirs)[1024] = malloc(SL_TECH_MAX_DIRS * sizeof *dirs);
    const char *origin[SL_TECH_MAX_DIRS];
    if (!dirs)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "technique search path");
    int nd = sl_tech_dirs(config_dirs, n, rel_dir, dirs, origin, SL_TECH_MAX_DIRS);
    struct sl_tech_set s;
    enum sl_err e = sl_tech_set_scan(&s, dirs, origin, nd, c_names, d);
    free(dirs);
    if (e)
        return e;
    for (int i = 0; i < s.n && !e; i++) {
        if (sl_packages_find(set, s.t[i].name))
            continue;   /* loaded from an earlier search path: the first wins */
        if (set->n == SL_TECH_MAX_SET) {
            e = sl_fail(d, SL_E_PACKAGE, s.t[i].file, 0, "name", "more than %d technique packages", SL_TECH_MAX_SET);
            break;
        }
        struct pkg *k = calloc(1, sizeof *k);
        if (!k) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "technique package");
            break;
        }
        k->t = s.t[i];              /* takes the sources over */
        s.t[i].map_src = s.t[i].lookup_src = NULL;
        memcpy(k->decl, k->t.param, (size_t)k->t.nparams * sizeof k->decl[0]);
        memcpy(k->decl + k->t.nparams, cascade_params, sizeof cascade_params);
        k->m = (struct sl_method){
            .name = k->t.name,
            .summary = k->t.summary,
            .family = k->t.family,
            .display = k->t.display[0] ? k->t.display : NULL,
            /* a hybrid's traced pixels are the truth's: checked on every cell */
            .exact = k->t.trace ? SL_EXACT_PROVED : 0,
            .lights = 0,
            .params = k->decl,
            .nparams = k->t.nparams + 2,
            .needs = pkg_needs,
            .configure = pkg_configure,
            .run = pkg_run,
        };
        set->pkg[set->n++] = k;
    }
    sl_tech_set_free(&s);
    return e;
}

const struct sl_method *sl_packages_find(const struct sl_packages *set, const char *name)
{
    for (int i = 0; set && i < set->n; i++)
        if (!strcmp(set->pkg[i]->t.name, name))
            return &set->pkg[i]->m;
    return NULL;
}

const struct sl_technique *sl_package_of(const struct sl_method *m)
{
    struct pkg *k = pkg_of_method(m);
    return k ? &k->t : NULL;
}

int sl_packages_count(const struct sl_packages *set) { return set ? set->n : 0; }
const struct sl_technique *sl_packages_at(const struct sl_packages *set, int i)
{
    return set && i >= 0 && i < set->n ? &set->pkg[i]->t : NULL;
}

enum sl_err sl_package_prepare(const struct sl_method *m, struct sl_diag *d)
{
    struct pkg *k = pkg_of_method(m);
    return k ? pkg_ready(k, d) : SL_OK;
}

enum sl_err sl_package_fits(const struct sl_method *m, const struct sl_method_params *p, int size, struct sl_diag *d)
{
    struct pkg *k = pkg_of_method(m);
    if (!k)
        return SL_OK;
    enum sl_err e = pkg_ready(k, d);
    struct sl_light_frame f = {.size = size};
    int g, n;
    return e ? e : sl_techpass_size(&k->pass, &f, &p->values, &g, &n, d);
}

void sl_packages_release_gl(struct sl_packages *set)
{
    for (int i = 0; set && i < set->n; i++)
        if (set->pkg[i]->ready) {
            sl_techpass_free(&set->pkg[i]->pass);
            set->pkg[i]->ready = 0;
        }
}

void sl_packages_free(struct sl_packages *set)
{
    for (int i = 0; set && i < set->n; i++) {
        sl_tech_free(&set->pkg[i]->t);
        free(set->pkg[i]);
    }
    if (set)
        set->n = 0;
}
