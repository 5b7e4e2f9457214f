/*
 * bench.c — see bench.h.
 *
 * Truth: bench_truth.c; churn: bench_churn.c; jobs: bench_jobs.c.
 *
 * Layers: each repetition renders the plain raster and then the layer, one
 * after the other, so drift of a shared VM hits both; a layer is rendered by
 * shadowmap.c itself (the code the studies run), from scratch each time
 * (BGSM2 reads the BGSM ids rendered before it, as in a run). The plain
 * raster's timer brackets the same work as shadowmap.c's: framebuffer and
 * textures created, cleared, drawn, glFinish; the readback of depth and ids
 * apart. The G-buffer is timed by gbuffer.c, its fragment count by a query
 * around the call.
 *
 * Studies run last, after this file's GL context and BVHs are freed: sl_run
 * makes its own (one OSMesa context at a time).
 */
#define _GNU_SOURCE   /* open_memstream, fopencookie */
#include "bench_int.h"
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>
#include <omp.h>
#include "adjacency.h"
#include "gbuffer.h"
#include "glctx.h"
#include "lightfit.h"
#include "provenance.h"
#include "run.h"
#include "scenefile.h"
#include "shadowmap.h"
#include "truth.h"
#include "util.h"

extern const char sl_glsl_depth_id_vs[];
extern const char sl_glsl_bench_plain_fs[];

#ifndef GL_FRAGMENT_SHADER_INVOCATIONS_ARB
#define GL_FRAGMENT_SHADER_INVOCATIONS_ARB 0x82F4
#endif

#define TARGET_RASTER_RATIO  2.0     /* a pass's render time over the plain raster's, at most */
#define TARGET_RSS_MIB       2048.0
#define TARGET_CONTEXT_MS    2000.0   /* the first context, driver loading included */

double sl_bench_cpu_s(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static const char *const stage_names[SL_BENCH_NSTAGES] = {
#define SL_BENCH_NAME(id, name) name,
    SL_BENCH_STAGES(SL_BENCH_NAME)
#undef SL_BENCH_NAME
};

const char *const sl_bench_layer_names[SL_LAYER_COUNT] = {
    "depth_id", "depth_id_back", "bgsm", "bgsm2", "sgsm", "sgsm_adj",
};

enum sl_err sl_bench_parse_stages(const char *list, unsigned *out, struct sl_diag *d)
{
    *out = 0;
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (int i = 0; i < SL_BENCH_NSTAGES; i++)
            if (strlen(stage_names[i]) == n && strncmp(p, stage_names[i], n) == 0) {
                *out |= 1u << i;
                found = 1;
            }
        if (!found)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "--only",
                           "unknown stage '%.*s' (known: truth, layers, backends, moderno, morais, jobs, churn, "
                           "startup, scoring, lightfit, bigmap)", (int)n, p);
        p += n;
        if (*p == ',')
            p++;
    }
    if (!*out)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--only", "no stage named");
    return SL_OK;
}

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

struct sl_bench_row *sl_bench_add_row(struct sl_bench_result *res, const char *stage, const char *unit,
                                      double value, double plain, double target, enum sl_bench_cmp cmp)
{
    if (res->nrows >= (int)(sizeof res->rows / sizeof res->rows[0]))
        return NULL;
    struct sl_bench_row *r = &res->rows[res->nrows++];
    memset(r, 0, sizeof *r);
    snprintf(r->stage, sizeof r->stage, "%s", stage);
    snprintf(r->unit, sizeof r->unit, "%s", unit);
    r->value = value;
    r->plain = plain;
    r->target = target;
    r->cmp = cmp;
    if (plain > 0) {
        /* rates: ours over plain (higher is better); times: ours over plain */
        r->ratio = value / plain;
    }
    double x = plain > 0 ? r->ratio : value;
    r->pass = cmp == SL_BENCH_AT_LEAST ? x >= target : x <= target;
    return r;
}


/* ---- layers and the G-buffer against a plain raster --------------------- */

struct raster_ms { double render, readback; uint64_t fragments; };

/* The layers' plain raster's framebuffer, kept across repetitions as
 * shadowmap.c keeps a layer's (made afresh each time, llvmpipe zeroed its textures in
 * fresh pages now and then: its median moved between ~20 and ~200 ms of
 * CPU from one row to the next, and a conservative layer measured "0.4x" a
 * plain raster). Made in the warm-up repetition, timed there only. */
