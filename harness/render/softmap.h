/*
 * softmap.h — the light frame of an area light and its two depth layers for
 * Curtis 2009's soft shadows (chapter 3): a square perspective frustum whose
 * projection point sits behind the light's centre, the NEAR (front faces,
 * nearest) and FAR (back faces, farthest) layers rendered from it with the
 * caller's pure receivers left out, and their min/max N-buffer.
 *
 * Frame (eq. 3.1): the projection point is eye = c - light_depth * n with
 * light_depth = s / (2 tan(fov/2)), s the light's larger side, so the light
 * rectangle fits the frustum's cross-section at depth light_depth exactly
 * (a square light fills it). The fov is either the caller's or fitted: the
 * smallest that holds every non-background G-buffer point in front of the
 * light. Since the frustum is convex and holds both ends of every shadow ray
 * (the light sample and the receiver), every point of every ray projects
 * inside the map — Curtis's condition for the depth comparison to be valid
 * along the whole ray — and occluders outside it cannot matter.
 * Fitting: a point at lateral offset (x, y) from the light's centre and at
 * depth t in front of it is inside when max(|x|, |y|) <= t T + s/2 with
 * T = tan(fov/2), so T = max over points of (max(|x|, |y|) - s/2) / t (small
 * margin, clamped to [tan(2.5 deg), tan(fov_max/2)]; points beyond the cap
 * are counted in n_outside and their lookups clamp to the map's edge).
 * Planes: znear just before the light's plane (nothing behind the light can
 * lie between it and a lit point), zfar beyond the farthest receiver and the
 * farthest vertex of any non-receiver mesh, so no occluder's back faces are
 * clipped away from the far layer.
 *
 * Layers hold LINEAR depth: the distance from the projection point along the
 * light's normal (world units), written by the fragment shader into an R32F
 * colour target while the 32-bit float depth buffer decides visibility.
 * Empty texels hold what Curtis's clears give: near = zfar, far = znear
 * (so an empty texel is "in front" and "behind" at once, never "between").
 * Map axes: u along -ex, v along ey of the light (sl_area_of), which makes
 * the frame right-handed so counter-clockwise front faces stay front faces.
 * Meshes must be closed (or two-sided, drawn unculled into both layers) to
 * be occluders: an open one-sided mesh has no back faces in the far layer.
 *
 * The N-buffer (3.5; Décoret 2005) of the two layers is built here too, on
 * the CPU, beside the layers it summarises (sl_softmap_nbuf_build): level n
 * holds, per texel (i, j), the extremes over the 2^n x 2^n window
 * [i, i + 2^n) x [j, j + 2^n), clipped to the map. Curtis centres the
 * windows so that a GPU fetch at a point covers its neighbourhood; on the
 * CPU a window is addressed by its corner, so any square of side 2^n
 * anywhere is one fetch and centring buys nothing. Every level is full
 * size: 16 bytes x size^2 x (log2 size + 1), 176 MB at 1024.
 *
 * Owns: the layer arrays (sl_softmap_free; NULL-safe), the pass's program
 * (sl_softmap_pass_free) and an N-buffer's array (sl_softmap_nbuf_free;
 * NULL-safe); the N-buffer is the caller's struct, kept apart from the
 * layers so that its memory outlives them and is reused by the next build
 * of the same size. Does not: search the layers or the N-buffer (softmc.c
 * does) or decide which meshes are pure receivers (the caller's flags do).
 */
#ifndef SL_SOFTMAP_H
#define SL_SOFTMAP_H
#include <stdint.h>
#include <cglm/cglm.h>
#include "arealight.h"
#include "glctx.h"
#include "view.h"

/* Zero means default in every field. */
struct sl_softmap_desc {
    int    size;              /* texels per side, a power of two; 0 = 1024 */
    double fov_deg;           /* full angle of the square frustum; 0 = fitted to the view */
    double fov_max_deg;       /* cap of a fitted angle; 0 = 150 */
    const uint8_t *receiver;  /* per scene range: nonzero = pure receiver, left out of both
                               * layers (Curtis 3.3); NULL = none */
};

/* The filled-in desc (defaults applied). */
void sl_softmap_defaults(const struct sl_softmap_desc *in, struct sl_softmap_desc *out);

/* One texel of the N-buffer: the extremes of both layers over its window.
 * far_min serves the strict umbra test (softmc.h). */
struct sl_softmap_texel {
    float near_min, near_max;   /* of the near layer */
    float far_min, far_max;     /* of the far layer */
};

struct sl_softmap_nbuf {
    int    size, levels;        /* levels = log2(size) + 1 */
    struct sl_softmap_texel *t; /* level-major: t[(n * size + j) * size + i] */
    double ms_build;
};

