/*
 * softmc.h — Curtis 2009 (chapter 3): Monte Carlo soft shadows of an area
 * light, per pixel on the CPU, by tracing a few rays from the light to each
 * visible point through the near and far depth layers of softmap.h.
 *
 * Per non-background pixel of a view: r x r rays to the points of a jittered
 * grid on the light (sl_area_jitter, 3.1; the same samples the area truth
 * draws for the same seed), each blocked when it leaves the surface on its
 * back side (3.7, first case) or passes between the two layers (3.3): the
 * layers bound solid occluders, near = front faces, far = back faces. The
 * visible fraction of the rays is the result, in [0, 1] (0 for points on or
 * behind the light's plane: it emits on one side).
 *
 * Searches (desc.search): the hierarchical one (3.5, Algorithm 2) through
 * the layers' N-buffer (min/max windows; softmap.h builds it beside the
 * layers and says how it is laid out: m->nbuf), or linear steps with binary
 * refinement on every change of state (3.3), ending with a test for a
 * crossing inside one texel (zero-thickness occluders have no "between");
 * linear steps are the shorter of
 * step_texels in the map and an even step in depth (in a wide frustum a
 * ray crosses the occluders' depths in its last few texels). desc.layers = 1
 * is the single-layer variant (3.2: anything behind the near layer
 * occludes; no refinement is possible).
 * desc.layers = 3 adds Curtis's third layer (3.4), the camera's G-buffer of
 * the view: a linear-search sample between the near and far layers is a hit
 * only when the camera does not see it, i.e. when it is not nearer to the
 * camera than the surfaces at its pixels (softmc.c, eye_sees: the margin and
 * the policy outside the view, where the two-layer answer stands); and a
 * ray that passes from outside the layers to such a seen point is a hit
 * unless the camera sees its samples outside too (free_change_blocked: a
 * thin surface crossed at a texel's edge). So the hollows and concavities
 * inside the two-layer hull that the camera sees stop shadowing
 * (self-shadowing gets inner penumbrae), and three layers never give less
 * light than two with the same samples. Linear search only:
 * the hierarchical search proves "may hit" over whole texels and windows
 * from min/max bounds, which cannot say which points of a texel's depth
 * range the camera sees, so sl_softmc_run refuses layers 3 with it (as
 * Curtis pairs the third layer with linear/binary search, fig. 3.5).
 * Bias (eq. 3.2): bias = bias_scale sqrt(2) z tan(fov/2) / (size max(n.l,
 * ndl_min)), z the point's depth, l toward the light's centre. Every ray of
 * a pixel ends at q' = the point moved toward the projection point until its
 * depth is z - bias; one shared end means the "endpoint inside a solid" test
 * (3.7) is one lookup per pixel, and is the conventional shadow-map test.
 * Shortcuts, each switchable off so that its effect can be measured:
 *   classify (3.6): from the N-buffer over the region all rays can cross
 *     below the occluders' nearest depth (eq. 3.3), refined class_iters
 *     times: "fully lit" (no layer can block a ray: the pixel gets the share
 *     of its rays that leave its surface on the front side) or umbra (0).
 *     No umbra test with three layers (3.6: rays may pass between the
 *     layers). The umbra test is "strict" by default: with two layers it needs
 *     z >= d = max(z_near_max, D) AND z_far_min >= d (D: the depth from
 *     which the region holds every ray), so that every ray is between the
 *     layers at depth d, which the hierarchical search would also find; curtis_umbra = 1 uses Curtis's z >= z_near_max alone, which
 *     assumes the near layer hides a solid reaching the far one (wrong under
 *     a leaf or through a hole: tests/test_softmc.c measures it).
 *   accel (3.7): endpoint inside a solid -> all rays blocked; per ray, the
 *     region its projection covers decides it lit when nothing there can
 *     reach it; rays shortened to [z_near_min, z_far_max] of the regions.
 * Exactness: the hierarchical search is conservative (it finds every hit a
 * point sample along the ray could find, within a relative depth tolerance
 * of 2^-20), and every shortcut proves only what that search would find, so
 * with the hierarchical search and the strict umbra the shortcuts never
 * change a result (tests/test_softmc.c checks it). With linear search they
 * can: shortened rays move the samples, and a proven hit may fall between
 * samples; a linear hit is always a hierarchical hit, with or without them.
 * Blur (as an option): separable Gaussian in screen space, each sample
 * weighted by 1 / (1 + k |eye depth - centre's eye depth|).
 * Determinism: a pixel's result depends only on its inputs and the seed;
 * rows run on OpenMP threads; counters are integer sums.
 *
 * Owns: result arrays (sl_softmc_result_free). Does not: render or build
 * the N-buffer (softmap.c: the layers and their N-buffer, which it only
 * reads; the third layer is the view's G-buffer as gbuffer.c rendered it,
 * read, never rendered again), trace exact rays (truth.c), or register
 * itself as a method.
 */
