#ifndef SL_BENCH_STAGES_H
#define SL_BENCH_STAGES_H
/* bench_stages.h — the bench's stages, one file each, and their targets:
 * what bench.c runs, in its order. A stage calls bench_row.h's helpers and
 * no other stage. */
#include "bench_row.h"
#include "frame.h"   /* SL_LAYER_COUNT, the layer names */

/* issue 20: the truth at 0.9x a plain loop's rays/s, at least */
#define SL_BENCH_TARGET_TRUTH_RATIO 0.9
/* and end to end, its set-up included, no slower than the plain loop's
 * set-up + trace over the same rays: the set-up the trace target leaves out
 * must not come back elsewhere */
#define SL_BENCH_TARGET_TRUTH_WHOLE 1.0

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

/* The truth pass against a plain Embree packet loop of the same width, at each width the CPU runs (bench_truth.c). */
enum sl_err sl_bench_truth(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* Each layer shadowmap.c renders, and the G-buffer, against a plain raster
 * of the same mesh (bench_layers.c). */
enum sl_err sl_bench_layers(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* Context creation, the G-buffer and each layer through OSMesa and through
 * EGL side by side, each in contexts of its own (bench_backends.c); a line
 * and no rows when one of the two is not built. */
enum sl_err sl_bench_backends(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* The study stages of `stages` (MODERNO, MORAIS), each in a child process
 * forked now (bench_study.c): their sections to out, their rows to res. */
enum sl_err sl_bench_studies(const struct sl_bench_opts *o, unsigned stages, FILE *out,
                             struct sl_bench_result *res, struct sl_diag *d);

/* issue 47: a study with the default repetitions at most 1.5x the CPU
 * (user+sys) of computing it once */
#define SL_BENCH_TARGET_TIMING_RATIO 1.5

/* The study at path with the default repetitions against `repetitions:
 * {mode: off}`, `pairs` runs of each alternating, each in a child process
 * (bench_study.c): CPU and wall min, median and max, the ratio of the CPU
 * medians against its target. */
enum sl_err sl_bench_timing(const char *path, enum sl_gl_backend gl, int pairs, FILE *out,
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

/* Each technique package of the source tree against plain passes of the
 * same maps and texel reads (bench_techniques.c). */
enum sl_err sl_bench_techniques(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d);

/* Start-up of version, validate CONFIG and help, lazy against the same
 * binary with its heavy libraries preloaded (bench_startup.c). */
enum sl_err sl_bench_startup(const char *config, int reps, FILE *out, struct sl_bench_result *res,
                             struct sl_diag *d);

#endif
