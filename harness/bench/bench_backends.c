/*
 * bench_backends.c — the `backends` stage of `shadowlab bench` (bench.h):
 * the two GL backends, OSMesa and EGL, side by side.
 */
#include "bench_stages.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "adjacency.h"
#include "gbuffer.h"
#include "glctx.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "util.h"

/* Context creation, the G-buffer and each layer through OSMesa and through
 * EGL in the same process. Each repetition opens a context of each backend
 * in turn (the order alternating, so drift of a shared VM hits both), runs
 * every pass once in it and closes it. The first repetition is a warm-up,
 * reported apart: it is the only one whose context creation loads the
 * backend's driver (EGL dlopens Mesa's DRI driver at eglInitialize; OSMesa's
 * llvmpipe is linked into libOSMesa, loaded with the program). Wall: context
 * creation whole, a pass's render + glFinish (as the layers stage, readback
 * apart); CPU: user + sys of the process (llvmpipe's threads included) over
 * the same context creation, and over the whole pass call (its readback
 * included); GPU: the pass's GL_TIME_ELAPSED. Judged per stage on the
 * minimum (the repetition least disturbed by other work): EGL within 5% of
 * OSMesa; the ratio of medians is printed beside it. */
#define BK_NSTAGES (2 + SL_LAYER_COUNT)   /* context, G-buffer, the layers */
#define TARGET_BACKEND_RATIO 1.05

struct bk_rep { double wall[BK_NSTAGES], cpu[BK_NSTAGES], gpu[BK_NSTAGES]; };

static enum sl_err backend_rep(const struct sl_bench_ctx *x, const struct sl_adjacency *adj, enum sl_gl_backend b,
                               struct bk_rep *out, struct sl_diag *d)
{
    struct sl_gl gl;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gp = {0};
    struct sl_shadowmap_pass sp = {0};
    struct sl_light_frame f;
    struct sl_view v;
    memset(&mesh, 0, sizeof mesh);
    memset(&f, 0, sizeof f);
    memset(&v, 0, sizeof v);
    memset(out, 0, sizeof *out);
    double t0 = sl_now(), c0 = sl_bench_cpu_s();
    enum sl_err e = sl_gl_open(&gl, &(struct sl_gl_desc){.backend = b}, d);
    out->wall[0] = 1e3 * (sl_now() - t0);
    out->cpu[0] = 1e3 * (sl_bench_cpu_s() - c0);
    if (e)
        return e;
    if ((e = sl_gl_mesh_upload(&mesh, &x->s, d)) || (e = sl_gl_mesh_upload_adjacency(&mesh, &x->s, adj, d)) ||
        (e = sl_gbuffer_init(&gp, &x->s, d)) || (e = sl_shadowmap_init(&sp, d)))
        goto out;
    double mb = 0;
    for (int k = 0; k < 2; k++) {
        /* the second time is timed: the first compiles the shader variants */
        sl_view_free(&v);
        c0 = sl_bench_cpu_s();
        if ((e = sl_gbuffer_render(&gp, &mesh, &x->s, x->vp[0], x->W, x->H, &v, &out->wall[1], &mb, &out->gpu[1],
                                   d)))
            goto out;
        out->cpu[1] = 1e3 * (sl_bench_cpu_s() - c0);
    }
    f.size = x->S;
    memcpy(f.dir, x->s.light_dir, sizeof f.dir);
    sl_light_fit(&x->s, &v, &f.box);
    f.texel_world = fmaxf(f.box.hi[0] - f.box.lo[0], f.box.hi[1] - f.box.lo[1]) / (float)x->S;
    f.depth_range = f.box.hi[2] - f.box.lo[2];
    for (int l = 0; l < 2 * SL_LAYER_COUNT && !e; l++) {
        if (l == SL_LAYER_COUNT) {
            /* timed: the first round compiled the shader variants */
            for (int i = 0; i < SL_LAYER_COUNT; i++) {
                free(f.layer[i].depth);
                free(f.layer[i].id);
                memset(&f.layer[i], 0, sizeof f.layer[i]);
            }
            f.have = 0;
        }
        int k = l % SL_LAYER_COUNT;
        c0 = sl_bench_cpu_s();
        e = sl_shadowmap_render(&sp, &mesh, &f, SL_NEED(k), d);   /* in order: BGSM before BGSM2 */
        out->cpu[2 + k] = 1e3 * (sl_bench_cpu_s() - c0);
        out->wall[2 + k] = f.layer[k].ms_render;
        out->gpu[2 + k] = f.layer[k].ms_gpu;
    }
out:
    sl_frame_free(&f);
    sl_view_free(&v);
    if (sp.prog_depth_id)
        sl_shadowmap_free(&sp);
    if (gp.prog)
        sl_gbuffer_free(&gp);
    sl_gl_mesh_free(&mesh);
    sl_gl_free(&gl);
    return e;
}

/* The median of the values that are not NaN (a GPU timer that failed,
 * glctx.h); NaN when none is. */
static double median_known(double *v, int n)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (!isnan(v[i]))
            v[k++] = v[i];
    return k ? sl_bench_median(v, k) : NAN;
}

static double min_of(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++)
        m = v[i] < m ? v[i] : m;
    return m;
}