#ifndef SL_SOFTMC_H
#define SL_SOFTMC_H
#include <stdint.h>
#include "softmap.h"
#include "view.h"

enum sl_softmc_search {
    SL_SOFTMC_HIER = 0,         /* Algorithm 2 through the N-buffer */
    SL_SOFTMC_LINEAR,           /* linear steps + binary refinement */
};

/* Zero means default in every field. */
struct sl_softmc_desc {
    int      grid;              /* r: r x r rays per pixel; 0 = 3 */
    uint32_t seed;              /* of sl_area_jitter (0 is a seed like any other) */
    int      search;            /* enum sl_softmc_search */
    int      layers;            /* 1 = near only (3.2), 2 = near + far, 3 = near + far + the
                                 * camera's G-buffer (3.4; linear search only); 0 = 2 */
    int      no_classify;       /* 1: no penumbra classification (3.6) */
    int      no_accel;          /* 1: none of 3.7's shortcuts but the back-face test */
    int      curtis_umbra;      /* 1: umbra on z >= z_near_max alone (see above) */
    int      class_iters;       /* refinements of eq. 3.3; 0 = 2 */
    double   step_texels;       /* linear search: step along the ray; 0 = 4 */
    int      refine;            /* linear search: binary steps per change of state; 0 = 4, < 0 = none */
    double   bias_scale;        /* times eq. 3.2; 0 = 1 */
    double   ndl_min;           /* eq. 3.2's lower limit of n.l; 0 = 0.1 */
    int      blur_radius;       /* pixels each side; 0 = no blur */
    double   blur_sigma;        /* pixels; 0 = radius / 2 */
    double   blur_depth_k;      /* per world unit of eye depth; 0 = 1 */
    int      threads;           /* 0 = OpenMP's default */
    int      centre;            /* 1: every ray to the light's centre (the light as a point: with
                                 * grid 1 and one layer, a conventional shadow map from the centre) */
};

/* The filled-in desc (defaults applied). */
void sl_softmc_defaults(const struct sl_softmc_desc *in, struct sl_softmc_desc *out);

/* Counts, machine-independent, so cost can be compared across machines. */
struct sl_softmc_stats {
    uint64_t pixels;            /* non-background */
    uint64_t px_unlit;          /* not in front of the light's plane: 0, no rays */
    uint64_t px_lit;            /* classified fully lit (3.6): its front-facing rays' share, no lookups */
    uint64_t px_umbra;          /* classified umbra (3.6): 0, no rays */
    uint64_t px_endpoint;       /* endpoint inside a solid (3.7): 0, no rays */
    uint64_t rays;              /* rays of the other pixels (pixels x r^2) */
    uint64_t rays_backface;     /* blocked: leave the surface on its back (3.7) */
    uint64_t rays_region;       /* lit: their own region holds nothing that can reach them (3.7) */
    uint64_t rays_searched;     /* traced through the layers */
    uint64_t rays_hit;          /* of which blocked */
    uint64_t lookups;           /* N-buffer / layer texel fetches, every kind */
    uint64_t lookups_search;    /* of which in the searches */
    uint64_t capped;            /* hierarchical searches stopped by the iteration cap (0 expected) */
    uint64_t eye_tests;         /* three layers: points tested against the camera (samples and
                                 * ray ends between the layers, and the samples outside them
                                 * around a change into the camera's seen space) */
    uint64_t eye_seen;          /* of which seen by it: no hit there */
    uint64_t eye_outside;       /* of which outside its view: the two-layer answer (a hit) */
    double   ms_trace, ms_blur;
};

struct sl_softmc_result {
    int    w, h;
    float *vis;                 /* w * h visible fraction, 0 on background */
    float *vis_blur;            /* the blurred one when blur_radius > 0, else NULL */
    struct sl_softmc_stats st;
};

/* Trace every non-background pixel of v through m's layers and their
 * N-buffer (m->nbuf, built: else SL_E_INTERNAL). */
enum sl_err sl_softmc_run(const struct sl_softmap *m, const struct sl_view *v, const struct sl_softmc_desc *desc,
                          struct sl_softmc_result *out, struct sl_diag *d);

/* The depth-sensitive blur alone (in and out: w * h, distinct). */
enum sl_err sl_softmc_blur(const struct sl_view *v, const float *in, float *out, int radius, double sigma,
                           double depth_k, struct sl_diag *d);

void sl_softmc_result_free(struct sl_softmc_result *r);

#endif
