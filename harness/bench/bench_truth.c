/*
 * bench_truth.c — the `truth` stage of `shadowlab bench` (bench.h): the
 * truth pass against the plain thing anyone would write with Embree alone:
 * rays prepared in advance as 4x4 packets, a scene with the same flags and
 * build quality but no filter function, rtcOccluded4/8/16 over the packets
 * on the same threads, in packets of the width the device runs natively
 * (the truth's own, packet.h: 16 under AVX-512, 8 under AVX2, 4 under
 * SSE; SHADOWLAB_EMBREE_CONFIG=isa=... measures each on one machine). The truth pass does more per ray (reads the G-buffer,
 * skips non-PFL pixels, rejects the own triangle in a filter, writes the
 * classification). It streams: each thread fills a chunk of packets from
 * the G-buffer, traces them, writes their answers back (truth.c), and
 * clocks the two apart (sl_rt_times), so the truth's filtered trace is
 * compared with the plain trace over prebuilt packets (issue 20's target),
 * and the truth end to end with the plain set-up + trace. Wall time on the
 * config's threads, and the CPU time of one thread on one thread, which
 * other work on a shared machine does not inflate (wall time there moves
 * by 2x); the truth's CPU time is split between set-up and trace in the
 * proportion its own clocks measured (preemption falls on both alike).
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <omp.h>
#include "bench_stages.h"
#include "packet.h"
#include "truth.h"
#include "util.h"

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

struct packets { struct sl_rt_tile *t; int n; uint64_t rays; };

static int build_packets(const struct sl_view *v, struct packets *p)
{
    int tx = (v->w + 3) / 4, ty = (v->h + 3) / 4;
    p->n = tx * ty;
    p->t = aligned_alloc(64, sizeof *p->t * (size_t)p->n);
    if (!p->t)
        return 0;
    p->rays = 0;
    for (int t = 0; t < p->n; t++) {
        int x0 = (t % tx) * 4, y0 = (t / tx) * 4;
        for (int k = 0; k < 16; k++) {
            int x = x0 + (k & 3), y = y0 + (k >> 2);
            p->t[t].valid[k] = 0;
            if (x >= v->w || y >= v->h)
                continue;
            size_t i = (size_t)y * (size_t)v->w + (size_t)x;
            if (v->cls[i] != SL_C_PFL)
                continue;
            p->t[t].valid[k] = -1;
            p->rays++;
        }
    }
    return 1;
}

/* Every lane written, as Embree's contract asks (packet.h): a traced
 * pixel's ray, or a dead ray. */
static void reset_packets(const struct sl_view *v, const struct sl_scene *s, int shift, struct packets *p)
{
    int tx = (v->w + 3) / 4;
    const float dir[3] = {-s->light_dir[0], -s->light_dir[1], -s->light_dir[2]};
    for (int t = 0; t < p->n; t++) {
        int x0 = (t % tx) * 4, y0 = (t / tx) * 4;
        struct sl_rt_tile *r = &p->t[t];
        for (int k = 0; k < 16; k++) {
            if (!r->valid[k]) {
                sl_tile_kill(r, shift, k);
                continue;
            }
            size_t i = (size_t)(y0 + (k >> 2)) * (size_t)v->w + (size_t)(x0 + (k & 3));
            const float *q = v->pos + 3 * i;
            sl_tile_ray(r, shift, k, q, dir, sl_rt_tnear(q), INFINITY, v->tri[i]);
        }
    }
}

static double plain_loop(const struct sl_rt *rt, struct packets *p)
{
    double t0 = sl_now();
#pragma omp parallel num_threads(rt->threads)
    {
        sl_rt_thread_init();
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
#pragma omp for schedule(dynamic, 4)
        for (int t = 0; t < p->n; t++)
            sl_rt_occluded_tile(rt, &ctx, &p->t[t]);
    }
    return sl_now() - t0;
}

/* CPU time of the calling thread: with one thread a parallel region runs
 * in it, so this is the work itself, whatever else the machine runs. */
static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* min and median of n values (sorted in place) */
static void min_med(double *v, int n, double *mn, double *md)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    *mn = v[0];
    *md = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Per repetition: 0 truth, 1 plain set-up, 2 plain trace on the config's
 * threads (wall); 3-5 the same on one thread (its CPU time); 6, 7 the
 * truth's set-up and filtered trace (wall, its share of 0 by its own
 * clocks); 8, 9 the same on one thread (CPU, share of 3). */
#define TR_N 10

/* The stage under one device config: Embree's own choice of kernels (isa
 * NULL: its three rows) or the kernels of `isa` (its trace row alone). */
