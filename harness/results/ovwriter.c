/*
 * ovwriter.c — see ovwriter.h.
 *
 * Invariants: one mutex guards every slot's state and the error; a slot is
 * FREE (the writer's, unused), FILLING (the cell's, between acquire and
 * submit), QUEUED or WRITING (the worker's). Sheets are written in the
 * order they were submitted (seq), so a run's files appear in cell order.
 * The worker reads a slot's buffers only while it is WRITING, and a cell
 * gets a slot only when it is FREE: no buffer is ever shared.
 */
#define _GNU_SOURCE   /* pthread_setname_np */
#include "ovwriter.h"
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "util.h"

enum slot_state { SLOT_FREE, SLOT_FILLING, SLOT_QUEUED, SLOT_WRITING };

struct slot {
    struct sl_ovw_slot pub;
    size_t cap;                      /* pixels the buffers hold */
    enum slot_state state;
    uint64_t seq;
    struct sl_image_sheet sheet;     /* its rgb and keep are pub's buffers */
    char path[1600];
};

struct sl_ovw {
    pthread_mutex_t mu;
    pthread_cond_t cv;               /* any change of state: one condition, broadcast (few waiters) */
    pthread_t thread;
    int depth, quit;
    struct slot slot[SL_OVW_MAX_DEPTH];
    uint64_t next_seq;
    enum sl_err err;                 /* the first failed write, sticky */
    struct sl_diag diag;
    int written;
    double ms, ms_cpu;
};

/* This thread's CPU time, ms (the worker's own, apart from the run's). */
static double thread_cpu_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

static struct slot *next_queued(struct sl_ovw *w)
{
    struct slot *best = NULL;
    for (int i = 0; i < w->depth; i++)
        if (w->slot[i].state == SLOT_QUEUED && (!best || w->slot[i].seq < best->seq))
            best = &w->slot[i];
    return best;
}

static void *worker(void *arg)
{
    struct sl_ovw *w = arg;
    pthread_setname_np(pthread_self(), "sl-overlays");   /* apart in perf and top */
    pthread_mutex_lock(&w->mu);
    for (;;) {
        struct slot *s;
        while (!(s = next_queued(w)) && !w->quit)
            pthread_cond_wait(&w->cv, &w->mu);
        if (!s)
            break;   /* quit with nothing queued */
        if (w->err) {   /* the run is failing: drop what is queued */
            s->state = SLOT_FREE;
            pthread_cond_broadcast(&w->cv);
            continue;
        }
        s->state = SLOT_WRITING;
        pthread_mutex_unlock(&w->mu);
        struct sl_diag d;
        memset(&d, 0, sizeof d);
        double t0 = sl_now(), c0 = thread_cpu_ms();
        enum sl_err e = sl_image_write_sheet(s->path, &s->sheet, &d);
        double ms = 1e3 * (sl_now() - t0), cpu = thread_cpu_ms() - c0;
        pthread_mutex_lock(&w->mu);
        w->ms += ms;
        w->ms_cpu += cpu;
        if (e && !w->err) {
            w->err = e;
            w->diag = d;
        } else if (!e) {
            w->written++;
        }
        s->state = SLOT_FREE;
        pthread_cond_broadcast(&w->cv);
    }
    pthread_mutex_unlock(&w->mu);
    return NULL;
}

enum sl_err sl_ovw_open(int depth, struct sl_ovw **out, struct sl_diag *d)
{
    *out = NULL;
    if (depth <= 0)
        depth = 2;
    if (depth > SL_OVW_MAX_DEPTH)
        depth = SL_OVW_MAX_DEPTH;
    struct sl_ovw *w = sl_calloc(1, sizeof *w);
    if (!w)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "overlay writer");
    w->depth = depth;
    pthread_mutex_init(&w->mu, NULL);
    pthread_cond_init(&w->cv, NULL);
    /* the worker inherits a mask blocking every signal: SIGINT and SIGTERM
     * go to the run's thread, whose handler sets the stop flag */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int rc = pthread_create(&w->thread, NULL, worker, w);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (rc != 0) {
        pthread_cond_destroy(&w->cv);
        pthread_mutex_destroy(&w->mu);
        free(w);
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "cannot start the overlay writer's thread");
    }
    *out = w;
    return SL_OK;
}

/* The sticky error into d; call with the mutex held. */
static enum sl_err failed(struct sl_ovw *w, struct sl_diag *d)
{
    if (d)
        *d = w->diag;
    return w->err;
}

