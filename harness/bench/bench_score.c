/*
 * bench_score.c — the `scoring` stage of `shadowlab bench` (bench.h): what a
 * hard-light cell's per-pixel scoring costs — the contour bands, the figures
 * of every region and the exactness count — against the floor anyone would
 * name for a pass over the pixels: one plain histogram of one byte per
 * pixel (the verdicts), 256 bins, one thread. Both in the same run, per
 * million pixels, with the scoring as it was before the fused pass (the
 * plain contour loop, figures pixel by pixel, the exactness loop, one
 * thread) beside them; fused is sl_score_fused, as cell.c calls it. The input is real: the bench scene's first
 * viewpoint, its truth, and NSM's verdicts from its own layer; the
 * exactness count asks all three guarantees of NSM (which has none), so
 * that it counts its wrong pixels and every pixel is checked. The fused
 * pass and the old one must agree to the pixel (bands) and to the count
 * (figures, violations), or the stage says so and fails its row.
 * Wall time on the config's threads, and one thread's CPU time on one
 * thread (what a loaded machine cannot inflate).
 */
#define _GNU_SOURCE
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/resource.h>
#include "bench_stages.h"
#include "contour.h"
#include "lightframe.h"
#include "figures.h"
#include "method.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "truth.h"
#include "util.h"

static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void min_med(double *v, int n, double *mn, double *md)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    *mn = v[0];
    *md = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Every timed pass starts from the same cache state: the pixels' arrays
 * out of cache, as in a cell, where the method's loops and the layers have
 * been through the caches since the truth and G-buffer were written.
 * Without it, a pass right after another that read the same bytes (the
 * histogram after the fused pass) measured 2x faster than one after a pass
 * over other arrays. */
static void evict(uint8_t *junk, size_t n)
{
    for (size_t i = 0; i < n; i += 64)
        junk[i]++;
}

/* the plain floor: a 256-bin histogram of one byte per pixel */
static uint64_t histogram(const uint8_t *p, size_t n, uint64_t *h)
{
    memset(h, 0, 256 * sizeof *h);
    for (size_t i = 0; i < n; i++)
        h[p[i]]++;
    return h[1];
}

/* the exactness count as cell.c's loop counted it before the fused pass */
static uint64_t exact_plain(const struct sl_view *v, const struct sl_verdicts *vd, unsigned exact)
{
    uint64_t bad = 0;
    for (int y = 0; y < v->h; y++)
        for (int x = 0; x < v->w; x++) {
            size_t i = (size_t)y * (size_t)v->w + (size_t)x;
            if (v->cls[i] != SL_C_PFL)
                continue;
            uint8_t how = vd->how[i];
            bad += (uint64_t)sl_exact_violated(exact, vd->v[i], how, v->truth[i]);
        }
    return bad;
}

static int same_figures(const struct sl_figures *a, const struct sl_figures *b)
{
    if (a->background != b->background || a->wrong_image != b->wrong_image || a->nregions != b->nregions)
        return 0;
    for (int r = 0; r < a->nregions; r++)
        if (memcmp(a->r[r].n, b->r[r].n, sizeof a->r[r].n) != 0)
            return 0;
    return 1;
}

/* per repetition: 0 histogram, 1 before (one thread), 2 fused (threads):
 * wall; 3 histogram, 4 before, 5 fused: one thread's CPU, on one thread */
#define SC_N 6

