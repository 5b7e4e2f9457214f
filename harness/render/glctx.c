/*
 * glctx.c — the GL context (OSMesa or EGL, glegl.c) and GL helpers.
 * Invariant: a 4.5 core context or a clear error (OSMesa returns NULL for
 * 4.6 on Mesa 22.3, so 4.5 is asked for exactly, through both backends).
 * Everything after sl_gl_open is the same for both backends.
 */
#include "glctx.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "adjacency.h"
#include "glegl.h"
#include "util.h"
#ifdef SL_HAVE_OSMESA
#include <GL/osmesa.h>
#endif
#include "glload.h"

const char *sl_gl_backend_name(enum sl_gl_backend b)
{
    switch (b) {
    case SL_GL_OSMESA: return "osmesa";
    case SL_GL_EGL: return "egl";
    default: return "default";
    }
}

enum sl_gl_backend sl_gl_backend_parse(const char *s)
{
    if (s && strcmp(s, "osmesa") == 0)
        return SL_GL_OSMESA;
    if (s && strcmp(s, "egl") == 0)
        return SL_GL_EGL;
    return SL_GL_DEFAULT;
}

enum sl_gl_backend sl_gl_backend_resolve(enum sl_gl_backend b)
{
    if (b != SL_GL_DEFAULT)
        return b;
    /* below the command line and the config, above the built default: CI
     * runs the rendering tests a second time with SHADOWLAB_GL=egl, and the
     * tests that open the context themselves (sl_gl_init) follow it too; a
     * bad value is refused by sl_gl_open */
    b = sl_gl_backend_parse(getenv("SHADOWLAB_GL"));
    if (b != SL_GL_DEFAULT)
        return b;
#ifdef SL_HAVE_OSMESA
    return SL_GL_OSMESA;
#else
    return SL_GL_EGL;
#endif
}

int sl_gl_backend_built(enum sl_gl_backend b)
{
    switch (b) {
#ifdef SL_HAVE_OSMESA
    case SL_GL_OSMESA: return 1;
#endif
#ifdef SL_HAVE_EGL
    case SL_GL_EGL: return 1;
#endif
    case SL_GL_DEFAULT: return 1;
    default: return 0;
    }
}

#ifdef SL_HAVE_OSMESA
static sl_glproc osmesa_proc(const char *name)
{
    return (sl_glproc)OSMesaGetProcAddress(name);
}

static enum sl_err osmesa_open(struct sl_gl *g, struct sl_diag *d)
{
    const int attribs[] = {
        OSMESA_FORMAT, OSMESA_RGBA,
        OSMESA_DEPTH_BITS, 0,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, 4,
        OSMESA_CONTEXT_MINOR_VERSION, 5,
        0,
    };
    char why[300];
    if (sl_osmesa_load(why, sizeof why))
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "%s", why);
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, NULL);
    if (!ctx)
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "OSMesa could not create a 4.5 core context");
    if (!OSMesaMakeCurrent(ctx, g->pixel, GL_UNSIGNED_BYTE, 1, 1)) {
        OSMesaDestroyContext(ctx);
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "OSMesaMakeCurrent failed");
    }
    const char *missing = sl_glfn_load(osmesa_proc);
    if (missing) {
        OSMesaDestroyContext(ctx);
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "OSMesa lacks %s", missing);
    }
    g->osmesa = ctx;
    return SL_OK;
}
#endif

