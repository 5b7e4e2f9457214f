/*
 * cube.c — see cube.h.
 *
 * Invariants: every pixel has exactly one face (face[], sl_cube_face_of);
 * a face with a PFL pixel has a frame (size > 0) holding every layer the
 * running method reads; a pixel's verdict, how, base, detail and tests are
 * those of the run on its own face (tests/test_cube.c: per-face counts,
 * seams against one wide frustum, exactness on the point scenes).
 */
#include "cube.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "lightfit.h"
#include "runhelp.h"
#include "util.h"

void sl_cube_drop(struct sl_cube *cb)
{
    for (int f = 0; f < 6; f++) {
        sl_light_box_free(&cb->f[f].box);
        sl_frame_free(&cb->f[f]);
    }
    free(cb->face);
    memset(cb, 0, sizeof *cb);
}

/* The faces of a new (view, map): the face of every pixel, each face's
 * frame fitted with its guard band (lightfit.h, sl_light_fit_cube_mt: the
 * six of sl_light_fit_face at once). */
static enum sl_err cube_fit(struct sl_cube *cb, struct sl_shadowmap_pass *sp, const struct sl_scene *s,
                            const struct sl_view *v, int map, int size, int threads, struct sl_diag *d)
{
    sl_cube_drop(cb);
    double t0 = sl_now();
    cb->npx = (size_t)v->w * (size_t)v->h;
    cb->face = malloc(cb->npx ? cb->npx : 1);
    if (!cb->face)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cube faces of %zu pixels", cb->npx);
    sl_cube_faces(s->light.pos, v, cb->face, threads);
    /* a map too small for the band on both sides gets none (lightfit.c) */
    const int guard = size > 4 * SL_CUBE_GUARD ? SL_CUBE_GUARD : 0;
    struct sl_light_box boxes[6];
    sl_light_fit_cube_mt(s, v, s->light.pos, cb->face, size, guard, boxes, threads);
    for (int f = 0; f < 6; f++) {
        struct sl_light_frame *fr = &cb->f[f];
        struct sl_light_box box = boxes[f];
        float axis[3];
        sl_cube_axis(f, axis);
        cb->cost[f].receivers = box.n_receivers;
        cb->cost[f].casters = box.n_casters;
        cb->cost[f].unmapped = box.n_unmapped;
        if (box.n_receivers == 0) {
            sl_light_box_free(&box);
            continue;   /* no PFL pixel looks this way: no map (size 0) */
        }
        fr->size = size;
        fr->pool = &sp->pool;
        memcpy(fr->dir, axis, sizeof fr->dir);
        fr->box = box;
        fr->texel_world = fmaxf(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1]) / (float)size;
        fr->depth_range = box.hi[2] - box.lo[2];
    }
    cb->map1 = map + 1;
    cb->size = size;
    cb->ms_fit = 1e3 * (sl_now() - t0);
    return SL_OK;
}

