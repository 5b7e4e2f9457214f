/*
 * gbuffer.h — the camera G-buffer pass: world position (RGBA32F), triangle
 * id + 1 (R32UI, 0 = background; the top bit marks a back face seen) and a
 * 32-bit float depth buffer; read back into an sl_view with the face normal
 * of each pixel's triangle turned toward the camera (by that bit), then
 * every pixel classified as background, PnFL or PFL against the scene's
 * light.
 *
 * Does not: decide lit or shadowed (truth.c does for the reference, methods
 * for themselves).
 */
#ifndef SL_GBUFFER_H
#define SL_GBUFFER_H
#include "glctx.h"
#include "view.h"

/* Owns its program, and its framebuffer, textures and readback array for
 * the last viewport size, kept from one render to the next (a new texture
 * is zeroed by llvmpipe in fresh memory; a new 1920x1080 RGBA32F readback
 * array is 33 MB of page faults). */
struct sl_gbuffer_pass {
    GLuint prog;
    int    w, h;                /* size of the kept target; 0 none */
    GLuint fbo, tex[2], depth;
    float *rgba;                /* w*h*4 readback of the positions */
    /* A view's arrays given back (sl_gbuffer_give_back), taken by the next
     * render of the same size: a view of 1024 x 1024 is 30 MB, and made
     * afresh for every view it was zeroed (calloc) or faulted page by
     * page. Empty (w 0) while a view holds them. */
    struct sl_view spare;
};

/* p zeroed: makes the pass; p made before (for another scene): keeps it,
 * with its target. Either way checks that s's ids fit. */
enum sl_err sl_gbuffer_init(struct sl_gbuffer_pass *p, const struct sl_scene *s, struct sl_diag *d);
void        sl_gbuffer_free(struct sl_gbuffer_pass *p);

/* Render viewpoint vp at w x h and fill v (pos, nrm, tri, cls; truth set to
 * SL_T_BACKGROUND / SL_T_PNFL, and SL_T_LIT for PFL pixels until truth.c
 * traces them). Times in ms go to *ms_render and *ms_readback (wall) and
 * *ms_gpu (GL_TIME_ELAPSED of the clears and the draw) when not NULL.
 * v NULL: a timed repetition only, the same render and readback (into the
 * pass's own buffer) and no view made. v's arrays are the pass's spare
 * ones when it holds some of this size, else new. */
enum sl_err sl_gbuffer_render(struct sl_gbuffer_pass *p, const struct sl_gl_mesh *m,
                              const struct sl_scene *s, int vp, int w, int h,
                              struct sl_view *v, double *ms_render, double *ms_readback,
                              double *ms_gpu, struct sl_diag *d);

/* Hand v's arrays to p for its next render (any spare ones it held are
 * freed) and zero v; v's arrays must have come from sl_gbuffer_render
 * with p. */
void sl_gbuffer_give_back(struct sl_gbuffer_pass *p, struct sl_view *v);

/* Camera matrices of a viewpoint at an aspect ratio. */
void sl_camera_matrices(const struct sl_viewpoint *vp, float aspect, mat4 view, mat4 proj);

#endif
