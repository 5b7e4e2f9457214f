/*
 * lightframe.c — see lightframe.h.
 *
 * Invariants: every pixel has exactly one face (face[], sl_cube_face_of);
 * a face with a PFL pixel has a frame (size > 0) holding every layer the
 * running method reads (tests/test_cube.c: per-face counts, seams against
 * one wide frustum, exactness on the point scenes). A repeated render is
 * timed only: it goes into a scratch copy of the frame, whose layer goes
 * back to the pool.
 */
#include "lightframe.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "util.h"

/* Shadow-map depths outside [0, 1] or not finite. */
uint64_t sl_layer_bad(const struct sl_depth_layer *l, int size)
{
    uint64_t n = 0;
    size_t nt = (size_t)size * (size_t)size;
    for (size_t i = 0; i < nt; i++)
        n += !(l->depth[i] >= 0.0f && l->depth[i] <= 1.0f);
    return n;
}

/* A stage without a policy (t->reps NULL: s.of NULL) is computed once and
 * repeats nothing. */
static int rep_more(struct sl_rep *s)
{
    return s->of ? sl_rep_more(s) : 0;
}

static void rep_end(const struct sl_layer_timing *t, struct sl_rep *s, int l)
{
    double ms[3], gpu[3];
    int n = 1;
    if (s->of) {
        n = sl_rep_end(s, ms, gpu);
    } else {
        ms[0] = ms[1] = ms[2] = s->ms[0];
        gpu[0] = gpu[1] = gpu[2] = s->gpu[0];
    }
    if (t->layer_ms)
        memcpy(t->layer_ms[l], ms, sizeof ms);
    if (t->layer_gpu)
        memcpy(t->layer_gpu[l], gpu, sizeof gpu);
    if (t->layer_runs)
        t->layer_runs[l] = n;
}

