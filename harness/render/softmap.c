/*
 * softmap.c — see softmap.h.
 * Invariants: the CPU projection (sl_softmap_project, double) and the GL
 * matrices describe the same frame, built from the same axes; the near
 * layer keeps the smallest window depth of front faces (GL_LESS, cleared to
 * 1), the far layer the largest of back faces (GL_GREATER, cleared to 0),
 * and window depth is monotonic in linear depth, so the linear depth stored
 * with each surviving fragment is the nearest (farthest) one.
 */
#include "softmap.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <omp.h>
#include "util.h"

extern const char sl_glsl_soft_depth_vs[];
extern const char sl_glsl_soft_depth_fs[];

#ifndef GL_FRAGMENT_SHADER_INVOCATIONS_ARB
#define GL_FRAGMENT_SHADER_INVOCATIONS_ARB 0x82F4
#endif

#define DEG (3.14159265358979323846 / 180.0)

void sl_softmap_defaults(const struct sl_softmap_desc *in, struct sl_softmap_desc *out)
{
    *out = *in;
    if (out->size <= 0)
        out->size = 1024;
    if (out->fov_max_deg <= 0.0)
        out->fov_max_deg = 150.0;
}

enum sl_err sl_softmap_init(struct sl_softmap_pass *p, struct sl_diag *d)
{
    p->prog = sl_gl_program(sl_glsl_soft_depth_vs, NULL, sl_glsl_soft_depth_fs, d);
    return p->prog ? SL_OK : SL_E_GL;
}

void sl_softmap_pass_free(struct sl_softmap_pass *p)
{
    if (p->prog)
        glDeleteProgram(p->prog);
    p->prog = 0;
}

void sl_softmap_free(struct sl_softmap *m)
{
    if (!m)
        return;
    free(m->near);
    free(m->far);
    m->near = m->far = NULL;
    m->nbuf = NULL;
}

/* ---- N-buffer ---------------------------------------------------------- */

static int log2i(int x)
{
    int n = 0;
    while ((1 << (n + 1)) <= x)
        n++;
    return n;
}

enum sl_err sl_softmap_nbuf_build(struct sl_softmap *m, int threads, struct sl_softmap_nbuf *nb,
                                  struct sl_diag *d)
{
    m->nbuf = NULL;
    if (!m->near || !m->far || m->size <= 0 || (m->size & (m->size - 1)))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "N-buffer of a map without layers");
    double t0 = sl_now();
    const int S = m->size;
    const size_t n = (size_t)S * (size_t)S;
    const int levels = log2i(S) + 1;
    /* a previous build of the same size is overwritten in place: a fresh
     * allocation costs more in first-touch page faults than the build itself
     * (176 MB at 1024) */
    if (!nb->t || nb->size != S || nb->levels != levels) {
        sl_softmap_nbuf_free(nb);
        nb->t = malloc(n * (size_t)levels * sizeof *nb->t);
        if (!nb->t)
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "N-buffer %dx%d, %d levels", S, S, levels);
        nb->size = S;
        nb->levels = levels;
    }
    if (threads <= 0)
        threads = omp_get_max_threads();
    for (size_t i = 0; i < n; i++) {
        struct sl_softmap_texel *t = &nb->t[i];
        t->near_min = t->near_max = m->near[i];
        t->far_min = t->far_max = m->far[i];
    }
    for (int L = 1; L < nb->levels; L++) {
        const int h = 1 << (L - 1);
        const struct sl_softmap_texel *src = nb->t + (size_t)(L - 1) * n;
        struct sl_softmap_texel *dst = nb->t + (size_t)L * n;
        /* the window [i, i + 2h) is [i, i + h) and [i + h, i + 2h) (the same
         * for j); a half that starts beyond the map is left out (clipped) */
#pragma omp parallel for num_threads(threads) schedule(static)
        for (int j = 0; j < S; j++) {
            const struct sl_softmap_texel *r0 = src + (size_t)j * S;
            const struct sl_softmap_texel *r1 = j + h < S ? r0 + (size_t)h * S : NULL;
            struct sl_softmap_texel *o = dst + (size_t)j * S;
            /* interior columns without a bounds test, so the loop vectorises */
            for (int i = 0; i < S - h; i++) {
                struct sl_softmap_texel r = r0[i];
                sl_softmap_texel_merge(&r, &r0[i + h]);
                if (r1) {
                    sl_softmap_texel_merge(&r, &r1[i]);
                    sl_softmap_texel_merge(&r, &r1[i + h]);
                }
                o[i] = r;
            }
            for (int i = S - h; i < S; i++) {
                struct sl_softmap_texel r = r0[i];
                if (r1)
                    sl_softmap_texel_merge(&r, &r1[i]);
                o[i] = r;
            }
        }
    }
    nb->ms_build = 1e3 * (sl_now() - t0);
    m->nbuf = nb;
    return SL_OK;
}

