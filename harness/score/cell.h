/*
 * cell.h — scoring one cell: a method's verdicts of one view and map size
 * against the truth, from explicit inputs (the view with its truth, the
 * frame, the verdicts, the scratch buffers), into the cell's figures.
 *
 * A hard-shadow method's cell gets its contours (drawn from its own result
 * image — config `contour_from: own` — or handed in precomputed: the
 * driver draws them once per view and map from NSM's image for
 * `contour_from: nsm`, the thesis's), its figures per region, the exactness check of what it declares
 * (method.h SL_EXACT_*, every PFL pixel; the first few violating pixels are
 * kept with the triangles their texel holds), coherence's patterns, its
 * error overlay sheet (overlay.h, image.h: the frame at 1:1 or cropped to
 * the scene, the densest error windows zoomed, a legend) and, when asked,
 * the per-pixel EXR layers behind the figures with their codes named in the
 * header. Under an area light its verdicts are also scored as a visible
 * fraction against the area truth (softfig.h), and its overlay is then the
 * soft error heat map. A soft method's cell gets the soft figures only.
 *
 * Owns: nothing (writes into the cell and the scratch it is handed). Does
 * not: run the method, render, trace, or print (a violation is counted in
 * the cell and reported by the caller).
 */
#ifndef SL_CELL_H
#define SL_CELL_H
#include <stdint.h>
#include "aliasing.h"
#include "cellkey.h"
#include "frame.h"
#include "figures.h"
#include "softfig.h"
#include "method.h"
#include "view.h"

struct sl_sheet_sink;   /* sheetsink.h */

/* Wall times of the stages of one cell, ms; view stages are shared by every
 * cell of the view and reported with each. The G-buffer render, the truth
 * (when traced, not cached), each shadow-map layer render and the method are
 * repeated as the config says (warm-up + runs): each keeps the median of the
 * timed runs with their min and max. The layers the method reads add up
 * (sum of medians, of mins, of maxes). The rest is timed once. */
struct sl_stage_ms {
    double gbuffer_render[3], gbuffer_readback, truth[3], fit;   /* [SL_MED], [SL_MIN], [SL_MAX] */
    double map_render[3], map_readback;
    double method[3], contours, figures, overlay;
    /* GPU time (GL_TIME_ELAPSED, glctx.h) of the same G-buffer and layer
     * renders over the same repetitions; 0 where no GL pass ran (no layer
     * read). The soft layers of an area light are rendered once: their
     * wall and GPU times go to map_render and gpu_map as they are. */
    double gpu_gbuffer[3], gpu_map[3];
    double flicker;   /* keeping the verdicts for the next frame and comparing them with the last (temporal.h) */
    /* The cell's cost by stages, one definition for every method, C or
     * package (cellcols.h: ms_map ... ms_cost): st_map the shadow-map
     * passes (the driver's layers it reads plus its own map passes),
     * st_post its post passes (blur, mipmaps), st_lookup its per-pixel
     * lookup, st_readback the maps' (or its visibility's) way back to the
     * CPU, st_rays its ray step; medians of their timed runs. total the
     * whole: {median, min, max}. gpu_post, gpu_lookup: a package's GPU
     * times of those passes (NAN where no GL pass ran). runs_method,
     * runs_map: how many runs of the method and of its layers were timed
     * (reps.h). method[] is the per-pixel step, lookup and rays. */
    double st_map, st_post, st_lookup, st_readback, st_rays, total[3];
    double gpu_post, gpu_lookup;
    int    runs_method, runs_map;
};

/* A pixel where a method broke the guarantee it declares (method.h
 * SL_EXACT_*): where, what, and which triangles its texel holds. */
struct sl_violation {
    int      x, y;                     /* pixel, y = 0 the bottom row */
    uint8_t  truth, verdict, how;
    uint32_t own_tri;                  /* triangle + 1 the pixel lies on */
    int      tx, ty;                   /* its texel */
    uint32_t layer_tri[SL_LAYER_COUNT];/* triangle + 1 each rendered layer holds there, 0 none */
};
#define SL_MAX_VIOLATIONS 4

