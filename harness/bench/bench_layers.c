/*
 * bench_layers.c — the `layers` stage of `shadowlab bench` (bench.h):
 * each layer and the G-buffer against a plain raster.
 *
 * Each repetition renders the plain raster and then the layer, one
 * after the other, so drift of a shared VM hits both; a layer is rendered by
 * shadowmap.c itself (the code the studies run), from scratch each time
 * (BGSM2 reads the BGSM ids rendered before it, as in a run). The plain
 * raster's timer brackets the same work as shadowmap.c's: framebuffer and
 * textures created, cleared, drawn, glFinish; the readback of depth and ids
 * apart. The G-buffer is timed by gbuffer.c, its fragment count by a query
 * around the call.
 */
#include "bench_stages.h"
#include <stdlib.h>
#include <string.h>
#include "adjacency.h"
#include "gbuffer.h"
#include "glctx.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "util.h"

extern const char sl_glsl_depth_id_vs[];
extern const char sl_glsl_bench_plain_fs[];

#ifndef GL_FRAGMENT_SHADER_INVOCATIONS_ARB
#define GL_FRAGMENT_SHADER_INVOCATIONS_ARB 0x82F4
#endif

#define TARGET_RASTER_RATIO  2.0     /* a pass's render time over the plain raster's, at most */

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
    double mr = sl_bench_median(t->render, reps), mb = sl_bench_median(t->readback, reps);
    double pr = sl_bench_median(t->p_render, reps), pb = sl_bench_median(t->p_readback, reps);
    double mc = sl_bench_median(t->cpu, reps), pc = sl_bench_median(t->p_cpu, reps);
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

enum sl_err sl_bench_layers(struct sl_bench_ctx *x, struct sl_bench_result *res, struct sl_diag *d)
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
        snprintf(name, sizeof name, "%s %d²", sl_layer_names[l], S);
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
