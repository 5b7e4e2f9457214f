/*
 * shadowmap.c — see shadowmap.h.
 * Invariants: depth is written in zero-to-one clip space (glClipControl), so
 * window depth is the orthographic depth itself with full float precision near
 * 0 and no [-1,1] -> [0,1] remap; a texel holds the triangle covering its
 * centre (GL's rasterisation rule), which is what the seeds' analysis assumes.
 */
#include "shadowmap.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "arealight.h"
#include "util.h"

extern const char sl_glsl_depth_id_vs[];
extern const char sl_glsl_depth_id_fs[];
extern const char sl_glsl_cons_gs[];
extern const char sl_glsl_cons_fs[];
extern const char sl_glsl_cons_adj_gs[];
extern const char sl_glsl_cons_setup[];

#ifndef GL_GEOMETRY_SHADER_PRIMITIVES_EMITTED_ARB
#define GL_GEOMETRY_SHADER_PRIMITIVES_EMITTED_ARB 0x82F3
#endif
#ifndef GL_FRAGMENT_SHADER_INVOCATIONS_ARB
#define GL_FRAGMENT_SHADER_INVOCATIONS_ARB 0x82F4
#endif

/* How a layer is drawn. */
enum kind { K_DEPTH, K_DEPTH_BACK, K_BGSM, K_BGSM2, K_SGSM, K_SGSM_ADJ };

/* A conservative-layer shader specialised for one layer: the file's
 * #version line, SL_MODE, then `pre` and `pre2` (shared code, NULL = none),
 * then the rest of the file. The caller frees it. */
static char *cons_source(const char *src, int mode, const char *pre, const char *pre2)
{
    const char *body = strchr(src, '\n');
    body = body ? body + 1 : src;
    pre = pre ? pre : "";
    pre2 = pre2 ? pre2 : "";
    size_t n = (size_t)(body - src) + 32 + strlen(pre) + strlen(pre2) + strlen(body) + 1;
    char *out = malloc(n);
    if (out)
        snprintf(out, n, "%.*s#define SL_MODE %d\n%s%s%s", (int)(body - src), src, mode, pre, pre2, body);
    return out;
}

enum sl_err sl_shadowmap_init(struct sl_shadowmap_pass *p, struct sl_diag *d)
{
    memset(p, 0, sizeof *p);
    p->chunk = SL_SHADOWMAP_CHUNK;
    p->prog_depth_id = sl_gl_program(sl_glsl_depth_id_vs, NULL, sl_glsl_depth_id_fs, d);
    if (!p->prog_depth_id)
        return SL_E_GL;
    /* modes 0-2 (BGSM, BGSM2, SGSM) share cons_gs, mode 3 (SGSM with
     * adjacency) has its own; mode 4 is its GS taking the triangles that
     * keep no edge, with SGSM's fragment shader (cons_adj_gs.glsl) */
    /* the margins as constants of the fragment shader (cons_fs.glsl), and
     * of the geometry shader, which turns BGSM's box test into integer
     * bounds (cons_gs.glsl): %.17g gives back the same double */
    char pre[128];
    snprintf(pre, sizeof pre, "#define SL_EPS %.17glf\n#define SL_ZEPS %.17glf\n", SL_CONS_EPS_TEXELS,
             SL_CONS_EPS_DEPTH);
    for (int mode = 0; mode < 5; mode++) {
        char *gs = cons_source(mode >= 3 ? sl_glsl_cons_adj_gs : sl_glsl_cons_gs, mode, pre, sl_glsl_cons_setup);
        char *fs = cons_source(sl_glsl_cons_fs, mode == 4 ? 2 : mode, pre, NULL);
        if (gs && fs)
            p->prog_cons[mode] = sl_gl_program(sl_glsl_depth_id_vs, gs, fs, d);
        else
            sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "shader source");
        free(gs);
        free(fs);
        if (!p->prog_cons[mode])
            return gs && fs ? SL_E_GL : SL_E_NOMEM;
    }
    return SL_OK;
}

static void target_free(struct sl_shadowmap_target *t)
{
    if (t->size) {
        glDeleteFramebuffers(1, &t->fbo);
        glDeleteTextures(2, t->tex);   /* a name of 0 (a texture gone already) is ignored */
    }
    memset(t, 0, sizeof *t);
}

static size_t target_bytes(const struct sl_shadowmap_target *t)
{
    return (size_t)t->size * (size_t)t->size * 8u;
}

/* The render target of size S: kept from before, or made, the least
 * recently used ones freed first while those kept beside it would exceed
 * SL_SHADOWMAP_KEEP_BYTES (or no slot is free). */
