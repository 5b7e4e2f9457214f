/*
 * reps.h — how often a timed stage runs: the config's `repetitions` policy
 * and the run's account of what each stage ran and why it stopped.
 *
 * A timed stage (a view's G-buffer and truth, a shadow-map layer, a cell's
 * method) is computed once for real; its repetitions only time it again. The
 * policy decides how many follow:
 *   off       none: the one computation is the stage's time (n = 1);
 *   fixed     `warmup` untimed runs (the real one first), then `runs` timed;
 *   adaptive  (the default) the real run is the warm-up (warmup 0: it is
 *             timed too; warmup > 1 counts as 1); timed repetitions
 *             follow while all of these hold: fewer than `runs` timed so far;
 *             the spread (max - min) / median of the timed ones is above
 *             `spread` or fewer than 3 are timed; this stage's repetitions
 *             have spent less than `budget_ms` (the next one estimated as
 *             long as the last); every stage's repetitions together stay
 *             within `share` of the run's wall time outside them. A stage
 *             whose own run already exceeds the budget (a truth trace, a
 *             large map) is timed once: its real computation; but the
 *             run's first stage of each kind is repeated at least once
 *             (with a warm-up asked), as its real run is cold.
 * Why a budget and a share rather than a count alone: a fixed {warmup 1,
 * runs 3} ran every stage 4 times and made a study 2.4x as costly as
 * computing it once; the share bounds that factor by 1 + share for any
 * study, and the stage budget spends the repetitions where they are cheap
 * and where the noise of one run matters most (short stages).
 *
 * Owns: nothing allocated. Does not: run or time a stage (its caller does,
 * and hands the times in); decide what a stage is.
 */
#ifndef SL_REPS_H
#define SL_REPS_H
#include <stddef.h>

/* At most this many runs of one stage (warm-up <= 100, runs <= 1000). */
#define SL_MAX_REPS 1100

/* In the order of the config's choice (config.c, repetitions.mode). */
enum sl_rep_mode { SL_REP_ADAPTIVE = 0, SL_REP_FIXED = 1, SL_REP_OFF = 2 };

/* Why a stage stopped repeating, with its word in the run's summary. */
#define SL_REP_STOPS(X)                                                        \
    X(OFF, "off")            /* mode off: computed and timed once */         \
    X(FIXED, "fixed")        /* mode fixed: warm-up + runs made */           \
    X(SPREAD, "spread")      /* adaptive: the spread fell below `spread` */  \
    X(RUNS, "runs")          /* adaptive: `runs` timed */                    \
    X(BUDGET, "budget")      /* adaptive: the stage's budget_ms spent */      \
    X(SHARE, "share")        /* adaptive: the run's share spent */
enum sl_rep_stop {
#define SL_REP_STOP_ENUM(id, word) SL_REP_STOP_##id,
    SL_REP_STOPS(SL_REP_STOP_ENUM)
#undef SL_REP_STOP_ENUM
    SL_REP_NSTOPS
};
extern const char *const sl_rep_stop_names[SL_REP_NSTOPS];

/* The stages the run times, with their names in the summary. */
enum sl_rep_kind { SL_REP_GBUFFER, SL_REP_TRUTH, SL_REP_LAYER, SL_REP_METHOD, SL_REP_KINDS };
extern const char *const sl_rep_kind_names[SL_REP_KINDS];

struct sl_reps {
    /* the policy (config.h: repetitions.*) */
    int    mode;          /* enum sl_rep_mode */
    int    warmup, runs;  /* fixed: untimed, timed; adaptive: runs is the most timed */
    double spread;        /* adaptive: (max - min) / median to stop at, with >= 3 timed */
    double budget_ms;     /* adaptive: a stage's repetitions' wall time at most */
    double share;         /* adaptive: every repetition's wall time at most share x the rest */
    /* the run's account */
    double t0;            /* sl_now() when the run began */
    double rep_ms;        /* wall time spent repeating (not in the real computations) */
    struct {
        int stages;       /* stages timed */
        long runs;        /* their runs, the real computations included */
        int stop[SL_REP_NSTOPS];
    } kind[SL_REP_KINDS];
};

/* One stage's runs: begun with the real computation's times, then
 * `while (sl_rep_more(&s)) { time it again; sl_rep_add(&s, ms, gpu); }`,
 * then sl_rep_end. */
struct sl_rep {
    struct sl_reps *of;
    int    kind;
    int    n;             /* runs made, the real one included */
    int    stop;          /* enum sl_rep_stop once ended */
    double spent;         /* wall time of its repetitions, ms */
    double started;       /* sl_now() when the repetition under way began */
    double ms[SL_MAX_REPS], gpu[SL_MAX_REPS];   /* per run: its wall and GPU time (NAN: none) */
};

/* The policy with the run's account zeroed, the run beginning now. */
void sl_reps_init(struct sl_reps *r, int mode, int warmup, int runs, double spread, double budget_ms, double share);

void sl_rep_begin(struct sl_rep *s, struct sl_reps *r, enum sl_rep_kind kind, double ms, double gpu);
/* Whether another repetition follows (and, if so, its wall clock starts);
 * when not, s->stop says why. */
int  sl_rep_more(struct sl_rep *s);
void sl_rep_add(struct sl_rep *s, double ms, double gpu);
/* The timed runs: [*first, *first + return). */
int  sl_rep_timed(const struct sl_rep *s, int *first);
/* {median, min, max} of the timed runs' wall and GPU times (either NULL:
 * not wanted), the stage counted in its run's account; returns how many
 * were timed. */
int  sl_rep_end(struct sl_rep *s, double ms[3], double gpu[3]);

/* One line for the run's summary: the policy, then per kind of stage how
 * many were timed, their runs (the real computations included) and why
 * they stopped, and what the repetitions added to the run_ms the run took. */
void sl_reps_describe(const struct sl_reps *r, double run_ms, char *out, size_t n);

/* {median, min, max} of x[first .. first + n), NAN ones left out (util.h's
 * sl_med_min_max on a copy). */
void sl_rep_stats(const double *x, int first, int n, double out[3]);

#endif
