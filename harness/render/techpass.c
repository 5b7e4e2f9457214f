/*
 * techpass.c — see techpass.h.
 * Invariants: texel (i, j) of the light frame is texel (i + g, j + g) of
 * the guarded maps; the package's shaders are techsrc.h's text, compiled as
 * it is, so the driver's line numbers below SL_TECHSRC_LINE_PRELUDE are the
 * package file's.
 */
#include "techpass.h"
#include "techsrc.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "shadowmap.h"
#include "util.h"

/* ---- sources ---- */

/* The scene's vertices: gl_Position computed as the C depth layers'
 * depth_id_vs.glsl computes it, so a map of g = 0 holds their depths. */
static const char vs_scene[] =
    "#version 450 core\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "uniform mat4 sl_light_vp;\n"
    "out vec3 sl_world;\n"
    "void main()\n"
    "{\n"
    "    sl_world = a_pos;\n"
    "    gl_Position = sl_light_vp * vec4(a_pos, 1.0);\n"
    "}\n";

/* One triangle covering the viewport (vertices 0, 1, 2: no buffer). */
static const char vs_full[] =
    "#version 450 core\n"
    "out vec3 sl_world;\n"
    "void main()\n"
    "{\n"
    "    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);\n"
    "    sl_world = vec3(0.0);\n"
    "    gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";

/* Separable box blur, 2r + 1 taps along sl_dir, clamped inside the map. */
static const char fs_blur[] =
    "#version 450 core\n"
    "uniform sampler2D sl_src;\n"
    "uniform ivec2 sl_dir;\n"
    "uniform int sl_radius;\n"
    "layout(location = 0) out vec4 sl_out;\n"
    "void main()\n"
    "{\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy), hi = textureSize(sl_src, 0) - 1;\n"
    "    vec4 s = vec4(0.0);\n"
    "    for (int k = -sl_radius; k <= sl_radius; k++)\n"
    "        s += texelFetch(sl_src, clamp(px + k * sl_dir, ivec2(0), hi), 0);\n"
    "    sl_out = s / float(2 * sl_radius + 1);\n"
    "}\n";

/* The maps' texels that are not finite (NaN, +-inf; read from the bits):
 * every other fragment is discarded, and an occlusion query counts the rest. */
static const char fs_finite[] =
    "#version 450 core\n"
    "uniform sampler2D sl_m[4];\n"
    "uniform int sl_nmaps;\n"
    "layout(location = 0) out vec4 sl_out;\n"
    "void main()\n"
    "{\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    bool bad = false;\n"
    "    for (int i = 0; i < sl_nmaps; i++) {\n"
    "        uvec4 b = floatBitsToUint(texelFetch(sl_m[i], px, 0)) & uvec4(0x7f800000u);\n"
    "        bad = bad || any(equal(b, uvec4(0x7f800000u)));\n"
    "    }\n"
    "    if (!bad)\n"
    "        discard;\n"
    "    sl_out = vec4(0.0);\n"
    "}\n";

/* ---- compiling, with the driver's log mapped to the package's file ---- */