struct sl_softmap {
    int      size;
    struct sl_area area;           /* the light */
    double   eye[3];               /* projection point, area.c - light_depth * area.n */
    double   right[3], up[3], fwd[3];   /* map axes: -area.ex, area.ey, area.n */
    double   tan_half, fov_deg;    /* T = tan(fov/2) */
    double   light_depth;          /* eq. 3.1: depth of the light's plane */
    double   znear, zfar;          /* clip planes (linear depth) */
    mat4     view, proj, vp;       /* the same frame for GL (zero-to-one clip space) */
    float   *near, *far;           /* size^2 linear depths, texel (i, j) at j * size + i */
    uint32_t n_fit;                /* view points in front of the light the frame holds */
    uint32_t n_outside;            /* of which outside the frustum (fitted fov capped) */
    uint32_t n_receiver_ranges;    /* scene ranges left out as pure receivers */
    double   ms_near, ms_far, ms_readback;
    double   ms_gpu_near, ms_gpu_far;   /* GL_TIME_ELAPSED of each layer's clears and draws */
    uint64_t frag_near, frag_far;  /* fragment shader invocations (GL query) */
    const struct sl_softmap_nbuf *nbuf;   /* the N-buffer of these layers, once built
                                           * (sl_softmap_nbuf_build); not owned; else NULL */
};

struct sl_softmap_pass {
    GLuint prog;
};

enum sl_err sl_softmap_init(struct sl_softmap_pass *p, struct sl_diag *d);
void        sl_softmap_pass_free(struct sl_softmap_pass *p);

/* The frame alone (no GL): light, fov, projection point, planes, matrices.
 * SL_E_SCENE when the scene's light is not an area light. */
enum sl_err sl_softmap_fit(const struct sl_scene *s, const struct sl_view *v,
                           const struct sl_softmap_desc *desc, struct sl_softmap *m, struct sl_diag *d);

/* Fit the frame to view v and render both layers into m. */
enum sl_err sl_softmap_render(const struct sl_softmap_pass *p, const struct sl_gl_mesh *gm,
                              const struct sl_scene *s, const struct sl_view *v,
                              const struct sl_softmap_desc *desc, struct sl_softmap *m, struct sl_diag *d);

/* Frees the layers and forgets the N-buffer (which is not freed). */
void sl_softmap_free(struct sl_softmap *m);

/* Build nb from m's layers and point m->nbuf at it. nb is zeroed (first
 * build) or a previous build, whose memory is reused when the size matches
 * (a fresh allocation costs more in first-touch page faults than the build
 * itself). Rows run on OpenMP threads (threads <= 0: OpenMP's default);
 * the result does not depend on their number. */
enum sl_err sl_softmap_nbuf_build(struct sl_softmap *m, int threads, struct sl_softmap_nbuf *nb,
                                  struct sl_diag *d);
void        sl_softmap_nbuf_free(struct sl_softmap_nbuf *nb);

/* Widen a to hold b too. Plain comparisons: fminf/fmaxf are libm calls when
 * NaNs must be honoured (no -ffast-math here), and the layers hold no NaN. */
static inline void sl_softmap_texel_merge(struct sl_softmap_texel *a, const struct sl_softmap_texel *b)
{
    a->near_min = b->near_min < a->near_min ? b->near_min : a->near_min;
    a->near_max = b->near_max > a->near_max ? b->near_max : a->near_max;
    a->far_min = b->far_min < a->far_min ? b->far_min : a->far_min;
    a->far_max = b->far_max > a->far_max ? b->far_max : a->far_max;
}

/* Flags for desc.receiver: 1 for every range whose name starts with prefix
 * (e.g. "ground"), 0 otherwise; returns how many were flagged. */
int sl_softmap_receivers_named(const struct sl_scene *s, const char *prefix, uint8_t *flags);

/* A world point in the frame: continuous texel coordinates (u, v; inside
 * [0, size) for points in the frustum) and linear depth. */
static inline void sl_softmap_project(const struct sl_softmap *m, const double p[3],
                                      double *u, double *v, double *depth)
{
    double q[3] = {p[0] - m->eye[0], p[1] - m->eye[1], p[2] - m->eye[2]};
    double x = q[0] * m->right[0] + q[1] * m->right[1] + q[2] * m->right[2];
    double y = q[0] * m->up[0] + q[1] * m->up[1] + q[2] * m->up[2];
    double z = q[0] * m->fwd[0] + q[1] * m->fwd[1] + q[2] * m->fwd[2];
    double k = 0.5 * (double)m->size / (m->tan_half * z);
    *u = x * k + 0.5 * (double)m->size;
    *v = y * k + 0.5 * (double)m->size;
    *depth = z;
}

#endif
