/*
 * bench_churn.c — the `churn` stage of `shadowlab bench` (bench.h): NSM's
 * layer (depth + id, front faces culled: what the studies' NSM reads) at
 * the bench's map size S and 2S (2048^2 and 4096^2 by default), rendered as a study renders it now — the pass's kept
 * render target, arrays from its pool — against the same layer rendered as
 * it was before issue 20 — a render target made for it and calloc'd
 * arrays, both freed after — in alternation, so drift of a shared VM hits
 * both. Each is timed as the whole sl_shadowmap_render call (target, clear,
 * draw, glFinish and the readback into the arrays; the program is compiled
 * once, untimed) in wall time, CPU time (user + sys of the process, so
 * llvmpipe's threads too) and minor page faults (getrusage).
 *
 * Target (issue 20): the 2S layer (4096^2) at most 5x the S one (2048^2),
 * for 4x the texels. Before, a 4096^2 layer's 64 MiB arrays were above glibc's mmap
 * threshold and faulted afresh every time (~12 us per 4 KB page here).
 */
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include "bench_stages.h"
#include "gbuffer.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "util.h"

struct usage { double wall, cpu, faults; };

static struct usage usage_now(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    struct usage u = {sl_now(), sl_bench_cpu_s(), (double)ru.ru_minflt};
    return u;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* min and median of n values (sorted in place) */
static void min_med(double *v, int n, double *mn, double *md)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    *mn = v[0];
    *md = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#define NSIZES 2
#define NWAYS 2   /* 0 kept + pooled, 1 fresh */

enum sl_err sl_bench_churn(const struct sl_scene *s, const struct sl_gl_mesh *m, struct sl_gbuffer_pass *gp,
                           int vp, int W, int H, int S, int reps, FILE *out, struct sl_bench_result *res,
                           struct sl_diag *d)
{
    const int sizes[NSIZES] = {S, 2 * S};
    const int l = SL_LAYER_DEPTH_ID_BACK;
    struct sl_view v;
    struct sl_shadowmap_pass kept, fresh;
    memset(&kept, 0, sizeof kept);
    memset(&fresh, 0, sizeof fresh);
    double *t = calloc((size_t)NSIZES * NWAYS * 3 * (size_t)reps, sizeof *t);
    if (!t)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "churn times");
#define T(si, w, k, r) t[(((size_t)(si) * NWAYS + (size_t)(w)) * 3 + (size_t)(k)) * (size_t)reps + (size_t)(r)]
    enum sl_err e = sl_gbuffer_render(gp, m, s, vp, W, H, &v, NULL, NULL, NULL, d);
    if (e) {
        free(t);
        return e;
    }
    if ((e = sl_shadowmap_init(&kept, d)) || (e = sl_shadowmap_init(&fresh, d)))
        goto out;
    for (int r = -1; r < reps && !e; r++) {        /* r = -1: a warm-up, not kept */
        for (int si = 0; si < NSIZES && !e; si++)
            for (int w = 0; w < NWAYS && !e; w++) {
                struct sl_light_frame f;
                memset(&f, 0, sizeof f);
                f.pool = w == 0 ? &kept.pool : NULL;
                f.size = sizes[si];
                memcpy(f.dir, s->light_dir, sizeof f.dir);
                sl_light_fit(s, &v, &f.box);
                struct usage u0 = usage_now();
                e = sl_shadowmap_render(w == 0 ? &kept : &fresh, m, &f, SL_NEED(l), d);
                /* the arrays go back (pool) or are freed (as before) inside the timing:
                 * a study pays for both */
                sl_light_box_free(&f.box);
                sl_frame_free(&f);
                if (w == 1) {
                    /* the target goes, as each layer's did before */
                    sl_shadowmap_release_targets(&fresh);
                    glFinish();
                }
                struct usage u1 = usage_now();
                if (r >= 0) {
                    T(si, w, 0, r) = 1e3 * (u1.wall - u0.wall);
                    T(si, w, 1, r) = 1e3 * (u1.cpu - u0.cpu);
                    T(si, w, 2, r) = u1.faults - u0.faults;
                }
            }
    }
    if (e)
        goto out;
    fprintf(out, "## Memory churn: NSM's layer (depth + id, front faces culled) kept vs made afresh (%s, %u "
                 "triangles, %d repetitions after a warm-up, alternating)\n\n", s->name, s->nt, reps);
    fprintf(out, "Kept: the pass's render target for the size and arrays from its pool (what a study does "
                 "now). Fresh: a target made and arrays calloc'd for the layer, freed after (what every "
                 "layer did before). Whole call: target, clear, draw, glFinish, readback, arrays given back. "
                 "CPU: user + sys of the process.\n\n");
    fprintf(out, "| size | way | wall min ms | wall median ms | CPU min ms | CPU median ms | minor faults median |\n");
    fprintf(out, "|---:|---|---:|---:|---:|---:|---:|\n");
    double med[NSIZES][NWAYS][3];
    for (int si = 0; si < NSIZES; si++)
        for (int w = 0; w < NWAYS; w++) {
            double mn[3];
            for (int k = 0; k < 3; k++)
                min_med(&T(si, w, k, 0), reps, &mn[k], &med[si][w][k]);
            fprintf(out, "| %d² | %s | %.1f | %.1f | %.1f | %.1f | %.0f |\n", sizes[si], w ? "fresh" : "kept",
                    mn[0], med[si][w][0], mn[1], med[si][w][1], med[si][w][2]);
        }
    fputc('\n', out);
    for (int w = 0; w < NWAYS; w++) {
        struct sl_bench_row *row = sl_bench_add_row(res, "churn", "ms", med[1][w][0], med[0][w][0], 5.0,
                                                    SL_BENCH_AT_MOST);
        if (row) {
            snprintf(row->name, sizeof row->name, "NSM layer %d² / %d², %s", sizes[1], sizes[0],
                     w ? "fresh (as before)" : "kept");
            snprintf(row->note, sizeof row->note, "CPU %.1f / %.1f ms; minor faults %.0f / %.0f",
                     med[1][w][1], med[0][w][1], med[1][w][2], med[0][w][2]);
        }
    }
    /* reuse must not cost more than what it replaces */
    struct sl_bench_row *row = sl_bench_add_row(res, "churn", "ms", med[1][0][1], med[1][1][1], 1.0,
                                                SL_BENCH_AT_MOST);
    if (row)
        snprintf(row->name, sizeof row->name, "NSM layer %d², CPU kept / fresh", sizes[1]);
out:
#undef T
    sl_view_free(&v);
    if (kept.prog_depth_id)
        sl_shadowmap_free(&kept);
    if (fresh.prog_depth_id)
        sl_shadowmap_free(&fresh);
    free(t);
    return e;
}