static GLuint compile(GLenum type, const char *src, char *log, size_t nlog)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        glGetShaderInfoLog(s, (GLsizei)nlog, NULL, log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint link(GLuint vs, GLuint fs, char *log, size_t nlog)
{
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        glGetProgramInfoLog(p, (GLsizei)nlog, NULL, log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

/* vs + fs linked; a failure of fs (the package's) is mapped to its file. */
static enum sl_err build(const char *vs_src, const char *fs_src, GLuint *prog, GLuint *fs_keep, const char *file,
                         struct sl_diag *d)
{
    char log[4096] = "";
    GLuint fs = fs_keep && *fs_keep ? *fs_keep : compile(GL_FRAGMENT_SHADER, fs_src, log, sizeof log);
    if (fs_keep)
        *fs_keep = fs;   /* the caller deletes it */
    if (!fs)
        return file ? sl_techsrc_log_error(file, log, d) : sl_fail(d, SL_E_GL, NULL, 0, NULL, "shader: %s", log);
    GLuint vs = compile(GL_VERTEX_SHADER, vs_src, log, sizeof log);
    if (!vs) {
        if (!fs_keep)
            glDeleteShader(fs);
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "harness vertex shader: %s", log);
    }
    *prog = link(vs, fs, log, sizeof log);
    glDeleteShader(vs);
    if (!fs_keep)
        glDeleteShader(fs);
    if (!*prog)
        return file ? sl_techsrc_log_error(file, log, d) : sl_fail(d, SL_E_GL, NULL, 0, NULL, "link: %s", log);
    return SL_OK;
}

enum sl_err sl_techpass_init(struct sl_techpass *p, const struct sl_technique *t, struct sl_diag *d)
{
    memset(p, 0, sizeof *p);
    p->t = t;
    char map_file[1400], lookup_file[1400];
    snprintf(map_file, sizeof map_file, "%s/%s", t->dir, t->map_shader);
    snprintf(lookup_file, sizeof lookup_file, "%s/%s", t->dir, t->lookup_shader);
    char *mfs = sl_techsrc(t, SL_TECHSRC_MAP), *lfs = sl_techsrc(t, SL_TECHSRC_LOOKUP);
    enum sl_err e = mfs && lfs ? SL_OK : sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "shader source");
    GLuint fs = 0;
    if (!e)
        e = build(vs_scene, mfs, &p->prog_map, &fs, map_file, d);
    if (!e)
        e = build(vs_full, mfs, &p->prog_empty, &fs, map_file, d);
    if (fs)
        glDeleteShader(fs);
    if (!e)
        e = build(vs_full, lfs, &p->prog_lookup, NULL, lookup_file, d);
    if (!e)
        e = build(vs_full, fs_blur, &p->prog_blur, NULL, NULL, d);
    if (!e)
        e = build(vs_full, fs_finite, &p->prog_finite, NULL, NULL, d);
    free(mfs);
    free(lfs);
    if (!e) {
        glCreateVertexArrays(1, &p->vao_empty);
        GLint mx = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &mx);
        p->max_tex = mx;
        glUseProgram(p->prog_empty);
        glUniform1f(glGetUniformLocation(p->prog_empty, "sl_empty"), 1.0f);
        glUseProgram(p->prog_map);
        glUniform1f(glGetUniformLocation(p->prog_map, "sl_empty"), -1.0f);
        glUseProgram(0);
        e = sl_gl_check("technique programs", d);
    }
    if (e)
        sl_techpass_free(p);
    return e;
}

static void maps_free(struct sl_techpass *p)
{
    glDeleteTextures(SL_TECH_MAX_MAPS, p->map_tex);
    glDeleteTextures(SL_TECH_MAX_MAPS, p->ping_tex);
    glDeleteFramebuffers(1, &p->map_fbo);
    glDeleteFramebuffers(1, &p->blur_fbo);
    glDeleteRenderbuffers(1, &p->depth_rb);
    memset(p->map_tex, 0, sizeof p->map_tex);
    memset(p->ping_tex, 0, sizeof p->ping_tex);
    p->map_fbo = p->blur_fbo = p->depth_rb = 0;
    p->size = 0;
}

static void lookup_free(struct sl_techpass *p)
{
    GLuint tex[4] = {p->g_pos, p->g_nrm, p->g_mask, p->out_tex};
    glDeleteTextures(4, tex);
    glDeleteFramebuffers(1, &p->out_fbo);
    p->g_pos = p->g_nrm = p->g_mask = p->out_tex = p->out_fbo = 0;
    free(p->ones);
    p->ones = NULL;
    p->lw = p->lh = 0;
}

void sl_techpass_free(struct sl_techpass *p)
{
    if (p->size)
        maps_free(p);
    if (p->lw)
        lookup_free(p);
    GLuint progs[6] = {p->prog_map, p->prog_empty, p->prog_lookup, p->prog_blur, p->prog_finite, p->prog_taps};
    for (int i = 0; i < 6; i++)
        if (progs[i])
            glDeleteProgram(progs[i]);
    if (p->vao_empty)
        glDeleteVertexArrays(1, &p->vao_empty);
    memset(p, 0, sizeof *p);
}

/* ---- bounded tiles (techpass.h) ---- */

static const char *const kind_name[SL_TECHPASS_KINDS] = {"map", "map", "post (blur)", "lookup"};

struct tiles {
    int kind, w, h;
    int x, y, tw, th;          /* the tile under way (tw 0: none yet) */
    double min_px;             /* the smallest tile */
    double t_pass, t_tile;     /* when the pass and the tile began */
    const char *file;          /* the package file the pass runs, for a message */
};

/* The map's scene is drawn again in every tile: its tiles are at least
 * 1/64 of the map, so a scene whose triangles alone take longer than a
 * tile's aim is drawn at most 64 times, not once per 8 x 8 texels. t_pass:
 * when the pass began (0: now; the scene's, the empty texels' start). */
static void tiles_begin(struct tiles *tl, int kind, int w, int h, const char *file, double t_pass)
{
    memset(tl, 0, sizeof *tl);
    tl->kind = kind;
    tl->w = w;
    tl->h = h;
    tl->file = file;
    tl->min_px = kind == SL_TECHPASS_SCENE ? fmax(64.0, (double)w * (double)h / 64.0) : 64.0;
    tl->t_pass = t_pass > 0 ? t_pass : sl_now();
    glEnable(GL_SCISSOR_TEST);
}

