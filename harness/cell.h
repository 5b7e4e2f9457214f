/*
 * cell.h — scoring one cell: a method's verdicts of one view and map size
 * against the truth, from explicit inputs (the view with its truth, the
 * frame, the verdicts, the scratch buffers), into the cell's figures.
 *
 * A hard-shadow method's cell gets its contours (drawn from its own result
 * image), its figures per region, the exactness check of what it declares
 * (method.h SL_EXACT_*, every PFL pixel; the first few violating pixels are
 * kept with the triangles their texel holds), coherence's patterns, its
 * error overlay and, when asked, the per-pixel EXR layers behind the
 * figures. Under an area light its verdicts are also scored as a visible
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
#include "frame.h"
#include "method.h"
#include "view.h"

struct sl_cell;

struct sl_cell_inputs {
    const struct sl_method      *method;
    const struct sl_view        *view;        /* with its truth */
    const struct sl_light_frame *frame;       /* the layers the group rendered (violations name their triangles) */
    const float                 *light_dir;   /* the scene's, for the overlay's shading */
    const int                   *regions;     /* contour thicknesses ascending, then 0 (whole image) */
    int                          nregions;
    int                          overlay_contour;   /* the contour drawn on the overlay, px */
    const float *soft_truth, *soft_se;        /* an area light's visible fraction and its error, else NULL */
    uint8_t *state, *band, *rgb;              /* scratch: w*h, w*h, 3*w*h bytes */
    const char *overlay_path;                 /* NULL: no overlay */
    const char *exr_path;                     /* NULL: no EXR layers */
};

/* Score the verdicts vd (a hard method under an area light also gets vd->vis
 * written: its verdicts as a visible fraction) into cell: fig, soft,
 * has_soft, has_patterns, pattern, violations and violation[], nonfinite
 * (added to), ms.contours, ms.figures, ms.overlay. Errors come only from
 * writing the overlay or the EXR file. */
enum sl_err sl_cell_score(const struct sl_cell_inputs *in, struct sl_verdicts *vd, struct sl_cell *cell,
                          struct sl_diag *d);

#endif