struct plain_target { GLuint fbo, tex[2]; int w, h; };

static void plain_target_free(struct plain_target *t)
{
    if (t->w) {
        glDeleteFramebuffers(1, &t->fbo);
        glDeleteTextures(2, t->tex);
    }
    memset(t, 0, sizeof *t);
}

/* The plain raster: depth32F + R32UI, trivial shaders, one draw of the
 * whole mesh, nothing culled; timed as shadowmap.c times a layer. */
static enum sl_err plain_raster(GLuint prog, const struct sl_gl_mesh *m, const mat4 vp, int w, int h,
                                int zero_to_one, float *depth, uint32_t *id, struct plain_target *pt,
                                struct raster_ms *r, struct sl_diag *d)
{
    size_t n = (size_t)w * (size_t)h;
    double t0 = sl_now();
    GLuint q;
    if (pt->w != w || pt->h != h) {
        plain_target_free(pt);
        pt->w = w;
        pt->h = h;
        glCreateFramebuffers(1, &pt->fbo);
        glCreateTextures(GL_TEXTURE_2D, 2, pt->tex);
        glTextureStorage2D(pt->tex[0], 1, GL_DEPTH_COMPONENT32F, w, h);
        glTextureStorage2D(pt->tex[1], 1, GL_R32UI, w, h);
        glNamedFramebufferTexture(pt->fbo, GL_DEPTH_ATTACHMENT, pt->tex[0], 0);
        glNamedFramebufferTexture(pt->fbo, GL_COLOR_ATTACHMENT0, pt->tex[1], 0);
        glNamedFramebufferDrawBuffer(pt->fbo, GL_COLOR_ATTACHMENT0);
    }
    const GLuint fbo = pt->fbo, *tex = pt->tex;
    enum sl_err e = SL_OK;
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        e = sl_fail(d, SL_E_GL, NULL, 0, NULL, "plain raster framebuffer incomplete");
    if (!e) {
        const GLuint zero_u[4] = {0, 0, 0, 0};
        const float one = 1.0f;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, w, h);
        glClipControl(GL_LOWER_LEFT, zero_to_one ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);
        glClearNamedFramebufferuiv(fbo, GL_COLOR, 0, zero_u);
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
        glUseProgram(prog);
        glUniformMatrix4fv(glGetUniformLocation(prog, "u_vp"), 1, GL_FALSE, (const float *)vp);
        glGenQueries(1, &q);
        glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q);
        glBindVertexArray(m->vao);
        glDrawElements(GL_TRIANGLES, m->count, GL_UNSIGNED_INT, NULL);
        glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        glFinish();
        double t1 = sl_now();
        GLuint64 frags = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &frags);
        glDeleteQueries(1, &q);
        glGetTextureImage(tex[0], 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(n * 4), depth);
        glGetTextureImage(tex[1], 0, GL_RED_INTEGER, GL_UNSIGNED_INT, (GLsizei)(n * 4), id);
        double t2 = sl_now();
        r->render = 1e3 * (t1 - t0);
        r->readback = 1e3 * (t2 - t1);
        r->fragments = (uint64_t)frags;
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        e = sl_gl_check("plain raster", d);
    }
    return e;
}

/* Medians of one pass and its plain counterpart over the repetitions. */
struct pair_ms {
    double *render, *readback, *p_render, *p_readback;
    double *cpu, *p_cpu;   /* process CPU (user+sys, llvmpipe's threads too) of the whole call, readback included */
    uint64_t gs_prims, fragments, p_fragments;
};