static const char *reset_name(GLenum r)
{
    return r == GL_GUILTY_CONTEXT_RESET ? "caused by this context"
           : r == GL_INNOCENT_CONTEXT_RESET ? "caused elsewhere" : "cause unknown";
}

/* After the tile under way (if any): its glFinish, the next area from its
 * time, then the checks: the driver's reset status, the stop flag, the
 * pass's time. Then the next tile's scissor rectangle: 1, or 0 when the
 * pass is done (*e SL_OK) or ended (*e the error; the scissor test off). */
static int tiles_next(struct sl_techpass *p, struct tiles *tl, enum sl_err *e, struct sl_diag *d)
{
    *e = SL_OK;
    double *area = &p->tile_px[tl->kind];
    if (tl->tw) {
        glFinish();
        const double now = sl_now(), t = now - tl->t_tile, px = (double)tl->tw * (double)tl->th;
        double f = t > 1e-6 ? SL_TECHPASS_TILE_SECONDS / t : 4.0;
        f = f < 0.25 ? 0.25 : f > 4.0 ? 4.0 : f;
        if (t <= SL_TECHPASS_TILE_SECONDS && f < 2.0)
            f = 2.0;   /* under the aim: grow, so a pass of fixed cost a tile ends in few */
        *area = fmax(px * f, tl->min_px);
        p->tiles++;
        const char *name = p->t->name, *pass = kind_name[tl->kind];
        const GLenum r = glGetGraphicsResetStatus();
        if (r != GL_NO_ERROR)
            *e = sl_fail(d, SL_E_GL, tl->file, 0, NULL, "technique %s: the GL context was reset during the %s "
                         "pass (%s): its results are lost", name, pass, reset_name(r));
        else if (p->limits.stop && *p->limits.stop)
            *e = sl_fail(d, SL_E_STOPPED, NULL, 0, NULL, "technique %s: stopped during the %s pass", name, pass);
        else if (p->limits.pass_seconds > 0 && now - tl->t_pass > p->limits.pass_seconds)
            *e = sl_fail(d, SL_E_PACKAGE, tl->file, 0, NULL, "technique %s: the %s pass ran %.1f s, over "
                         "limits.pass_seconds (%g s), and was ended: a loop that does not end? (nothing stored "
                         "for the cell)", name, pass, now - tl->t_pass, p->limits.pass_seconds);
        tl->x += tl->tw;
        if (tl->x >= tl->w) {
            tl->x = 0;
            tl->y += tl->th;
        }
        if (*e || tl->y >= tl->h) {
            glDisable(GL_SCISSOR_TEST);
            return 0;
        }
    }
    double a = fmin(fmax(*area, tl->min_px), (double)tl->w * (double)tl->h);
    if (p->tile_max_px > 0)
        a = fmin(a, fmax(p->tile_max_px, 64.0));
    if (tl->x == 0) {   /* a band's height: whole rows, or a square tile's; a multiple of 8 */
        int th = 8;
        if (a >= (double)tl->w * (double)(tl->h - tl->y))
            th = tl->h - tl->y;
        else if (a >= 8.0 * tl->w)
            th = (int)(a / tl->w) & ~7;
        else
            while (4.0 * th * th <= a)
                th *= 2;
        tl->th = th < tl->h - tl->y ? th : tl->h - tl->y;
    }
    int tw = a >= (double)tl->th * (double)(tl->w - tl->x) ? tl->w - tl->x : (int)(a / tl->th) & ~7;
    tw = tw < 8 ? 8 : tw;
    tl->tw = tw < tl->w - tl->x ? tw : tl->w - tl->x;
    glScissor(tl->x, tl->y, tl->tw, tl->th);
    tl->t_tile = sl_now();
    return 1;
}

/* ---- maps ---- */

static const GLenum fmt_internal[4] = {GL_R32F, GL_RG32F, GL_RGBA32F, GL_RGBA16F};
static const GLenum fmt_upload[4] = {GL_RED, GL_RG, GL_RGBA, GL_RGBA};

static int has_mips(const struct sl_tech_map *m)
{
    return m->post == SL_TECH_POST_MIPMAPS || m->post == SL_TECH_POST_BLUR_MIPMAPS;
}

static int mip_levels(int n)
{
    int l = 1;
    while (n > 1) {
        n >>= 1;
        l++;
    }
    return l;
}

