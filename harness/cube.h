/*
 * cube.h — a point light's cube of shadow maps, and every hard-shadow
 * method run over it (issue 22).
 *
 * A point light shines every way, so one perspective frame cannot hold its
 * receivers: the cube has six, one per axis direction (lightfit.h,
 * sl_cube_face_of: face 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z), each a
 * perspective frame from the light's position along its axis, fitted to the
 * PFL pixels whose direction from the light selects the face (the major
 * axis of p - light; ties to the lower axis) with a guard band of
 * SL_CUBE_GUARD texels beyond them (lightfit.h, sl_light_fit_face).
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
 *
 * Each method runs once per face with receivers, on a copy of the view in
 * which the other faces' pixels are background (as methods/zpart.c runs
 * NSM per slice), and the verdicts are merged by face. Costs: the cell's
 * are summed over the faces (its ms_map_render is the six faces' renders
 * of each layer, its texels the six maps'); each face's own are kept here
 * (struct sl_cube_face_cost) for the run's per-face report. Scoring sees
 * which face served each pixel through sl_verdicts' frames and slice.
 *
 * Owns: the six frames (layers from the shadow-map pass's pool) and the
 * per-pixel face index. Does not: decide a verdict itself, print, or talk
 * to the store.
 */
#ifndef SL_CUBE_H
#define SL_CUBE_H
#include <stdint.h>
#include "frame.h"
#include "method.h"
#include "scene.h"
#include "shadowmap.h"
#include "view.h"

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
 * given back. `reps` = warmup + runs repetitions time each new layer as the
 * run times the cell's frame (the six faces' renders summed per
 * repetition); layer_ms, layer_gpu get {median, min, max} of those,
 * layer_bad the faces' bad depths, layers[l] one count per face rendered.
 * `stats`, the cell's own frame, gets the six faces' readback times,
 * primitives and fragments per layer (no arrays). */
struct sl_cube_timing {
    int warmup, runs;
    double (*layer_ms)[3], (*layer_gpu)[3];
    uint64_t *layer_bad;
    int *layers;
    int threads;   /* of the faces' fit (lightfit.h, _mt; <= 0: every core) */
};
enum sl_err sl_cube_ensure(struct sl_cube *cb, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
                           const struct sl_scene *s, const struct sl_view *v, int map, int size, unsigned now,
                           unsigned keep, const struct sl_cube_timing *t, struct sl_light_frame *stats,
                           struct sl_diag *d);

/* Method m over a point light's cube (per face, merged; out gets the six
 * frames and the face per pixel for scoring), or m->run itself when the
 * cube holds nothing (not a point light: cb->map1 = 0) or m reads no layer
 * (raytrace: its rays go to the light's position whatever the frame, so
 * one run is the answer; it costs no face). */
enum sl_err sl_cube_method_run(struct sl_cube *cb, const struct sl_method *m, const struct sl_method_args *a,
                               struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d);

/* Verdicts copied from another run of the cube (the contour's NSM): hand
 * them the cube's frames and faces again. No-op without a cube. */
enum sl_err sl_cube_mark(const struct sl_cube *cb, struct sl_verdicts *out, struct sl_diag *d);

/* A cell's per-face costs (cellcols.h): the faces the last method run ran
 * on and its time on the slowest; 0 and NAN when it ran once (no cube, or
 * a method reading no layer). A cell that reuses the contour's NSM run (run.c)
 * reads the cube's last run: the contour's when its label's cell is the
 * group's first, as in every config here (nsm listed first). */
void sl_cube_cell_costs(const struct sl_cube *cb, uint64_t *faces, double *ms_face_max);

/* Every face's layers back to the pool, the face index freed; map1 = 0. */
void sl_cube_drop(struct sl_cube *cb);

#endif
