/*
 * bench.c — see bench.h.
 *
 * The plain loop is what anyone would write with Embree alone: rays prepared
 * in advance as 4x4 packets, a scene with the same flags and build quality but
 * no filter function, rtcOccluded16 over the packets on the same threads. The
 * truth pass does more per ray (reads the G-buffer, skips non-PFL pixels,
 * rejects the own triangle in a filter, writes the classification), and its
 * time is measured end to end.
 */
#include "bench.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <omp.h>
#include "gbuffer.h"
#include "provenance.h"
#include "glctx.h"
#include "run.h"
#include "scenefile.h"
#include "truth.h"
#include "util.h"

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_d);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct packets { struct RTCRay16 *r; int (*valid)[16]; int n; uint64_t rays; };

static int build_packets(const struct sl_view *v, struct packets *p)
{
    int tx = (v->w + 3) / 4, ty = (v->h + 3) / 4;
    p->n = tx * ty;
    p->r = aligned_alloc(64, sizeof *p->r * (size_t)p->n);
    p->valid = aligned_alloc(64, sizeof *p->valid * (size_t)p->n);
    if (!p->r || !p->valid)
        return 0;
    p->rays = 0;
    for (int t = 0; t < p->n; t++) {
        int x0 = (t % tx) * 4, y0 = (t / tx) * 4;
        for (int k = 0; k < 16; k++) {
            int x = x0 + (k & 3), y = y0 + (k >> 2);
            p->valid[t][k] = 0;
            if (x >= v->w || y >= v->h)
                continue;
            size_t i = (size_t)y * (size_t)v->w + (size_t)x;
            if (v->cls[i] != SL_C_PFL)
                continue;
            p->valid[t][k] = -1;
            p->rays++;
        }
    }
    return 1;
}

