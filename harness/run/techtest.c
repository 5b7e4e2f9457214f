/*
 * techtest.c — a technique package's test (techtest.h).
 * Invariants: every draw is the package at its defaults over the same
 * light frame and the same PFL pixels; the runs differ only in what
 * techtest.h says each one changes (nothing, the fill, the tap count), so
 * a difference between two is the package's. Comparisons are of the bits a
 * lookup returned (NaN equal to NaN: the readback makes every non-finite
 * value one NaN), and of the verdict the threshold gives.
 */
#include "techtest.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "gbuffer.h"
#include "lightfit.h"
#include "lightframe.h"
#include "method.h"
#include "preview.h"
#include "scenefile.h"
#include "techcheck.h"
#include "technique.h"
#include "techpass.h"
#include "util.h"

/* The package of that name on the search path, as `show technique` finds
 * it; SL_E_USAGE naming those found when none is. */
static enum sl_err find_package(const char *name, struct sl_tech_set *s, const struct sl_technique **t,
                                struct sl_diag *d)
{
    static const char *c_names[64];
    int nc = 0;
    for (int i = 0; i < sl_method_count() && nc < 63; i++)
        c_names[nc++] = sl_method_at(i)->name;
    c_names[nc] = NULL;
    char (*dirs)[1024] = malloc(SL_TECH_MAX_DIRS * sizeof *dirs);
    const char *origin[SL_TECH_MAX_DIRS];
    if (!dirs)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "technique search path");
    int nd = sl_tech_dirs(NULL, 0, NULL, dirs, origin, SL_TECH_MAX_DIRS);
    enum sl_err e = sl_tech_set_scan(s, dirs, origin, nd, c_names, d);
    free(dirs);
    if (e)
        return e;
    *t = sl_tech_find(s, name);
    if (*t)
        return SL_OK;
    char names[600] = "";
    for (int i = 0; i < s->n; i++)
        sl_known_add(names, sizeof names, s->t[i].name);
    e = sl_fail(d, SL_E_USAGE, NULL, 0, name, "no technique package of that name (found: %s; "
                "`shadowlab list techniques` says where)", s->n ? names : "none");
    sl_tech_set_free(s);
    return e;
}

/* Pixels where a and b differ (bits; NaN equal to NaN) among those mask
 * marks; of them, those whose verdict at thr differs; the first (x, y). */
static uint64_t differ(const float *a, const float *b, const uint8_t *mask, int w, int h, double thr,
                       uint64_t *verdicts, int *fx, int *fy)
{
    uint64_t n = 0, nv = 0;
    *fx = *fy = -1;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (!mask[i] || (isnan(a[i]) && isnan(b[i])) || memcmp(&a[i], &b[i], sizeof a[i]) == 0)
                continue;
            if (!n++) {
                *fx = x;
                *fy = y;
            }
            nv += (a[i] >= thr) != (b[i] >= thr);
        }
    if (verdicts)
        *verdicts = nv;
    return n;
}

/* The package's maps and lookup over frame f: vis gets w * h values. */
static enum sl_err draw(struct sl_techpass *p, const struct sl_gl_mesh *m, const struct sl_light_frame *f,
                        const struct sl_params *v, const struct sl_view *view, const uint8_t *mask, float *vis,
                        struct sl_diag *d)
{
    enum sl_err e = sl_techpass_render(p, m, f, v, d);
    return e ? e : sl_techpass_lookup(p, f, v, view->pos, view->nrm, mask, view->w, view->h, vis, d);
}

/* The checks of techtest.h on one view and frame, the pass made, added to
 * r (counts summed, the first reach pixel kept, the taps' sum in *taps_sum). */
