/*
 * softtruth.h — the ground truth of soft shadows from a rectangular area
 * light (scene.h, SL_LIGHT_AREA): per pixel, the fraction V in [0, 1] of the
 * light's rectangle that the pixel sees, estimated with Embree from an n x n
 * stratified (jittered-grid) sample of the rectangle, with its standard
 * error. Curtis (2009) builds his references by averaging 4096 point lights;
 * the default here is n = 32 (1024 samples), and the standard error says
 * how far from the exact V each pixel may be.
 *
 * V is geometric visibility only: the fraction of the light's AREA that is
 * unoccluded and faces the pixel, with no cosine or distance weighting —
 * Curtis's "fraction of the light source that is occluded", and what his
 * and our `soft_mc` method estimate. A sample point q of the light counts
 * as visible from the pixel at p (face normal n turned toward the camera,
 * light normal m) when all three hold:
 *   - q lies strictly in front of the pixel's surface: dot(n, q - p) > 0;
 *   - p lies strictly on the emitting side of the light: dot(m, p - q) > 0;
 *   - the segment p -> q is unoccluded: an Embree occlusion ray with the
 *     own-triangle filter (truth.h) over [sl_rt_tnear(p), |q - p| -
 *     sl_rt_tnear(q)] — the segment is cut short at the light by the same
 *     rule that starts it off the surface, so geometry touching the light
 *     (a ceiling it is set into) does not hide it.
 *
 * Random source: sample k of pixel (x, y) (y = 0 the bottom row, the view's
 * own pixel order) is sl_area_jitter(x, y, k, n, seed) (arealight.h), the
 * source `soft_mc` draws from too. Every value depends only on the pixel,
 * the sample indices and the seed: a fixed seed gives bit-identical images
 * whatever the thread count.
 *
 * Owns nothing: the caller passes the output arrays (w * h floats each).
 * Does not: render, build the BVH (truth.c's sl_rt_build, with the
 * own-triangle filter on), weight by the light's emission, or print.
 */
#ifndef SL_SOFTTRUTH_H
#define SL_SOFTTRUTH_H
#include <stdint.h>
#include "scene.h"
#include "truth.h"
#include "view.h"

/* Bump when anything here or in softtruth.c changes what the estimate is
 * (estimator, standard error, side tests, the segment's ends): the driver
 * keys its cache of area truths with it (run.c), so cached truths of older
 * rules are never read. The sample pattern (arealight.h) keys it apart. */
#define SL_SOFT_TRUTH_VERSION "soft-truth-v1 stratified-jitter collapsed-pairs-stderr face-and-emit-sides " \
                              "segment-tnear-both-ends"

#define SL_SOFT_TRUTH_SIDE_DEFAULT 32     /* samples per side: 1024 samples per pixel */
#define SL_SOFT_TRUTH_SIDE_MAX     1024   /* 2^20 samples per pixel; far beyond any use */

struct sl_soft_truth_stats {
    int      side;        /* samples per side actually used (0 resolved to the default) */
    uint32_t seed;
    uint64_t pixels;      /* non-background pixels estimated */
    uint64_t lit;         /* ... of which V == 1 exactly */
    uint64_t umbra;       /* ... of which V == 0 exactly (including pixels facing away) */
    uint64_t rays;        /* shadow rays traced: samples failing a side test are not traced */
    double   ms_trace;    /* wall clock of the whole estimate */
};

/* The samples per side used for a requested value: 0 = the default. */
int sl_soft_truth_side(int samples_per_side);

/* For every pixel of v: visible[i] = V, the visible fraction of the
 * scene's area light (n = samples_per_side, 0 = SL_SOFT_TRUTH_SIDE_DEFAULT,
 * 2 .. SL_SOFT_TRUTH_SIDE_MAX), and, when stderr_out is not NULL,
 * stderr_out[i] = its standard error (softtruth.c says which estimator and
 * why). Background pixels (v->tri[i] == 0) get V = 0 and standard error 0
 * and are left out of the stats. st may be NULL.
 * Errors: SL_E_SCENE (key "light.type") when the scene's light is not an
 * area light, or its rectangle is degenerate; SL_E_USAGE for a side out of
 * range or a NULL argument; SL_E_EMBREE when Embree reports a failure. */
enum sl_err sl_soft_truth(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                          int samples_per_side, uint32_t seed, float *visible, float *stderr_out,
                          struct sl_soft_truth_stats *st, struct sl_diag *d);

#endif