void sl_softmap_nbuf_free(struct sl_softmap_nbuf *nb)
{
    if (!nb)
        return;
    free(nb->t);
    memset(nb, 0, sizeof *nb);
}

int sl_softmap_receivers_named(const struct sl_scene *s, const char *prefix, uint8_t *flags)
{
    int n = 0;
    size_t len = strlen(prefix);
    for (int r = 0; r < s->nranges; r++) {
        flags[r] = strncmp(s->ranges[r].name, prefix, len) == 0;
        n += flags[r];
    }
    return n;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Offsets of a point from the light's centre: across (ex, ey) and in front (n). */
static void light_local(const struct sl_area *a, const float p[3], double *x, double *y, double *t)
{
    double q[3] = {(double)p[0] - a->c[0], (double)p[1] - a->c[1], (double)p[2] - a->c[2]};
    *x = dot3(q, a->ex);
    *y = dot3(q, a->ey);
    *t = dot3(q, a->n);
}

static int is_power_of_two(int x)
{
    return x > 0 && (x & (x - 1)) == 0;
}

enum sl_err sl_softmap_fit(const struct sl_scene *s, const struct sl_view *v,
                           const struct sl_softmap_desc *desc_in, struct sl_softmap *m, struct sl_diag *d)
{
    struct sl_softmap_desc desc;
    sl_softmap_defaults(desc_in, &desc);
    memset(m, 0, sizeof *m);
    if (s->light.type != SL_LIGHT_AREA)
        return sl_fail(d, SL_E_SCENE, s->path, 0, "light.type", "soft shadows need an area light");
    if (!is_power_of_two(desc.size) || desc.size > 16384)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "size", "map size %d is not a power of two up to 16384",
                       desc.size);
    if (desc.fov_deg < 0.0 || desc.fov_deg >= 180.0 || desc.fov_max_deg >= 180.0)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "fov", "fov must be in (0, 180) degrees");
    m->size = desc.size;
    sl_area_of(&s->light, &m->area);
    const struct sl_area *a = &m->area;
    const double half = 0.5 * fmax(a->w, a->h);
    const size_t n = (size_t)v->w * (size_t)v->h;

    /* the fov: given, or the smallest holding every visible point in front of
     * the light (the only points whose rays are traced) */
    const double t_min = tan(2.5 * DEG), t_cap = tan(0.5 * desc.fov_max_deg * DEG);
    double T = desc.fov_deg > 0.0 ? tan(0.5 * desc.fov_deg * DEG) : t_min;
    double need_max = 0.0, tmax = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (!v->tri[i])
            continue;
        double x, y, t;
        light_local(a, v->pos + 3 * i, &x, &y, &t);
        if (!(t > 0.0))
            continue;   /* behind the light's plane: unlit, never traced */
        m->n_fit++;
        double need = (fmax(fabs(x), fabs(y)) - half) / t;
        if (need > need_max)
            need_max = need;
        if (t > tmax)
            tmax = t;
    }
    if (desc.fov_deg <= 0.0) {
        /* 1% wider than the tightest, so the extreme points are strictly inside */
        T = fmin(fmax(need_max * 1.01 + 1e-6, t_min), t_cap);
    }
    m->tan_half = T;
    m->fov_deg = 2.0 * atan(T) / DEG;
    m->light_depth = half / T;                          /* eq. 3.1 */
    if (need_max > T) {
        for (size_t i = 0; i < n; i++) {
            if (!v->tri[i])
                continue;
            double x, y, t;
            light_local(a, v->pos + 3 * i, &x, &y, &t);
            if (t > 0.0 && fmax(fabs(x), fabs(y)) > t * T + half)
                m->n_outside++;
        }
    }
    for (int k = 0; k < 3; k++) {
        m->eye[k] = a->c[k] - m->light_depth * a->n[k];
        m->right[k] = -a->ex[k];
        m->up[k] = a->ey[k];
        m->fwd[k] = a->n[k];
    }

    /* far plane: past the farthest receiver and every occluder vertex, so no
     * occluder loses its back faces to clipping */
    double zfar = m->light_depth + tmax;
    for (int r = 0; r < s->nranges; r++) {
        if (desc.receiver && desc.receiver[r])
            continue;
        const struct sl_mesh_range *g = &s->ranges[r];
        for (uint32_t t = g->first; t < g->first + g->count; t++)
            for (int c = 0; c < 3; c++) {
                double x, y, tt;
                light_local(a, s->pos + 3 * (size_t)s->idx[3 * (size_t)t + c], &x, &y, &tt);
                if (m->light_depth + tt > zfar)
                    zfar = m->light_depth + tt;
            }
    }
    if (desc.receiver)
        for (int r = 0; r < s->nranges; r++)
            m->n_receiver_ranges += desc.receiver[r] != 0;
    m->znear = m->light_depth * (1.0 - 1e-4);
    m->zfar = zfar * (1.0 + 1e-3) + 1e-6;
    if (!(m->zfar > m->light_depth * 1.001))
        m->zfar = m->light_depth * 2.0;   /* nothing in front of the light: any sane frustum */

    /* GL matrices (cglm, column-major): rows right, up, -fwd; perspective
     * zero-to-one with the same T */
    glm_mat4_identity(m->view);
    for (int k = 0; k < 3; k++) {
        m->view[k][0] = (float)m->right[k];
        m->view[k][1] = (float)m->up[k];
        m->view[k][2] = (float)-m->fwd[k];
    }
    m->view[3][0] = (float)-dot3(m->right, m->eye);
    m->view[3][1] = (float)-dot3(m->up, m->eye);
    m->view[3][2] = (float)dot3(m->fwd, m->eye);
    glm_mat4_zero(m->proj);
    const double zn = m->znear, zf = m->zfar;
    m->proj[0][0] = (float)(1.0 / T);
    m->proj[1][1] = (float)(1.0 / T);
    m->proj[2][2] = (float)(zf / (zn - zf));
    m->proj[2][3] = -1.0f;
    m->proj[3][2] = (float)(zn * zf / (zn - zf));
    glm_mat4_mul(m->proj, m->view, m->vp);
    return SL_OK;
}