static enum sl_err checks(struct sl_techpass *p, const struct sl_technique *t, const struct sl_gl_mesh *m,
                          const struct sl_light_frame *f, const struct sl_view *view, const uint8_t *mask,
                          struct sl_techtest_result *r, double *taps_sum, struct sl_diag *d)
{
    struct sl_params v;
    sl_tech_defaults(t, &v);
    const size_t n = (size_t)view->w * (size_t)view->h;
    float *run[4];
    for (int i = 0; i < 4; i++)
        run[i] = malloc(n * sizeof(float));
    enum sl_err e = run[0] && run[1] && run[2] && run[3] ? SL_OK
                    : sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "visibility of %zu pixels", n);
    /* determinism: the ordinary draw twice */
    if (!e)
        e = draw(p, m, f, &v, view, mask, run[0], d);
    if (!e)
        e = draw(p, m, f, &v, view, mask, run[1], d);
    if (!e) {   /* the second run's costs: the first's hold the driver's first use of the programs */
        const struct sl_techpass_costs *c = &p->costs;
        r->ms_map += c->ms_map;
        r->ms_post += c->ms_post;
        r->ms_lookup += c->ms_lookup;
        r->pixels += c->pixels;
        r->nonfinite += c->nonfinite;
        r->map_nonfinite += c->map_nonfinite;
        r->guard = c->guard;
        r->reach = sl_tech_reach(t, &v);
    }
    int x, y;
    if (!e)
        r->unstable += differ(run[0], run[1], mask, view->w, view->h, t->threshold, NULL, &x, &y);
    /* reach: the band beyond the declared guard, near and empty */
    for (int k = 0; k < 2 && !e; k++) {
        p->extra = SL_TECHTEST_EXTRA;
        p->fill = (float)k;
        e = draw(p, m, f, &v, view, mask, run[2 + k], d);
    }
    p->extra = 0;
    if (!e) {
        uint64_t nv = 0;
        const uint64_t nc = differ(run[2], run[3], mask, view->w, view->h, t->threshold, &nv, &x, &y);
        if (nc && !r->reach_changed) {
            r->reach_x = x;
            r->reach_y = y;
        }
        r->reach_changed += nc;
        r->reach_verdicts += nv;
    }
    /* taps: the reads counted per pixel */
    if (!e) {
        p->count_taps = 1;
        e = draw(p, m, f, &v, view, mask, run[2], d);
        p->count_taps = 0;
    }
    for (size_t i = 0; !e && i < n; i++) {
        if (!mask[i])
            continue;
        const uint32_t c = (uint32_t)run[2][i];
        *taps_sum += c;
        r->taps_min = c < r->taps_min ? c : r->taps_min;
        r->taps_max = c > r->taps_max ? c : r->taps_max;
    }
    for (int i = 0; i < 4; i++)
        free(run[i]);
    return e;
}

/* The taps count is a finding when the package declares taps and no pixel
 * made as many reads as it declares, or some made more: the declared count
 * is the cost a run records for every pixel, so it must lie within what
 * the pixels did. */
static int taps_finding(const struct sl_techtest_result *r)
{
    if (!r->taps_given || r->pixels == 0)
        return 0;
    return r->taps_declared > (double)r->taps_max + 1e-9 || r->taps_declared < (double)r->taps_min - 1e-9;
}

/* The view's light frames as a run fits them (a point light: the faces of
 * its cube with receivers, each over its own pixels), the checks over each. */
static enum sl_err frames_run(struct sl_techpass *p, const struct sl_technique *t, const struct sl_scene *s,
                              const struct sl_gl_mesh *m, const struct sl_view *view, struct sl_techtest_result *r,
                              struct sl_diag *d)
{
    const size_t n = (size_t)view->w * (size_t)view->h;
    const int size = r->map_size, cube = s->light.type == SL_LIGHT_POINT;
    uint8_t *mask = malloc(n), *face = cube ? malloc(n) : NULL;
    if (!mask || (cube && !face)) {
        free(mask);
        free(face);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "lookup mask %dx%d", view->w, view->h);
    }
    struct sl_light_box box[6];
    memset(box, 0, sizeof box);
    if (cube) {
        sl_cube_faces(s->light.pos, view, face, 0);
        /* the cube's own band, as lightframe.c fits it */
        sl_light_fit_cube_mt(s, view, s->light.pos, face, size, size > 4 * SL_CUBE_GUARD ? SL_CUBE_GUARD : 0, box,
                             0);
    } else {
        sl_light_fit(s, view, &box[0]);
    }
    p->light_width = s->light.type == SL_LIGHT_AREA ? fmaxf(s->light.size[0], s->light.size[1]) : 0.0f;
    r->taps_min = UINT32_MAX;
    double taps_sum = 0;
    enum sl_err e = SL_OK;
    for (int k = 0; k < (cube ? 6 : 1); k++) {
        if (e || box[k].n_receivers == 0)
            continue;
        struct sl_light_frame f;
        memset(&f, 0, sizeof f);
        f.size = size;
        if (cube)
            sl_cube_axis(k, f.dir);
        else
            memcpy(f.dir, s->light_dir, sizeof f.dir);
        f.box = box[k];
        f.texel_world = fmaxf(box[k].hi[0] - box[k].lo[0], box[k].hi[1] - box[k].lo[1]) / (float)size;
        f.depth_range = box[k].hi[2] - box[k].lo[2];
        for (size_t i = 0; i < n; i++)
            mask[i] = view->cls[i] == SL_C_PFL && (!cube || face[i] == k);
        e = checks(p, t, m, &f, view, mask, r, &taps_sum, d);
        r->frames++;
    }
    for (int k = 0; k < 6; k++)
        sl_light_box_free(&box[k]);
    r->taps_mean = r->pixels ? taps_sum / (double)r->pixels : 0.0;
    if (!r->pixels)
        r->taps_min = 0;
    struct sl_params v;
    sl_tech_defaults(t, &v);
    r->taps_declared = sl_tech_taps(t, &v);
    r->taps_given = t->taps.given;
    free(mask);
    free(face);
    return e;
}