struct sl_cell {
    int index;                         /* in the sweep */
    struct sl_cell_key key;
    char scene[64];
    char viewpoint[32];
    struct sl_figures  fig;
    struct sl_cost     cost;
    struct sl_stage_ms ms;
    uint64_t gs_prims, fragments;      /* of the layers the method reads (GL queries) */
    int      truth_cached;
    uint64_t truth_rays;
    uint64_t n_pfl, n_pnfl, n_background, n_truth_lit, n_truth_shadow;
    uint64_t n_outside_cone;           /* of n_pnfl, outside a spot light's cone (view.h) */
    char     light[48];                /* the scene's light in words (sl_light_heading) */
    int      has_soft;                 /* an area light's cell: soft figures instead of fig's regions */
    int      has_frac;                 /* with has_soft under a hard light: the soft figures are the
                                        * fractional errors of a method's visibility (vd->has_vis)
                                        * against the 0/1 truth over the PFL pixels */
    struct sl_soft_figures soft;
    uint64_t violations;               /* of the method's declared exactness; must be 0 */
    uint64_t flicker, flicker_compared;/* against the previous frame of its path (temporal.h); 0, 0 none */
    uint64_t nonfinite;                /* G-buffer values not finite, depths of the layers it reads
                                        * outside [0, 1], the method's visibility not finite or
                                        * outside [0, 1], its own maps' texels not finite
                                        * (vd->nonfinite); must be 0: stored, flagged, and a
                                        * failure of check unless the baseline holds it */
    /* texel coherence (Moderno 2011 Tables 20/22): per region, PFL pixels by
     * how many of the tested texels say shadow, and of those how many are
     * shadowed in truth; has_patterns when the method reports it */
    int      has_patterns;
    uint64_t pattern[SL_MAX_REGIONS][10][2];
    uint64_t texels;                   /* texels of the shadow maps the method looked up (each map once,
                                        * whatever its layers): size^2, k size^2 for zpart's k slices */
    uint64_t faces;                    /* a point light: its cube's faces with a map (lightframe.h); else 0 */
    double   ms_face_max;              /* and the method's time on the slowest face (NAN: no cube) */
    int      has_alias;                /* a hard cell: its wrong pixels by aliasing error m (aliasing.h) */
    struct sl_alias_figures alias;
    struct sl_violation violation[SL_MAX_VIOLATIONS];
};


struct sl_cell_inputs {
    const struct sl_method      *method;
    const struct sl_method_params *params;    /* its parameters (which layers it reads: texels) */
    const struct sl_view        *view;        /* with its truth */
    const struct sl_light_frame *frame;       /* the layers the group rendered (violations name their triangles) */
    const float                 *light_dir;   /* the scene's, for the overlay's shading */
    const float                 *light_pos;   /* a light at a point (spot, point, area): its position; else NULL */
    const int                   *regions;     /* contour thicknesses ascending, then 0 (whole image) */
    int                          nregions;
    int                          overlay_contour;   /* the contour drawn on the overlay, px */
    const float *soft_truth, *soft_se;        /* an area light's visible fraction and its error, else NULL */
    uint8_t *state, *band, *rgb;              /* scratch: w*h, w*h, 3*w*h bytes */
    const uint8_t *shared_band;               /* non-NULL: the contour bands to score on (w*h, as
                                               * sl_contour_bands writes them), drawn once for the
                                               * view and map by the caller; NULL: drawn here from
                                               * the method's own verdicts */
    double shared_band_ms;                    /* what drawing shared_band cost, ms (ms.contours) */
    const char *label;                        /* the method's label (overlay title); NULL: its name */
    const char *overlay_path;                 /* NULL: no overlay */
    const struct sl_sheet_sink *sheets;       /* where the sheet goes (sheetsink.h; the run's overlay
                                               * writer): drawn into one of its slots and written by
                                               * it; NULL: written here, in the rgb scratch */
    const char *exr_path;                     /* NULL: no EXR layers */
    const struct sl_scene *scene;             /* its named meshes: the EXR's mesh layer (NULL: that
                                               * layer all 0) */
    const char *visibility_path;              /* the visibility as scored, an EXR of V, A and Z (config
                                               * outputs.visibility: exr; doc/grade.md); NULL: none */
    int threads;                              /* the scoring pass's (the config's threads; 0: every core) */
    int aliasing;                             /* the aliasing error m's figures wanted (config) */
    struct sl_alias_cache *alias_cache;       /* m of the view under the cell's frame, kept for the next
                                               * cells of the view (aliasing.h); NULL: computed per cell */
    struct sl_overlay_shade *overlay_shade;   /* the overlay's lit colours, kept for the view's next cells
                                               * (overlay.h); NULL: drawn per cell */
};

/* Score the verdicts vd (a hard method under an area light also gets vd->vis
 * written: its verdicts as a visible fraction) into cell: fig, soft,
 * has_soft, has_patterns, pattern, violations and violation[], nonfinite
 * (added to), ms.contours, ms.figures, ms.overlay (bands drawn here are
 * drawn inside the figure pass, sl_score_fused: ms.contours is then 0 and
 * ms.figures holds both). ms.overlay is what the cell pays on its own
 * path: drawing the overlay, its crop and insets, and, with a writer, the
 * wait for a free slot (composing and compressing the PNG run on the
 * writer's thread, not counted; without a writer they are). Errors come only
 * from writing the overlay or the EXR file (with a writer, possibly an
 * earlier cell's overlay: its file is named). */
enum sl_err sl_cell_score(const struct sl_cell_inputs *in, struct sl_verdicts *vd, struct sl_cell *cell,
                          struct sl_diag *d);

#endif