enum sl_err sl_bench_score(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
{
    FILE *out = x->out;
    const int W = x->W, H = x->H, S = x->S, reps = x->reps;
    const size_t npx = (size_t)W * (size_t)H;
    const unsigned exact = SL_EXACT_LIT | SL_EXACT_SHADOW | SL_EXACT_PROVED;
    static const int regions[] = {2, 4, 6, 0};
    const int nreg = 4, dil = 6 / 2 - 1;
    struct sl_rt rt = {0};
    struct sl_view v;
    memset(&v, 0, sizeof v);
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    struct sl_shadowmap_pass sp = {0};
    struct sl_verdicts vd;
    memset(&vd, 0, sizeof vd);
    uint8_t *band0 = sl_calloc(npx, 1), *band1 = sl_calloc(npx, 1);
    struct sl_figures *fig = sl_calloc(2, sizeof *fig);
    double *tm = sl_calloc((size_t)reps * SC_N, sizeof *tm);
    vd.w = W;
    vd.h = H;
    vd.v = sl_calloc(npx, 1);
    vd.how = sl_calloc(npx, 1);
    vd.base = sl_calloc(npx, 1);
    vd.tests = sl_calloc(npx, 1);
    vd.detail = sl_calloc(npx, 1);
    vd.vis = sl_calloc(npx, sizeof(float));
    const struct sl_method *m = sl_method_find("nsm");
    enum sl_err e = SL_OK;
    if (!band0 || !band1 || !fig || !tm || !vd.v || !vd.how || !vd.base || !vd.tests || !vd.detail || !vd.vis) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "scoring bench buffers");
        goto out;
    }
    if (!m) {
        e = sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "scoring bench: no method nsm");
        goto out;
    }
    struct sl_method_params p;
    sl_method_params_init(m, &p);
    struct sl_cost cost;
    memset(&cost, 0, sizeof cost);
    if ((e = sl_method_configure(m, &p, d)) || (e = sl_rt_build(&rt, &x->s, x->threads, 1, d)) ||
        (e = sl_gbuffer_render(&x->gp, &x->mesh, &x->s, x->vp[0], W, H, &v, NULL, NULL, NULL, d)) ||
        (e = sl_truth_trace(&rt, &x->s, &v, NULL, d)) || (e = sl_shadowmap_init(&sp, d)))
        goto out;
    /* the light frame of that view, as run.c fits it (bench_layers.c) */
    f.size = S;
    memcpy(f.dir, x->s.light_dir, sizeof f.dir);
    sl_light_fit(&x->s, &v, &f.box);
    f.texel_world = fmaxf(f.box.hi[0] - f.box.lo[0], f.box.hi[1] - f.box.lo[1]) / (float)S;
    f.depth_range = f.box.hi[2] - f.box.lo[2];
    if ((e = sl_shadowmap_render(&sp, &x->mesh, &f, m->needs(&p) & ((1u << SL_LAYER_COUNT) - 1u), d)))
        goto out;
    struct sl_method_args a = {.scene = &x->s, .view = &v, .frame = &f, .params = &p, .rt = &rt,
                               .spass = &sp, .mesh = &x->mesh, .threads = x->threads};
    if ((e = m->run(&a, &vd, &cost, d)))
        goto out;

    uint64_t h[256], sink = 0, bad_before = 0, bad_fused = 0;
    int agree = 1;
    const size_t njunk = (size_t)64 << 20;   /* above any L3 this runs on */
    uint8_t *junk = calloc(njunk, 1);
    if (!junk) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "scoring bench: cache-clearing buffer");
        goto out;
    }
    for (int r = -1; r < reps; r++) {
        double w[SC_N];
        evict(junk, njunk);
        double t0 = sl_now();
        sink += histogram(vd.v, npx, h);
        double t1 = sl_now();
        evict(junk, njunk);
        double t1b = sl_now();
        sl_contour_bands_plain(W, H, vd.v, dil, band0);
        sl_figures_compute_pixelwise(&v, &vd, band0, regions, nreg, &fig[0]);
        bad_before = exact_plain(&v, &vd, exact);
        double t2 = sl_now();
        evict(junk, njunk);
        double t2b = sl_now();
        bad_fused = sl_score_fused(&v, &vd, vd.v, dil, band1, regions, nreg, exact, x->threads, &fig[1]);
        double t3 = sl_now();
        w[0] = 1e3 * (t1 - t0);
        w[1] = 1e3 * (t2 - t1b);
        w[2] = 1e3 * (t3 - t2b);
        agree &= memcmp(band0, band1, npx) == 0 && same_figures(&fig[0], &fig[1]) && bad_before == bad_fused;
        evict(junk, njunk);
        double c0 = thread_cpu();
        sink += histogram(vd.v, npx, h);
        double c1 = thread_cpu();
        evict(junk, njunk);
        double c1b = thread_cpu();
        sl_contour_bands_plain(W, H, vd.v, dil, band0);
        sl_figures_compute_pixelwise(&v, &vd, band0, regions, nreg, &fig[0]);
        bad_before = exact_plain(&v, &vd, exact);
        double c2 = thread_cpu();
        evict(junk, njunk);
        double c2b = thread_cpu();
        bad_fused = sl_score_fused(&v, &vd, vd.v, dil, band1, regions, nreg, exact, 1, &fig[1]);
        double c3 = thread_cpu();
        w[3] = 1e3 * (c1 - c0);
        w[4] = 1e3 * (c2 - c1b);
        w[5] = 1e3 * (c3 - c2b);
        agree &= memcmp(band0, band1, npx) == 0 && same_figures(&fig[0], &fig[1]) && bad_before == bad_fused;
        if (r >= 0)
            for (int k = 0; k < SC_N; k++)
                tm[(size_t)k * (size_t)reps + (size_t)r] = w[k];
    }
    double mn[SC_N], md[SC_N], per = 1e6 / (double)npx;
    for (int k = 0; k < SC_N; k++) {
        min_med(tm + (size_t)k * (size_t)reps, reps, &mn[k], &md[k]);
        mn[k] *= per;
        md[k] *= per;
    }
    fprintf(out, "## Per-cell scoring vs one histogram pass (%s, %s, %dx%d, NSM's verdicts from its %d² layer, "
                 "contours of 2, 4, 6 px and the whole image, min and median of %d after a warm-up)\n\n",
            x->s.name, x->s.vp[x->vp[0]].name, W, H, S, reps);
    fprintf(out, "Per 1 M pixels. Scoring: the contour bands, the figures of every region and the exactness "
                 "count (all three guarantees asked of NSM: %llu of its pixels break one). Before: the plain "
                 "contour loop, the figures pixel by pixel and the exactness loop, one thread. Fused: one pass, "
                 "blocks of rows on %d threads, each block's bands drawn and its keys counted (figures and "
                 "exactness) while in cache. "
                 "Floor: a 256-bin histogram of the verdict bytes, one thread. Each pass starts with the "
                 "caches cleared (64 MiB written). Fused and before %s.\n\n",
            (unsigned long long)bad_fused, x->threads,
            agree ? "agree on every band, figure and violation" : "**DISAGREE** (a bug)");
    fprintf(out, "| | histogram ms | before ms | fused ms | before / histogram | fused / histogram |\n");
    fprintf(out, "|---|---:|---:|---:|---:|---:|\n");
    fprintf(out, "| wall, min | %.3f | %.3f | %.3f | %.2f | %.2f |\n", mn[0], mn[1], mn[2], mn[1] / mn[0], mn[2] / mn[0]);
    fprintf(out, "| wall, median | %.3f | %.3f | %.3f | %.2f | **%.2f** |\n", md[0], md[1], md[2], md[1] / md[0],
            md[2] / md[0]);
    fprintf(out, "| 1 thread CPU, min | %.3f | %.3f | %.3f | %.2f | %.2f |\n", mn[3], mn[4], mn[5], mn[4] / mn[3],
            mn[5] / mn[3]);
    fprintf(out, "| 1 thread CPU, median | %.3f | %.3f | %.3f | %.2f | **%.2f** |\n\n", md[3], md[4], md[5],
            md[4] / md[3], md[5] / md[3]);
    (void)sink;
    free(junk);
    struct sl_bench_row *row = sl_bench_add_row(res, "scoring", "ms/Mpx", md[2], md[0], SL_BENCH_TARGET_SCORE_RATIO,
                                                SL_BENCH_AT_MOST);
    if (row) {
        snprintf(row->name, sizeof row->name, "scoring %dx%d, wall, %d threads", W, H, x->threads);
        snprintf(row->note, sizeof row->note, "fused vs a histogram pass; before %.2f×%s", md[1] / md[0],
                 agree ? "" : "; DISAGREES");
        row->pass &= agree;
    }
    row = sl_bench_add_row(res, "scoring", "ms/Mpx", md[5], md[3], SL_BENCH_TARGET_SCORE_RATIO, SL_BENCH_AT_MOST);
    if (row) {
        snprintf(row->name, sizeof row->name, "scoring, 1 thread, CPU time");
        snprintf(row->note, sizeof row->note, "fused vs a histogram pass; before %.2f×", md[4] / md[3]);
        row->pass &= agree;
    }
