/*
 * reps.c — see reps.h.
 *
 * Invariants: run 0 is the real computation; a stage's timed runs are a
 * contiguous tail of its runs (fixed: after its warm-ups; adaptive: all
 * but the real one when a warm-up is asked and a repetition followed,
 * else all);
 * rep_ms counts only repetitions, so the share compares what timing adds
 * with what the run would cost without it.
 */
#include "reps.h"
#include <math.h>
#include <string.h>
#include "util.h"

const char *const sl_rep_stop_names[SL_REP_NSTOPS] = {
#define SL_REP_STOP_NAME(id, word) word,
    SL_REP_STOPS(SL_REP_STOP_NAME)
#undef SL_REP_STOP_NAME
};
const char *const sl_rep_kind_names[SL_REP_KINDS] = {"G-buffer", "truth", "layer", "method"};

/* Fewer timed runs than this say nothing of a spread. */
#define SPREAD_MIN_RUNS 3

void sl_reps_init(struct sl_reps *r, int mode, int warmup, int runs, double spread, double budget_ms, double share)
{
    memset(r, 0, sizeof *r);
    r->mode = mode;
    r->warmup = warmup < 0 ? 0 : warmup;
    r->runs = runs < 1 ? 1 : runs;
    if (r->warmup + r->runs > SL_MAX_REPS)
        r->runs = SL_MAX_REPS - r->warmup;
    r->spread = spread;
    r->budget_ms = budget_ms;
    r->share = share;
    r->t0 = sl_now();
}

void sl_rep_begin(struct sl_rep *s, struct sl_reps *r, enum sl_rep_kind kind, double ms, double gpu)
{
    s->of = r;
    s->kind = (int)kind;
    s->n = 1;
    s->stop = -1;
    s->spent = 0.0;
    s->started = 0.0;
    s->ms[0] = ms;
    s->gpu[0] = gpu;
}

int sl_rep_timed(const struct sl_rep *s, int *first)
{
    const struct sl_reps *r = s->of;
    int f = 0;
    if (r->mode == SL_REP_FIXED)
        f = r->warmup < s->n ? r->warmup : s->n - 1;   /* a stage cut short keeps its last run */
    else if (r->mode == SL_REP_ADAPTIVE)
        f = r->warmup > 0 && s->n > 1;
    *first = f;
    return s->n - f;
}

void sl_rep_stats(const double *x, int first, int n, double out[3])
{
    double t[SL_MAX_REPS];
    if (n > SL_MAX_REPS)
        n = SL_MAX_REPS;
    memcpy(t, x + first, (size_t)(n > 0 ? n : 0) * sizeof t[0]);
    sl_med_min_max(t, n, out);
}

static int stop_with(struct sl_rep *s, enum sl_rep_stop why)
{
    s->stop = (int)why;
    return 0;
}

int sl_rep_more(struct sl_rep *s)
{
    const struct sl_reps *r = s->of;
    if (s->n >= SL_MAX_REPS)
        return stop_with(s, r->mode == SL_REP_ADAPTIVE ? SL_REP_STOP_RUNS : SL_REP_STOP_FIXED);
    switch (r->mode) {
    case SL_REP_OFF:
        return stop_with(s, SL_REP_STOP_OFF);
    case SL_REP_FIXED:
        if (s->n >= r->warmup + r->runs)
            return stop_with(s, SL_REP_STOP_FIXED);
        break;
    default: {
        /* the timed runs so far: the repetitions, and the real run too without a warm-up */
        const int from = r->warmup > 0, timed = s->n - from;
        if (timed >= r->runs)
            return stop_with(s, SL_REP_STOP_RUNS);
        /* the run's first stage of a kind pays what no later one does (shaders
         * compiled, the driver's first draw, memory first touched; measured:
         * a 256x256 G-buffer 376 ms once, 5 ms after): it is repeated once
         * whatever the budget, so its time is not that */
        if (r->warmup > 0 && s->n == 1 && r->kind[s->kind].stages == 0) {
            s->started = sl_now();
            return 1;
        }
        if (timed >= SPREAD_MIN_RUNS) {
            double st[3];
            sl_rep_stats(s->ms, from, timed, st);
            if (st[0] > 0.0 && (st[2] - st[1]) / st[0] <= r->spread)
                return stop_with(s, SL_REP_STOP_SPREAD);
        }
        /* the next repetition, as long as the last run */
        const double next = isnan(s->ms[s->n - 1]) ? 0.0 : s->ms[s->n - 1];
        if (s->spent + next > r->budget_ms)
            return stop_with(s, SL_REP_STOP_BUDGET);
        const double elapsed = 1e3 * (sl_now() - r->t0);
        if (r->rep_ms + next > r->share * (elapsed - r->rep_ms))
            return stop_with(s, SL_REP_STOP_SHARE);
        break;
    }
    }
    s->started = sl_now();
    return 1;
}