enum sl_err sl_techtest(const struct sl_techtest_opts *o, struct sl_techtest_result *r, struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    r->reach_x = r->reach_y = -1;
    r->w = o->w > 0 ? o->w : 256;
    r->h = o->h > 0 ? o->h : 256;
    r->map_size = o->map_size > 0 ? o->map_size : 512;
    const char *scene = o->scene ? o->scene : "primitives";
    struct sl_tech_set set;
    const struct sl_technique *t = NULL;
    enum sl_err e = find_package(o->name, &set, &t, d);
    if (e)
        return e;
    snprintf(r->file, sizeof r->file, "%s", t->file);
    if ((e = sl_techcheck(t, d))) {
        sl_tech_set_free(&set);
        return e;
    }
    struct sl_scene s;
    e = sl_file_is_scene(scene) ? sl_scene_load(scene, &s, d) : sl_scene_build(scene, &s, d);
    if (e) {
        sl_tech_set_free(&set);
        return e;
    }
    snprintf(r->scene, sizeof r->scene, "%s", s.name);
    int vp = o->viewpoint ? -1 : 0;
    for (int i = 0; i < s.nvp && vp < 0; i++)
        if (!strcmp(s.vp[i].name, o->viewpoint))
            vp = i;
    if (vp < 0 || s.nvp == 0) {
        char known[512] = "";
        for (int i = 0; i < s.nvp; i++)
            sl_known_add(known, sizeof known, s.vp[i].name);
        e = sl_fail(d, SL_E_USAGE, NULL, 0, o->viewpoint ? o->viewpoint : s.name,
                    "no such viewpoint (the scene has: %s)", s.nvp ? known : "none");
    }
    if (!e)
        snprintf(r->viewpoint, sizeof r->viewpoint, "%s", s.vp[vp].name);
    struct sl_gl gl;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gp;
    struct sl_techpass pass;
    struct sl_view view;
    memset(&gl, 0, sizeof gl);
    memset(&mesh, 0, sizeof mesh);
    memset(&gp, 0, sizeof gp);
    memset(&pass, 0, sizeof pass);
    memset(&view, 0, sizeof view);
    const struct sl_gl_desc gd = {.backend = o->gl};
    if (!e && !(e = sl_gl_open(&gl, &gd, d)) && !(e = sl_gl_mesh_upload(&mesh, &s, d)) &&
        !(e = sl_gbuffer_init(&gp, &s, d)) && !(e = sl_techpass_init(&pass, t, d)) &&
        !(e = sl_gbuffer_render(&gp, &mesh, &s, vp, r->w, r->h, &view, NULL, NULL, NULL, d))) {
        snprintf(r->renderer, sizeof r->renderer, "%s", gl.renderer);
        e = frames_run(&pass, t, &s, &mesh, &view, r, d);
    }
    if (view.pos)
        sl_view_free(&view);
    if (pass.t)
        sl_techpass_free(&pass);
    if (gp.prog)
        sl_gbuffer_free(&gp);
    if (gl.backend) {
        sl_gl_mesh_free(&mesh);
        sl_gl_free(&gl);
    }
    sl_scene_free(&s);
    sl_tech_set_free(&set);
    if (!e)
        r->findings = (r->unstable > 0) + (r->reach_changed > 0) + (r->nonfinite + r->map_nonfinite > 0) +
                      (r->taps_off = taps_finding(r));
    return e;
}
