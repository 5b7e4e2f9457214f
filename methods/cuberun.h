/*
 * cuberun.h — every hard-shadow method run over a point light's cube of
 * shadow maps (issue 22; the cube itself: lightframe.h).
 *
 * Each method runs once per face with receivers, on a copy of the view in
 * which the other faces' pixels are background (as methods/zpart.c runs
 * NSM per slice), and the verdicts are merged by face. A technique package
 * (SL_NEED_OWN_MAPS) runs the same way: its map, post and lookup passes
 * per face, over the face's perspective frame; its visibility and its
 * count of texels not finite are merged too. Costs: the cell's
 * are summed over the faces (its ms_map_render is the six faces' renders
 * of each layer, its texels the six maps'); each face's own are kept in
 * the cube (struct sl_cube_face_cost) for the run's per-face report.
 * Scoring sees which face served each pixel through sl_verdicts' frames
 * and slice.
 *
 * Owns: nothing (the faces are the cube's). Does not: decide a verdict
 * itself, print, or talk to the store.
 */
#ifndef SL_CUBERUN_H
#define SL_CUBERUN_H
#include <stdint.h>
#include "lightframe.h"
#include "method.h"

/* Method m over a point light's cube (per face, merged; out gets the six
 * frames and the face per pixel for scoring), or m->run itself when the
 * cube holds nothing (not a point light: cb->map1 = 0) or m reads no layer
 * and renders no maps of its own (raytrace: its rays go to the light's
 * position whatever the frame, so one run is the answer; it costs no
 * face). */
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

#endif
