/*
 * runhelp.c — see runhelp.h.
 */
#include "runhelp.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "cellcols.h"
#include "util.h"

/* G-buffer values that are not finite (positions, normals of non-background
 * pixels). A hard case must never produce one (tests/test_hard.c). */
uint64_t sl_run_view_bad(const struct sl_view *v)
{
    uint64_t n = 0;
    size_t np = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < np; i++)
        if (v->cls[i] != SL_C_BACKGROUND)
            for (int k = 0; k < 3; k++)
                n += !isfinite(v->pos[3 * i + k]) + !isfinite(v->nrm[3 * i + k]);
    return n;
}

/* Shadow-map depths outside [0, 1] or not finite. */
uint64_t sl_run_layer_bad(const struct sl_depth_layer *l, int size)
{
    uint64_t n = 0;
    size_t nt = (size_t)size * (size_t)size;
    for (size_t i = 0; i < nt; i++)
        n += !(l->depth[i] >= 0.0f && l->depth[i] <= 1.0f);
    return n;
}

enum sl_err sl_run_render_layers(struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m, struct sl_light_frame *f,
                                 unsigned set, unsigned gather, const struct sl_view *v,
                                 const struct sl_cube_timing *t, struct sl_diag *d)
{
    unsigned before = f->have;
    enum sl_err e = sl_shadowmap_render(sp, m, f, set, d);
    int reps = t->warmup + t->runs;
    for (int l = 0; l < SL_LAYER_COUNT && !e; l++) {
        if (!((f->have & ~before) & SL_NEED(l)))
            continue;
        t->layers[l]++;
        t->layer_bad[l] = sl_run_layer_bad(&f->layer[l], f->size);
        double times[SL_MAX_REPS], gpu[SL_MAX_REPS];
        times[0] = f->layer[l].ms_render;
        gpu[0] = f->layer[l].ms_gpu;
        for (int r = 1; r < reps && !e; r++) {
            /* the same layer again into a scratch copy of the frame (which
             * shares the other layers, e.g. BGSM for BGSM2), timed only */
            struct sl_light_frame again = *f;
            again.have &= ~SL_NEED(l);
            memset(&again.layer[l], 0, sizeof again.layer[l]);
            e = sl_shadowmap_render(sp, m, &again, SL_NEED(l), d);
            times[r] = again.layer[l].ms_render;
            gpu[r] = again.layer[l].ms_gpu;
            sl_frame_drop_layer(&again, l);   /* back to the pool for the next repetition */
        }
        if (!e) {
            sl_run_med_min_max(times + t->warmup, t->runs, t->layer_ms[l]);
            sl_run_med_min_max(gpu + t->warmup, t->runs, t->layer_gpu[l]);
        }
        /* timed as the readback: the layer's values reach the readers per pixel */
        double t0 = sl_now();
        if (!e && (gather & SL_NEED(l)) && !(e = sl_frame_gather(f, l, v, t->threads, d)))
            f->layer[l].ms_readback += 1e3 * (sl_now() - t0);
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

enum sl_err sl_run_alt_frame(struct sl_alt_frames *a, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
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

void sl_run_alt_free(struct sl_alt_frames *a)
{
    for (int i = 0; i < a->n; i++)
        sl_frame_free(&a->e[i].f);
    a->n = 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* {median, min, max} of n >= 1 times (sorted in place), NaN ones (a GPU
 * timer that failed, glctx.h) left out; all NaN: NaN (not measured). */
void sl_run_med_min_max(double *t, int n, double out[3])
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (!isnan(t[i]))
            t[k++] = t[i];
    if ((n = k) == 0) {
        out[SL_MED] = out[SL_MIN] = out[SL_MAX] = NAN;
        return;
    }
    qsort(t, (size_t)n, sizeof t[0], cmp_double);
    out[SL_MED] = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
    out[SL_MIN] = t[0];
    out[SL_MAX] = t[n - 1];
}

int sl_run_contour_label(const struct sl_config *c)
{
    for (int i = 0; i < c->nmethods; i++)
        if (strcmp(c->methods[i].method->name, "nsm") == 0 &&
            c->methods[i].params.self_shadow == SL_SELF_FRONT_FACES && c->methods[i].frame_fit.fit == SL_FIT_TIGHT)
            return i;
    return -1;
}

enum sl_err sl_run_make_looks(struct sl_light_frame *f, int own_frame, const struct sl_view *v,
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