static void reset_packets(const struct sl_view *v, const struct sl_scene *s, struct packets *p)
{
    int tx = (v->w + 3) / 4;
    for (int t = 0; t < p->n; t++) {
        int x0 = (t % tx) * 4, y0 = (t / tx) * 4;
        struct RTCRay16 *r = &p->r[t];
        for (int k = 0; k < 16; k++) {
            if (!p->valid[t][k])
                continue;
            size_t i = (size_t)(y0 + (k >> 2)) * (size_t)v->w + (size_t)(x0 + (k & 3));
            const float *q = v->pos + 3 * i;
            r->org_x[k] = q[0]; r->org_y[k] = q[1]; r->org_z[k] = q[2];
            r->tnear[k] = sl_rt_tnear(q);
            r->dir_x[k] = -s->light_dir[0]; r->dir_y[k] = -s->light_dir[1]; r->dir_z[k] = -s->light_dir[2];
            r->time[k] = 0.0f;
            r->tfar[k] = INFINITY;
            r->mask[k] = 0xffffffffu;
            r->id[k] = v->tri[i];
            r->flags[k] = 0;
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
            rtcOccluded16(p->valid[t], rt->scene, &ctx, &p->r[t]);
    }
    return sl_now() - t0;
}

enum sl_err sl_bench(const struct sl_bench_opts *o, struct sl_diag *d)
{
    const char *cfg_path = o->config ? o->config : "configs/default.yaml";
    int reps = o->reps > 0 ? o->reps : 7;
    FILE *out = o->out ? o->out : stdout;
    struct sl_config c;
    enum sl_err e = sl_config_load(cfg_path, &c, d);
    if (e)
        return e;

    struct sl_scene s;
    struct sl_gl gl = {0};
    struct sl_gl_mesh mesh = {0};
    struct sl_gbuffer_pass gp = {0};
    struct sl_rt rt = {0}, plain = {0};
    if ((e = sl_scene_load(c.scenes[0].path, &s, d)))
        return e;
    if ((e = sl_gl_init(&gl, d)) || (e = sl_gl_mesh_upload(&mesh, &s, d)) ||
        (e = sl_gbuffer_init(&gp, &s, d)) || (e = sl_rt_build(&rt, &s, c.threads, 1, d)) ||
        (e = sl_rt_build(&plain, &s, c.threads, 0, d)))
        goto out;
    fprintf(out, "# shadowlab bench: %s, scene %s, git %s, %d threads, Embree %s, %s\n\n", cfg_path,
            s.name, sl_git_sha(), c.threads, rt.version, gl.renderer);
    fprintf(out, "## Truth pass vs a plain rtcOccluded16 loop over the same rays (median of %d, after a warm-up)\n\n", reps);
    fprintf(out, "| viewpoint | viewport | rays | truth ms | truth Mrays/s | plain ms | plain Mrays/s | ratio |\n");
    fprintf(out, "|---|---|---:|---:|---:|---:|---:|---:|\n");
    /* the first scene of the config, all its configured viewpoints */
    int nvp = c.scenes[0].nviewpoints;
    double sum_truth = 0, sum_plain = 0;
    uint64_t sum_rays = 0;
    for (int vi = 0; vi < nvp && !e; vi++) {
        int vp = sl_scene_find_viewpoint(&s, c.scenes[0].viewpoints[vi]);
        int W = c.viewport_w[0], H = c.viewport_h[0];
        struct sl_view v;
        if ((e = sl_gbuffer_render(&gp, &mesh, &s, vp, W, H, &v, NULL, NULL, d)))
            break;
        struct packets pk = {0};
        if (!build_packets(&v, &pk)) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "ray packets");
            sl_view_free(&v);
            break;
        }
        double *tt = calloc((size_t)reps, sizeof *tt), *tp = calloc((size_t)reps, sizeof *tp);
        uint64_t rays = 0;
        for (int r = -1; r < reps && !e; r++) {
            /* the truth pass reclassifies from the G-buffer each time */
            struct sl_truth_stats ts;
            e = sl_truth_trace(&rt, &s, &v, &ts, d);
            rays = ts.rays;
            reset_packets(&v, &s, &pk);
            double pl = plain_loop(&plain, &pk);
            if (r >= 0) {
                tt[r] = ts.ms_trace * 1e-3;
                tp[r] = pl;
            }
        }
        /* the same rays must give the same answers: count the plain loop's
         * occluded rays against the truth's shadowed pixels */
        uint64_t plain_occ = 0;
        for (int t = 0; t < pk.n; t++)
            for (int k = 0; k < 16; k++)
                plain_occ += pk.valid[t][k] && pk.r[t].tfar[k] == -INFINITY;
        if (plain_occ != v.n_shadow)
            fprintf(out, "note: %s: plain loop %llu occluded, truth %llu shadowed (own-triangle hits "
                         "the filter rejects)\n", s.vp[vp].name, (unsigned long long)plain_occ,
                    (unsigned long long)v.n_shadow);
        double mt = median(tt, reps), mpl = median(tp, reps);
        fprintf(out, "| %s | %dx%d | %llu | %.2f | %.1f | %.2f | %.1f | %.2f |\n", s.vp[vp].name, W, H,
                (unsigned long long)rays, 1e3 * mt, rays / mt * 1e-6, 1e3 * mpl, pk.rays / mpl * 1e-6,
                (rays / mt) / (pk.rays / mpl));
        sum_truth += mt;
        sum_plain += mpl;
        sum_rays += rays;
        free(tt);
        free(tp);
        free(pk.r);
        free(pk.valid);
        sl_view_free(&v);
    }
    if (!e)
        fprintf(out, "| **all** | | %llu | %.2f | %.1f | %.2f | %.1f | **%.2f** |\n\n",
                (unsigned long long)sum_rays, 1e3 * sum_truth, sum_rays / sum_truth * 1e-6,
                1e3 * sum_plain, sum_rays / sum_plain * 1e-6, sum_plain / sum_truth);
out:
    sl_rt_free(&plain);
    sl_rt_free(&rt);
    if (gl.ctx) {
        sl_gbuffer_free(&gp);
        sl_gl_mesh_free(&mesh);
        sl_gl_free(&gl);
    }
    sl_scene_free(&s);
    if (e)
        return e;

    /* stage times of one whole run of the config (warm: GL programs compiled above) */
    struct sl_run_opts ro = {.out_root = NULL, .table_out = NULL, .write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result res;
    if ((e = sl_run(&c, &ro, &res, d)))
        return e;
    fprintf(out, "## Stage times of one run of %s (ms, no files written)\n\n", cfg_path);
    fprintf(out, "| viewpoint | map | label | G-buffer render | readback | truth | fit | map render | map readback | method | contours | figures |\n");
    fprintf(out, "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < res.ncells; i++) {
        const struct sl_cell *cl = &res.cells[i];
        const struct sl_stage_ms *m = &cl->ms;
        fprintf(out, "| %s | %d | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n",
                cl->viewpoint, c.maps[cl->key.map], c.methods[cl->key.method].label, m->gbuffer_render[SL_MED],
                m->gbuffer_readback, m->truth[SL_MED], m->fit, m->map_render[SL_MED], m->map_readback, m->method[SL_MED],
                m->contours, m->figures);
    }
    fprintf(out, "\nwhole run: %.0f ms (scene %.1f ms, BVH %.1f ms)\n", res.ms_total, res.ms_scene, res.ms_bvh);
    sl_run_result_free(&res);
    return SL_OK;
}