void sl_rep_add(struct sl_rep *s, double ms, double gpu)
{
    double wall = 1e3 * (sl_now() - s->started);
    if (s->n < SL_MAX_REPS) {
        s->ms[s->n] = ms;
        s->gpu[s->n] = gpu;
        s->n++;
    }
    /* the stage's budget counts the stage's own time (its wall clock if
     * longer, or if it gave none); the run's share counts the wall clock */
    s->spent += fmax(ms, wall);
    s->of->rep_ms += wall;
}

int sl_rep_end(struct sl_rep *s, double ms[3], double gpu[3])
{
    struct sl_reps *r = s->of;
    int first, n = sl_rep_timed(s, &first);
    if (ms)
        sl_rep_stats(s->ms, first, n, ms);
    if (gpu)
        sl_rep_stats(s->gpu, first, n, gpu);
    if (s->stop < 0)
        s->stop = r->mode == SL_REP_OFF ? SL_REP_STOP_OFF : r->mode == SL_REP_FIXED ? SL_REP_STOP_FIXED
                                                                                   : SL_REP_STOP_RUNS;
    r->kind[s->kind].stages++;
    r->kind[s->kind].runs += s->n;
    r->kind[s->kind].stop[s->stop]++;
    return n;
}

void sl_reps_describe(const struct sl_reps *r, double run_ms, char *out, size_t n)
{
    static const char *const modes[] = {"adaptive", "fixed", "off"};
    size_t o = 0;
#define PUT(...) (o += (size_t)snprintf(out + (o < n ? o : n), o < n ? n - o : 0, __VA_ARGS__))
    PUT("timing (repetitions: %s", modes[r->mode >= 0 && r->mode <= 2 ? r->mode : 0]);
    if (r->mode == SL_REP_FIXED)
        PUT(", warm-up %d, runs %d", r->warmup, r->runs);
    else if (r->mode == SL_REP_ADAPTIVE)
        PUT(", runs <= %d, spread %g, budget %g ms, share %g", r->runs, r->spread, r->budget_ms, r->share);
    PUT("):");
    int any = 0;
    for (int k = 0; k < SL_REP_KINDS; k++) {
        if (!r->kind[k].stages)
            continue;
        PUT("%s %s %d x, %ld runs (", any ? ";" : "", sl_rep_kind_names[k], r->kind[k].stages, r->kind[k].runs);
        for (int w = 0, first = 1; w < SL_REP_NSTOPS; w++)
            if (r->kind[k].stop[w]) {
                PUT("%s%s %d", first ? "" : ", ", sl_rep_stop_names[w], r->kind[k].stop[w]);
                first = 0;
            }
        PUT(")");
        any = 1;
    }
    if (!any)
        PUT(" nothing timed");
    double rest = run_ms - r->rep_ms;
    PUT("; repetitions %.1f s, %.0f%% on top of the run's other %.1f s", r->rep_ms / 1e3,
        rest > 0 ? 100.0 * r->rep_ms / rest : 0.0, rest / 1e3);
#undef PUT
}