out:
    free(vd.v);
    free(vd.how);
    free(vd.base);
    free(vd.tests);
    free(vd.detail);
    free(vd.vis);
    sl_verdicts_drop_frames(&vd);
    free(band0);
    free(band1);
    free(fig);
    free(tm);
    sl_frame_free(&f);
    sl_shadowmap_free(&sp);
    sl_view_free(&v);
    sl_rt_free(&rt);
    return e;
}

/* ---- the light fit on threads against one thread (issue 20) ----
 * The fit of every view (run.c) at 3840x2160, the size the issue measured
 * it at (180 ms on one thread): the bench scene's first viewpoint under its
 * own directional light, then the same view under a point light above the
 * scene's middle (its G-buffer classed again for that light) fitted as a
 * run fits it: the view's summary box (six faces, run.c) and, for the
 * map size of the layer stage, lightframe.c's faces (each pixel's face, then six
 * frames with their guard band). Each repetition fits on one thread, then
 * on the config's threads, and checks the boxes bit for bit. Wall time, and
 * CPU time (user + sys of the whole process, getrusage: the threads' work
 * summed, an idle OpenMP thread's spinning included). */
#define LF_W 3840
#define LF_H 2160
#define LF_KINDS 3

static const char *const lf_kind_name[LF_KINDS] = {
    "directional (the scene's light)", "point light: the view's box (six faces)",
    "point light: the cube's six frames (lightframe.c)"};