static struct sl_shadowmap_target *target_get(struct sl_shadowmap_pass *p, int S, struct sl_diag *d,
                                              enum sl_err *e)
{
    p->tick++;
    for (int i = 0; i < SL_SHADOWMAP_TARGETS; i++)
        if (p->tgt[i].size == S) {
            p->tgt[i].used = p->tick;
            return &p->tgt[i];
        }
    for (;;) {
        size_t kept = 0;
        int lru = -1, nfree = 0;
        for (int i = 0; i < SL_SHADOWMAP_TARGETS; i++) {
            if (!p->tgt[i].size) {
                nfree++;
                continue;
            }
            kept += target_bytes(&p->tgt[i]);
            if (lru < 0 || p->tgt[i].used < p->tgt[lru].used)
                lru = i;
        }
        if (lru < 0 || (nfree && kept <= SL_SHADOWMAP_KEEP_BYTES))
            break;
        target_free(&p->tgt[lru]);
    }
    struct sl_shadowmap_target *t = NULL;
    for (int i = 0; i < SL_SHADOWMAP_TARGETS && !t; i++)
        if (!p->tgt[i].size)
            t = &p->tgt[i];
    t->size = S;
    t->used = p->tick;
    p->targets_made++;
    glCreateFramebuffers(1, &t->fbo);
    glCreateTextures(GL_TEXTURE_2D, 2, t->tex);
    glTextureStorage2D(t->tex[0], 1, GL_DEPTH_COMPONENT32F, S, S);
    glTextureStorage2D(t->tex[1], 1, GL_R32UI, S, S);
    glNamedFramebufferTexture(t->fbo, GL_DEPTH_ATTACHMENT, t->tex[0], 0);
    glNamedFramebufferTexture(t->fbo, GL_COLOR_ATTACHMENT0, t->tex[1], 0);
    glNamedFramebufferDrawBuffer(t->fbo, GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(t->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        target_free(t);
        *e = sl_fail(d, SL_E_GL, NULL, 0, NULL, "shadow-map framebuffer incomplete (%dx%d)", S, S);
        return NULL;
    }
    return t;
}

void sl_shadowmap_release_targets(struct sl_shadowmap_pass *p)
{
    for (int i = 0; i < SL_SHADOWMAP_TARGETS; i++)
        target_free(&p->tgt[i]);
}

void sl_shadowmap_free(struct sl_shadowmap_pass *p)
{
    sl_shadowmap_release_targets(p);
    sl_layer_pool_free(&p->pool);
    sl_layer_pool_free(&p->pix_pool);
    if (p->prog_depth_id)
        glDeleteProgram(p->prog_depth_id);
    for (int mode = 0; mode < 5; mode++)
        if (p->prog_cons[mode])
            glDeleteProgram(p->prog_cons[mode]);
    memset(p, 0, sizeof *p);
}

/* One layer array of n 32-bit elements: from the frame's pool, else zeroed. */
static void *layer_array(struct sl_light_frame *f, size_t n)
{
    return f->pool ? sl_layer_pool_get(f->pool, n * 4) : sl_calloc(n, 4);
}

/* Make prog current with the layer's uniforms; returns u_first's location. */
static GLint use_program(GLuint prog, const struct sl_light_frame *f, int cons)
{
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_vp"), 1, GL_FALSE, (const float *)f->box.vp);
    if (cons) {
        /* lambda: Morais 2015 eq. 21 with eta = 1, the half texel
         * diagonal, grown by the coverage margin on both counts */
        glUniform1f(glGetUniformLocation(prog, "u_size"), (float)f->size);
        glUniform1f(glGetUniformLocation(prog, "u_lambda"),  /* -1 (unused) in the adjacency GS */
                    (float)(0.70710678 * (1.0 + 1.0 / 1024.0) + 2.0 * SL_CONS_EPS_TEXELS));
        /* a point light's unmapped triangles (frame.h) are left out */
        glUniform1f(glGetUniformLocation(prog, "u_wmin"), f->box.wmin);
        glUniform1f(glGetUniformLocation(prog, "u_guard"), f->box.guard);
    }
    return glGetUniformLocation(prog, "u_first");
}

static enum sl_err render_layer(struct sl_shadowmap_pass *p, const struct sl_gl_mesh *m,
                                struct sl_light_frame *f, enum kind kind,
                                struct sl_depth_layer *out, struct sl_diag *d)
{
    const int cull_front = kind == K_DEPTH_BACK;
    const int cons = kind >= K_BGSM;
    const GLuint prog = cons ? p->prog_cons[kind - K_BGSM] : p->prog_depth_id;
    if (kind == K_SGSM_ADJ && !m->vao_adj)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "SGSM with adjacency without adjacency indices");
    int S = f->size;
    size_t n = (size_t)S * (size_t)S;
    const int want_id = kind != K_BGSM2;   /* BGSM2's ids are read by no one (shadowmap.h) */
    out->stamp = ++p->stamps;
    if (!(out->depth = layer_array(f, n)) || (want_id && !(out->id = layer_array(f, n))))
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "shadow map %dx%d", S, S);
    /* the target's making is timed with the layer, as it was when every
     * layer made its own: the first layer of a size pays for it */
    double t0 = sl_now();
    enum sl_err e = SL_OK;
    struct sl_shadowmap_target *tg = target_get(p, S, d, &e);
    if (!tg)
        return e;
    const GLuint fbo = tg->fbo;
    {
        const GLuint zero_u[4] = {0, 0, 0, 0};
        const float one = 1.0f;
        struct sl_gl_timer gt;
        sl_gl_timer_begin(&gt);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, S, S);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glCullFace(GL_FRONT);
        glFrontFace(GL_CCW);
        if (kind == K_BGSM2) {
            /* no colour attachment: tex[1] keeps the first layer's ids,
             * which this layer reads as an image (below) */
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, 0, 0);
            glNamedFramebufferDrawBuffer(fbo, GL_NONE);
        } else {
            glClearNamedFramebufferuiv(fbo, GL_COLOR, 0, zero_u);
        }
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
        /* SGSM with adjacency is drawn as two programs, the triangles that
         * keep no edge first (cons_adj_gs.glsl); the others, one */
        const int npass = kind == K_SGSM_ADJ ? 2 : 1;
        GLint first_loc = use_program(npass == 2 ? p->prog_cons[4] : prog, f, cons);
        GLuint first_ids = 0;
        if (cons) {
            if (kind == K_BGSM2) {
                /* the second layer leaves out, per texel, the triangle the
                 * first one stored there */
                const struct sl_depth_layer *b = &f->layer[SL_LAYER_BGSM];
                first_ids = tg->tex[1];
                if (!b->stamp || b->stamp != tg->ids_stamp) {
                    /* another layer (or none) was drawn here since: put BGSM's ids back */
                    glTextureSubImage2D(first_ids, 0, 0, 0, S, S, GL_RED_INTEGER, GL_UNSIGNED_INT, b->id);
                    tg->ids_stamp = b->stamp;
                    p->ids_uploads++;
                }
                /* read as an image: on llvmpipe imageLoad costs less per
                 * fragment than texelFetch (measured: BGSM2 -12%) */
                glBindImageTexture(0, first_ids, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
            }
        }
        GLuint q[2];
        glGenQueries(2, q);
        glBeginQuery(GL_GEOMETRY_SHADER_PRIMITIVES_EMITTED_ARB, q[0]);
        glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q[1]);
        glBindVertexArray(kind == K_SGSM_ADJ ? m->vao_adj : m->vao);
        /* two-sided meshes (leaves) are never culled: culling the side that
         * faces the light would remove the leaf from the map altogether; the
         * conservative layers cull nothing (see methods/conservative.c) */
        for (int pass = 0; pass < npass; pass++) {
            if (pass) {
                glFlush();   /* as between chunks */
                first_loc = use_program(prog, f, cons);
            }
            for (int r = 0; r < m->nruns; r++) {
                if (cull_front && !m->runs[r].two_sided)
                    glEnable(GL_CULL_FACE);
                else
                    glDisable(GL_CULL_FACE);
                /* in chunks, each flushed: llvmpipe bins a whole draw before it
                 * rasterises, in 64 KB blocks that grow with triangles x tiles
                 * (57 MB for SGSM with adjacency at 4096^2 in the Morais study,
                 * at its peak); a flush hands the bins over. The triangles reach
                 * the framebuffer in the same order, so the layer is the same.
                 * (SGSM with adjacency's two programs do change the order:
                 * a triangle keeping no edge now comes before one that keeps
                 * any. Only which id a texel keeps among triangles of exactly
                 * equal depth there could differ, and either is a proof of the
                 * same depth bound; layers::golden_hashes found no texel
                 * changed over its 7 scenes.) */
                for (uint32_t c0 = 0; c0 < m->runs[r].count; c0 += p->chunk) {
                    const uint32_t t0 = m->runs[r].first + c0;
                    const uint32_t nt = m->runs[r].count - c0 < p->chunk ? m->runs[r].count - c0
                                                                                    : p->chunk;
                    if (c0)
                        glFlush();
                    glUniform1ui(first_loc, t0);   /* gl_PrimitiveID restarts with every draw */
                    if (kind == K_SGSM_ADJ)
                        glDrawElements(GL_TRIANGLES_ADJACENCY, (GLsizei)(6 * nt), GL_UNSIGNED_INT,
                                       (const void *)((size_t)t0 * 6 * sizeof(uint32_t)));
                    else
                        glDrawElements(GL_TRIANGLES, (GLsizei)(3 * nt), GL_UNSIGNED_INT,
                                       (const void *)((size_t)t0 * 3 * sizeof(uint32_t)));
                }
            }
        }
        glEndQuery(GL_GEOMETRY_SHADER_PRIMITIVES_EMITTED_ARB);
        glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        sl_gl_timer_end(&gt);
        glFinish();
        double t1 = sl_now();
        GLuint64 prims = 0, frags = 0;
        glGetQueryObjectui64v(q[0], GL_QUERY_RESULT, &prims);
        glGetQueryObjectui64v(q[1], GL_QUERY_RESULT, &frags);
        glDeleteQueries(2, q);
        out->gs_prims = cons ? (uint64_t)prims : 0;
        out->fragments = (uint64_t)frags;
        if (first_ids) {
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tg->tex[1], 0);
            glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
        } else {
            tg->ids_stamp = out->stamp;
        }
        /* straight into the frame's arrays (warm when they come from its pool) */
        glGetTextureImage(tg->tex[0], 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(n * 4), out->depth);
        if (want_id)
            glGetTextureImage(tg->tex[1], 0, GL_RED_INTEGER, GL_UNSIGNED_INT, (GLsizei)(n * 4), out->id);
        double t2 = sl_now();
        out->ms_gpu = sl_gl_timer_ms(&gt, 1e3 * (t1 - t0));   /* after the readback: no extra wait */
        out->ms_render = 1e3 * (t1 - t0);
        out->ms_readback = 1e3 * (t2 - t1);
        glDisable(GL_CULL_FACE);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        e = sl_gl_check("shadow-map pass", d);
    }
    return e;
}

