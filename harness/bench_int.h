#ifndef SL_BENCH_INT_H
#define SL_BENCH_INT_H
/* bench_int.h — what bench.c shares with the stages kept in their own files
 * (bench_jobs.c, bench_startup.c): a row against its target, and those stages. */
#include "bench.h"
#include "gbuffer.h"

/* issue 20: the truth at 0.9x a plain loop's rays/s, at least */
#define SL_BENCH_TARGET_TRUTH_RATIO 0.9
/* and end to end, its set-up included, no slower than the plain loop's
 * set-up + trace over the same rays: the set-up the trace target leaves out
 * must not come back elsewhere */
#define SL_BENCH_TARGET_TRUTH_WHOLE 1.0

/* What the truth, layer and churn stages work on. */
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

/* issue 20: contours + figures + exactness per pixel, at most 3x one
 * histogram pass over the same pixels */
#define SL_BENCH_TARGET_SCORE_RATIO 3.0

/* The per-cell scoring against one histogram pass (bench_score.c). */
enum sl_err sl_bench_score(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* issue 20: the light fit on T threads at least 60% efficient on the wall
 * clock (wall <= serial / (0.6 T)); bit for bit the serial fit, always */
#define SL_BENCH_TARGET_LIGHTFIT_EFF 0.6

/* The light fit at 3840x2160, threads against one (bench_score.c). */
enum sl_err sl_bench_lightfit(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* The truth pass against a plain rtcOccluded16 loop (bench_truth.c). */
enum sl_err sl_bench_truth(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* The layers' names in the bench's rows, by SL_LAYER_* (bench.c). */
extern const char *const sl_bench_layer_names[SL_LAYER_COUNT];

/* This process's CPU time so far, user + sys, in seconds (getrusage). */
double sl_bench_cpu_s(void);

/* The load average (1, 5, 15 min) as "a b c", or "unknown". */
void sl_bench_loadavg(char *buf, size_t n);

struct sl_bench_row *sl_bench_add_row(struct sl_bench_result *res, const char *stage, const char *unit,
                                      double value, double plain, double target, enum sl_bench_cmp cmp);

/* The study stages of `stages` (MODERNO, MORAIS), each in a child process
 * forked now (bench_study.c): their sections to out, their rows to res. */
enum sl_err sl_bench_studies(const struct sl_bench_opts *o, unsigned stages, FILE *out,
                             struct sl_bench_result *res, struct sl_diag *d);

/* One study as one process against `run --jobs 2` (bench_jobs.c). */
enum sl_err sl_bench_jobs(const char *path, enum sl_gl_backend gl, FILE *out, struct sl_bench_result *res,
                          struct sl_diag *d);

/* One view's conservative layers at S^2: peak RSS, and each layer against a
 * plain render (bench_mem.c). */
enum sl_err sl_bench_bigmap(struct sl_bench_ctx *x, int S, struct sl_bench_result *res, struct sl_diag *d);

/* NSM's layer kept vs made afresh (bench_churn.c). */
enum sl_err sl_bench_churn(const struct sl_scene *s, const struct sl_gl_mesh *m, struct sl_gbuffer_pass *gp,
                           int vp, int W, int H, int S, int reps, FILE *out, struct sl_bench_result *res,
                           struct sl_diag *d);

/* This binary (/proc/self/exe) run with argv and envp, its output to
 * /dev/null; its exit status (128 + signal when killed), -1 when it could
 * not be started. ru (may be NULL) receives the child's own rusage. */
struct rusage;
int sl_bench_spawn_self(char *const *argv, char *const *envp, struct rusage *ru);

/* Start-up of version, validate CONFIG and help, lazy against the same
 * binary with its heavy libraries preloaded (bench_startup.c). */
enum sl_err sl_bench_startup(const char *config, int reps, FILE *out, struct sl_bench_result *res,
                             struct sl_diag *d);

#endif