static int box_same(const struct sl_light_box *a, const struct sl_light_box *b)
{
    return memcmp(a->vp, b->vp, sizeof a->vp) == 0 && memcmp(a->view, b->view, sizeof a->view) == 0 &&
           memcmp(a->proj, b->proj, sizeof a->proj) == 0 && memcmp(a->lo, b->lo, sizeof a->lo) == 0 &&
           memcmp(a->hi, b->hi, sizeof a->hi) == 0 && a->n_receivers == b->n_receivers &&
           a->n_outside == b->n_outside && a->n_casters == b->n_casters && a->n_unmapped == b->n_unmapped &&
           (a->unmapped == NULL) == (b->unmapped == NULL) &&
           (!a->unmapped || memcmp(a->unmapped, b->unmapped, a->n_unmapped * sizeof *a->unmapped) == 0);
}

/* One fit of a kind on `threads`, its boxes into out[0..5] (kinds 0, 1:
 * out[0] only); how many boxes. */
static int lf_fit(const struct sl_scene *s, const struct sl_view *v, int kind, int size, int threads, uint8_t *face,
                  struct sl_light_box *out)
{
    if (kind < 2) {
        sl_light_fit_mt(s, v, &out[0], threads);
        return 1;
    }
    sl_cube_faces(s->light.pos, v, face, threads);
    /* lightframe.c's guard band, as it picks it: lightframe.h's SL_CUBE_GUARD texels
     * (none on a map too small to hold it) */
    const int guard = size > 4 * SL_CUBE_GUARD ? SL_CUBE_GUARD : 0;
    sl_light_fit_cube_mt(s, v, s->light.pos, face, size, guard, out, threads);
    return 6;
}

