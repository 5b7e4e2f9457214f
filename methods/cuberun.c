/*
 * cuberun.c — see cuberun.h.
 *
 * Invariants: a pixel's verdict, how, base, detail, tests and visibility
 * (a package's) are those of the run on its own face (tests/test_cube.c:
 * per-face counts, seams against one wide frustum, exactness on the point
 * scenes; packages beside them, nsm_glsl against nsm).
 */
#include "cuberun.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "util.h"

enum sl_err sl_cube_mark(const struct sl_cube *cb, struct sl_verdicts *out, struct sl_diag *d)
{
    sl_verdicts_drop_frames(out);
    if (!cb->map1)
        return SL_OK;
    out->frames = calloc(6, sizeof *out->frames);
    out->slice = malloc(cb->npx ? cb->npx : 1);
    if (!out->frames || !out->slice) {
        sl_verdicts_drop_frames(out);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cube frames for scoring");
    }
    /* scoring reads a frame's box and size only: copies without layers or
     * unmapped lists, which stay the cube's */
    for (int f = 0; f < 6; f++) {
        out->frames[f].size = cb->f[f].size;
        memcpy(out->frames[f].dir, cb->f[f].dir, sizeof out->frames[f].dir);
        out->frames[f].box = cb->f[f].box;
        out->frames[f].box.unmapped = NULL;
        out->frames[f].box.n_unmapped = 0;
        out->frames[f].texel_world = cb->f[f].texel_world;
        out->frames[f].depth_range = cb->f[f].depth_range;
    }
    memcpy(out->slice, cb->face, cb->npx);
    out->nframes = out->nown = 6;
    return SL_OK;
}

enum sl_err sl_cube_method_run(struct sl_cube *cb, const struct sl_method *m, const struct sl_method_args *a,
                               struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d)
{
    cb->ran = 0;
    if (!cb->map1 || !(m->needs(a->params) & (((1u << SL_LAYER_COUNT) - 1u) | SL_NEED_OWN_MAPS)))
        return m->run(a, out, c, d);
    const struct sl_view *v = a->view;
    const size_t n = (size_t)v->w * (size_t)v->h;
    if (n != cb->npx)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "cube: %zu pixels, the view %zu", cb->npx, n);
    double t0 = sl_now();
    uint8_t *cls = malloc(n), *buf = malloc(5 * n);
    /* a face's visibility (a package's) apart: its run writes every pixel,
     * the other faces' as background */
    float *vis = out->vis ? malloc(n * sizeof *vis) : NULL;
    if (!cls || !buf || (out->vis && !vis)) {
        free(cls);
        free(buf);
        free(vis);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cube: per-face copies of %zu pixels", n);
    }
    /* fixed verdicts first; a face without a PFL pixel runs nothing, its
     * pixels keep them (background, or shadow by definition) */
    for (size_t i = 0; i < n; i++) {
        sl_verdict_fixed(v, i, out);
        if (v->cls[i] == SL_C_PFL) {   /* every PFL pixel's face runs: overwritten below */
            out->v[i] = SL_V_UNCERTAIN;
            out->how[i] = SL_HOW_NONE;
        }
        out->base[i] = out->v[i];
        out->detail[i] = 0;
        out->tests[i] = 0;
        if (out->vis)
            out->vis[i] = 0.0f;
    }
    struct sl_verdicts tmp = *out;
    tmp.v = buf;
    tmp.how = buf + n;
    tmp.base = buf + 2 * n;
    tmp.detail = buf + 3 * n;
    tmp.tests = buf + 4 * n;
    tmp.vis = vis;
    tmp.frames = NULL;
    tmp.slice = NULL;
    tmp.nframes = tmp.nown = 0;
    struct sl_view mv = *v;
    mv.cls = cls;
    int has_base = 0, has_detail = 0, has_vis = 0;
    enum sl_err e = SL_OK;
    for (int f = 0; f < 6 && !e; f++) {
        cb->cost[f].ms_method = 0.0;
        cb->cost[f].lookups = cb->cost[f].rays = cb->cost[f].tri_tests = 0;
        if (cb->f[f].size == 0)
            continue;
        cb->ran++;
        uint32_t npfl = 0, npnfl = 0, nbg = 0;
        for (size_t i = 0; i < n; i++) {
            cls[i] = cb->face[i] == f ? v->cls[i] : (uint8_t)SL_C_BACKGROUND;
            npfl += cls[i] == SL_C_PFL;
            npnfl += cls[i] == SL_C_PNFL;
        }
        nbg = (uint32_t)n - npfl - npnfl;
        mv.n_pfl = npfl;
        mv.n_pnfl = npnfl;
        mv.n_background = nbg;
        struct sl_method_args na = *a;
        na.view = &mv;
        na.frame = &cb->f[f];
        struct sl_cost nc = {0};
        tmp.has_base = tmp.has_detail = tmp.has_vis = 0;
        memset(tmp.tests, 0, n);
        if ((e = m->run(&na, &tmp, &nc, d)))
            break;
        sl_verdicts_drop_frames(&tmp);   /* a method's own frames: none under a point light (zpart refuses it) */
        for (size_t i = 0; i < n; i++)
            if (cb->face[i] == f && v->cls[i] != SL_C_BACKGROUND) {
                out->v[i] = tmp.v[i];
                out->how[i] = tmp.how[i];
                out->tests[i] = tmp.tests[i];
                if (tmp.has_base)
                    out->base[i] = tmp.base[i];
                if (tmp.has_detail)
                    out->detail[i] = tmp.detail[i];
                if (tmp.has_vis)
                    out->vis[i] = tmp.vis[i];
            }
        has_base |= tmp.has_base;
        has_detail |= tmp.has_detail;
        has_vis |= tmp.has_vis;
        cb->cost[f].ms_method = nc.ms_method;
        cb->cost[f].lookups = nc.lookups;
        cb->cost[f].rays = nc.rays;
        cb->cost[f].tri_tests = nc.tri_tests;
        c->ms_trace += nc.ms_trace;
        c->ms_map += nc.ms_map;
        c->ms_post += nc.ms_post;
        c->ms_readback += nc.ms_readback;
        c->gpu_map += nc.gpu_map;
        c->gpu_post += nc.gpu_post;
        c->gpu_lookup += nc.gpu_lookup;
        c->gl_passes |= nc.gl_passes;
        for (int k = 0; k < 4; k++)
            c->ms_step[k] += nc.ms_step[k];
        c->lookups += nc.lookups;
        c->rays += nc.rays;
        c->tri_tests += nc.tri_tests;
    }
    free(cls);
    free(buf);
    free(vis);
    if (e)
        return e;
    out->has_base = has_base;
    out->has_detail = has_detail;
    out->has_vis = has_vis;
    out->nonfinite = tmp.nonfinite;   /* the faces' counts, added to the run's (tmp began as out) */
    /* the method's time is the whole per-face loop: the faces' own runs and
     * the copies and merges the cube adds */
    c->ms_method += 1e3 * (sl_now() - t0);
    return sl_cube_mark(cb, out, d);
}

void sl_cube_cell_costs(const struct sl_cube *cb, uint64_t *faces, double *ms_face_max)
{
    *faces = 0;
    *ms_face_max = NAN;
    for (int f = 0; f < 6 && cb->map1 && cb->ran; f++)
        if (cb->f[f].size > 0) {
            (*faces)++;
            if (isnan(*ms_face_max) || cb->cost[f].ms_method > *ms_face_max)
                *ms_face_max = cb->cost[f].ms_method;
        }
}
