/*
 * lightframe.h — the light frame of a view beyond one fit (frame.h,
 * lightfit.h): its layers rendered on demand, timed and gathered per pixel;
 * a point light's cube of six frames; the frames of labels with a
 * stabilised light frame of their own (config light_frame, lightfit.h).
 *
 * The cube (issue 22). A point light shines every way, so one perspective
 * frame cannot hold its receivers: the cube has six, one per axis direction
 * (lightfit.h, sl_cube_face_of: face 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z),
 * each a perspective frame from the light's position along its axis,
 * fitted to the PFL pixels whose direction from the light selects the face
 * (the major axis of p - light; ties to the lower axis) with a guard band
 * of SL_CUBE_GUARD texels beyond them (lightfit.h, sl_light_fit_face).
 *
 * Seams. A method's lookups read up to one texel beyond the receiver's own
 * (the 3x3 neighbourhoods of coherence and neighbours; texel and the chain
 * read the same), and the conservative layers enlarge each triangle by
 * half a texel's diagonal plus their margins (frame.h). Every triangle is
 * drawn into every face (GL clips it to the face's frustum, guard band
 * included), so a lookup that crosses the face's edge reads the
 * neighbouring face's geometry, rendered into this face's own band at this
 * face's texel grid: no lookup reads a border, a clamp or another face's
 * map. The conservative layers hold every triangle touching a texel of
 * the band exactly as anywhere else in the map, so they stay conservative
 * across the seam; a triangle crossing the face's plane is listed as
 * unmapped and tested on the CPU (lightfit.c), as under a spot light.
 * Running a method over the faces and merging its verdicts is the
 * methods' side (methods/cuberun.h).
 *
 * Owns: the cube's six frames (layers from the shadow-map pass's pool) and
 * its per-pixel face index; the labels' own frames. Does not: run a
 * method, decide a verdict, print, or talk to the store; it reads no
 * config (the run passes the counts and sizes it needs).
 */
#ifndef SL_LIGHTFRAME_H
#define SL_LIGHTFRAME_H
#include <stdint.h>
#include "frame.h"
#include "lightfit.h"
#include "scene.h"
#include "shadowmap.h"
#include "reps.h"
#include "view.h"

/* How the layers rendered are timed and counted: each new layer's render
 * is its real computation, then repeated (timed only) as reps says
 * (reps.h; NULL: not repeated); layer_ms, layer_gpu get {median, min, max}
 * of the timed runs (reps.h), layer_runs how many were timed, layer_bad the
 * bad depths (sl_layer_bad), layers[l] one count per layer (per face for a
 * cube) rendered. Any pointer may be NULL: not wanted. */
struct sl_layer_timing {
    struct sl_reps *reps;
    double (*layer_ms)[3], (*layer_gpu)[3];
    uint64_t *layer_bad;
    int *layers;
    int *layer_runs;
    int threads;   /* of the per-pixel gather and the faces' fit (lightfit.h, _mt; <= 0: every core) */
};

/* Shadow-map depths outside [0, 1] or not finite. */
uint64_t sl_layer_bad(const struct sl_depth_layer *l, int size);

/* The layers in `set` that f lacks rendered into it (one render each, then
 * t->reps's timed repetitions into a scratch copy of the frame, timings
 * and bad values into t), then those in `gather` gathered
 * per pixel of v (sl_frame_gather) once their repetitions are done. */
enum sl_err sl_frame_render_timed(struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m, struct sl_light_frame *f,
                                  unsigned set, unsigned gather, const struct sl_view *v,
                                  const struct sl_layer_timing *t, struct sl_diag *d);

/* Guard band, texels: the reach every method's lookup is allowed
 * (frame.h, SL_GUARD_TEXELS, where a method author reads it). */
#define SL_CUBE_GUARD SL_GUARD_TEXELS

struct sl_cube_face_cost {
    uint32_t receivers;   /* PFL pixels the face holds */
    uint32_t casters;     /* triangles that can shadow them (lightfit.h) */
    uint32_t unmapped;    /* of which out of the conservative layers */
    double   ms_method;   /* the last method run on the face */
    uint64_t lookups, rays, tri_tests;
};

struct sl_cube {
    int      map1;         /* map index + 1 the faces are for; 0 none (a zeroed cube is empty) */
    int      size;
    size_t   npx;
    uint8_t *face;         /* per pixel: its face 0..5 (every pixel has one) */
    struct sl_light_frame f[6];   /* size 0: a face without receivers (no map) */
    struct sl_cube_face_cost cost[6];
    double   ms_fit;
    int      ran;          /* faces the last sl_cube_method_run ran on (0: it ran the method once) */
};

/* The cube of view v at map index `map` of size `size`: the faces fitted on
 * a new (view, map) (the cube is dropped with the frame), then the layers in
 * `now` rendered into each face with receivers, and those not in `keep`
 * given back. Each new layer is repeated as t->reps says, as the run times
 * the cell's frame (a repetition renders the six faces again: their times
 * summed); layer_ms, layer_gpu get {median, min, max} of those,
 * layer_bad the faces' bad depths, layers[l] one count per face rendered.
 * `stats`, the cell's own frame, gets the six faces' readback times,
 * primitives and fragments per layer (no arrays). */
enum sl_err sl_cube_ensure(struct sl_cube *cb, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
                           const struct sl_scene *s, const struct sl_view *v, int map, int size, unsigned now,
                           unsigned keep, const struct sl_layer_timing *t, struct sl_light_frame *stats,
                           struct sl_diag *d);

/* Every face's layers back to the pool, the face index freed; map1 = 0. */
void sl_cube_drop(struct sl_cube *cb);

/* Frames of labels whose light_frame is not the shared tight fit: one per
 * (map size, fit), fitted for each view and rendered once with the layers
 * the labels' methods need (added when a later label needs more). A view
 * whose fit gives the very same box (same matrices, same light) keeps the
 * rendered layers: the frame is shared between frames of a path where a
 * fixed-size frame did not move. Dropped with the scene. At most
 * SL_ALT_FRAMES kinds per scene. */
#define SL_ALT_FRAMES 4
struct sl_alt_frames {
    int n;
    struct {
        int map;
        struct sl_fit_opts fit;
        int vp, vw, vh;               /* the view it was last fitted for: viewpoint, viewport */
        struct sl_light_frame f;
    } e[SL_ALT_FRAMES];
};
/* *out: the frame of (map, fit o) of view v, with the layers in needs;
 * layers[l] counts each layer rendered. */
enum sl_err sl_alt_frame(struct sl_alt_frames *a, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
                         const struct sl_scene *s, const struct sl_view *v, int map, int size,
                         const struct sl_fit_opts *o, unsigned needs, struct sl_light_frame **out, int *layers,
                         struct sl_diag *d);
void sl_alt_frames_free(struct sl_alt_frames *a);

#endif