enum sl_err sl_bench_lightfit(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
{
    FILE *out = x->out;
    const int reps = x->reps, T = x->threads;
    const size_t npx = (size_t)LF_W * (size_t)LF_H;
    char la0[64], la1[64];
    sl_bench_loadavg(la0, sizeof la0);
    struct sl_view v[2];
    memset(v, 0, sizeof v);
    /* the scene under a point light: above the middle of its bounds by half their height */
    struct sl_scene pt = x->s;
    float bmin[3] = {INFINITY, INFINITY, INFINITY}, bmax[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < x->s.nv; i++)
        for (int k = 0; k < 3; k++) {
            bmin[k] = fminf(bmin[k], x->s.pos[3 * i + k]);
            bmax[k] = fmaxf(bmax[k], x->s.pos[3 * i + k]);
        }
    pt.light.type = SL_LIGHT_POINT;
    for (int k = 0; k < 3; k++)
        pt.light.pos[k] = 0.5f * (bmin[k] + bmax[k]);
    pt.light.pos[1] = bmax[1] + 0.5f * (bmax[1] - bmin[1]);
    double *tm = sl_calloc((size_t)reps * LF_KINDS * 4, sizeof *tm);   /* [kind][serial wall, cpu, mt wall, cpu] */
    struct sl_light_box *bx = sl_calloc(12, sizeof *bx);
    uint8_t *face = malloc(npx);
    enum sl_err e = SL_OK;
    int agree = 1;
    uint32_t receivers[LF_KINDS] = {0}, unmapped[LF_KINDS] = {0};
    if (!tm || !bx || !face) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "light-fit bench buffers");
        goto out;
    }
    if ((e = sl_gbuffer_render(&x->gp, &x->mesh, &x->s, x->vp[0], LF_W, LF_H, &v[0], NULL, NULL, NULL, d)) ||
        (e = sl_gbuffer_render(&x->gp, &x->mesh, &pt, x->vp[0], LF_W, LF_H, &v[1], NULL, NULL, NULL, d)))
        goto out;
    for (int r = -1; r < reps; r++)
        for (int k = 0; k < LF_KINDS; k++) {
            const struct sl_scene *s = k == 0 ? &x->s : &pt;
            const struct sl_view *vw = &v[k == 0 ? 0 : 1];
            double w0 = sl_now(), c0 = sl_bench_cpu_s();
            int nb = lf_fit(s, vw, k, x->S, 1, face, bx);
            double w1 = sl_now(), c1 = sl_bench_cpu_s();
            lf_fit(s, vw, k, x->S, T, face, bx + 6);
            double w2 = sl_now(), c2 = sl_bench_cpu_s();
            receivers[k] = unmapped[k] = 0;
            for (int b = 0; b < nb; b++) {
                agree &= box_same(&bx[b], &bx[6 + b]);
                receivers[k] += bx[b].n_receivers;
                unmapped[k] += bx[b].n_unmapped;
                sl_light_box_free(&bx[b]);
                sl_light_box_free(&bx[6 + b]);
            }
            if (r >= 0) {
                double *t = tm + ((size_t)k * 4) * (size_t)reps + (size_t)r;
                t[0] = 1e3 * (w1 - w0);
                t[(size_t)reps] = 1e3 * (c1 - c0);
                t[2 * (size_t)reps] = 1e3 * (w2 - w1);
                t[3 * (size_t)reps] = 1e3 * (c2 - c1);
            }
        }
    sl_bench_loadavg(la1, sizeof la1);
    fprintf(out, "## Light fit on %d threads vs one (%s, %s, %dx%d, min and median of %d after a warm-up)\n\n",
            T, x->s.name, x->s.vp[x->vp[0]].name, LF_W, LF_H, reps);
    fprintf(out, "Each repetition fits on one thread, then on %d, and compares the boxes bit for bit: %s. CPU: "
                 "user + sys of the process (getrusage). The point light is at (%.1f, %.1f, %.1f); cube frames "
                 "for %d² maps. Load average before %s, after %s.\n\n",
            T, agree ? "identical in every repetition" : "**DIFFERENT** (a bug)", pt.light.pos[0],
            pt.light.pos[1], pt.light.pos[2], x->S, la0, la1);
    fprintf(out, "| fit | receivers | unmapped | 1 thread wall min / median ms | CPU min / median ms | %d threads "
                 "wall min / median ms | CPU min / median ms | wall speed-up (medians) | CPU ratio (medians) |\n",
            T);
    fprintf(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int k = 0; k < LF_KINDS; k++) {
        double mn[4], md[4];
        for (int j = 0; j < 4; j++)
            min_med(tm + ((size_t)k * 4 + (size_t)j) * (size_t)reps, reps, &mn[j], &md[j]);
        fprintf(out, "| %s | %u | %u | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %.2f× | %.2f |\n",
                lf_kind_name[k], receivers[k], unmapped[k], mn[0], md[0], mn[1], md[1], mn[2], md[2], mn[3], md[3],
                md[0] / md[2], md[3] / md[1]);
        /* target: the threads at least 60% used on the wall clock */
        struct sl_bench_row *row = sl_bench_add_row(res, "lightfit", "ms", md[2], md[0],
                                                    T > 1 ? 1.0 / (SL_BENCH_TARGET_LIGHTFIT_EFF * T) : 1.0,
                                                    SL_BENCH_AT_MOST);
        if (row) {
            snprintf(row->name, sizeof row->name, "light fit %s, %dx%d, wall, %d threads", k == 0 ? "dir" :
                     k == 1 ? "point box" : "cube frames", LF_W, LF_H, T);
            snprintf(row->note, sizeof row->note, "vs one thread; CPU %.1f vs %.1f ms%s", md[3], md[1],
                     agree ? "" : "; BOXES DIFFER");
            row->pass &= agree;
        }
    }
    fprintf(out, "\n");
out:
    free(tm);
    free(bx);
    free(face);
    sl_view_free(&v[0]);
    sl_view_free(&v[1]);
    return e;
}
