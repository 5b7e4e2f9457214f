/*
 * gbuffer.c — camera pass and pixel classification.
 * Invariant: every non-background pixel has a triangle id, a world position
 * and a unit normal; its class depends on that normal and the light only.
 */
#include "gbuffer.h"
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include "arealight.h"
#include "util.h"

extern const char sl_glsl_gbuffer_vs[];
extern const char sl_glsl_gbuffer_fs[];

/* The id's top bit: the camera sees the triangle's back (gbuffer_fs.glsl). */
#define SL_BACK_FACING 0x80000000u

void sl_camera_matrices(const struct sl_viewpoint *vp, float aspect, mat4 view, mat4 proj)
{
    vec3 eye, dir, up;
    glm_vec3_copy((float *)vp->pos, eye);
    glm_vec3_copy((float *)vp->dir, dir);
    glm_vec3_copy((float *)vp->up, up);
    glm_look(eye, dir, up, view);
    glm_perspective(glm_rad(vp->fov_deg), aspect, vp->znear, vp->zfar, proj);
}

enum sl_err sl_gbuffer_init(struct sl_gbuffer_pass *p, const struct sl_scene *s, struct sl_diag *d)
{
    if (s->nt >= SL_BACK_FACING)
        return sl_fail(d, SL_E_SCENE, s->path, 0, NULL, "%u triangles: the G-buffer's ids hold at most 2^31 - 1",
                       s->nt);
    /* the program and the target do not depend on the scene: kept for the
     * next (a new 1024 x 1024 target is 40 MB that llvmpipe zeroes, and
     * each of its pages faults) */
    if (p->prog)
        return SL_OK;
    memset(p, 0, sizeof *p);
    p->prog = sl_gl_program(sl_glsl_gbuffer_vs, NULL, sl_glsl_gbuffer_fs, d);
    return p->prog ? SL_OK : SL_E_GL;
}

static void target_free(struct sl_gbuffer_pass *p)
{
    if (p->w) {
        glDeleteFramebuffers(1, &p->fbo);
        glDeleteTextures(2, p->tex);
        glDeleteRenderbuffers(1, &p->depth);
    }
    free(p->rgba);
    p->rgba = NULL;
    p->w = p->h = 0;
    p->fbo = p->tex[0] = p->tex[1] = p->depth = 0;
}

void sl_gbuffer_free(struct sl_gbuffer_pass *p)
{
    target_free(p);
    sl_view_free(&p->spare);
    if (p->prog) glDeleteProgram(p->prog);
    memset(p, 0, sizeof *p);
}

void sl_gbuffer_give_back(struct sl_gbuffer_pass *p, struct sl_view *v)
{
    if (!v->pos) {
        sl_view_free(v);
        return;
    }
    sl_view_free(&p->spare);
    p->spare = *v;
    memset(v, 0, sizeof *v);
}

/* v's arrays for n pixels: the spare ones when they fit (2; 3 with a new
 * outside array), else new and zeroed (1); 0 when out of memory. The
 * render writes every element of every array but the normals of
 * background pixels and the outside flags of pixels inside a spot's cone,
 * which it zeroes in spare arrays only: new ones are zero already, and
 * their untouched pages (a background's normals can be a third of a 12 MB
 * array) need not be faulted in. */
static int view_arrays(struct sl_gbuffer_pass *p, struct sl_view *v, size_t n, int spot)
{
    struct sl_view *k = &p->spare;
    int got = 1;
    if (k->pos && (size_t)k->w * (size_t)k->h == n) {
        got = 2;
        v->pos = k->pos;
        v->nrm = k->nrm;
        v->tri = k->tri;
        v->cls = k->cls;
        v->truth = k->truth;
        v->outside = k->outside;
        memset(k, 0, sizeof *k);
    } else {
        sl_view_free(k);
        v->pos = sl_calloc(n * 3, sizeof(float));
        v->nrm = sl_calloc(n * 3, sizeof(float));
        v->tri = sl_calloc(n, sizeof(uint32_t));
        v->cls = sl_calloc(n, 1);
        v->truth = sl_calloc(n, 1);
    }
    if (spot && !v->outside) {
        v->outside = sl_calloc(n, 1);
        got = got == 2 ? 3 : got;
    } else if (!spot) {
        free(v->outside);
        v->outside = NULL;
    }
    return v->pos && v->nrm && v->tri && v->cls && v->truth && (!spot || v->outside) ? got : 0;
}