enum sl_err sl_frame_render_timed(struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m, struct sl_light_frame *f,
                                  unsigned set, unsigned gather, const struct sl_view *v,
                                  const struct sl_layer_timing *t, struct sl_diag *d)
{
    unsigned before = f->have;
    enum sl_err e = sl_shadowmap_render(sp, m, f, set, d);
    for (int l = 0; l < SL_LAYER_COUNT && !e; l++) {
        if (!((f->have & ~before) & SL_NEED(l)))
            continue;
        if (t->layers)
            t->layers[l]++;
        if (t->layer_bad)
            t->layer_bad[l] = sl_layer_bad(&f->layer[l], f->size);
        struct sl_rep s;
        s.of = NULL;
        if (t->reps)
            sl_rep_begin(&s, t->reps, SL_REP_LAYER, f->layer[l].ms_render, f->layer[l].ms_gpu);
        else
            s.ms[0] = f->layer[l].ms_render, s.gpu[0] = f->layer[l].ms_gpu;
        /* each run's readback too: the layer's is the median of the timed runs' */
        double rb[SL_MAX_REPS];
        rb[0] = f->layer[l].ms_readback;
        while (!e && rep_more(&s)) {
            /* the same layer again into a scratch copy of the frame (which
             * shares the other layers, e.g. BGSM for BGSM2), timed only */
            struct sl_light_frame again = *f;
            again.have &= ~SL_NEED(l);
            memset(&again.layer[l], 0, sizeof again.layer[l]);
            e = sl_shadowmap_render(sp, m, &again, SL_NEED(l), d);
            rb[s.n] = again.layer[l].ms_readback;
            sl_rep_add(&s, again.layer[l].ms_render, again.layer[l].ms_gpu);
            sl_frame_drop_layer(&again, l);   /* back to the pool for the next repetition */
        }
        if (!e && s.of) {
            int first, n = sl_rep_timed(&s, &first);
            double med[3];
            sl_rep_stats(rb, first, n, med);
            f->layer[l].ms_readback = med[0];
        }
        if (!e)
            rep_end(t, &s, l);
        /* timed as the readback: the layer's values reach the readers per pixel */
        double t0 = sl_now();
        if (!e && (gather & SL_NEED(l)) && !(e = sl_frame_gather(f, l, v, t->threads, d)))
            f->layer[l].ms_readback += 1e3 * (sl_now() - t0);
    }
    return e;
}

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
                           unsigned keep, const struct sl_layer_timing *t, struct sl_light_frame *stats,
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
        double ms = 0.0, gpu = 0.0;
        for (int f = 0; f < 6 && !e; f++) {
            struct sl_light_frame *fr = &cb->f[f];
            if (fr->size == 0 || (fr->have & SL_NEED(l)))
                continue;
            if ((e = sl_shadowmap_render(sp, m, fr, SL_NEED(l), d)))
                break;
            fresh |= 1 << f;
            if (t->layers)
                t->layers[l]++;
            ms += fr->layer[l].ms_render;
            gpu += fr->layer[l].ms_gpu;
        }
        if (e || !fresh)
            continue;
        struct sl_rep s;
        s.of = NULL;
        if (t->reps)
            sl_rep_begin(&s, t->reps, SL_REP_LAYER, ms, gpu);
        else
            s.ms[0] = ms, s.gpu[0] = gpu;
        while (!e && rep_more(&s)) {
            /* the faces rendered now, again, each into a scratch copy of the face, timed only */
            double again_ms = 0.0, again_gpu = 0.0;
            for (int f = 0; f < 6 && !e; f++) {
                if (!(fresh & (1 << f)))
                    continue;
                struct sl_light_frame again = cb->f[f];
                again.have &= ~SL_NEED(l);
                memset(&again.layer[l], 0, sizeof again.layer[l]);
                e = sl_shadowmap_render(sp, m, &again, SL_NEED(l), d);
                again_ms += again.layer[l].ms_render;
                again_gpu += again.layer[l].ms_gpu;
                sl_frame_drop_layer(&again, l);
            }
            sl_rep_add(&s, again_ms, again_gpu);
        }
        if (!e) {
            uint64_t bad = 0;
            for (int f = 0; f < 6; f++)
                if (cb->f[f].have & SL_NEED(l))
                    bad += sl_layer_bad(&cb->f[f].layer[l], cb->f[f].size);
            if (t->layer_bad)
                t->layer_bad[l] = bad;
            rep_end(t, &s, l);
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

/* Two fits that put the same map in the same place: a camera that moved
 * less than a texel under a snapped fixed-size frame, or one that holds
 * still while nothing else changes. */
static int same_box(const struct sl_light_frame *f, const struct sl_light_box *b, const float dir[3])
{
    return memcmp(f->box.vp, b->vp, sizeof b->vp) == 0 && memcmp(f->box.lo, b->lo, sizeof b->lo) == 0 &&
           memcmp(f->box.hi, b->hi, sizeof b->hi) == 0 && memcmp(f->dir, dir, sizeof f->dir) == 0;
}

enum sl_err sl_alt_frame(struct sl_alt_frames *a, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
                         const struct sl_scene *s, const struct sl_view *v, int map, int size,
                         const struct sl_fit_opts *o, unsigned needs, struct sl_light_frame **out, int *layers,
                         struct sl_diag *d)
{
    needs &= (1u << SL_LAYER_COUNT) - 1u;
    int i = 0;
    while (i < a->n && !(a->e[i].map == map && a->e[i].fit.fit == o->fit && a->e[i].fit.snap == o->snap))
        i++;
    if (i == a->n && a->n == SL_ALT_FRAMES)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, "light_frame", "more than %d light frames in one scene",
                       SL_ALT_FRAMES);
    struct sl_light_frame *f = &a->e[i].f;
    if (i == a->n || a->e[i].vp != v->vp || a->e[i].vw != v->w || a->e[i].vh != v->h) {
        /* a new view: its fit; the layers already rendered stay when the
         * frame is the same (the light frame shared between frames of a path) */
        struct sl_light_box box;
        sl_light_fit_stable(s, v, o, size, &box);
        if (i < a->n && same_box(f, &box, s->light_dir)) {
            sl_light_box_free(&f->box);
            f->box = box;
        } else {
            if (i < a->n)
                sl_frame_free(f);
            else
                a->n++;
            memset(&a->e[i], 0, sizeof a->e[i]);
            a->e[i].map = map;
            a->e[i].fit = *o;
            f->size = size;
            memcpy(f->dir, s->light_dir, sizeof f->dir);
            f->box = box;
            f->texel_world = fmaxf(box.hi[0] - box.lo[0], box.hi[1] - box.lo[1]) / (float)size;
            f->depth_range = box.hi[2] - box.lo[2];
        }
        a->e[i].vp = v->vp;
        a->e[i].vw = v->w;
        a->e[i].vh = v->h;
    }
    unsigned before = f->have;
    enum sl_err e = sl_shadowmap_render(sp, m, f, needs, d);
    for (int l = 0; l < SL_LAYER_COUNT && layers; l++)
        layers[l] += ((f->have & ~before) >> l) & 1u;
    *out = f;
    return e;
}

void sl_alt_frames_free(struct sl_alt_frames *a)
{
    for (int i = 0; i < a->n; i++)
        sl_frame_free(&a->e[i].f);
    a->n = 0;
}