enum sl_err sl_ovw_acquire(struct sl_ovw *w, int width, int height, struct sl_ovw_slot **out, struct sl_diag *d)
{
    *out = NULL;
    size_t npx = (size_t)width * (size_t)height;
    pthread_mutex_lock(&w->mu);
    struct slot *s = NULL;
    for (;;) {
        if (w->err) {
            enum sl_err e = failed(w, d);
            pthread_mutex_unlock(&w->mu);
            return e;
        }
        /* prefer a slot already of this size: no allocation, warm pages */
        for (int i = 0; i < w->depth; i++)
            if (w->slot[i].state == SLOT_FREE && (!s || (s->cap < npx && w->slot[i].cap >= npx)))
                s = &w->slot[i];
        if (s)
            break;
        pthread_cond_wait(&w->cv, &w->mu);
    }
    s->state = SLOT_FILLING;
    pthread_mutex_unlock(&w->mu);
    if (s->cap < npx) {
        /* a slot keeps its largest buffers: a sweep's viewports repeat */
        free(s->pub.rgb);
        free(s->pub.keep);
        s->pub.rgb = malloc(3 * npx);
        s->pub.keep = malloc(npx);
        s->cap = s->pub.rgb && s->pub.keep ? npx : 0;
        if (!s->cap) {
            free(s->pub.rgb);
            free(s->pub.keep);
            s->pub.rgb = s->pub.keep = NULL;
            sl_ovw_release(w, &s->pub);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "overlay writer: %dx%d sheet buffers", width, height);
        }
    }
    s->pub.w = width;
    s->pub.h = height;
    *out = &s->pub;
    return SL_OK;
}

enum sl_err sl_ovw_submit(struct sl_ovw *w, struct sl_ovw_slot *slot, const char *path,
                          const struct sl_image_sheet *sh, struct sl_diag *d)
{
    struct slot *s = (struct slot *)slot;   /* pub is the first member */
    if (sh->rgb != slot->rgb || (sh->keep && sh->keep != slot->keep) || sh->w != slot->w || sh->h != slot->h ||
        sh->nattrs != 0 || strlen(path) >= sizeof s->path) {
        sl_ovw_release(w, slot);
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "overlay writer: a sheet not drawn in its slot");
    }
    pthread_mutex_lock(&w->mu);
    s->sheet = *sh;
    s->sheet.attrs = NULL;
    snprintf(s->path, sizeof s->path, "%s", path);
    s->seq = w->next_seq++;
    s->state = SLOT_QUEUED;
    pthread_cond_broadcast(&w->cv);
    enum sl_err e = w->err ? failed(w, d) : SL_OK;
    pthread_mutex_unlock(&w->mu);
    return e;
}

void sl_ovw_release(struct sl_ovw *w, struct sl_ovw_slot *slot)
{
    struct slot *s = (struct slot *)slot;
    pthread_mutex_lock(&w->mu);
    s->state = SLOT_FREE;
    pthread_cond_broadcast(&w->cv);
    pthread_mutex_unlock(&w->mu);
}

enum sl_err sl_ovw_wait(struct sl_ovw *w, struct sl_diag *d)
{
    if (!w)
        return SL_OK;
    pthread_mutex_lock(&w->mu);
    for (;;) {
        int busy = 0;
        for (int i = 0; i < w->depth; i++)
            busy += w->slot[i].state == SLOT_QUEUED || w->slot[i].state == SLOT_WRITING;
        if (!busy)
            break;
        pthread_cond_wait(&w->cv, &w->mu);
    }
    enum sl_err e = w->err ? failed(w, d) : SL_OK;
    pthread_mutex_unlock(&w->mu);
    return e;
}

void sl_ovw_stats(const struct sl_ovw *w, int *written, double *ms, double *ms_cpu)
{
    struct sl_ovw *m = (struct sl_ovw *)w;   /* the mutex only */
    pthread_mutex_lock(&m->mu);
    *written = m->written;
    *ms = m->ms;
    if (ms_cpu)
        *ms_cpu = m->ms_cpu;
    pthread_mutex_unlock(&m->mu);
}

void sl_ovw_close(struct sl_ovw *w)
{
    if (!w)
        return;
    sl_ovw_wait(w, NULL);
    pthread_mutex_lock(&w->mu);
    w->quit = 1;
    pthread_cond_broadcast(&w->cv);
    pthread_mutex_unlock(&w->mu);
    pthread_join(w->thread, NULL);
    for (int i = 0; i < w->depth; i++) {
        free(w->slot[i].pub.rgb);
        free(w->slot[i].pub.keep);
    }
    pthread_cond_destroy(&w->cv);
    pthread_mutex_destroy(&w->mu);
    free(w);
}

static enum sl_err sink_acquire(void *ctx, int width, int height, void **slot, unsigned char **rgb,
                                unsigned char **keep, struct sl_diag *d)
{
    struct sl_ovw_slot *s;
    enum sl_err e = sl_ovw_acquire(ctx, width, height, &s, d);
    *slot = e ? NULL : s;
    if (!e) {
        *rgb = s->rgb;
        *keep = s->keep;
    }
    return e;
}

static enum sl_err sink_submit(void *ctx, void *slot, const char *path, const struct sl_image_sheet *s,
                               struct sl_diag *d)
{
    return sl_ovw_submit(ctx, slot, path, s, d);
}

static void sink_release(void *ctx, void *slot)
{
    sl_ovw_release(ctx, slot);
}

struct sl_sheet_sink sl_ovw_sink(struct sl_ovw *w)
{
    return (struct sl_sheet_sink){.ctx = w, .acquire = sink_acquire, .submit = sink_submit, .release = sink_release};
}