static void layer_row(struct sl_bench_result *res, FILE *out, const char *stage, const char *name,
                      struct pair_ms *t, int reps)
{
    double mr = median(t->render, reps), mb = median(t->readback, reps);
    double pr = median(t->p_render, reps), pb = median(t->p_readback, reps);
    double mc = median(t->cpu, reps), pc = median(t->p_cpu, reps);
    fprintf(out, "| %s | %.2f | %.2f | %.2f | %.2f | **%.2f** | %.2f | %.2f | %.2f | %llu | %llu | %llu | %.2f |\n",
            name, mr, pr, mb, pb, mr / pr, mc, pc, pc > 0 ? mc / pc : 0.0, (unsigned long long)t->gs_prims,
            (unsigned long long)t->fragments,
            (unsigned long long)t->p_fragments, t->p_fragments ? (double)t->fragments / (double)t->p_fragments : 0.0);
    struct sl_bench_row *row = sl_bench_add_row(res, stage, "ms", mr, pr, TARGET_RASTER_RATIO, SL_BENCH_AT_MOST);
    if (row) {
        snprintf(row->name, sizeof row->name, "%s", name);
        row->gs_prims = t->gs_prims;
        row->fragments = t->fragments;
        row->plain_fragments = t->p_fragments;
        snprintf(row->note, sizeof row->note, "readback %.2f ms, plain %.2f ms; CPU %.2f ms, plain %.2f ms", mb, pb,
                 mc, pc);
    }
}

static enum sl_err bench_layers(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
{
    FILE *out = x->out;
    int reps = x->reps, W = x->W, H = x->H, S = x->S, vp = x->vp[0];
    size_t nmax = (size_t)(W * H > S * S ? W * H : S * S);
    struct sl_shadowmap_pass sp = {0};
    struct sl_adjacency adj = {0};
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    struct sl_view v;
    memset(&v, 0, sizeof v);
    GLuint prog = 0;
    struct plain_target pt = {0};
    float *depth = sl_calloc(nmax, sizeof(float));
    uint32_t *id = sl_calloc(nmax, sizeof(uint32_t));
    double *buf = sl_calloc((size_t)reps * 6, sizeof(double));
    struct pair_ms t = {buf, buf + reps, buf + 2 * reps, buf + 3 * reps, buf + 4 * reps, buf + 5 * reps, 0, 0, 0};
    enum sl_err e = SL_OK;
    if (!depth || !id || !buf) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "plain raster buffers");
        goto out;
    }
    if ((e = sl_shadowmap_init(&sp, d)) || (e = sl_adjacency_build(&x->s, &adj, d)) ||
        (e = sl_gl_mesh_upload_adjacency(&x->mesh, &x->s, &adj, d)))
        goto out;
    prog = sl_gl_program(sl_glsl_depth_id_vs, NULL, sl_glsl_bench_plain_fs, d);
    if (!prog) {
        e = SL_E_GL;
        goto out;
    }
    fprintf(out, "## Passes vs a plain raster of the same mesh, size and matrix (%s, %u triangles, viewpoint %s; "
                 "median of %d after a warm-up)\n\n", x->s.name, x->s.nt, x->s.vp[vp].name, reps);
    fprintf(out, "Plain raster: depth32F + R32UI, the layers' vertex shader, a fragment shader writing "
                 "gl_PrimitiveID + 1, no geometry shader, one draw, nothing culled, its framebuffer kept "
                 "across repetitions as the passes keep theirs. Render = clear + draw + glFinish; readback "
                 "of depth and ids apart. Fragments: fragment shader "
                 "invocations (GL query), before any discard. CPU: the process's user+sys time "
                 "(llvmpipe's threads included) over the whole call, readback included.\n\n");
    fprintf(out, "| pass | render ms | plain ms | readback ms | plain readback ms | ratio | CPU ms | plain CPU ms | "
                 "CPU ratio | GS prims | fragments | plain fragments | fragment ratio |\n");
    fprintf(out, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");

    /* the G-buffer at the viewport, against a plain raster with the camera */
    mat4 cam;
    for (int r = -1; r < reps && !e; r++) {
        struct raster_ms pm;
        sl_view_free(&v);
        double mr = 0, mb = 0;
        GLuint q;
        glGenQueries(1, &q);
        glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q);
        double c0 = sl_bench_cpu_s();
        e = sl_gbuffer_render(&x->gp, &x->mesh, &x->s, vp, W, H, &v, &mr, &mb, NULL, d);
        double c1 = sl_bench_cpu_s();
        glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        GLuint64 frags = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &frags);
        glDeleteQueries(1, &q);
        if (e)
            break;
        glm_mat4_mul(v.proj, v.view, cam);
        double c2 = sl_bench_cpu_s();
        /* the G-buffer's plain counterpart as before: its framebuffer made
         * afresh each time (kept, this row's own view arrays, made afresh
         * too, faulted in at every repetition: 20 ms of readback) */
        struct plain_target gpt = {0};
        e = plain_raster(prog, &x->mesh, cam, W, H, 0, depth, id, &gpt, &pm, d);
        plain_target_free(&gpt);
        if (e)
            break;
        if (r >= 0) {
            t.cpu[r] = 1e3 * (c1 - c0);
            t.p_cpu[r] = 1e3 * (sl_bench_cpu_s() - c2);
            t.render[r] = mr;
            t.readback[r] = mb;
            t.p_render[r] = pm.render;
            t.p_readback[r] = pm.readback;
        }
        t.fragments = (uint64_t)frags;
        t.p_fragments = pm.fragments;
    }
    if (e)
        goto out;
    char name[64];
    snprintf(name, sizeof name, "gbuffer %dx%d", W, H);
    t.gs_prims = 0;
    layer_row(res, out, "gbuffer", name, &t, reps);

    /* the light frame of that view, as run.c fits it, its arrays from the
     * pass's pool as a run's are (calloc'd afresh, a layer's readback
     * faulted its pages in now and then: +140 ms of CPU in one repetition) */
    f.pool = &sp.pool;
    f.size = S;
    memcpy(f.dir, x->s.light_dir, sizeof f.dir);
    sl_light_fit(&x->s, &v, &f.box);
    f.texel_world = fmaxf(f.box.hi[0] - f.box.lo[0], f.box.hi[1] - f.box.lo[1]) / (float)S;
    f.depth_range = f.box.hi[2] - f.box.lo[2];
    for (int l = 0; l < SL_LAYER_COUNT && !e; l++) {
        for (int r = -1; r < reps && !e; r++) {
            struct raster_ms pm;
            double c0 = sl_bench_cpu_s();
            if ((e = plain_raster(prog, &x->mesh, f.box.vp, S, S, 1, depth, id, &pt, &pm, d)))
                break;
            double c1 = sl_bench_cpu_s();
            sl_frame_drop_layer(&f, l);
            double c2 = sl_bench_cpu_s();
            if ((e = sl_shadowmap_render(&sp, &x->mesh, &f, SL_NEED(l), d)))
                break;
            if (r >= 0) {
                t.p_cpu[r] = 1e3 * (c1 - c0);
                t.cpu[r] = 1e3 * (sl_bench_cpu_s() - c2);
                t.render[r] = f.layer[l].ms_render;
                t.readback[r] = f.layer[l].ms_readback;
                t.p_render[r] = pm.render;
                t.p_readback[r] = pm.readback;
            }
            t.gs_prims = f.layer[l].gs_prims;
            t.fragments = f.layer[l].fragments;
            t.p_fragments = pm.fragments;
        }
        if (e)
            break;
        snprintf(name, sizeof name, "%s %d²", sl_bench_layer_names[l], S);
        layer_row(res, out, "layer", name, &t, reps);
    }
    if (!e)
        fputc('\n', out);
