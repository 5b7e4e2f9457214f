/*
 * glctx.h — the OpenGL 4.5 core context (no window) and the scene's GL
 * buffers.
 *
 * Owns: the one context of the process, from one of two backends: OSMesa
 * (Mesa's off-screen library, removed from Mesa 25.1) or EGL (surfaceless;
 * an EGL device chosen as glegl.c says: hardware first, the software device
 * or EGL_PLATFORM_SURFACELESS_MESA as fallbacks). All passes render into
 * their own framebuffer objects, never into a window-system buffer, so
 * everything above the context is shared. Also the scene's vertex and index
 * buffers (uploaded once per scene).
 * Does not: decide what to render (gbuffer.c, shadowmap.c do), or read back.
 * GL entry points: all looked up through the backend (glfn.h says why).
 */
#ifndef SL_GLCTX_H
#define SL_GLCTX_H
#include <GL/gl.h>
#include <GL/glext.h>
#include "glfn.h"
#include "scene.h"
#include "glbackend.h"
#include "sl_error.h"

struct sl_gl_desc {
    enum sl_gl_backend backend;   /* SL_GL_DEFAULT = OSMesa where built, else EGL */
};

struct sl_gl {
    enum sl_gl_backend backend;   /* the one in use */
    void *osmesa;                 /* OSMesaContext */
    unsigned char pixel[4];       /* the 1x1 OSMesa surface we make current */
    void *egl_display, *egl_ctx;  /* EGLDisplay, EGLContext */
    char renderer[128];
    char version[128];
    /* EGL: what was used, e.g. "device 0 (EGL_MESA_device_software), vendor Mesa
     * Project" or "surfaceless (Mesa Project)"; OSMesa: "". */
    char device[160];
};

/* The default backend (zero desc). SL_E_USAGE: a backend not built, a bad
 * SHADOWLAB_GL (checked even when desc names a backend) or SHADOWLAB_EGL_DEVICE; SL_E_GL: no display, no 4.5 core context, or an entry
 * point missing. */
enum sl_err sl_gl_init(struct sl_gl *g, struct sl_diag *d);
enum sl_err sl_gl_open(struct sl_gl *g, const struct sl_gl_desc *desc, struct sl_diag *d);
void        sl_gl_free(struct sl_gl *g);

/* "osmesa" or "egl <device>": the backend and device, for provenance. */
void sl_gl_describe(const struct sl_gl *g, char *buf, size_t n);

/* Link a program from sources (gs may be NULL); 0 and diag on failure. */
GLuint sl_gl_program(const char *vs, const char *gs, const char *fs, struct sl_diag *d);

/* GPU time of a pass: a GL_TIME_ELAPSED query (core since 3.3) around the
 * pass's clears and draws. Only one may be open at a time. Its result is read
 * by sl_gl_timer_ms after the pass's readback, which has already waited for
 * the GPU, so reading it adds no stall to what the wall clock measures. On
 * llvmpipe "GPU" time is the rasteriser threads' span, reported as it is. */
struct sl_gl_timer { GLuint q; };
void   sl_gl_timer_begin(struct sl_gl_timer *t);
void   sl_gl_timer_end(struct sl_gl_timer *t);
/* Elapsed ms (waits for the result if not ready); frees the query. NaN (not
 * measured) when the result lies outside [0, wall_ms], the wall time of a
 * bracket that holds the query: no working timer can report that. llvmpipe
 * does for a query begun before any work of a fresh context (no rasteriser
 * thread records a start, and the result is the time since boot). */
double sl_gl_timer_ms(struct sl_gl_timer *t, double wall_ms);

/* glGetError after a pass, as an sl_err naming the pass. */
enum sl_err sl_gl_check(const char *what, struct sl_diag *d);

/* Runs of triangles drawn with the same face culling: one-sided meshes may
 * be culled, two-sided ones (leaves) never are. Consecutive scene meshes of
 * the same sidedness are merged into one run. */
struct sl_gl_run { uint32_t first, count; int two_sided; };

struct sl_gl_mesh {
    GLuint vao, vbo, ebo;
    GLsizei count;            /* indices */
    GLuint vao_adj, ebo_adj;  /* GL_TRIANGLES_ADJACENCY indices, 6 per triangle, when uploaded */
    struct sl_gl_run *runs;
    int nruns;
};
enum sl_err sl_gl_mesh_upload(struct sl_gl_mesh *m, const struct sl_scene *s, struct sl_diag *d);
void        sl_gl_mesh_free(struct sl_gl_mesh *m);

struct sl_adjacency;
/* The GL_TRIANGLES_ADJACENCY index buffer from the scene's edge adjacency:
 * per triangle v0, opposite(v0 v1), v1, opposite(v1 v2), v2, opposite(v2 v0);
 * an open or non-manifold edge repeats its first vertex ("no neighbour"). */
enum sl_err sl_gl_mesh_upload_adjacency(struct sl_gl_mesh *m, const struct sl_scene *s,
                                        const struct sl_adjacency *a, struct sl_diag *d);

#endif
