/*
 * techpass.h — a technique package (technique.h) on the GL: its map pass
 * per light frame, the post passes, and its lookup over a grid of points.
 *
 * Map pass: the package's map shader (`#version 450 core`, the harness
 * prelude, `#line 1 1`, the package file, the harness main calling
 * sl_map(gl_FragCoord.z)) into maps of S + 2g texels, g the guard band
 * (sl_tech_guard): the light frame's clip x, y scaled by S / (S + 2g), so a
 * texel is as wide as the frame's and texel (i, j) of the frame is texel
 * (i + g, j + g) of the maps (with g = 0 the frame's own matrix, unscaled:
 * the same bits as the C depth layers' pass). First a fullscreen pass of
 * sl_map(1.0) (empty texels), then the scene with a depth test (depth
 * cleared to 1, GL_LESS) and the package's culling (two-sided runs never
 * culled, as shadowmap.c). Post passes per map: a separable box blur of
 * radius r (2r + 1 taps, clamped inside the guarded map; harness shader,
 * two passes through a ping-pong texture), then mipmaps.
 *
 * Lookup pass: a fullscreen triangle over a w x h R32F target; per pixel
 * the G-buffer's position and normal (CPU arrays, 3 floats a pixel, index
 * y * w + x), skipped where mask is 0; the light-clip position computed as
 * sl_frame_project computes it on the CPU (the same float operations in the
 * same order, with the frame's own matrix and size, division correctly
 * rounded), so a package that compares depths with texels picks the texel
 * and the depth a C method would; then sl_lookup, clamped to [0, 1]. A
 * value sl_lookup returns that is not finite (NaN, +-inf) is not clamped
 * into a shadow: it comes back as NaN and is counted (costs.nonfinite).
 * After the map and post passes the maps' texels that are not finite are
 * counted on the GL (costs.map_nonfinite: an rgba16f map overflows to inf
 * where a float32 one would not).
 *
 * Prelude additions to the contract (set by the harness before sl_lookup):
 *   ivec2 sl_home_texel;  the texel the point lands in, in the guarded map:
 *                         (floor(u) + g, floor(v) + g), not clamped
 *   vec2  sl_map_pos;     (u + g, v + g): the point in texels of the guarded
 *                         map (uv * sl_map_size up to rounding)
 *   ivec2 sl_pixel;       the view pixel looked up (gl_FragCoord.xy of the
 *                         lookup pass; x + y * w its index in the arrays)
 *
 * Bounded tiles: a package's shader may run for minutes (a loop), and the
 * GL cannot cancel a draw. So the map pass, the blur and the lookup are
 * drawn in scissor rectangles, each followed by glFinish; between two the
 * caller's limits (struct sl_techpass_limits) are checked and the driver's
 * reset status read. A tile's area follows the pass's measured speed, from
 * 8 x 8 pixels up, aiming at SL_TECHPASS_TILE_SECONDS a tile, so a stop
 * waits for about that long, not for the pass. The map pass's scene is
 * drawn again in each of its tiles, which are therefore at least 1/64 of
 * the map; its empty texels (every texel, the package's map shader) come
 * first in tiles of their own, from 8 x 8 up, where a map shader that
 * runs away is caught. The scissor test is on for
 * the whole pass (GL's invariance rules exempt the rectangle, not the
 * enable) and only discards fragments outside the tile, which are drawn by
 * another: the tiles change no texel and no visibility. A pass the limits
 * end leaves no result: the caller gets an error, never a partial map.
 *
 * GLSL errors of a package name its file and line: `DIR/lookup.glsl:LINE:
 * GLSL: message`, SL_E_PACKAGE, the driver's log read by
 * sl_techsrc_log_error (its errors first, then its warnings). The shaders'
 * text is techsrc.h's, which techcheck.h compiles without GL at validate.
 *
 * Owns: the programs, the maps, their ping-pong and depth buffers, the
 * lookup's G-buffer textures and target, kept across calls and remade when
 * a size changes (sl_techpass_free).
 * Does not: own the technique (borrowed, must outlive the pass), decide
 * verdicts (a caller applies the threshold), read the truth.
 */
#ifndef SL_TECHPASS_H
#define SL_TECHPASS_H
#include <stdint.h>
#include "frame.h"
#include "glctx.h"
#include "technique.h"

/* What the last map/post/lookup calls cost: wall ms and GL_TIME_ELAPSED ms
 * (sl_gl_timer; NaN when not measured). */
struct sl_techpass_costs {
    double ms_map, gpu_map;         /* the map pass (empty texels + the scene) */
    double ms_post, gpu_post;       /* every post pass together (blur, mipmaps) */
    double ms_lookup, gpu_lookup;   /* the lookup pass, G-buffer upload included */
    double ms_readback;             /* the visibility read back */
    uint64_t lookups;               /* taps x pixels looked up */
    uint64_t pixels;                /* pixels looked up */
    uint64_t nonfinite;             /* of those, looked up as NaN or +-inf (vis NaN there) */
    uint64_t map_nonfinite;         /* texels of the maps (level 0, guard band too) not finite */
    int guard;                      /* g, texels */
    int map_size;                   /* S + 2g */
};