/* The target at w x h: the kept one, or made (the old one freed). */
static enum sl_err target_get(struct sl_gbuffer_pass *p, int w, int h, struct sl_diag *d)
{
    if (p->w == w && p->h == h)
        return SL_OK;
    target_free(p);
    p->rgba = malloc((size_t)w * (size_t)h * 4 * sizeof(float));
    if (!p->rgba)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "G-buffer %dx%d", w, h);
    p->w = w;
    p->h = h;
    glCreateFramebuffers(1, &p->fbo);
    glCreateTextures(GL_TEXTURE_2D, 2, p->tex);
    glTextureStorage2D(p->tex[0], 1, GL_RGBA32F, w, h);
    glTextureStorage2D(p->tex[1], 1, GL_R32UI, w, h);
    glCreateRenderbuffers(1, &p->depth);
    glNamedRenderbufferStorage(p->depth, GL_DEPTH_COMPONENT32F, w, h);
    for (int i = 0; i < 2; i++)
        glNamedFramebufferTexture(p->fbo, GL_COLOR_ATTACHMENT0 + (GLenum)i, p->tex[i], 0);
    glNamedFramebufferRenderbuffer(p->fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, p->depth);
    const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(p->fbo, 2, bufs);
    if (glCheckNamedFramebufferStatus(p->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        target_free(p);
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "G-buffer framebuffer incomplete");
    }
    return SL_OK;
}

