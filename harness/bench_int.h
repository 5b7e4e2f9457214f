#ifndef SL_BENCH_INT_H
#define SL_BENCH_INT_H
/* bench_int.h — what bench.c shares with the stages kept in their own files
 * (bench_jobs.c): a row against its target, and those stages. */
#include "bench.h"

struct sl_bench_row *sl_bench_add_row(struct sl_bench_result *res, const char *stage, const char *unit,
                                      double value, double plain, double target, enum sl_bench_cmp cmp);

/* One study as one process against `run --jobs 2` (bench_jobs.c). */
enum sl_err sl_bench_jobs(const char *path, enum sl_gl_backend gl, FILE *out, struct sl_bench_result *res,
                          struct sl_diag *d);

/* NSM's layer kept vs made afresh (bench_churn.c). */
struct sl_gbuffer_pass;
struct sl_gl_mesh;
enum sl_err sl_bench_churn(const struct sl_scene *s, const struct sl_gl_mesh *m, struct sl_gbuffer_pass *gp,
                           int vp, int W, int H, int reps, FILE *out, struct sl_bench_result *res,
                           struct sl_diag *d);

#endif