out:
    plain_target_free(&pt);
    if (prog)
        glDeleteProgram(prog);
    sl_frame_free(&f);
    sl_view_free(&v);
    sl_adjacency_free(&adj);
    if (sp.prog_depth_id)
        sl_shadowmap_free(&sp);
    free(depth);
    free(id);
    free(buf);
    return e;
}

/* ---- the two GL backends side by side ------------------------------------ */

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
    return k ? median(v, k) : NAN;
}

static double min_of(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++)
        m = v[i] < m ? v[i] : m;
    return m;
}

static enum sl_err bench_backends(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
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
            md[i] = median(w, reps);
            cpu[i] = median(c, reps);
            gpu[i] = median_known(g, reps);
        }
        char name[64];
        if (s == 0)
            snprintf(name, sizeof name, "context");
        else if (s == 1)
            snprintf(name, sizeof name, "gbuffer %dx%d", x->W, x->H);
        else
            snprintf(name, sizeof name, "%s %d²", sl_bench_layer_names[s - 2], x->S);
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

/* ---- whole studies -------------------------------------------------------- */


/* ---- output ---------------------------------------------------------------- */

static void target_text(const struct sl_bench_row *r, char *buf, size_t n)
{
    const char *op = r->cmp == SL_BENCH_AT_LEAST ? "≥" : "≤";
    if (r->plain > 0)
        snprintf(buf, n, "ratio %s %g", op, r->target);
    else
        snprintf(buf, n, "%s %g %s", op, r->target, r->unit);
}

