/*
 * aliasing.h — the aliasing error m of every pixel (seed 004, appendix A:
 * m = w_l / w_c, eq. 61) and the figures that sort a cell's wrong pixels by
 * it: is an error aliasing (m > 1: one texel spreads over more than one
 * pixel) or something else (self-shadowing, a leak)?
 *
 * m of a pixel: the footprint on the surface of the shadow-map texel that
 * serves the pixel, measured in pixel footprints. Both footprints are found
 * the same way, exactly: the beams through the pixel's (texel's) edge
 * midpoints at +-1/2 in x and y are unprojected through the inverse of the
 * camera's (the frame's) view-projection and cut with the pixel's tangent
 * plane (its G-buffer position and normal). For an orthographic camera or a
 * directional light this is eq. 56 exactly (w' = w / cos theta); for a
 * perspective one it is eq. 58, whose first-order form eq. 59 (= eq. 56)
 * breaks down where [d sin theta]^2 is not small against [2 n cos theta]^2,
 * i.e. near grazing, theta -> (pi - phi) / 2, where a beam edge runs
 * parallel to the plane and w' grows without bound. A pixel is about 1e-3
 * of the projection distance across, so eq. 59 is off by more than 1% only
 * beyond about 89.7 degrees; we use the exact form everywhere, so no switch
 * point is needed and the grazing pixels get the right (large) footprint.
 * An edge beam that misses the plane (parallel, or behind the eye) makes
 * that footprint infinite.
 *
 * In 3-D the two footprints are parallelograms. With the pixel's spans
 * (a_c, b_c) and the texel's (a_l, b_l) in the tangent plane, T =
 * [a_c b_c]^-1 [a_l b_l] gives a texel's extent in pixels; m is T's largest
 * singular value: the most pixels one texel covers along any direction.
 * Where the camera's and light's planes of incidence agree this is
 * max(eq. 61, the cross-plane ratio): eq. 61 itself along the stretched
 * direction (the thesis's 1-D analysis), and the plain texel/pixel ratio
 * across it. (Seed 004's Figure 37 also notes the off-axis term of eq. 60:
 * it is in the unprojection, not approximated away.)
 *
 * m is defined for PFL pixels (the ones a map decides); the rest get NAN.
 * A PFL pixel whose pixel and texel footprints are both infinite has no
 * defined ratio (NAN, counted as m_none).
 *
 * Owns: nothing. Does not: render, write files or store (cell.c, the store).
 */
#ifndef SL_ALIASING_H
#define SL_ALIASING_H
#include <math.h>
#include <stdint.h>
#include <cglm/cglm.h>
#include "figrec.h"
#include "figures.h"
#include "frame.h"
#include "method.h"
#include "view.h"

/* The band of m (0 .. SL_ALIAS_BANDS-1); m must not be NAN. */
static inline int sl_alias_band(double m)
{
    return m <= 1.0 ? 0 : m <= 2.0 ? 1 : m <= 4.0 ? 2 : m <= 8.0 ? 3 : 4;
}

/* m as the EXR layer's code: 0 for NAN, else 128 + 8 log2 m rounded,
 * clamped to 1..255 (1/8 octave steps; m = 1, 2, 4, 8 at 128, 136, 144, 152). */
static inline uint8_t sl_alias_code(float m)
{
    if (isnan(m))
        return 0;
    if (!(m > 0.0f))
        return 1;
    float c = 128.0f + 8.0f * log2f(m);
    return c <= 1.0f ? 1 : c >= 255.0f ? 255 : (uint8_t)lrintf(c);
}

/* The footprint spans on the plane through p with unit normal nrm of the
 * beam through p's own window point (x, y) of a view-projection vp over a
 * window of w x h (pixels or texels): a = the plane's points at x +- 1/2
 * apart, b = at y +- 1/2; returns 0 when an edge beam misses the plane
 * (the footprint is then infinite). Exact for orthographic and perspective
 * vp (eq. 58 and the off-axis eq. 60 included). */
int sl_alias_spans(const mat4 vp, int w, int h, const float p[3], const float nrm[3], double a[3], double b[3]);

/* m at p (unit normal nrm) for a camera (cam_vp over cw x ch pixels) and a
 * light frame (light_vp over a size x size map): see the top. INFINITY when
 * only the texel's footprint is infinite, 0 when only the pixel's, NAN when
 * both. */
double sl_alias_m(const mat4 cam_vp, int cw, int ch, const mat4 light_vp, int size, const float p[3],
                  const float nrm[3]);

/* m of every PFL pixel of v (NAN elsewhere) into m[w*h]: the frame whose
 * texel served the pixel is vd->frames[vd->slice[i]] when vd->nframes > 0
 * (slice NULL: frames[0]; a slice byte 255: no frame, NAN), else f. */
void sl_alias_image(const struct sl_view *v, const struct sl_light_frame *f, const struct sl_verdicts *vd,
                    int threads, float *m);

/* m of a view under one frame, kept across the view's cells: m depends on
 * the view's pixels and the frame's projection alone, not on the method or
 * its verdicts, so the cells of one (view, map size) group that share a
 * frame compute it once (on the Morais study it was half the CPU time,
 * computed again for each of its eight methods). The key is the view's
 * serial (view.h) and the frame's view-projection and size. Owned by the
 * caller: zero it before the first use, sl_alias_cache_free at the end. */
struct sl_alias_cache {
    float   *m;        /* w*h values as sl_alias_image writes them; NULL: none yet */
    size_t   cap;      /* floats m holds */
    uint64_t serial;   /* the view's; 0: nothing held */
    mat4     vp;       /* the frame's view-projection */
    int      size;     /* and its map size */
    /* The figures that do not depend on the verdicts (each region's PFL
     * pixels by band of m, and their median), kept with the bands and
     * regions they were counted on: the cells of a group scoring on the
     * same bands (contour_from: nsm) count them once. */
    uint64_t gen;                                   /* m's computations so far */
    uint64_t pfl_gen;                               /* the one they were counted on; 0 none */
    uint8_t *band;                                  /* w*h, the bands */
    size_t   band_cap;
    int      nregions, thickness[SL_MAX_REGIONS];
    uint64_t pfl_n[SL_MAX_REGIONS][SL_AFIG_COUNT];  /* only the PFL-side figures filled */
    uint64_t pfl[SL_MAX_REGIONS];
};

/* m of every pixel of v under f (sl_alias_image without per-pixel frames):
 * the cache's values when they are this view's under the same frame, else
 * computed into it. NULL when no memory. */
const float *sl_alias_cached(struct sl_alias_cache *c, const struct sl_view *v, const struct sl_light_frame *f,
                             int threads);
void sl_alias_cache_free(struct sl_alias_cache *c);

/* The figures per region (thickness[], as sl_figures_compute takes them;
 * band: the contour bands, contour.h). */
void sl_alias_figures_compute(const struct sl_view *v, const struct sl_verdicts *vd, const float *m,
                              const uint8_t *band, const int *thickness, int nregions,
                              struct sl_alias_figures *out);
/* The same, the PFL side (PFL pixels by band of m, their median) taken
 * from the cache when m is the cache's own and the bands and regions are
 * those it was counted on, else counted and kept there. k NULL: counted. */
void sl_alias_figures_cached(struct sl_alias_cache *k, const struct sl_view *v, const struct sl_verdicts *vd,
                             const float *m, const uint8_t *band, const int *thickness, int nregions,
                             struct sl_alias_figures *out);

#endif