enum sl_err sl_gbuffer_render(struct sl_gbuffer_pass *p, const struct sl_gl_mesh *m,
                              const struct sl_scene *s, int vp, int w, int h,
                              struct sl_view *v, double *ms_render, double *ms_readback,
                              double *ms_gpu, struct sl_diag *d)
{
    static _Atomic uint64_t serials;
    size_t n = (size_t)w * (size_t)h;
    mat4 view, proj, vpm;
    int arrays = 0;   /* view_arrays: 1 new, 2 spare, 3 spare with a new outside */
    sl_camera_matrices(&s->vp[vp], (float)w / (float)h, view, proj);
    glm_mat4_mul(proj, view, vpm);
    if (v) {
        memset(v, 0, sizeof *v);
        v->serial = atomic_fetch_add(&serials, 1) + 1;
        v->w = w;
        v->h = h;
        v->vp = vp;
        glm_mat4_copy(view, v->view);
        glm_mat4_copy(proj, v->proj);
        if (!(arrays = view_arrays(p, v, n, s->light.type == SL_LIGHT_SPOT))) {
            sl_view_free(v);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "G-buffer %dx%d", w, h);
        }
    }

    /* the target's making is timed with the render, as when each render
     * made its own: the first of a size pays for it */
    double t0 = sl_now();
    enum sl_err e = target_get(p, w, h, d);
    const GLuint fbo = p->fbo;
    float *rgba_pos = p->rgba;
    if (!e) {
        const float zero4[4] = {0, 0, 0, 0};
        const GLuint zero_u[4] = {0, 0, 0, 0};
        const float one = 1.0f;
        struct sl_gl_timer gt;
        sl_gl_timer_begin(&gt);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, w, h);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);   /* back faces are seen only where the mesh is open */
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero4);
        glClearNamedFramebufferuiv(fbo, GL_COLOR, 1, zero_u);
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
        glUseProgram(p->prog);
        glUniformMatrix4fv(glGetUniformLocation(p->prog, "u_vp"), 1, GL_FALSE, (const float *)vpm);
        glBindVertexArray(m->vao);
        glDrawElements(GL_TRIANGLES, m->count, GL_UNSIGNED_INT, NULL);
        sl_gl_timer_end(&gt);
        glFinish();
        double t1 = sl_now();
        glGetTextureImage(p->tex[0], 0, GL_RGBA, GL_FLOAT, (GLsizei)(n * 16), rgba_pos);
        /* a timed repetition reads the ids over the positions, used by no one */
        glGetTextureImage(p->tex[1], 0, GL_RED_INTEGER, GL_UNSIGNED_INT, (GLsizei)(n * 4),
                          v ? (void *)v->tri : (void *)rgba_pos);
        double t2 = sl_now();
        double gpu = sl_gl_timer_ms(&gt, 1e3 * (t1 - t0));   /* after the readback: no extra wait */
        if (ms_gpu) *ms_gpu = gpu;
        if (ms_render) *ms_render = 1e3 * (t1 - t0);
        if (ms_readback) *ms_readback = 1e3 * (t2 - t1);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        e = sl_gl_check("G-buffer pass", d);
    }

    if (!e && v) {
        const float *L = s->light_dir;
        const int at_point = s->light.type != SL_LIGHT_DIRECTIONAL;
        for (size_t i = 0; i < n; i++) {
            for (int k = 0; k < 3; k++)
                v->pos[3 * i + k] = rgba_pos[4 * i + k];
            /* the face normal, negated (exactly) where the back is seen */
            uint32_t id = v->tri[i] & ~SL_BACK_FACING;
            if (id) {
                const float *fn = s->fn + 3 * (size_t)(id - 1);
                float sg = (v->tri[i] & SL_BACK_FACING) ? -1.0f : 1.0f;
                for (int k = 0; k < 3; k++)
                    v->nrm[3 * i + k] = sg * fn[k];
            } else if (arrays >= 2) {
                for (int k = 0; k < 3; k++)
                    v->nrm[3 * i + k] = 0.0f;
            }
            if (arrays == 2 && v->outside)
                v->outside[i] = 0;
            v->tri[i] = id;
            if (v->tri[i] == 0) {
                v->cls[i] = SL_C_BACKGROUND;
                v->truth[i] = SL_T_BACKGROUND;
                v->n_background++;
                continue;
            }
            /* toward the light is -L; under a light at a point (spot,
             * point, an area light's centre) a pixel faces the point, and
             * lies inside a spot's cone, on an area light's emitting side
             * (arealight.h, sl_point_faces) */
            float ndl = -(v->nrm[3 * i] * L[0] + v->nrm[3 * i + 1] * L[1] + v->nrm[3 * i + 2] * L[2]);
            if (at_point ? sl_point_faces(&s->light, v->pos + 3 * i, v->nrm + 3 * i) : ndl > 0.0f) {
                v->cls[i] = SL_C_PFL;
                v->truth[i] = SL_T_LIT;   /* until truth.c traces it */
                v->n_pfl++;
            } else {
                v->cls[i] = SL_C_PNFL;
                v->truth[i] = SL_T_PNFL;
                v->n_pnfl++;
                /* outside a spot's cone: counted apart (view.h), whether
                 * or not the surface also faces away. Our choice: the cone
                 * is the light's own bound and does not depend on the
                 * surface, so a pixel outside it gets no light whatever
                 * its normal; counting by position alone makes the region
                 * the cone's clean footprint (no facing-away holes in it)
                 * and the count a recount of sl_spot_inside on the
                 * G-buffer's positions. */
                if (v->outside && !sl_spot_inside(&s->light, v->pos + 3 * i)) {
                    v->outside[i] = 1;
                    v->n_outside_cone++;
                }
            }
        }
    }
    if (e && v)
        sl_view_free(v);
    return e;
}