static void write_summary(const struct sl_bench_result *res, FILE *out)
{
    fprintf(out, "## Summary\n\n");
    fprintf(out, "| stage | measurement | unit | value | plain | ratio | target | result |\n");
    fprintf(out, "|---|---|---|---:|---:|---:|---|---|\n");
    for (int i = 0; i < res->nrows; i++) {
        const struct sl_bench_row *r = &res->rows[i];
        char tgt[48], plain[32] = "", ratio[32] = "";
        target_text(r, tgt, sizeof tgt);
        if (r->plain > 0) {
            snprintf(plain, sizeof plain, "%.2f", r->plain);
            snprintf(ratio, sizeof ratio, "%.2f", r->ratio);
        }
        fprintf(out, "| %s | %s | %s | %.2f | %s | %s | %s | %s |\n", r->stage, r->name, r->unit, r->value, plain,
                ratio, tgt, r->pass ? "PASS" : "**MISS**");
    }
    fputc('\n', out);
}

static enum sl_err write_csv(const struct sl_bench_result *res, const char *path, struct sl_diag *d)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot write the CSV");
    fprintf(f, "git_sha,stage,name,unit,value,plain,ratio,target,cmp,result,gs_prims,fragments,plain_fragments,note\n");
    for (int i = 0; i < res->nrows; i++) {
        const struct sl_bench_row *r = &res->rows[i];
        fprintf(f, "%s,%s,\"%s\",%s,%.6g,%.6g,%.6g,%g,%s,%s,%llu,%llu,%llu,\"%s\"\n", sl_git_sha(), r->stage,
                r->name, r->unit, r->value, r->plain, r->ratio, r->target,
                r->cmp == SL_BENCH_AT_LEAST ? "at_least" : "at_most", r->pass ? "PASS" : "MISS",
                (unsigned long long)r->gs_prims, (unsigned long long)r->fragments,
                (unsigned long long)r->plain_fragments, r->note);
    }
    return fclose(f) == 0 ? SL_OK : sl_fail(d, SL_E_IO, path, 0, NULL, "cannot write the CSV");
}

/* ---- --markdown FILE: the same text, under a header, into a file ---------- */

/* The bench's Markdown goes to its stream as the stages finish (a run of
 * every stage takes minutes) and, with --markdown, also into memory: a
 * stream that writes each block to both. The real stream is flushed with
 * every block, so nothing of it sits in a buffer when a study is forked. */
struct tee { FILE *a, *b; };

static ssize_t tee_write(void *c, const char *buf, size_t n)
{
    struct tee *t = c;
    if (fwrite(buf, 1, n, t->a) != n || fwrite(buf, 1, n, t->b) != n)
        return -1;
    fflush(t->a);
    return (ssize_t)n;
}

static int tee_close(void *c)
{
    (void)c;
    return 0;
}

/* The command line that made this process, as a shell would read it back. */
static void command_line(char *buf, size_t n)
{
    snprintf(buf, n, "(unknown)");
    FILE *f = fopen("/proc/self/cmdline", "rb");
    if (!f)
        return;
    char raw[2048];
    size_t len = fread(raw, 1, sizeof raw - 1, f);
    fclose(f);
    raw[len] = '\0';
    size_t o = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < len && o + 4 < n;) {
        const char *arg = raw + i;
        size_t al = strlen(arg);
        int quote = al == 0 || strpbrk(arg, " \t'\"$`\\*?;&|<>()[]{}") != NULL;
        if (o)
            buf[o++] = ' ';
        if (quote && o + 1 < n)
            buf[o++] = '\'';
        for (size_t k = 0; k < al && o + 6 < n; k++) {
            if (arg[k] == '\'') {
                memcpy(buf + o, "'\\''", 4);
                o += 4;
            } else {
                buf[o++] = arg[k];
            }
        }
        if (quote && o + 1 < n)
            buf[o++] = '\'';
        buf[o] = '\0';
        i += al + 1;
    }
}

/* FILE gets the header and then body, or is left as it was: written under
 * a temporary name in its own folder, synced, renamed over it. */
