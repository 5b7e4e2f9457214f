#ifndef SL_BENCH_ROW_H
#define SL_BENCH_ROW_H
/*
 * bench_row.h — what every stage of the bench uses and none of them owns:
 * a row against its target, the timing helpers (CPU time, medians, the load
 * average, this binary as a child), the context the in-process stages work
 * on, and the writers of the rows (the Markdown summary, the CSV, the
 * --markdown file).
 *
 * Below the stages: it calls none of them, and nothing here knows which
 * stages exist (bench.c runs them; bench_stages.h declares them).
 */
#include "bench.h"
#include "gbuffer.h"
#include "provenance.h"

/* What the truth, layer and churn stages work on (set up by bench.c). */
struct sl_bench_ctx {
    struct sl_scene s;
    int nvp;
    int vp[SL_MAX_VIEWPOINTS];
    int W, H, S, threads, reps;
    struct sl_gl gl;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gp;
    FILE *out;
};

/* A row appended to res (NULL when it is full): ratio = value / plain when
 * plain > 0, and its pass against target. */
struct sl_bench_row *sl_bench_add_row(struct sl_bench_result *res, const char *stage, const char *unit,
                                      double value, double plain, double target, enum sl_bench_cmp cmp);

/* This process's CPU time so far, user + sys, in seconds (getrusage). */
double sl_bench_cpu_s(void);

/* The median of n values, sorted in place. */
double sl_bench_median(double *v, int n);

/* The load average (1, 5, 15 min) as "a b c", or "unknown". */
void sl_bench_loadavg(char *buf, size_t n);

/* This binary (/proc/self/exe) run with argv and envp, its output to
 * /dev/null; its exit status (128 + signal when killed), -1 when it could
 * not be started. ru (may be NULL) receives the child's own rusage. */
struct rusage;
int sl_bench_spawn_self(char *const *argv, char *const *envp, struct rusage *ru);

/* The summary table of every row, as Markdown. */
void sl_bench_write_summary(const struct sl_bench_result *res, FILE *out);

/* The rows as CSV into path, with the git SHA. */
enum sl_err sl_bench_write_csv(const struct sl_bench_result *res, const char *path, struct sl_diag *d);

/* path gets a header (the command line, stages, provenance, the load
 * averages) and then body, or is left as it was: written under a temporary
 * name in its own folder, synced, renamed over it. */
enum sl_err sl_bench_write_markdown(const char *path, const struct sl_provenance *p, const char *stages,
                                    const char *load0, const char *load1, const char *body, size_t len,
                                    struct sl_diag *d);

#endif