enum sl_err sl_gl_open(struct sl_gl *g, const struct sl_gl_desc *desc, struct sl_diag *d)
{
    memset(g, 0, sizeof *g);
    const char *env = getenv("SHADOWLAB_GL");
    if (env && env[0] && sl_gl_backend_parse(env) == SL_GL_DEFAULT)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_GL", "'%s': osmesa or egl", env);
    enum sl_gl_backend b = sl_gl_backend_resolve(desc ? desc->backend : SL_GL_DEFAULT);
    if (!sl_gl_backend_built(b))
        return sl_fail(d, SL_E_USAGE, NULL, 0, "gl",
                       "this shadowlab was built without the %s backend (its library was not found at "
                       "configure time)",
                       sl_gl_backend_name(b));
    enum sl_err e = SL_E_INTERNAL;
#ifdef SL_HAVE_OSMESA
    if (b == SL_GL_OSMESA)
        e = osmesa_open(g, d);
#endif
#ifdef SL_HAVE_EGL
    if (b == SL_GL_EGL)
        e = sl_egl_open(g, d);
#endif
    if (e)
        return e;
    g->backend = b;
    snprintf(g->renderer, sizeof g->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    snprintf(g->version, sizeof g->version, "%s", (const char *)glGetString(GL_VERSION));
    return SL_OK;
}

enum sl_err sl_gl_init(struct sl_gl *g, struct sl_diag *d)
{
    return sl_gl_open(g, NULL, d);
}

void sl_gl_free(struct sl_gl *g)
{
    if (!g)
        return;
#ifdef SL_HAVE_OSMESA
    if (g->osmesa)
        OSMesaDestroyContext(g->osmesa);
    g->osmesa = NULL;
#endif
#ifdef SL_HAVE_EGL
    sl_egl_close(g);
#endif
    g->backend = SL_GL_DEFAULT;   /* closed: callers test it */
}

void sl_gl_describe(const struct sl_gl *g, char *buf, size_t n)
{
    if (g->device[0])
        snprintf(buf, n, "%s %s", sl_gl_backend_name(g->backend), g->device);
    else
        snprintf(buf, n, "%s", sl_gl_backend_name(g->backend));
}

static GLuint compile(GLenum type, const char *src, struct sl_diag *d)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[400];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        glDeleteShader(s);
        sl_fail(d, SL_E_GL, NULL, 0, NULL, "shader compile: %s", log);
        return 0;
    }
    return s;
}

GLuint sl_gl_program(const char *vs, const char *gs, const char *fs, struct sl_diag *d)
{
    GLuint sh[3] = {0, 0, 0};
    sh[0] = compile(GL_VERTEX_SHADER, vs, d);
    if (gs)
        sh[1] = compile(GL_GEOMETRY_SHADER, gs, d);
    sh[2] = compile(GL_FRAGMENT_SHADER, fs, d);
    GLuint p = 0;
    if (sh[0] && (!gs || sh[1]) && sh[2]) {
        p = glCreateProgram();
        for (int i = 0; i < 3; i++)
            if (sh[i])
                glAttachShader(p, sh[i]);
        glLinkProgram(p);
        GLint ok = 0;
        glGetProgramiv(p, GL_LINK_STATUS, &ok);
        if (!ok) {
            char log[400];
            glGetProgramInfoLog(p, sizeof log, NULL, log);
            sl_fail(d, SL_E_GL, NULL, 0, NULL, "program link: %s", log);
            glDeleteProgram(p);
            p = 0;
        }
    }
    for (int i = 0; i < 3; i++)
        if (sh[i])
            glDeleteShader(sh[i]);
    return p;
}

void sl_gl_timer_begin(struct sl_gl_timer *t)
{
    glGenQueries(1, &t->q);
    glBeginQuery(GL_TIME_ELAPSED, t->q);
}

void sl_gl_timer_end(struct sl_gl_timer *t)
{
    (void)t;
    glEndQuery(GL_TIME_ELAPSED);
}

double sl_gl_timer_ms(struct sl_gl_timer *t, double wall_ms)
{
    GLuint64 ns = 0;
    glGetQueryObjectui64v(t->q, GL_QUERY_RESULT, &ns);
    glDeleteQueries(1, &t->q);
    t->q = 0;
    double ms = 1e-6 * (double)ns;
    return ms <= wall_ms ? ms : NAN;
}