static enum sl_err write_markdown(const char *path, const struct sl_provenance *p, const char *stages,
                                  const char *load0, const char *load1, const char *body, size_t len,
                                  struct sl_diag *d)
{
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp-XXXXXX", path) >= (int)sizeof tmp)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "path too long");
    int fd = mkstemp(tmp);
    if (fd < 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the Markdown: %s", strerror(errno));
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        unlink(tmp);
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the Markdown: %s", strerror(errno));
    }
    fchmod(fd, 0644);
    char cmd[2048];
    command_line(cmd, sizeof cmd);
    fprintf(f, "# Performance\n\n");
    fprintf(f, "Written by `shadowlab bench --markdown`; regenerate it, on a quiet machine, with the command "
               "below rather than editing it. What each stage measures and its target: `shadowlab help bench` "
               "and the man page; a missed target is a MISS, not an error.\n\n");
    fprintf(f, "| | |\n|---|---|\n");
    fprintf(f, "| command | `%s` |\n", cmd);
    fprintf(f, "| stages | %s |\n", stages);
    fprintf(f, "| git SHA | `%s` |\n", p->git_sha);
    fprintf(f, "| time (UTC) | %s |\n", p->time_utc);
    fprintf(f, "| machine | %s |\n", p->host);
    fprintf(f, "| CPU | %s (%s), %d threads |\n", p->cpu, p->isa, p->threads);
    fprintf(f, "| GL renderer | %s, %s |\n", p->gl_renderer, p->gl_version);
    fprintf(f, "| GL backend | %s |\n", p->gl_backend[0] ? p->gl_backend : "(unknown)");
    fprintf(f, "| Embree | %s |\n", p->embree);
    fprintf(f, "| load average (1, 5, 15 min) | %s at the start, %s at the end |\n\n", load0, load1);
    fwrite(body, 1, len, f);
    int bad = ferror(f) != 0;
    bad |= fflush(f) != 0;
    bad |= fsync(fd) != 0;
    bad |= fclose(f) != 0;
    if (bad || rename(tmp, path) != 0) {
        int err = errno;
        unlink(tmp);
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the Markdown: %s", strerror(err));
    }
    return SL_OK;
}

/* ---- the driver -------------------------------------------------------------- */

/* Other work on a shared machine skews every time: say how busy it was. */
void sl_bench_loadavg(char *buf, size_t n)
{
    snprintf(buf, n, "unknown");
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return;
    double a, b, c;
    if (fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3)
        snprintf(buf, n, "%.2f %.2f %.2f", a, b, c);
    fclose(f);
}

static enum sl_err setup(const struct sl_bench_opts *o, struct sl_bench_ctx *x, struct sl_diag *d)
{
    struct sl_config c;
    int have_cfg = o->config != NULL;
    enum sl_err e;
    if (have_cfg && (e = sl_config_load(o->config, &c, d)))
        return e;
    const char *ref = o->scene ? o->scene : have_cfg ? c.scenes[0].path : "bench";
    if ((e = sl_scene_build(ref, &x->s, d)))
        return e;
    x->nvp = 0;
    if (have_cfg && !o->scene) {
        for (int i = 0; i < c.scenes[0].nviewpoints; i++) {
            int vp = sl_scene_find_viewpoint(&x->s, c.scenes[0].viewpoints[i]);
            if (vp >= 0)
                x->vp[x->nvp++] = vp;
        }
    } else {
        for (int i = 0; i < x->s.nvp; i++)
            x->vp[x->nvp++] = i;
    }
    if (x->nvp == 0)
        return sl_fail(d, SL_E_SCENE, x->s.path, 0, NULL, "scene %s has no viewpoint", x->s.name);
    x->W = o->width > 0 ? o->width : have_cfg ? c.viewport_w[0] : 1024;
    x->H = o->height > 0 ? o->height : have_cfg ? c.viewport_h[0] : 1024;
    x->S = o->map > 0 ? o->map : 2048;
    x->threads = have_cfg ? c.threads : omp_get_num_procs();
    x->reps = o->reps > 0 ? o->reps : 7;
    return SL_OK;
}

