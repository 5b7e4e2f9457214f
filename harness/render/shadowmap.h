/*
 * shadowmap.h — light-space passes: a 32-bit float depth buffer and an R32UI
 * buffer holding the id (+1) of the nearest triangle per texel, rendered from
 * the fitted orthographic box and read back.
 *
 * Owns: the programs for its layers, and the framebuffers and textures they
 * render into, one set per map size, made once and reused by every layer,
 * frame and repetition of that size (llvmpipe zeroes each new texture in
 * fresh memory: the largest single cost of a study before they were kept).
 * Does not: look anything up (methods do, with sl_frame_project /
 * sl_frame_texel).
 */
#ifndef SL_SHADOWMAP_H
#define SL_SHADOWMAP_H
#include "frame.h"
#include "glctx.h"

/* A map size's render target: depth32F + R32UI. BGSM2 reads BGSM's ids
 * straight from tex[1] (drawn with no colour attachment: its own ids are
 * read by no one), so no copy of them is kept; ids_stamp says whose ids
 * tex[1] holds, and BGSM2 uploads BGSM's from the frame when they are not
 * the ones there. */
struct sl_shadowmap_target {
    int      size;              /* 0: slot unused */
    GLuint   fbo, tex[2];
    uint64_t used;              /* the pass's tick when last used (least recently used goes first) */
    uint64_t ids_stamp;         /* sl_depth_layer.stamp of the layer whose ids tex[1] holds, 0: none known */
};
#define SL_SHADOWMAP_TARGETS 4
/* Targets kept beside the one being made, in bytes of texture: every size
 * of a study up to 4096^2 stays (170 MiB for 512^2..4096^2); an 8192^2 or
 * 16384^2 one pushes the others out. */
#define SL_SHADOWMAP_KEEP_BYTES ((size_t)256 << 20)
/* Triangles per draw call of a layer: llvmpipe bins a whole draw before it
 * rasterises, so the bins of a big draw at a big map size stay in memory
 * together; a flush between chunks hands them over (shadowmap.c). */
#define SL_SHADOWMAP_CHUNK 8192u
/* Big targets are kept too. Freeing one after its layer (and its id
 * texture before the depth array is taken) was tried and measured worse:
 * Mesa's state tracker hands the GL state to llvmpipe only at the next
 * layer's draw, so a freed target's textures lived on until after the next
 * one was made — 2,553 MiB peak for bench --only bigmap --map 8192 (with a
 * 1x1 clear or draw in between, which did not release them), against
 * 2,036 MiB kept. */

struct sl_shadowmap_pass {
    struct sl_shadowmap_target tgt[SL_SHADOWMAP_TARGETS];
    uint64_t tick;
    uint64_t targets_made;      /* render targets created, all told (tests, bench) */
    uint64_t stamps;            /* the last sl_depth_layer.stamp handed out */
    uint64_t ids_uploads;       /* BGSM2 layers that had to upload BGSM's ids (tests, bench) */
    uint32_t chunk;             /* triangles per draw call, flushed between (SL_SHADOWMAP_CHUNK; tests vary it) */
    struct sl_layer_pool pool;  /* layer arrays for the frames that take them (f->pool = &pass->pool);
                                 * freed by sl_shadowmap_free: free those frames first */
    struct sl_layer_pool pix_pool;  /* the same for layers gathered per pixel (f->pix_pool, frame.h) */
    GLuint prog_depth_id;
    /* conservative layers, one program each (BGSM, BGSM2, SGSM: geometry
     * shader + exact per-texel tests; SGSM with adjacency:
     * GL_TRIANGLES_ADJACENCY input, drawn as two programs: [4] the
     * triangles that keep no edge, then [3] the others), specialised so
     * that no layer pays for another's code */
    GLuint prog_cons[5];
};

enum sl_err sl_shadowmap_init(struct sl_shadowmap_pass *p, struct sl_diag *d);
void        sl_shadowmap_free(struct sl_shadowmap_pass *p);
/* Free the kept render targets (not the programs, not the pool): the next
 * layer of each size makes its own again. */
void        sl_shadowmap_release_targets(struct sl_shadowmap_pass *p);

/* Render the layers in `needs` (SL_NEED bits) into f, whose size, dir and box
 * are set by the caller. Layers already present are not rendered again.
 * The arrays come from f->pool when it has one. BGSM2's id array is not
 * read back (NULL): no method reads it, and at 16384^2 it is 1 GiB. */
enum sl_err sl_shadowmap_render(struct sl_shadowmap_pass *p, const struct sl_gl_mesh *m,
                                struct sl_light_frame *f, unsigned needs, struct sl_diag *d);

#endif
