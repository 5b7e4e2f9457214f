/*
 * temporal.h — errors over motion: flicker between consecutive frames of a
 * path (pathfile.h), and the small state the run keeps so frame t's
 * verdicts are still there when frame t + 1 is scored.
 *
 * Flicker: a pixel whose verdict changes between two consecutive frames while
 * its truth does not. Compared by surface point: each non-background pixel
 * p of the earlier frame is carried through its G-buffer world position into
 * the later frame's camera; it is compared only when it lands inside the
 * image on a pixel q showing the same triangle (so a point hidden in the
 * later frame, or off screen, is not compared) whose truth equals p's; of
 * those compared pixels, the ones with verdict(p) != verdict(q) flicker. A
 * pixel a method leaves undecided (SL_V_UNCERTAIN) shows what the shadow ray
 * it is left for answers, the truth: a method whose undecided pixels come
 * and go between frames (texel coherence's) flickers only where it decides
 * wrongly, as the image it feeds would.
 * When both frames have the same camera (a light path, or a still one) the
 * comparison is pixel for pixel: q = p, still on the same triangle and with
 * the same truth. A method whose verdicts equal the truth never flickers.
 *
 * The choice where the issue is silent: q is the pixel the point falls in
 * (floor of its window coordinates, no filtering), and every non-background
 * pixel counts (PnFL too: their verdict is shadow by definition, so they
 * flicker only if a method breaks that, which is worth seeing).
 *
 * Owns: the previous and current frame's G-buffer copies and per-(map,
 * label) verdicts (sl_temporal_free). Does not: render, trace, or know the
 * store.
 */
#ifndef SL_TEMPORAL_H
#define SL_TEMPORAL_H
#include <stdint.h>
#include <cglm/cglm.h>
#include "scene.h"
#include "sl_error.h"
#include "view.h"

/* One frame's pixels, as flicker reads them. */
struct sl_temporal_frame {
    int             w, h;
    const float    *pos;     /* 3 per pixel, world */
    const uint32_t *tri;     /* triangle + 1, 0 background */
    const uint8_t  *truth;   /* enum sl_truth */
    mat4            vp;      /* the camera's proj * view */
};

/* Flicker from frame a to frame b with verdicts va, vb (enum sl_verdict per
 * pixel); *compared: the pixels compared (same surface, same truth).
 * same_camera: pixel for pixel. */
uint64_t sl_temporal_flicker(const struct sl_temporal_frame *a, const uint8_t *va,
                             const struct sl_temporal_frame *b, const uint8_t *vb, int same_camera,
                             uint64_t *compared);
/* The two halves of it, so a view pair is matched once for all its labels:
 * match[p] = q + 1 for each pixel p of a compared with pixel q of b, else 0
 * (a->w * a->h entries); then the count over those pairs. */
void     sl_temporal_match(const struct sl_temporal_frame *a, const struct sl_temporal_frame *b, int same_camera,
                           uint32_t *match);
uint64_t sl_temporal_count(const struct sl_temporal_frame *a, const uint8_t *va, const struct sl_temporal_frame *b,
                           const uint8_t *vb, const uint32_t *match, uint64_t *compared);

#define SL_TEMPORAL_SLOTS 1024   /* (map index, label index) pairs: 32 x 32 */

/* What the run keeps between frames. Zero is a valid empty state. */
struct sl_temporal {
    int w, h;
    int cur;                               /* which of the two snapshots is the current frame */
    int have[2];                           /* the snapshot holds a path's frame */
    int scene[2], viewport[2];             /* and its key */
    struct sl_viewpoint vp[2];             /* its viewpoint (path, frame, camera) */
    float    *pos[2];
    uint32_t *tri[2];
    uint8_t  *truth[2];
    mat4      cam[2];
    uint32_t *match;                       /* the previous frame's pixels in the current one (sl_temporal_match) */
    int       have_match;
    double    ms_match;                    /* the view's copies and match, ms: shared by its cells, reported
                                            * with each */
    uint8_t  *v[2][SL_TEMPORAL_SLOTS];     /* verdicts of each (map, label) of that frame */
    int       has_v[2][SL_TEMPORAL_SLOTS];
};

/* A view begins (its truth in place). A frame of a path that follows the
 * previous view (same scene, viewport and path, the next frame number)
 * keeps that view as the previous frame; any other view forgets it. Views
 * that are not frames of a path copy nothing. */
enum sl_err sl_temporal_view(struct sl_temporal *t, int scene, int viewport, const struct sl_viewpoint *vp,
                             const struct sl_view *v, struct sl_diag *d);

/* A cell of the current view: its verdicts are kept for the next frame and,
 * when the previous frame holds the same (map, label), compared with them.
 * *measured = 1 with *flicker and *compared set when compared, else 0
 * (the view is no frame, or the first of its path; a run scores the frame
 * before the first it computes of a path as warm-up cells, run.c, so the
 * counts do not depend on where a slice or a resume begins); *ms (when
 * not NULL): the wall time it took, keeping the verdicts included, plus
 * the view's copies and match (shared by its cells, reported with each as
 * view stages are). */
enum sl_err sl_temporal_cell(struct sl_temporal *t, int map, int label, const uint8_t *verdicts, int *measured,
                             uint64_t *flicker, uint64_t *compared, double *ms, struct sl_diag *d);

void sl_temporal_free(struct sl_temporal *t);

#endif