/* Whether the target of size S still holds layer b's ids (BGSM2 reads them
 * there; one gathered per pixel, frame.h, has no map of them to upload). */
static int ids_in_target(const struct sl_shadowmap_pass *p, const struct sl_depth_layer *b, int S)
{
    for (int i = 0; i < SL_SHADOWMAP_TARGETS; i++)
        if (p->tgt[i].size == S)
            return b->stamp && p->tgt[i].ids_stamp == b->stamp;
    return 0;
}

enum sl_err sl_shadowmap_render(struct sl_shadowmap_pass *p, const struct sl_gl_mesh *m,
                                struct sl_light_frame *f, unsigned needs, struct sl_diag *d)
{
    for (int l = 0; l < SL_LAYER_COUNT; l++) {
        if (!(needs & SL_NEED(l)) || (f->have & SL_NEED(l)))
            continue;
        enum sl_err e = SL_OK;
        switch ((enum sl_layer_id)l) {
        case SL_LAYER_DEPTH_ID:
            e = render_layer(p, m, f, K_DEPTH, &f->layer[l], d);
            break;
        case SL_LAYER_DEPTH_ID_BACK:
            e = render_layer(p, m, f, K_DEPTH_BACK, &f->layer[l], d);
            break;
        case SL_LAYER_BGSM:
            e = render_layer(p, m, f, K_BGSM, &f->layer[l], d);
            break;
        case SL_LAYER_BGSM2:
            /* reads the first layer's ids */
            if (!(f->have & SL_NEED(SL_LAYER_BGSM)))
                return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "BGSM2 asked for without BGSM");
            if (f->layer[SL_LAYER_BGSM].per_pixel && !ids_in_target(p, &f->layer[SL_LAYER_BGSM], f->size))
                return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL,
                               "BGSM2 asked for with BGSM gathered per pixel and its ids gone from the target");
            e = render_layer(p, m, f, K_BGSM2, &f->layer[l], d);
            break;
        case SL_LAYER_SGSM:
            e = render_layer(p, m, f, K_SGSM, &f->layer[l], d);
            break;
        case SL_LAYER_SGSM_ADJ:
            e = render_layer(p, m, f, K_SGSM_ADJ, &f->layer[l], d);
            break;
        case SL_LAYER_COUNT:
            break;
        }
        if (e)
            return e;
        f->have |= SL_NEED(l);
    }
    return SL_OK;
}