enum sl_err sl_gl_check(const char *what, struct sl_diag *d)
{
    GLenum e = glGetError();
    if (e != GL_NO_ERROR)
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "%s: GL error 0x%04x", what, e);
    return SL_OK;
}

enum sl_err sl_gl_mesh_upload(struct sl_gl_mesh *m, const struct sl_scene *s, struct sl_diag *d)
{
    memset(m, 0, sizeof *m);
    glCreateVertexArrays(1, &m->vao);
    glCreateBuffers(1, &m->vbo);
    glCreateBuffers(1, &m->ebo);
    glNamedBufferStorage(m->vbo, (GLsizeiptr)s->nv * 3 * sizeof(float), s->pos, 0);
    glNamedBufferStorage(m->ebo, (GLsizeiptr)s->nt * 3 * sizeof(uint32_t), s->idx, 0);
    glVertexArrayVertexBuffer(m->vao, 0, m->vbo, 0, 3 * sizeof(float));
    glVertexArrayElementBuffer(m->vao, m->ebo);
    glEnableVertexArrayAttrib(m->vao, 0);
    glVertexArrayAttribFormat(m->vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(m->vao, 0, 0);
    m->count = (GLsizei)(s->nt * 3);
    m->runs = calloc((size_t)(s->nranges > 0 ? s->nranges : 1), sizeof *m->runs);
    if (!m->runs)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "draw runs");
    if (s->nranges == 0) {
        m->runs[0].count = s->nt;
        m->nruns = 1;
    }
    for (int i = 0; i < s->nranges; i++) {
        const struct sl_mesh_range *r = &s->ranges[i];
        struct sl_gl_run *last = m->nruns ? &m->runs[m->nruns - 1] : NULL;
        if (last && last->two_sided == r->two_sided && last->first + last->count == r->first)
            last->count += r->count;
        else
            m->runs[m->nruns++] = (struct sl_gl_run){r->first, r->count, r->two_sided};
    }
    return sl_gl_check("mesh upload", d);
}

enum sl_err sl_gl_mesh_upload_adjacency(struct sl_gl_mesh *m, const struct sl_scene *s,
                                        const struct sl_adjacency *a, struct sl_diag *d)
{
    uint32_t *ix = malloc((size_t)s->nt * 6 * sizeof(uint32_t));
    if (!ix)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "adjacency indices");
    for (uint32_t t = 0; t < s->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t v = s->idx[3 * t + k], o = a->opposite[3 * t + k];
            ix[6 * t + 2 * k] = v;
            ix[6 * t + 2 * k + 1] = (o == SL_ADJ_NONE || o == SL_ADJ_MULTI) ? v : o;
        }
    glCreateVertexArrays(1, &m->vao_adj);
    glCreateBuffers(1, &m->ebo_adj);
    glNamedBufferStorage(m->ebo_adj, (GLsizeiptr)s->nt * 6 * sizeof(uint32_t), ix, 0);
    free(ix);
    glVertexArrayVertexBuffer(m->vao_adj, 0, m->vbo, 0, 3 * sizeof(float));
    glVertexArrayElementBuffer(m->vao_adj, m->ebo_adj);
    glEnableVertexArrayAttrib(m->vao_adj, 0);
    glVertexArrayAttribFormat(m->vao_adj, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(m->vao_adj, 0, 0);
    return sl_gl_check("adjacency upload", d);
}

void sl_gl_mesh_free(struct sl_gl_mesh *m)
{
    if (m->vao_adj) glDeleteVertexArrays(1, &m->vao_adj);
    if (m->ebo_adj) glDeleteBuffers(1, &m->ebo_adj);
    if (m->vao) glDeleteVertexArrays(1, &m->vao);
    if (m->vbo) glDeleteBuffers(1, &m->vbo);
    if (m->ebo) glDeleteBuffers(1, &m->ebo);
    free(m->runs);
    memset(m, 0, sizeof *m);
}