static enum sl_err truth_variant(struct sl_bench_ctx *x, struct sl_bench_result *res, const char *isa,
                                 int *width, struct sl_diag *d)
{
    struct sl_rt rt = {0}, plain = {0}, rt1 = {0}, plain1 = {0};
    enum sl_err e;
    if ((e = sl_rt_build_isa(&rt, &x->s, x->threads, 1, isa, d)) ||
        (e = sl_rt_build_isa(&plain, &x->s, x->threads, 0, isa, d)) ||
        (e = sl_rt_build_isa(&rt1, &x->s, 1, 1, isa, d)) || (e = sl_rt_build_isa(&plain1, &x->s, 1, 0, isa, d)))
        goto done;
    if (width)
        *width = 1 << rt.shift;
    FILE *out = x->out;
    int reps = x->reps;
    const char *wait = getenv("OMP_WAIT_POLICY");
    fprintf(out, "## Truth pass vs a plain rtcOccluded%d loop over the same rays (%s, min and median of %d "
                 "after a warm-up, Embree %s, device config '%s', OMP_WAIT_POLICY %s)\n\n", 1 << rt.shift, x->s.name,
            reps, rt.version, rt.config, wait ? wait : "unset (libgomp: active)");
    fprintf(out, "The truth pass streams: each thread fills a chunk of packets from the G-buffer, traces them "
                 "(rtcOccluded%d, the device's native width, own-triangle filter), writes the answers back, "
                 "and clocks set-up (fill + write-back) and trace apart; the truth's time is split in that proportion. The plain loop's "
                 "set-up (its packets from the same G-buffer, all at once) and its trace are timed apart. Wall: "
                 "%d threads. CPU: the same on one thread, that thread's CPU time (what a loaded machine cannot "
                 "inflate). Ratios are rays/s: the truth's filtered trace over the plain trace (**trace**), the "
                 "truth end to end over the plain set-up + trace (**whole**), and the truth end to end over the "
                 "plain trace alone (as this bench measured before). Medians.\n\n", 1 << rt.shift, x->threads);
    fprintf(out, "| viewpoint | rays | truth ms min / med | its set-up / trace | plain set-up | plain trace min / med | "
                 "trace | whole | end to end / plain trace | 1 thread CPU: truth ms | its set-up / trace | "
                 "plain set-up | plain trace | trace | whole | end to end / plain trace |\n");
    fprintf(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    double sum[TR_N] = {0};
    uint64_t sum_rays = 0;
    char notes[128] = "";
    for (int vi = 0; vi < x->nvp && !e; vi++) {
        int vp = x->vp[vi];
        struct sl_view v;
        if ((e = sl_gbuffer_render(&x->gp, &x->mesh, &x->s, vp, x->W, x->H, &v, NULL,
                                   NULL, NULL, d)))
            break;
        struct packets pk = {0};
        double *tm = calloc((size_t)reps * TR_N, sizeof *tm);
        if (!build_packets(&v, &pk) || !tm)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "ray packets");
        uint64_t rays = 0;
        for (int r = -1; r < reps && !e; r++) {
            /* the truth pass reclassifies from the G-buffer each time */
            struct sl_truth_stats ts;
            double w[TR_N];
            if ((e = sl_truth_trace(&rt, &x->s, &v, &ts, d)))
                break;
            rays = ts.rays;
            w[0] = ts.ms_trace;
            const double f = ts.ms_setup + ts.ms_rays > 0 ? ts.ms_rays / (ts.ms_setup + ts.ms_rays) : 0.0;
            w[6] = w[0] * (1.0 - f);
            w[7] = w[0] * f;
            double t0 = sl_now();
            reset_packets(&v, &x->s, plain.shift, &pk);
            w[1] = 1e3 * (sl_now() - t0);
            w[2] = 1e3 * plain_loop(&plain, &pk);
            double c0 = thread_cpu();
            if ((e = sl_truth_trace(&rt1, &x->s, &v, &ts, d)))
                break;
            double c1 = thread_cpu();
            const double f1 = ts.ms_setup + ts.ms_rays > 0 ? ts.ms_rays / (ts.ms_setup + ts.ms_rays) : 0.0;
            reset_packets(&v, &x->s, plain.shift, &pk);
            double c2 = thread_cpu();
            plain_loop(&plain1, &pk);
            double c3 = thread_cpu();
            w[3] = 1e3 * (c1 - c0);
            w[4] = 1e3 * (c2 - c1);
            w[5] = 1e3 * (c3 - c2);
            w[8] = w[3] * (1.0 - f1);
            w[9] = w[3] * f1;
            if (r >= 0)
                for (int k = 0; k < TR_N; k++)
                    tm[(size_t)k * (size_t)reps + (size_t)r] = w[k];
        }
        if (!e) {
            /* the same rays must give the same answers: count the plain
             * loop's occluded rays against the truth's shadowed pixels */
            uint64_t plain_occ = 0;
            for (int t = 0; t < pk.n; t++)
                for (int k = 0; k < 16; k++)
                    plain_occ += pk.t[t].valid[k] && sl_tile_occluded(&pk.t[t], plain.shift, k);
            if (plain_occ != v.n_shadow) {
                size_t len = strlen(notes);
                snprintf(notes + len, sizeof notes - len, "%s%s: plain +%lld occluded", len ? "; " : "",
                         x->s.vp[vp].name, (long long)plain_occ - (long long)v.n_shadow);
            }
            double mn[TR_N], md[TR_N];
            for (int k = 0; k < TR_N; k++) {
                min_med(tm + (size_t)k * (size_t)reps, reps, &mn[k], &md[k]);
                sum[k] += md[k];
            }
            fprintf(out, "| %s | %llu | %.2f / %.2f | %.2f / %.2f | %.2f | %.2f / %.2f | %.2f | %.2f | %.2f | %.2f | "
                         "%.2f / %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", x->s.vp[vp].name,
                    (unsigned long long)rays, mn[0], md[0], md[6], md[7], md[1], mn[2], md[2], md[2] / md[7],
                    (md[1] + md[2]) / md[0], md[2] / md[0], md[3], md[8], md[9], md[4], md[5], md[5] / md[9],
                    (md[4] + md[5]) / md[3], md[5] / md[3]);
            sum_rays += rays;
        }
        free(tm);
        free(pk.t);
        sl_view_free(&v);
    }
    if (!e) {
        fprintf(out, "| **all** | %llu | %.2f | %.2f / %.2f | %.2f | %.2f | **%.2f** | %.2f | %.2f | %.2f | %.2f / %.2f | "
                     "%.2f | %.2f | **%.2f** | %.2f | %.2f |\n\n", (unsigned long long)sum_rays, sum[0], sum[6],
                sum[7], sum[1], sum[2], sum[2] / sum[7], (sum[1] + sum[2]) / sum[0], sum[2] / sum[0], sum[3], sum[8],
                sum[9], sum[4], sum[5], sum[5] / sum[9], (sum[4] + sum[5]) / sum[3], sum[5] / sum[3]);
        if (notes[0])
            fprintf(out, "Occluded rays the plain loop counts beyond the truth's shadowed pixels (rays "
                         "crossing their own triangle beyond tnear, which the truth's filter rejects): %s\n\n",
                    notes);
        const double mr = sum_rays * 1e-3;   /* Mrays/s from ms */
        /* issue 20's target: the truth's filtered trace against the plain
         * trace over the same rays, on one thread's CPU time */
        struct sl_bench_row *row = sl_bench_add_row(res, "truth", "Mrays/s", mr / sum[9], mr / sum[5],
                                                    SL_BENCH_TARGET_TRUTH_RATIO, SL_BENCH_AT_LEAST);
        if (row) {
            snprintf(row->name, sizeof row->name, "truth %s, %d viewpoints, %dx%d, packets of %d%s%s", x->s.name,
                     x->nvp, x->W, x->H, 1 << rt.shift, isa ? ", isa=" : "", isa ? isa : "");
            snprintf(row->note, sizeof row->note, "%llu rays; filtered trace vs plain trace, 1 thread CPU; "
                     "set-up %.2f vs %.2f ms", (unsigned long long)sum_rays, sum[8], sum[4]);
        }
        if (isa)
            goto done;
        /* the set-up is not hidden: end to end, the truth against the plain
         * loop's set-up + trace */
        row = sl_bench_add_row(res, "truth", "Mrays/s", mr / sum[3], mr / (sum[4] + sum[5]),
                               SL_BENCH_TARGET_TRUTH_WHOLE, SL_BENCH_AT_LEAST);
        if (row) {
            snprintf(row->name, sizeof row->name, "truth, 1 thread, CPU time");
            snprintf(row->note, sizeof row->note, "end to end vs plain set-up + trace; vs the plain trace "
                     "alone %.2f×", sum[5] / sum[3]);
        }
        row = sl_bench_add_row(res, "truth", "Mrays/s", mr / sum[0], mr / (sum[1] + sum[2]),
                               SL_BENCH_TARGET_TRUTH_WHOLE, SL_BENCH_AT_LEAST);
        if (row) {
            snprintf(row->name, sizeof row->name, "truth, wall, %d threads", x->threads);
            snprintf(row->note, sizeof row->note, "end to end vs plain set-up + trace; filtered trace vs "
                     "plain trace %.2f×; end to end vs plain trace %.2f×", sum[2] / sum[7], sum[2] / sum[0]);
        }
    }
done:
    sl_rt_free(&plain1);
    sl_rt_free(&rt1);
    sl_rt_free(&plain);
    sl_rt_free(&rt);
    return e;
}

enum sl_err sl_bench_truth(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
{
    int native = 0;
    enum sl_err e = truth_variant(x, res, NULL, &native, d);
    /* The narrower packets this CPU also runs, each with Embree's kernels
     * for that ISA: what a machine without AVX-512 (AMD EPYC: AVX2, 8) or
     * without AVX (SSE4.2, 4) gets, measured here against the plain loop
     * of the same width. Not when SHADOWLAB_EMBREE_CONFIG already says how
     * to trace. */
    if (!e && !sl_rt_env_config() && native > 8 && sl_rt_cpu_runs("avx2"))
        e = truth_variant(x, res, "avx2", NULL, d);
    if (!e && !sl_rt_env_config() && native > 4 && sl_rt_cpu_runs("sse4.2"))
        e = truth_variant(x, res, "sse4.2", NULL, d);
    return e;
}