/* What ends a pass between two tiles; zero: nothing. */
struct sl_techpass_limits {
    const volatile int *stop;   /* non-zero (a signal): SL_E_STOPPED */
    double pass_seconds;        /* > 0: a pass running longer fails, SL_E_PACKAGE naming the
                                 * package's file and the pass */
};

/* A tile's aim, seconds: a stop waits for one tile. */
#define SL_TECHPASS_TILE_SECONDS 0.25

/* The passes drawn in tiles, each with its own measured speed: the map
 * pass as its empty texels (a fullscreen pass) and then its scene. */
enum sl_techpass_kind {
    SL_TECHPASS_EMPTY, SL_TECHPASS_SCENE, SL_TECHPASS_BLUR, SL_TECHPASS_LOOKUP, SL_TECHPASS_KINDS
};

struct sl_techpass {
    const struct sl_technique *t;
    GLuint prog_map, prog_empty, prog_lookup, prog_blur, prog_finite;
    GLuint vao_empty;               /* for the fullscreen triangles */
    /* the maps of the last frame, size N = S + 2g */
    int size, guard, levels;
    GLuint map_tex[SL_TECH_MAX_MAPS], ping_tex[SL_TECH_MAX_MAPS];
    GLuint map_fbo, blur_fbo, depth_rb;
    float light_vp[16];             /* the guarded map's matrix (column-major) */
    /* the lookup's inputs and target, size lw x lh */
    int lw, lh;
    GLuint g_pos, g_nrm, g_mask, out_tex, out_fbo;
    uint8_t *ones;                  /* lw * lh ones: the mask when none is given */
    struct sl_techpass_costs costs;
    /* the lookup's sl_light_width: an area light's width in world units
     * (the larger side), 0 for a light without one; the caller sets it */
    float light_width;
    int max_tex;                    /* GL_MAX_TEXTURE_SIZE */
    struct sl_techpass_limits limits;   /* the caller sets it */
    double tile_px[SL_TECHPASS_KINDS];  /* the next tile's area, pixels (0: the smallest) */
    int tiles;                      /* tiles drawn since init */
    double tile_max_px;             /* tests: tiles of at most this area (0: no bound) */
    /* The package's test (`shadowlab test technique`), zero in a run:
     * extra > 0 grows the maps by `extra` texels a side beyond the guard
     * band the package declares (sl_home_texel and sl_map_pos move with
     * it) and, after the map pass and before the post passes, fills those
     * texels with sl_map(fill) (0: a surface at the near plane, 1: none),
     * so a lookup that reads beyond its reach reads what the fill chose;
     * count_taps makes the lookup return, for each pixel, the texel reads
     * it made (techsrc.h, SL_TECHSRC_LOOKUP_TAPS) instead of its
     * visibility. */
    int extra;
    float fill;
    int count_taps;
    GLuint prog_taps;               /* compiled at the first lookup with count_taps */
};

/* Compile the package's programs (map, empty-texel and lookup) and the
 * harness's blur. SL_E_PACKAGE with the package file's line for a GLSL
 * error in it, SL_E_GL for the harness's own. */
enum sl_err sl_techpass_init(struct sl_techpass *p, const struct sl_technique *t, struct sl_diag *d);
void        sl_techpass_free(struct sl_techpass *p);

/* The guard band and map size for frame f at values v, checked: SL_E_METHOD
 * naming the parameter (sl_tech_guard_param) when S + 2g exceeds the GL's
 * maximum texture size or SL_TECH_MAX_MAP_SIZE. */
enum sl_err sl_techpass_size(struct sl_techpass *p, const struct sl_light_frame *f,
                             const struct sl_params *v, int *guard, int *size, struct sl_diag *d);

/* Render the maps of light frame f (f->size, f->box.vp, ...) with mesh m,
 * then the post passes. */
enum sl_err sl_techpass_render(struct sl_techpass *p, const struct sl_gl_mesh *m, const struct sl_light_frame *f,
                               const struct sl_params *v, struct sl_diag *d);

/* For tests: the guarded maps' texels given directly, texels[i] holding
 * N * N * channels floats of map i (N = S + 2g from sl_techpass_size, rows
 * from the bottom, channels as its format: 1, 2, 4 or 4), then the post
 * passes, as if rendered. */
enum sl_err sl_techpass_upload(struct sl_techpass *p, const struct sl_light_frame *f,
                               const struct sl_params *v, const float *const *texels, struct sl_diag *d);

/* Look up the points of a w x h grid in the maps of frame f (rendered or
 * uploaded last): pos, nrm 3 floats per point, mask NULL (all) or 0 = skip;
 * vis gets w * h visibilities in [0, 1] (skipped points: 0). */
enum sl_err sl_techpass_lookup(struct sl_techpass *p, const struct sl_light_frame *f,
                               const struct sl_params *v, const float *pos, const float *nrm,
                               const uint8_t *mask, int w, int h, float *vis, struct sl_diag *d);

#endif
