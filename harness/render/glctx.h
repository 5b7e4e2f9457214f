/*
 * glctx.h — the OpenGL 4.5 core context (OSMesa, no window) and the scene's
 * GL buffers.
 *
 * Owns: the OSMesa context (one per process; all passes render into their own
 * framebuffer objects, never into the OSMesa buffer), the scene's vertex and
 * index buffers (uploaded once per scene).
 * Does not: decide what to render (gbuffer.c, shadowmap.c do), or read back.
 * GL entry points come from libOSMesa itself (GL_GLEXT_PROTOTYPES): libepoxy
 * aborts under OSMesa, and OSMesa exports every gl* symbol.
 */
#ifndef SL_GLCTX_H
#define SL_GLCTX_H
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include "glfn.h"
#include "scene.h"
#include "sl_error.h"

struct sl_gl {
    OSMesaContext ctx;
    unsigned char pixel[4];   /* the 1x1 OSMesa surface we make current */
    char renderer[128];
    char version[128];
};

enum sl_err sl_gl_init(struct sl_gl *g, struct sl_diag *d);
void        sl_gl_free(struct sl_gl *g);

/* Link a program from sources (gs may be NULL); 0 and diag on failure. */
GLuint sl_gl_program(const char *vs, const char *gs, const char *fs, struct sl_diag *d);

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
