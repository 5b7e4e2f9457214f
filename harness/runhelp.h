/*
 * runhelp.h — small checks of the run loop (run.c), kept apart so run.c
 * stays within its size limit: values of a view and of a shadow-map layer
 * that are not finite or out of range; the frames of labels with a
 * stabilised light frame of their own (config light_frame, lightfit.h).
 *
 * Owns: nothing. Does not: print or decide anything (the run counts them
 * into the cell's `nonfinite`).
 */
#ifndef SL_RUNHELP_H
#define SL_RUNHELP_H
#include <stdint.h>
#include "frame.h"
#include "config.h"
#include "cube.h"
#include "lightfit.h"
#include "shadowmap.h"
#include "view.h"

/* Repetitions of a timed stage: the config's warm-up runs, then its timed
 * runs; the stage's real computation is repetition 0, so a config with one
 * run and no warm-up times each stage once and repeats nothing. */
#define SL_MAX_REPS 1100   /* config: warm-up <= 100, runs <= 1000 */

/* G-buffer values that are not finite (positions, normals of non-background
 * pixels). A hard case must never produce one (tests/test_hard.c). */
uint64_t sl_run_view_bad(const struct sl_view *v);

/* {median, min, max} (SL_MED, SL_MIN, SL_MAX of cellcols.h) of n >= 1
 * times (sorted in place), NaN ones (a GPU timer that failed, glctx.h)
 * left out; all NaN: NaN (not measured). */
void sl_run_med_min_max(double *t, int n, double out[3]);

/* The config's first label whose run is the contour's NSM (method nsm,
 * front faces culled: the configured parameters are then exactly those),
 * -1 none (run.c: contour_from nsm). */
int sl_run_contour_label(const struct sl_config *c);

/* Shadow-map depths outside [0, 1] or not finite. */
uint64_t sl_run_layer_bad(const struct sl_depth_layer *l, int size);

/* Each pixel's lookup in the dense layers method m reads (needs) and
 * declares (looks), once per (frame, view) for every such method of the
 * view (frame.h: sl_frame_look). Made only where two readers or more
 * share them (`shared`: layers so read by the rest of the group, plan.h),
 * on the view's own frame (own_frame): one reader alone would pay a pass
 * and its arrays for nothing. Lookups made already get the parts m asks
 * for. */
enum sl_err sl_run_make_looks(struct sl_light_frame *f, int own_frame, const struct sl_view *v,
                              const struct sl_method *m, unsigned needs, unsigned shared, int threads,
                              struct sl_diag *d);

/* The layers in `set` that f lacks rendered into it (one render each, then
 * t->warmup + t->runs - 1 timed repetitions into a scratch copy of the
 * frame, timings and bad values into t), then those in `gather` gathered
 * per pixel of v (sl_frame_gather) once their repetitions are done. */
enum sl_err sl_run_render_layers(struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m, struct sl_light_frame *f,
                                 unsigned set, unsigned gather, const struct sl_view *v,
                                 const struct sl_cube_timing *t, struct sl_diag *d);

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
enum sl_err sl_run_alt_frame(struct sl_alt_frames *a, struct sl_shadowmap_pass *sp, const struct sl_gl_mesh *m,
                             const struct sl_scene *s, const struct sl_view *v, int map, int size,
                             const struct sl_fit_opts *o, unsigned needs, struct sl_light_frame **out, int *layers,
                             struct sl_diag *d);
void sl_run_alt_free(struct sl_alt_frames *a);

#endif