/* One layer: front faces nearest (far = 0) or back faces farthest (far = 1). */
static enum sl_err render_layer(const struct sl_softmap_pass *p, const struct sl_gl_mesh *gm,
                                const struct sl_scene *s, const uint8_t *receiver, int far,
                                struct sl_softmap *m, float *out, double *ms_render, double *ms_gpu,
                                uint64_t *frags, struct sl_diag *d)
{
    const int S = m->size;
    const size_t n = (size_t)S * (size_t)S;
    double t0 = sl_now();
    GLuint fbo, tex[2];
    glCreateFramebuffers(1, &fbo);
    glCreateTextures(GL_TEXTURE_2D, 2, tex);
    glTextureStorage2D(tex[0], 1, GL_DEPTH_COMPONENT32F, S, S);
    glTextureStorage2D(tex[1], 1, GL_R32F, S, S);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, tex[0], 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex[1], 0);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
    enum sl_err e = SL_OK;
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        e = sl_fail(d, SL_E_GL, NULL, 0, NULL, "soft-shadow layer framebuffer incomplete");
    if (!e) {
        /* Curtis's clears: near layer to the far plane, far layer to the near one */
        const float clear_depth = far ? 0.0f : 1.0f;
        const float clear_lin[4] = {(float)(far ? m->znear : m->zfar), 0, 0, 0};
        struct sl_gl_timer gt;
        sl_gl_timer_begin(&gt);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, S, S);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(far ? GL_GREATER : GL_LESS);
        glFrontFace(GL_CCW);
        glCullFace(far ? GL_FRONT : GL_BACK);
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, clear_lin);
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &clear_depth);
        glUseProgram(p->prog);
        glUniformMatrix4fv(glGetUniformLocation(p->prog, "u_vp"), 1, GL_FALSE, (const float *)m->vp);
        glUniformMatrix4fv(glGetUniformLocation(p->prog, "u_view"), 1, GL_FALSE, (const float *)m->view);
        GLuint q;
        glGenQueries(1, &q);
        glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, q);
        glBindVertexArray(gm->vao);
        /* scene ranges, not the merged GL runs: receivers are left out one
         * range at a time; two-sided ranges (leaves) go unculled into both
         * layers, a zero-thickness occluder */
        for (int r = 0; r < s->nranges; r++) {
            const struct sl_mesh_range *g = &s->ranges[r];
            if ((receiver && receiver[r]) || g->count == 0)
                continue;
            if (g->two_sided)
                glDisable(GL_CULL_FACE);
            else
                glEnable(GL_CULL_FACE);
            glDrawElements(GL_TRIANGLES, (GLsizei)(3 * g->count), GL_UNSIGNED_INT,
                           (const void *)((size_t)g->first * 3 * sizeof(uint32_t)));
        }
        glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
        sl_gl_timer_end(&gt);
        glFinish();
        double t1 = sl_now();
        GLuint64 f = 0;
        glGetQueryObjectui64v(q, GL_QUERY_RESULT, &f);
        glDeleteQueries(1, &q);
        *frags = (uint64_t)f;
        *ms_render = 1e3 * (t1 - t0);
        double t2 = sl_now();
        glGetTextureImage(tex[1], 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), out);
        m->ms_readback += 1e3 * (sl_now() - t2);
        *ms_gpu = sl_gl_timer_ms(&gt, *ms_render);   /* after the readback: no extra wait */
        glDisable(GL_CULL_FACE);
        glDepthFunc(GL_LESS);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        e = sl_gl_check(far ? "soft-shadow far layer" : "soft-shadow near layer", d);
    }
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, tex);
    return e;
}

enum sl_err sl_softmap_render(const struct sl_softmap_pass *p, const struct sl_gl_mesh *gm,
                              const struct sl_scene *s, const struct sl_view *v,
                              const struct sl_softmap_desc *desc, struct sl_softmap *m, struct sl_diag *d)
{
    enum sl_err e = sl_softmap_fit(s, v, desc, m, d);
    if (e)
        return e;
    const size_t n = (size_t)m->size * (size_t)m->size;
    m->near = sl_calloc(n, sizeof(float));
    m->far = sl_calloc(n, sizeof(float));
    if (!m->near || !m->far) {
        sl_softmap_free(m);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "soft-shadow layers %dx%d", m->size, m->size);
    }
    e = render_layer(p, gm, s, desc->receiver, 0, m, m->near, &m->ms_near, &m->ms_gpu_near, &m->frag_near, d);
    if (!e)
        e = render_layer(p, gm, s, desc->receiver, 1, m, m->far, &m->ms_far, &m->ms_gpu_far, &m->frag_far, d);
    if (e)
        sl_softmap_free(m);
    return e;
}
