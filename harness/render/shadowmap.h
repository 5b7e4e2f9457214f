/*
 * shadowmap.h — light-space passes: a 32-bit float depth buffer and an R32UI
 * buffer holding the id (+1) of the nearest triangle per texel, rendered from
 * the fitted orthographic box and read back.
 *
 * Owns: the programs for its layers. Does not: look anything up (methods do,
 * with sl_frame_project / sl_frame_texel).
 */
#ifndef SL_SHADOWMAP_H
#define SL_SHADOWMAP_H
#include "frame.h"
#include "glctx.h"

struct sl_shadowmap_pass {
    GLuint prog_depth_id;
    /* conservative layers, one program each (BGSM, BGSM2, SGSM: geometry
     * shader + exact per-texel tests; SGSM with adjacency:
     * GL_TRIANGLES_ADJACENCY input), specialised so that no layer pays for
     * another's code */
    GLuint prog_cons[4];
};

enum sl_err sl_shadowmap_init(struct sl_shadowmap_pass *p, struct sl_diag *d);
void        sl_shadowmap_free(struct sl_shadowmap_pass *p);

/* Render the layers in `needs` (SL_NEED bits) into f, whose size, dir and box
 * are set by the caller. Layers already present are not rendered again. */
enum sl_err sl_shadowmap_render(const struct sl_shadowmap_pass *p, const struct sl_gl_mesh *m,
                                struct sl_light_frame *f, unsigned needs, struct sl_diag *d);

#endif