enum sl_err sl_bench(const struct sl_bench_opts *o, struct sl_bench_result *res_out, struct sl_diag *d)
{
    /* bigmap only when named: 16384^2 layers take GBs and minutes */
    unsigned stages = o->stages ? o->stages : SL_BENCH_ALL & ~SL_BENCH_STAGE(BIGMAP);
    FILE *out = o->out ? o->out : stdout;
    struct sl_bench_result *res = sl_calloc(1, sizeof *res);
    if (!res)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench rows");
    /* --markdown: everything written to out is also kept for the file */
    char *md_body = NULL;
    size_t md_len = 0;
    FILE *md_mem = NULL, *md_tee = NULL;
    struct tee md_t = {out, NULL};
    if (o->markdown) {
        md_mem = open_memstream(&md_body, &md_len);
        md_t.b = md_mem;
        md_tee = md_mem ? fopencookie(&md_t, "w", (cookie_io_functions_t){.write = tee_write, .close = tee_close})
                        : NULL;
        if (!md_tee) {
            if (md_mem)
                fclose(md_mem);
            free(md_body);
            free(res);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench Markdown");
        }
        out = md_tee;
    }
    char load0[64] = "unknown", stage_list[256] = "";
    int have_prov = 0;
    struct sl_bench_ctx x;
    memset(&x, 0, sizeof x);
    x.out = out;
    enum sl_err e = SL_OK;
    int need_scene = (stages & (SL_BENCH_STAGE(TRUTH) | SL_BENCH_STAGE(LAYERS) | SL_BENCH_STAGE(BACKENDS) |
                                SL_BENCH_STAGE(CHURN) | SL_BENCH_STAGE(SCORING) | SL_BENCH_STAGE(LIGHTFIT) |
                                SL_BENCH_STAGE(BIGMAP))) != 0;

    /* the studies' table (below): declared before any jump to done, which frees it */
    char *studies_md = NULL;
    size_t studies_len = 0;
    struct sl_bench_result study_rows;
    memset(&study_rows, 0, sizeof study_rows);

    /* start-up first, while this process has loaded nothing heavy (its own
     * RSS is the floor of its children's; bench_startup.c); its table is
     * printed in its turn, after the header */
    char *startup_md = NULL;
    size_t startup_len = 0;
    if (stages & SL_BENCH_STAGE(STARTUP)) {
        FILE *mem = open_memstream(&startup_md, &startup_len);
        if (!mem)
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench start-up table");
        e = sl_bench_startup(o->config ? o->config : "configs/default.yaml", o->reps > 0 ? o->reps : 7, mem, res, d);
        fclose(mem);
        if (e)
            goto done;
    }

