/*
 * package.c — technique packages as methods (package.h).
 */
#include "package.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "techpass.h"
#include "util.h"

struct pkg {
    struct sl_method    m;
    struct sl_technique t;      /* the package (sources owned) */
    struct sl_techpass  pass;   /* its GL programs and maps, once prepared */
    int                 ready;
};

static struct pkg *pkgs[SL_TECH_MAX_SET];
static int         npkgs;

static struct pkg *pkg_of_tech(const struct sl_technique *t)
{
    for (int i = 0; i < npkgs; i++)
        if (&pkgs[i]->t == t)
            return pkgs[i];
    return NULL;
}

static unsigned pkg_needs(const struct sl_method_params *p)
{
    (void)p;
    return 0;   /* the maps are its own (techpass.h), rendered in run */
}

static enum sl_err pkg_configure(struct sl_method_params *p, struct sl_diag *d)
{
    if (p->set)   /* the config gives a package no knob (config.c takes its keys as parameters) */
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "a technique package takes its own parameters only");
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
    const struct sl_tech_values *tv = &a->params->pkg;
    size_t npx = (size_t)v->w * (size_t)v->h;
    uint8_t *mask = malloc(npx);
    if (!mask)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "lookup mask %dx%d", v->w, v->h);
    for (size_t i = 0; i < npx; i++)
        mask[i] = v->cls[i] == SL_C_PFL;
    e = sl_techpass_render(&k->pass, a->mesh, a->frame, tv, d);
    if (!e)
        e = sl_techpass_lookup(&k->pass, a->frame, tv, v->pos, v->nrm, mask, v->w, v->h, out->vis, d);
    free(mask);
    if (e)
        return e;
    const struct sl_techpass_costs *pc = &k->pass.costs;
    const float thr = (float)k->t.threshold;
    for (size_t i = 0; i < npx; i++) {
        if (sl_verdict_fixed(v, i, out)) {
            out->vis[i] = 0.0f;
            continue;
        }
        out->v[i] = out->vis[i] >= thr ? SL_V_LIT : SL_V_SHADOW;
        out->how[i] = SL_HOW_MAP;
    }
    out->has_vis = 1;
    c->ms_step[0] += pc->ms_map;
    c->ms_step[1] += pc->ms_post;
    c->ms_step[2] += pc->ms_lookup;
    c->ms_step[3] += pc->ms_readback;
    c->ms_method += pc->ms_map + pc->ms_post + pc->ms_lookup + pc->ms_readback;
    c->lookups += pc->lookups;
    return SL_OK;
}

enum sl_err sl_packages_load(const char *const *config_dirs, int n, const char *rel_dir,
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
        if (sl_package_find(s.t[i].name))
            continue;   /* loaded from an earlier search path: the first wins */
        if (npkgs == SL_TECH_MAX_SET) {
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
        k->m = (struct sl_method){
            .name = k->t.name,
            .summary = k->t.summary,
            .exact = 0,
            .lights = SL_LIGHTS_NO_POINT,
            .params_ok = 0,
            .needs = pkg_needs,
            .configure = pkg_configure,
            .run = pkg_run,
        };
        pkgs[npkgs++] = k;
    }
    sl_tech_set_free(&s);
    return e;
}

const struct sl_method *sl_package_find(const char *name)
{
    for (int i = 0; i < npkgs; i++)
        if (!strcmp(pkgs[i]->t.name, name))
            return &pkgs[i]->m;
    return NULL;
}

const struct sl_technique *sl_package_of(const struct sl_method *m)
{
    for (int i = 0; i < npkgs; i++)
        if (&pkgs[i]->m == m)
            return &pkgs[i]->t;
    return NULL;
}

int sl_package_count(void) { return npkgs; }
const struct sl_technique *sl_package_at(int i) { return i >= 0 && i < npkgs ? &pkgs[i]->t : NULL; }

enum sl_err sl_package_prepare(const struct sl_method *m, struct sl_diag *d)
{
    for (int i = 0; i < npkgs; i++)
        if (&pkgs[i]->m == m)
            return pkg_ready(pkgs[i], d);
    return SL_OK;
}

void sl_packages_release_gl(void)
{
    for (int i = 0; i < npkgs; i++)
        if (pkgs[i]->ready) {
            sl_techpass_free(&pkgs[i]->pass);
            pkgs[i]->ready = 0;
        }
}