enum sl_err sl_cube_ensure(struct sl_cube *cb, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
                           const struct sl_scene *s, const struct sl_view *v, int map, int size, unsigned now,
                           unsigned keep, const struct sl_cube_timing *t, struct sl_light_frame *stats,
                           struct sl_diag *d)
{
    now &= (1u << SL_LAYER_COUNT) - 1u;
    enum sl_err e = SL_OK;
    if (cb->map1 != map + 1 && (e = cube_fit(cb, sp, s, v, map, size, t->threads, d)))
        return e;
    /* give back what no remaining cell reads first: six faces hold six times a frame's layers */
    for (int f = 0; f < 6; f++)
        for (int l = 0; l < SL_LAYER_COUNT; l++)
            if (cb->f[f].have & ~keep & SL_NEED(l))
                sl_frame_drop_layer(&cb->f[f], l);
    for (int l = 0; l < SL_LAYER_COUNT && !e; l++) {
        if (!(now & SL_NEED(l)))
            continue;
        /* the layer with what it reads (BGSM2 reads BGSM, already rendered: now holds it) */
        int fresh = 0;
        double times[1100], gpu[1100];
        for (int r = 0; r < t->warmup + t->runs && r < 1100; r++)
            times[r] = gpu[r] = 0.0;
        for (int f = 0; f < 6 && !e; f++) {
            struct sl_light_frame *fr = &cb->f[f];
            if (fr->size == 0 || (fr->have & SL_NEED(l)))
                continue;
            if ((e = sl_shadowmap_render(sp, m, fr, SL_NEED(l), d)))
                break;
            fresh = 1;
            if (t->layers)
                t->layers[l]++;
            times[0] += fr->layer[l].ms_render;
            gpu[0] += fr->layer[l].ms_gpu;
            for (int r = 1; r < t->warmup + t->runs && r < 1100 && !e; r++) {
                /* the same layer again into a scratch copy of the face, timed only (as run.c's frame) */
                struct sl_light_frame again = *fr;
                again.have &= ~SL_NEED(l);
                memset(&again.layer[l], 0, sizeof again.layer[l]);
                e = sl_shadowmap_render(sp, m, &again, SL_NEED(l), d);
                times[r] += again.layer[l].ms_render;
                gpu[r] += again.layer[l].ms_gpu;
                sl_frame_drop_layer(&again, l);
            }
        }
        if (!e && fresh) {
            uint64_t bad = 0;
            for (int f = 0; f < 6; f++)
                if (cb->f[f].have & SL_NEED(l))
                    bad += sl_run_layer_bad(&cb->f[f].layer[l], cb->f[f].size);
            if (t->layer_bad)
                t->layer_bad[l] = bad;
            if (t->layer_ms)
                sl_run_med_min_max(times + t->warmup, t->runs, t->layer_ms[l]);
            if (t->layer_gpu)
                sl_run_med_min_max(gpu + t->warmup, t->runs, t->layer_gpu[l]);
        }
    }
    /* the cell's frame carries the faces' sums (run.c reads its layers' counters) */
    for (int l = 0; l < SL_LAYER_COUNT && stats; l++) {
        struct sl_depth_layer *L = &stats->layer[l];
        L->ms_readback = 0.0;
        L->gs_prims = L->fragments = 0;
        for (int f = 0; f < 6; f++)
            if (cb->f[f].have & SL_NEED(l)) {
                L->ms_readback += cb->f[f].layer[l].ms_readback;
                L->gs_prims += cb->f[f].layer[l].gs_prims;
                L->fragments += cb->f[f].layer[l].fragments;
            }
    }
    return e;
}

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
    if (!cb->map1 || !(m->needs(a->params) & ((1u << SL_LAYER_COUNT) - 1u)))
        return m->run(a, out, c, d);
    const struct sl_view *v = a->view;
    const size_t n = (size_t)v->w * (size_t)v->h;
    if (n != cb->npx)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "cube: %zu pixels, the view %zu", cb->npx, n);
    double t0 = sl_now();
    uint8_t *cls = malloc(n), *buf = malloc(5 * n);
    if (!cls || !buf) {
        free(cls);
        free(buf);
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
    }
    struct sl_verdicts tmp = *out;
    tmp.v = buf;
    tmp.how = buf + n;
    tmp.base = buf + 2 * n;
    tmp.detail = buf + 3 * n;
    tmp.tests = buf + 4 * n;
    tmp.frames = NULL;
    tmp.slice = NULL;
    tmp.nframes = tmp.nown = 0;
    struct sl_view mv = *v;
    mv.cls = cls;
    int has_base = 0, has_detail = 0;
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
        tmp.has_base = tmp.has_detail = 0;
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
            }
        has_base |= tmp.has_base;
        has_detail |= tmp.has_detail;
        cb->cost[f].ms_method = nc.ms_method;
        cb->cost[f].lookups = nc.lookups;
        cb->cost[f].rays = nc.rays;
        cb->cost[f].tri_tests = nc.tri_tests;
        c->ms_trace += nc.ms_trace;
        for (int k = 0; k < 4; k++)
            c->ms_step[k] += nc.ms_step[k];
        c->lookups += nc.lookups;
        c->rays += nc.rays;
        c->tri_tests += nc.tri_tests;
    }
    free(cls);
    free(buf);
    if (e)
        return e;
    out->has_base = has_base;
    out->has_detail = has_detail;
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