    /* the studies next, each in a child forked while this process is still
     * a single thread with nothing made (bench_study.c) */
    if (stages & (SL_BENCH_STAGE(MODERNO) | SL_BENCH_STAGE(MORAIS))) {
        FILE *mem = open_memstream(&studies_md, &studies_len);
        if (!mem) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench studies' table");
            goto done;
        }
        fflush(out);
        e = sl_bench_studies(o, stages, mem, &study_rows, d);
        fclose(mem);
        if (e)
            goto done;
    }

    /* provenance first: a short-lived context for the renderer's name; the
     * process's first context, so its time includes loading the driver */
    struct sl_provenance prov;
    memset(&prov, 0, sizeof prov);
    const struct sl_gl_desc gdesc = {.backend = o->gl};
    double ctx_t0 = sl_now(), ctx_c0 = sl_bench_cpu_s();
    if ((e = sl_gl_open(&x.gl, &gdesc, d)))
        goto done;
    double ctx_ms = 1e3 * (sl_now() - ctx_t0), ctx_cpu_ms = 1e3 * (sl_bench_cpu_s() - ctx_c0);
    snprintf(prov.gl_renderer, sizeof prov.gl_renderer, "%s", x.gl.renderer);
    snprintf(prov.gl_version, sizeof prov.gl_version, "%s", x.gl.version);
    sl_gl_describe(&x.gl, prov.gl_backend, sizeof prov.gl_backend);
    enum sl_gl_backend used = x.gl.backend;
    sl_gl_free(&x.gl);
    snprintf(prov.embree, sizeof prov.embree, "%d.%d.%d", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
    prov.threads = omp_get_num_procs();
    sl_provenance_fill(&prov);
    fprintf(out, "# shadowlab bench\n\n```\n");
    sl_provenance_write(&prov, out, "");
    fprintf(out, "stages:");
    for (int i = 0; i < SL_BENCH_NSTAGES; i++)
        if (stages & (1u << i)) {
            fprintf(out, " %s", stage_names[i]);
            size_t sl = strlen(stage_list);
            snprintf(stage_list + sl, sizeof stage_list - sl, "%s%s", sl ? ", " : "", stage_names[i]);
        }
    have_prov = 1;
    char la[64];
    sl_bench_loadavg(la, sizeof la);
    snprintf(load0, sizeof load0, "%s", la);
    fprintf(out, "\nload average at start: %s\n```\n\n", la);
    fflush(out);

    if (need_scene) {
        if ((e = setup(o, &x, d)) || (e = sl_gl_open(&x.gl, &gdesc, d)) || (e = sl_gl_mesh_upload(&x.mesh, &x.s, d)) ||
            (e = sl_gbuffer_init(&x.gp, &x.s, d)))
            goto done;
        if (stages & SL_BENCH_STAGE(TRUTH))
            e = sl_bench_truth(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(LAYERS)))
            e = bench_layers(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(CHURN)))
            e = sl_bench_churn(&x.s, &x.mesh, &x.gp, x.vp[0], x.W, x.H, x.S, x.reps, out, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(SCORING)))
            e = sl_bench_score(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(LIGHTFIT)))
            e = sl_bench_lightfit(&x, res, d);
        fflush(out);
        if (!e && (stages & SL_BENCH_STAGE(BIGMAP)))
            e = sl_bench_bigmap(&x, o->map > 0 ? o->map : 16384, res, d);
        fflush(out);
        sl_gbuffer_free(&x.gp);
        sl_gl_mesh_free(&x.mesh);
        sl_gl_free(&x.gl);
        /* with no context of this file's open: it opens its own, both kinds */
        if (!e && (stages & SL_BENCH_STAGE(BACKENDS)))
            e = bench_backends(&x, res, d);
        fflush(out);
        if (e)
            goto done;
    }
    /* the studies' sections, measured first (above), in their turn */
    if (studies_md) {
        fputs(studies_md, out);
        fflush(out);
    }
    for (int i = 0; i < study_rows.nrows; i++) {
        struct sl_bench_row *row = sl_bench_add_row(res, "study", "", 0, 0, 0, SL_BENCH_AT_MOST);
        if (row)
            *row = study_rows.rows[i];
    }
    if (stages & SL_BENCH_STAGE(JOBS)) {
        e = sl_bench_jobs(o->config ? o->config : o->morais ? o->morais : "configs/morais-2015.yaml", o->gl, out, res, d);
        fflush(out);
        if (e)
            goto done;
    }
    if (startup_md) {
        fputs(startup_md, out);
        fflush(out);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    struct sl_bench_row *row = sl_bench_add_row(res, "memory", "MiB", ru.ru_maxrss / 1024.0, 0, TARGET_RSS_MIB,
                                       SL_BENCH_AT_MOST);
    if (row)
        snprintf(row->name, sizeof row->name, "peak RSS after all stages");
    /* last, so the stages' rows keep their places */
    struct sl_bench_row *crow = sl_bench_add_row(res, "context", "ms", ctx_ms, 0, TARGET_CONTEXT_MS, SL_BENCH_AT_MOST);
    if (crow)
        snprintf(crow->name, sizeof crow->name, "first GL context (%s), cpu %.1f ms",
                 sl_gl_backend_name(used), ctx_cpu_ms);
    write_summary(res, out);
    sl_bench_loadavg(la, sizeof la);
    fprintf(out, "load average at the end: %s\n\n", la);
    if (o->csv)
        e = write_csv(res, o->csv, d);
    if (!e && md_tee) {
        fclose(md_tee);
        md_tee = NULL;
        fclose(md_mem);
        md_mem = NULL;
        if (have_prov)
            e = write_markdown(o->markdown, &prov, stage_list, load0, la, md_body, md_len, d);
    }
done:
    if (md_tee)
        fclose(md_tee);
    if (md_mem)
        fclose(md_mem);
    free(md_body);
    if (x.gl.backend) {
        sl_gbuffer_free(&x.gp);
        sl_gl_mesh_free(&x.mesh);
        sl_gl_free(&x.gl);
    }
    if (need_scene)
        sl_scene_free(&x.s);
    if (res_out && !e)
        *res_out = *res;
    free(res);
    free(startup_md);
    free(studies_md);
    return e;
}