enum sl_err sl_techpass_size(struct sl_techpass *p, const struct sl_light_frame *f,
                             const struct sl_params *v, int *guard, int *size, struct sl_diag *d)
{
    const struct sl_technique *t = p->t;
    int g = sl_tech_guard(t, v);
    long long n = (long long)f->size + 2ll * g;
    int mx = p->max_tex > 0 && p->max_tex < SL_TECH_MAX_MAP_SIZE ? p->max_tex : SL_TECH_MAX_MAP_SIZE;
    if (f->size < 1 || n > mx) {
        int gp = sl_tech_guard_param(t);
        if (gp >= 0)
            return sl_fail(d, SL_E_METHOD, t->file, 0, t->param[gp].name, "%s = %g gives a guard band of %d texels: "
                           "the maps would be %d + 2 x %d = %lld texels wide, over the limit of %d",
                           t->param[gp].name, v->v[gp], g, f->size, g, n, mx);
        return sl_fail(d, SL_E_METHOD, t->file, 0, NULL, "map size %d + 2 x %d (guard band) = %lld texels: over "
                       "the limit of %d", f->size, g, n, mx);
    }
    *guard = g;
    *size = (int)n;
    return SL_OK;
}

static enum sl_err maps_make(struct sl_techpass *p, int N, struct sl_diag *d)
{
    if (p->size == N)
        return SL_OK;
    if (p->size)
        maps_free(p);
    const struct sl_technique *t = p->t;
    glCreateTextures(GL_TEXTURE_2D, t->nmaps, p->map_tex);
    glCreateTextures(GL_TEXTURE_2D, t->nmaps, p->ping_tex);
    glCreateFramebuffers(1, &p->map_fbo);
    glCreateFramebuffers(1, &p->blur_fbo);
    glCreateRenderbuffers(1, &p->depth_rb);
    GLenum bufs[SL_TECH_MAX_MAPS];
    for (int i = 0; i < t->nmaps; i++) {
        const struct sl_tech_map *m = &t->map[i];
        const int mips = has_mips(m), lin = m->filter == SL_TECH_LINEAR;
        glTextureStorage2D(p->map_tex[i], mips ? mip_levels(N) : 1, fmt_internal[m->format], N, N);
        glTextureParameteri(p->map_tex[i], GL_TEXTURE_MIN_FILTER,
                            mips ? (lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST)
                                 : (lin ? GL_LINEAR : GL_NEAREST));
        glTextureParameteri(p->map_tex[i], GL_TEXTURE_MAG_FILTER, lin ? GL_LINEAR : GL_NEAREST);
        glTextureParameteri(p->map_tex[i], GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(p->map_tex[i], GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureStorage2D(p->ping_tex[i], 1, fmt_internal[m->format], N, N);
        glTextureParameteri(p->ping_tex[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(p->ping_tex[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glNamedFramebufferTexture(p->map_fbo, GL_COLOR_ATTACHMENT0 + (GLenum)i, p->map_tex[i], 0);
        bufs[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
    }
    glNamedRenderbufferStorage(p->depth_rb, GL_DEPTH_COMPONENT32F, N, N);
    glNamedFramebufferRenderbuffer(p->map_fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, p->depth_rb);
    glNamedFramebufferDrawBuffers(p->map_fbo, t->nmaps, bufs);
    p->size = N;
    if (glCheckNamedFramebufferStatus(p->map_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        maps_free(p);
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "technique %s: map framebuffer incomplete (%dx%d)", t->name, N, N);
    }
    return sl_gl_check("technique maps", d);
}

/* The guarded map's matrix: x, y of the frame's clip scaled by S / N (the
 * frame's own matrix, unscaled, when N == S). */
static void guarded_vp(struct sl_techpass *p, const struct sl_light_frame *f, int N)
{
    const float *vp = (const float *)f->box.vp;
    memcpy(p->light_vp, vp, sizeof p->light_vp);
    if (N == f->size)
        return;
    const float s = (float)f->size / (float)N;
    for (int c = 0; c < 4; c++) {
        p->light_vp[4 * c + 0] = vp[4 * c + 0] * s;
        p->light_vp[4 * c + 1] = vp[4 * c + 1] * s;
    }
}

static void set_params(GLuint prog, const struct sl_technique *t, const struct sl_params *v)
{
    for (int i = 0; i < t->nparams; i++) {
        GLint loc = glGetUniformLocation(prog, t->param[i].name);
        double x = i < v->n ? v->v[i] : t->param[i].def;
        if (t->param[i].type == SL_PARAM_FLOAT)
            glUniform1f(loc, (float)x);
        else
            glUniform1i(loc, (GLint)x);
    }
}

static void set_light(GLuint prog, const struct sl_techpass *p, const struct sl_light_frame *f)
{
    glUniformMatrix4fv(glGetUniformLocation(prog, "sl_light_vp"), 1, GL_FALSE, p->light_vp);
    glUniform1i(glGetUniformLocation(prog, "sl_persp"), f->box.persp);
}

/* Blur and mipmaps, timed together. */
static enum sl_err post_passes(struct sl_techpass *p, const struct sl_params *v, struct sl_diag *d)
{
    const struct sl_technique *t = p->t;
    const int N = p->size;
    int any = 0;
    for (int i = 0; i < t->nmaps; i++)
        any |= t->map[i].post != SL_TECH_POST_NONE;
    p->costs.ms_post = 0.0;
    p->costs.gpu_post = 0.0;
    if (!any)
        return SL_OK;
    char file[1400];
    snprintf(file, sizeof file, "%s/%s", t->dir, t->map_shader);
    enum sl_err e = SL_OK;
    double t0 = sl_now();
    struct sl_gl_timer gt;
    sl_gl_timer_begin(&gt);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, N, N);
    glBindVertexArray(p->vao_empty);
    for (int i = 0; i < t->nmaps; i++) {
        const struct sl_tech_map *m = &t->map[i];
        int r = m->blur >= 0 && m->blur < v->n ? (int)v->v[m->blur] : 0;
        if (r > 0) {
            glUseProgram(p->prog_blur);
            glUniform1i(glGetUniformLocation(p->prog_blur, "sl_src"), 0);
            glUniform1i(glGetUniformLocation(p->prog_blur, "sl_radius"), r);
            GLint dir = glGetUniformLocation(p->prog_blur, "sl_dir");
            glBindFramebuffer(GL_FRAMEBUFFER, p->blur_fbo);
            for (int pass = 0; pass < 2 && !e; pass++) {
                GLuint src = pass ? p->ping_tex[i] : p->map_tex[i], dst = pass ? p->map_tex[i] : p->ping_tex[i];
                glNamedFramebufferTexture(p->blur_fbo, GL_COLOR_ATTACHMENT0, dst, 0);
                glNamedFramebufferDrawBuffer(p->blur_fbo, GL_COLOR_ATTACHMENT0);
                glBindTextureUnit(0, src);
                glUniform2i(dir, pass ? 0 : 1, pass ? 1 : 0);
                struct tiles tl;
                for (tiles_begin(&tl, SL_TECHPASS_BLUR, N, N, file, 0); tiles_next(p, &tl, &e, d);)
                    glDrawArrays(GL_TRIANGLES, 0, 3);
            }
            glNamedFramebufferTexture(p->blur_fbo, GL_COLOR_ATTACHMENT0, 0, 0);
            glBindTextureUnit(0, 0);
        }
        if (e)
            break;
        if (has_mips(m))
            glGenerateTextureMipmap(p->map_tex[i]);
    }
    sl_gl_timer_end(&gt);
    glFinish();
    double ms = 1e3 * (sl_now() - t0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    p->costs.ms_post = ms;
    p->costs.gpu_post = sl_gl_timer_ms(&gt, ms);
    return e ? e : sl_gl_check("technique post passes", d);
}

/* Count the maps' texels (level 0, guard band included) that are not
 * finite into costs.map_nonfinite: drawn into the scratch ping texture of
 * map 0, which no later pass reads before the blur writes it. Not timed: a
 * check of the harness, not the technique's work. */
static enum sl_err maps_finite(struct sl_techpass *p, struct sl_diag *d)
{
    const struct sl_technique *t = p->t;
    const int N = p->size;
    GLuint q = 0;
    glGenQueries(1, &q);
    glBindFramebuffer(GL_FRAMEBUFFER, p->blur_fbo);
    glNamedFramebufferTexture(p->blur_fbo, GL_COLOR_ATTACHMENT0, p->ping_tex[0], 0);
    glNamedFramebufferDrawBuffer(p->blur_fbo, GL_COLOR_ATTACHMENT0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, N, N);
    glUseProgram(p->prog_finite);
    char name[16];
    for (int i = 0; i < t->nmaps; i++) {
        glBindTextureUnit((GLuint)i, p->map_tex[i]);
        snprintf(name, sizeof name, "sl_m[%d]", i);
        glUniform1i(glGetUniformLocation(p->prog_finite, name), i);
    }
    glUniform1i(glGetUniformLocation(p->prog_finite, "sl_nmaps"), t->nmaps);
    glBindVertexArray(p->vao_empty);
    glBeginQuery(GL_SAMPLES_PASSED, q);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 n = 0;
    glGetQueryObjectui64v(q, GL_QUERY_RESULT, &n);
    glDeleteQueries(1, &q);
    for (int i = 0; i < t->nmaps; i++)
        glBindTextureUnit((GLuint)i, 0);
    glNamedFramebufferTexture(p->blur_fbo, GL_COLOR_ATTACHMENT0, 0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    p->costs.map_nonfinite = (uint64_t)n;
    return sl_gl_check("technique maps' finite check", d);
}

static enum sl_err maps_ready(struct sl_techpass *p, const struct sl_light_frame *f, const struct sl_params *v,
                              struct sl_diag *d)
{
    int g = 0, N = 0;
    enum sl_err e = sl_techpass_size(p, f, v, &g, &N, d);
    if (!e && p->extra > 0) {
        g += p->extra;
        N += 2 * p->extra;
    }
    if (!e)
        e = maps_make(p, N, d);
    if (e)
        return e;
    p->guard = g;
    p->costs.guard = g;
    p->costs.map_size = N;
    guarded_vp(p, f, N);
    return SL_OK;
}

/* The texels beyond the declared guard band (techpass.h, extra): four
 * strips drawn with sl_map(p->fill), each in its scissor rectangle. */
static enum sl_err fill_extra(struct sl_techpass *p, const struct sl_light_frame *f, const struct sl_params *v,
                              struct sl_diag *d)
{
    const int N = p->size, E = p->extra;
    const int rect[4][4] = {{0, 0, N, E}, {0, N - E, N, E}, {0, E, E, N - 2 * E}, {N - E, E, E, N - 2 * E}};
    glBindFramebuffer(GL_FRAMEBUFFER, p->map_fbo);
    glViewport(0, 0, N, N);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(p->prog_empty);
    set_light(p->prog_empty, p, f);
    set_params(p->prog_empty, p->t, v);
    glUniform1f(glGetUniformLocation(p->prog_empty, "sl_empty"), p->fill);
    glBindVertexArray(p->vao_empty);
    glEnable(GL_SCISSOR_TEST);
    for (int i = 0; i < 4; i++) {
        glScissor(rect[i][0], rect[i][1], rect[i][2], rect[i][3]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_SCISSOR_TEST);
    glUniform1f(glGetUniformLocation(p->prog_empty, "sl_empty"), 1.0f);
    glFinish();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    return sl_gl_check("technique maps' extra guard band", d);
}

enum sl_err sl_techpass_render(struct sl_techpass *p, const struct sl_gl_mesh *m, const struct sl_light_frame *f,
                               const struct sl_params *v, struct sl_diag *d)
{
    const struct sl_technique *t = p->t;
    double t0 = sl_now();   /* a new size's maps are made inside the timed pass, as in shadowmap.c */
    enum sl_err e = maps_ready(p, f, v, d);
    if (e)
        return e;
    const int N = p->size;
    char file[1400];
    snprintf(file, sizeof file, "%s/%s", t->dir, t->map_shader);
    struct sl_gl_timer gt;
    sl_gl_timer_begin(&gt);
    glBindFramebuffer(GL_FRAMEBUFFER, p->map_fbo);
    glViewport(0, 0, N, N);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    const float one = 1.0f;
    glClearNamedFramebufferfv(p->map_fbo, GL_DEPTH, 0, &one);   /* before the tiles: a clear obeys the scissor */
    glUseProgram(p->prog_empty);
    set_light(p->prog_empty, p, f);
    set_params(p->prog_empty, t, v);
    glUseProgram(p->prog_map);
    set_light(p->prog_map, p, f);
    set_params(p->prog_map, t, v);
    glDepthFunc(GL_LESS);
    glFrontFace(GL_CCW);
    if (t->cull != SL_TECH_CULL_NONE)
        glCullFace(t->cull == SL_TECH_CULL_FRONT ? GL_FRONT : GL_BACK);
    const uint32_t chunk = SL_SHADOWMAP_CHUNK;
    /* empty texels: sl_map(1.0) everywhere */
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(p->prog_empty);
    glBindVertexArray(p->vao_empty);
    struct tiles tl;
    for (tiles_begin(&tl, SL_TECHPASS_EMPTY, N, N, file, 0); tiles_next(p, &tl, &e, d);)
        glDrawArrays(GL_TRIANGLES, 0, 3);
    /* the scene, nearest fragment wins */
    glEnable(GL_DEPTH_TEST);
    glUseProgram(p->prog_map);
    glBindVertexArray(m->vao);
    const double t_pass = tl.t_pass;
    if (!e)
        tiles_begin(&tl, SL_TECHPASS_SCENE, N, N, file, t_pass);
    while (!e && tiles_next(p, &tl, &e, d)) {
        for (int r = 0; r < m->nruns; r++) {
            /* two-sided meshes (leaves) are never culled, as in shadowmap.c */
            if (t->cull != SL_TECH_CULL_NONE && !m->runs[r].two_sided)
                glEnable(GL_CULL_FACE);
            else
                glDisable(GL_CULL_FACE);
            /* in flushed chunks, as shadowmap.c draws (llvmpipe's bins) */
            for (uint32_t c0 = 0; c0 < m->runs[r].count; c0 += chunk) {
                const uint32_t t0i = m->runs[r].first + c0;
                const uint32_t nt = m->runs[r].count - c0 < chunk ? m->runs[r].count - c0 : chunk;
                if (c0)
                    glFlush();
                glDrawElements(GL_TRIANGLES, (GLsizei)(3 * nt), GL_UNSIGNED_INT,
                               (const void *)((size_t)t0i * 3 * sizeof(uint32_t)));
            }
        }
    }
    sl_gl_timer_end(&gt);
    glFinish();
    double ms = 1e3 * (sl_now() - t0);
    glDisable(GL_CULL_FACE);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    p->costs.ms_map = ms;
    p->costs.gpu_map = sl_gl_timer_ms(&gt, ms);
    if (e) {
        glDisable(GL_DEPTH_TEST);
        return e;
    }
    e = sl_gl_check("technique map pass", d);
    if (!e && p->extra > 0)
        e = fill_extra(p, f, v, d);
    if (!e)
        e = post_passes(p, v, d);
    return e ? e : maps_finite(p, d);
}

enum sl_err sl_techpass_upload(struct sl_techpass *p, const struct sl_light_frame *f,
                               const struct sl_params *v, const float *const *texels, struct sl_diag *d)
{
    enum sl_err e = maps_ready(p, f, v, d);
    if (e)
        return e;
    const int N = p->size;
    for (int i = 0; i < p->t->nmaps; i++) {
        const struct sl_tech_map *m = &p->t->map[i];
        glTextureSubImage2D(p->map_tex[i], 0, 0, 0, N, N, fmt_upload[m->format], GL_FLOAT, texels[i]);
    }
    p->costs.ms_map = p->costs.gpu_map = 0.0;
    e = sl_gl_check("technique map upload", d);
    if (!e)
        e = post_passes(p, v, d);
    return e ? e : maps_finite(p, d);
}

/* ---- lookup ---- */

static enum sl_err lookup_make(struct sl_techpass *p, int w, int h, struct sl_diag *d)
{
    if (p->lw == w && p->lh == h)
        return SL_OK;
    if (p->lw)
        lookup_free(p);
    p->ones = malloc((size_t)w * (size_t)h);
    if (!p->ones)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "lookup mask %dx%d", w, h);
    memset(p->ones, 1, (size_t)w * (size_t)h);
    GLuint tex[4];
    glCreateTextures(GL_TEXTURE_2D, 4, tex);
    p->g_pos = tex[0];
    p->g_nrm = tex[1];
    p->g_mask = tex[2];
    p->out_tex = tex[3];
    glTextureStorage2D(p->g_pos, 1, GL_RGB32F, w, h);
    glTextureStorage2D(p->g_nrm, 1, GL_RGB32F, w, h);
    glTextureStorage2D(p->g_mask, 1, GL_R8UI, w, h);
    glTextureStorage2D(p->out_tex, 1, GL_R32F, w, h);
    for (int i = 0; i < 4; i++) {
        glTextureParameteri(tex[i], GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(tex[i], GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glCreateFramebuffers(1, &p->out_fbo);
    glNamedFramebufferTexture(p->out_fbo, GL_COLOR_ATTACHMENT0, p->out_tex, 0);
    glNamedFramebufferDrawBuffer(p->out_fbo, GL_COLOR_ATTACHMENT0);
    p->lw = w;
    p->lh = h;
    if (glCheckNamedFramebufferStatus(p->out_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        lookup_free(p);
        return sl_fail(d, SL_E_GL, NULL, 0, NULL, "lookup framebuffer incomplete (%dx%d)", w, h);
    }
    return sl_gl_check("technique lookup target", d);
}

enum sl_err sl_techpass_lookup(struct sl_techpass *p, const struct sl_light_frame *f,
                               const struct sl_params *v, const float *pos, const float *nrm,
                               const uint8_t *mask, int w, int h, float *vis, struct sl_diag *d)
{
    const struct sl_technique *t = p->t;
    if (!p->size)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "technique %s: lookup before its maps", t->name);
    if (w < 1 || h < 1)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "lookup grid %dx%d", w, h);
    double t0 = sl_now();
    enum sl_err e = lookup_make(p, w, h, d);
    if (e)
        return e;
    const size_t n = (size_t)w * (size_t)h;
    uint64_t pixels = 0;
    if (mask) {
        for (size_t i = 0; i < n; i++)
            pixels += mask[i] != 0;
    } else {
        pixels = n;
    }
    struct sl_gl_timer gt;
    sl_gl_timer_begin(&gt);
    glTextureSubImage2D(p->g_pos, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, pos);
    glTextureSubImage2D(p->g_nrm, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, nrm);
    /* the mask's rows are w bytes: packed, not padded to 4 (GL's default
     * alignment would read a width not a multiple of 4 past each row) */
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(p->g_mask, 0, 0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_BYTE, mask ? mask : p->ones);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindFramebuffer(GL_FRAMEBUFFER, p->out_fbo);
    glViewport(0, 0, w, h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(p->out_fbo, GL_COLOR, 0, zero);
    char file[1400];
    snprintf(file, sizeof file, "%s/%s", t->dir, t->lookup_shader);
    if (p->count_taps && !p->prog_taps) {
        char *src = sl_techsrc(t, SL_TECHSRC_LOOKUP_TAPS);
        e = src ? build(vs_full, src, &p->prog_taps, NULL, file, d)
                : sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "shader source");
        free(src);
        if (e)
            return e;
    }
    const GLuint prog = p->count_taps ? p->prog_taps : p->prog_lookup;
    glUseProgram(prog);
    set_light(prog, p, f);
    set_params(prog, t, v);
    for (int i = 0; i < t->nmaps; i++) {
        glBindTextureUnit((GLuint)i, p->map_tex[i]);
        glUniform1i(glGetUniformLocation(prog, t->map[i].name), i);
    }
    glBindTextureUnit(4, p->g_pos);
    glBindTextureUnit(5, p->g_nrm);
    glBindTextureUnit(6, p->g_mask);
    glUniform1i(glGetUniformLocation(prog, "sl_gpos"), 4);
    glUniform1i(glGetUniformLocation(prog, "sl_gnrm"), 5);
    glUniform1i(glGetUniformLocation(prog, "sl_gmask"), 6);
    glUniformMatrix4fv(glGetUniformLocation(prog, "sl_frame_vp"), 1, GL_FALSE, (const float *)f->box.vp);
    glUniform1f(glGetUniformLocation(prog, "sl_frame_size"), (float)f->size);
    glUniform1i(glGetUniformLocation(prog, "sl_guard"), p->guard);
    glUniform3f(glGetUniformLocation(prog, "sl_light_dir"), f->dir[0], f->dir[1], f->dir[2]);
    glUniform3f(glGetUniformLocation(prog, "sl_light_pos"), f->box.eye[0], f->box.eye[1], f->box.eye[2]);
    glUniform2f(glGetUniformLocation(prog, "sl_texel"), 1.0f / (float)p->size, 1.0f / (float)p->size);
    glUniform1f(glGetUniformLocation(prog, "sl_map_size"), (float)p->size);
    glUniform1f(glGetUniformLocation(prog, "sl_texel_world"), f->texel_world);
    glUniform1f(glGetUniformLocation(prog, "sl_depth_range"), f->depth_range);
    glUniform1f(glGetUniformLocation(prog, "sl_light_width"), p->light_width);
    glBindVertexArray(p->vao_empty);
    struct tiles tl;
    for (tiles_begin(&tl, SL_TECHPASS_LOOKUP, w, h, file, 0); tiles_next(p, &tl, &e, d);)
        glDrawArrays(GL_TRIANGLES, 0, 3);
    sl_gl_timer_end(&gt);
    glFinish();
    double t1 = sl_now();
    if (e) {
        for (int i = 0; i < 7; i++)
            glBindTextureUnit((GLuint)i, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glUseProgram(0);
        return e;
    }
    glGetTextureImage(p->out_tex, 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), vis);
    double t2 = sl_now();
    uint64_t bad = 0;
    for (size_t i = 0; i < n; i++)
        if (vis[i] < 0.0f && (!mask || mask[i])) {   /* the main's mark of a value not finite */
            vis[i] = NAN;
            bad++;
        }
    for (int i = 0; i < 7; i++)
        glBindTextureUnit((GLuint)i, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    p->costs.ms_lookup = 1e3 * (t1 - t0);
    p->costs.gpu_lookup = sl_gl_timer_ms(&gt, p->costs.ms_lookup);
    p->costs.ms_readback = 1e3 * (t2 - t1);
    p->costs.pixels = pixels;
    p->costs.nonfinite = bad;
    p->costs.lookups = (uint64_t)llround(sl_tech_taps(t, v) * (double)pixels);
    return sl_gl_check("technique lookup pass", d);
}