enum sl_err sl_bench_backends(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
{
    FILE *out = x->out;
    if (!sl_gl_backend_built(SL_GL_OSMESA) || !sl_gl_backend_built(SL_GL_EGL)) {
        fprintf(out, "## GL backends side by side\n\nSkipped: this build has only the %s backend.\n\n",
                sl_gl_backend_name(sl_gl_backend_resolve(SL_GL_DEFAULT)));
        return SL_OK;
    }
    const enum sl_gl_backend be[2] = {SL_GL_OSMESA, SL_GL_EGL};
    int reps = x->reps;
    struct bk_rep cold[2], *rep = sl_calloc((size_t)reps * 2, sizeof *rep);
    double *buf = sl_calloc((size_t)reps * 6, sizeof *buf);
    struct sl_adjacency adj = {0};
    char device[2][160] = {"", ""};
    enum sl_err e = SL_OK;
    if (!rep || !buf) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "backend times");
        goto out;
    }
    if ((e = sl_adjacency_build(&x->s, &adj, d)))
        goto out;
    for (int r = -1; r < reps && !e; r++)
        for (int k = 0; k < 2 && !e; k++) {
            int i = (r & 1) ? 1 - k : k;   /* the order alternates; the warm-up opens OSMesa first */
            e = backend_rep(x, &adj, be[i], r < 0 ? &cold[i] : &rep[2 * r + i], d);
        }
    if (e)
        goto out;
    /* what EGL chose (the device line), from one more context */
    for (int i = 0; i < 2 && !e; i++) {
        struct sl_gl g;
        if (!(e = sl_gl_open(&g, &(struct sl_gl_desc){.backend = be[i]}, d))) {
            sl_gl_describe(&g, device[i], sizeof device[i]);
            sl_gl_free(&g);
        }
    }
    if (e)
        goto out;
    fprintf(out, "## GL backends side by side (%s, %dx%d, layers %d², viewpoint %s; %d repetitions after a "
                 "warm-up, min and median)\n\n", x->s.name, x->W, x->H, x->S, x->s.vp[x->vp[0]].name, reps);
    fprintf(out, "OSMesa: %s. EGL: %s. Each repetition opens one context of each backend (order alternating), "
                 "runs each pass once and closes it. Wall: context creation; a pass's render + glFinish "
                 "(readback apart). CPU: user+sys of the process (llvmpipe threads included) over the same "
                 "creation, over the whole pass call (medians; on a loaded machine the steadier comparison, as "
                 "waiting for a core adds to wall time only). GPU: GL_TIME_ELAPSED. Target: EGL's min within "
                 "%.0f%% of OSMesa's; the ratio of medians beside it.\n\n",
            device[0], device[1], 100.0 * (TARGET_BACKEND_RATIO - 1.0));
    fprintf(out, "| stage | OSMesa min | OSMesa median | EGL min | EGL median | ratio (min) | ratio (median) | "
                 "OSMesa CPU | EGL CPU | ratio (CPU) | OSMesa GPU | EGL GPU | warm-up OSMesa | warm-up EGL | result |\n");
    fprintf(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int s = 0; s < BK_NSTAGES; s++) {
        double mn[2], md[2], cpu[2], gpu[2];
        for (int i = 0; i < 2; i++) {
            double *w = buf, *c = buf + reps, *g = buf + 2 * reps;
            for (int r = 0; r < reps; r++) {
                w[r] = rep[2 * r + i].wall[s];
                c[r] = rep[2 * r + i].cpu[s];
                g[r] = rep[2 * r + i].gpu[s];
            }
            mn[i] = min_of(w, reps);
            md[i] = sl_bench_median(w, reps);
            cpu[i] = sl_bench_median(c, reps);
            gpu[i] = median_known(g, reps);
        }
        char name[64];
        if (s == 0)
            snprintf(name, sizeof name, "context");
        else if (s == 1)
            snprintf(name, sizeof name, "gbuffer %dx%d", x->W, x->H);
        else
            snprintf(name, sizeof name, "%s %d²", sl_layer_names[s - 2], x->S);
        struct sl_bench_row *row = sl_bench_add_row(res, "backend", "ms", mn[1], mn[0], TARGET_BACKEND_RATIO,
                                           SL_BENCH_AT_MOST);
        char gp[2][24] = {"", ""};
        for (int i = 0; i < 2 && s > 0; i++)
            snprintf(gp[i], sizeof gp[i], "%.2f", gpu[i]);
        fprintf(out,
                "| %s | %.2f | %.2f | %.2f | %.2f | **%.3f** | %.3f | %.2f | %.2f | %.3f | %s | %s | %.2f | %.2f | %s |\n",
                name, mn[0], md[0], mn[1], md[1], mn[1] / mn[0], md[1] / md[0], cpu[0], cpu[1], cpu[1] / cpu[0], gp[0],
                gp[1],
                cold[0].wall[s], cold[1].wall[s], mn[1] / mn[0] <= TARGET_BACKEND_RATIO ? "PASS" : "**MISS**");
        if (row) {
            snprintf(row->name, sizeof row->name, "EGL vs OSMesa: %s", name);
            snprintf(row->note, sizeof row->note,
                     "min; medians %.2f vs %.2f ms; CPU %.2f vs %.2f ms; warm-up %.2f vs %.2f ms", md[1], md[0],
                     cpu[1], cpu[0], cold[1].wall[s], cold[0].wall[s]);
        }
    }
    fputc('\n', out);
out:
    sl_adjacency_free(&adj);
    free(rep);
    free(buf);
    return e;
}
