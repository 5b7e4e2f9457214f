/*
 * frame.h — the light frame: one fitted light frustum per view and the
 * shadow-map layers rendered for it at one map size.
 *
 * Layers are rendered only when a requested method needs them (the union of
 * the methods' `needs` bits), once, and shared by every method that reads
 * them. Texel (i, j) is at index j * size + i, j = 0 the bottom row.
 *
 * Owns: layer arrays (sl_frame_free), taken from its pool when it has one.
 * Does not: know which method reads what.
 */
#ifndef SL_FRAME_H
#define SL_FRAME_H
#include <stddef.h>
#include <stdint.h>
#include <cglm/cglm.h>
#include "sl_error.h"
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

/* The layers: id, name (the bench's rows, lower case), title (prose).
 * One list: the enum and both spellings are made from it. */
#define SL_LAYERS(X)                                                         \
    /* nearest surface, both faces: depth + id */                            \
    X(DEPTH_ID,      "depth_id",      "depth_id")                            \
    /* front faces culled (Moderno 2011): depth + id */                      \
    X(DEPTH_ID_BACK, "depth_id_back", "depth_id_back")                       \
    /* conservative: every triangle touching a texel, its lowest depth       \
     * there; the id carries SL_FULL when the triangle covers the texel */   \
    X(BGSM,          "bgsm",          "BGSM")                                \
    /* the same without the triangle BGSM stored at the texel (needs BGSM) */\
    X(BGSM2,         "bgsm2",         "BGSM2")                               \
    /* triangles covering the whole texel, their highest depth there */      \
    X(SGSM,          "sgsm",          "SGSM")                                \
    /* the same, a triangle extended across edges to away-facing neighbours */\
    X(SGSM_ADJ,      "sgsm_adj",      "SGSM with adjacency")

enum sl_layer_id {
#define SL_LAYER_ID(id, name, title) SL_LAYER_##id,
    SL_LAYERS(SL_LAYER_ID)
#undef SL_LAYER_ID
    SL_LAYER_COUNT
};
/* "bgsm" and "BGSM", by SL_LAYER_* (frame.c) */
extern const char *const sl_layer_names[SL_LAYER_COUNT];
extern const char *const sl_layer_titles[SL_LAYER_COUNT];
#define SL_NEED(layer) (1u << (layer))

/* How far a method's lookup may reach: SL_LOOK_REACH texels beyond the
 * receiver's own texel (a 3x3 neighbourhood, method.h). A point light's
 * cube faces are each rendered with a guard band of SL_GUARD_TEXELS around
 * their receivers (cube.h): that reach, one texel of the conservative
 * layers' enlargement (half a diagonal and its margins, rounded up), and
 * two more against the rounding of a receiver's texel at the band's own
 * edge. A wider footprint needs both raised together. */
#define SL_LOOK_REACH   1
#define SL_GUARD_TEXELS (SL_LOOK_REACH + 1 + 2)

/* The light's frustum in light view space. A directional light's is an
 * orthographic box: x, y across the light, depth = distance along the light
 * direction (positive away from the light). An area light taken as a point
 * at its centre (`persp`) has a perspective frustum from that point along
 * the light's normal: lo/hi[0..1] bound x/depth and y/depth (the tangents
 * across the axis), lo/hi[2] are the near and far depths. Window depth is
 * then A - B / depth (zero-to-one clip, A = far / (far - near), B = far *
 * near / (far - near)): not linear in depth, but affine across a triangle in
 * window space, so the conservative layers' depth planes hold unchanged. */
struct sl_light_box {
    mat4  view, proj, vp;       /* vp = proj * view, depth in [0, 1] (zero-to-one clip) */
    float lo[3], hi[3];         /* x, y, depth (perspective: x/depth, y/depth, depth) */
    int   persp;                /* 1: a point light at `eye` (perspective), 0: directional (orthographic) */
    float eye[3];               /* persp: the light's position, world */
    uint32_t n_receivers;       /* pixels the box was fitted to */
    uint32_t n_outside;         /* persp: PFL pixels left outside it (too far off the axis, lightfit.c) */
    uint32_t n_casters;         /* triangles that can shadow them */
    /* persp: triangles the conservative layers cannot hold — reaching to
     * within wmin of the light's plane or behind it, or beyond the guard
     * band across it, where window coordinates lose the precision their
     * exact tests need. Their geometry shaders leave them out; a method
     * that claims light from those layers must see its ray surely miss
     * each (sl_method_unmapped_missed). The plain layers draw them, GL
     * clipping them at the near plane. */
    uint32_t n_unmapped;
    uint32_t *unmapped;         /* their triangle indices (owned: sl_light_box_free); NULL with
                                 * n_unmapped > 0 if the list could not be allocated */
    float wmin;                 /* persp: clip w below which the geometry shaders drop a triangle */
    float guard;                /* persp: |x/w|, |y/w| (NDC) beyond which they drop it; 0: never (ortho) */
};

void sl_light_box_free(struct sl_light_box *b);

struct sl_depth_layer {
    float    *depth;            /* size*size window depth in [0,1], 1 = empty */
    uint32_t *id;               /* triangle + 1, 0 = empty; NULL for BGSM2 (shadowmap.h: no one reads it) */
    uint64_t  stamp;            /* which render made it (unique per shadow-map pass; shadowmap.h) */
    double    ms_render, ms_readback;
    double    ms_gpu;           /* GL_TIME_ELAPSED of the clears and draws (glctx.h) */
    uint64_t  gs_prims;         /* primitives the geometry shader emitted (GL query; 0 without GS) */
    uint64_t  fragments;        /* fragment shader invocations (GL query) */
    /* 1: depth and id hold, per pixel of the view the frame was gathered
     * for, the values at that pixel's own texel (sl_frame_gather), indexed
     * by pixel: read them through sl_layer_at. */
    int       per_pixel;
};

/* Where a reader finds texel k as seen from pixel i: k in a dense layer,
 * i in one gathered per pixel. */
static inline size_t sl_layer_at(const struct sl_depth_layer *L, uint32_t k, size_t i)
{
    return L->per_pixel ? i : (size_t)k;
}

/* BGSM marks a texel wholly inside its stored triangle (Hertel's "fully
 * covered"): readers of its ids mask it off. */
#define SL_FULL 0x80000000u

/* Margins of the conservative layers, shared by the shaders (uniforms) and
 * the methods that read them; see methods/conservative.c for why each is
 * large enough. */
#define SL_CONS_EPS_TEXELS (1.0 / 128.0)      /* coverage margin, texels */
#define SL_CONS_EPS_DEPTH  (0x1p-18)          /* depth margin, window depth units */

/* A pool of layer arrays, reused across layers, frames, views and
 * repetitions. Fresh memory is what a study spends most of its time on
 * here (each 4 KB page faults at ~12 us, 0.33 GB/s against 21 GB/s warm;
 * arrays above glibc's mmap threshold, every 4096^2 layer, come back fresh
 * on every allocation): a run keeps its arrays and hands them out again.
 * An array serves any request up to its size, so the pool settles at the
 * number of arrays a frame holds at once, each of the largest size asked
 * for; an array too small for a request is freed and replaced, not kept
 * beside the larger one. Large arrays are 2 MiB aligned and advised
 * MADV_HUGEPAGE (one fault per 2 MiB where the kernel grants it). Arrays
 * come back uninitialised: every caller overwrites every element. */
#define SL_POOL_SLOTS 32
struct sl_layer_pool {
    int n;
    struct { void *p; size_t bytes; int busy; } slot[SL_POOL_SLOTS];
    uint64_t allocs;            /* arrays allocated afresh, all told */
    size_t   bytes;             /* bytes the pool holds, busy or not */
};

/* An array of at least `bytes`, NULL when out of memory. */
void *sl_layer_pool_get(struct sl_layer_pool *p, size_t bytes);
/* Give an array back (NULL: nothing; one the pool did not hand out: freed). */
void  sl_layer_pool_put(struct sl_layer_pool *p, void *ptr);
/* Free every array; none may be busy. */
void  sl_layer_pool_free(struct sl_layer_pool *p);

/* One pixel's lookup in a dense layer (sl_frame_look): its texel
 * coordinates u, v and window depth z (sl_frame_project), and its texel k
 * (sl_frame_texel) with SL_LOOK_SHADOW set when the layer's depth there
 * is below z (the normal shadow-map test, z <= depth[k] lit). */
struct sl_pix_look {
    float u, v, z;
    uint32_t k;
};
#define SL_LOOK_SHADOW 0x80000000u   /* k < 16384^2 = 2^28: the top bit is free */

/* The lookups of every pixel of one view in one dense layer of a frame,
 * made once and read by each method of the view that asks (frame.h:
 * sl_frame_look). */
struct sl_frame_look {
    struct sl_pix_look *px;     /* per pixel; the fixed pixels (sl_verdict_fixed) hold zeros */
    uint32_t *id;               /* the layer's id at k, per pixel (0 for the fixed ones) */
    uint8_t *pcf;               /* with SL_LOOK_PCF, per pixel: sl_frame_pcf_lit's count over 4
                                 * texels (bits 0-3) and over 9 (bits 4-7); else NULL */
    int layer;                  /* which layer */
    uint64_t serial;            /* of that view (view.h) */
    size_t n;                   /* and that many pixels */
    double ms;                  /* wall time of the pass that made them */
    double ms_pcf;              /* and of the one that added pcf */
};

struct sl_light_frame {
    int   size;
    struct sl_layer_pool *pool; /* where its layer arrays come from and go back to; NULL: calloc/free.
                                 * The pool must outlive the frame. */
    struct sl_layer_pool *pix_pool;  /* the same for layers gathered per pixel (sl_frame_gather): arrays
                                      * of a view's size, kept apart from the map-sized ones */
    uint32_t *pix_texel;        /* sl_frame_gather's texel of each pixel (from pix_pool), for the view */
    uint64_t  pix_serial;       /* of that serial (view.h) */
    size_t    pix_n;            /* and that many pixels */
    float dir[3];               /* direction the light travels (persp: the frustum's axis) */
    struct sl_light_box box;
    float texel_world;          /* world units across one texel (the larger side); persp: at depth 1 */
    float depth_range;          /* world units of depth from 0 to 1 (persp: far - near) */
    unsigned have;              /* SL_NEED bits of the layers rendered */
    struct sl_depth_layer layer[SL_LAYER_COUNT];
    struct sl_frame_look look;  /* sl_frame_look's, px NULL when none */
};

/* (p, 1) as a vec4 for glm_mat4_mulv, in one 16-byte store. Written as
 * {x, y, z, 1} it was stored in two 8-byte halves, and the product's
 * 16-byte load waited on store forwarding: perf put half the time of the
 * per-pixel loops that project every pixel (conservative, hertel, nsm) on
 * that wait. The same values into the same product: the same bits. */
static inline void sl_point4(const float p[3], vec4 w)
{
#if defined(__SSE2__)
    _mm_store_ps(w, _mm_setr_ps(p[0], p[1], p[2], 1.0f));
#else
    w[0] = p[0], w[1] = p[1], w[2] = p[2], w[3] = 1.0f;
#endif
}

/* Project a world point into the frame: texel coordinates in [0, size) (not
 * clamped; u, v may fall outside for points outside the box) and window
 * depth. Where w is 1 (the orthographic box of a directional light: its last
 * row is 0, 0, 0, 1) the three divisions are skipped: x / 1 == x in IEEE
 * arithmetic for every x, so the bits are the same, and the divisions were
 * the longest step of every method's per-pixel projection. */
static inline void sl_frame_project(const struct sl_light_frame *f, const float p[3],
                                    float *u, float *v, float *z)
{
    vec4 w, c;
    sl_point4(p, w);
    glm_mat4_mulv((vec4 *)f->box.vp, w, c);
    if (c[3] != 1.0f) {
        c[0] /= c[3];
        c[1] /= c[3];
        c[2] /= c[3];
    }
    *u = (c[0] * 0.5f + 0.5f) * (float)f->size;
    *v = (c[1] * 0.5f + 0.5f) * (float)f->size;
    *z = c[2];
}

/* The unit direction from p toward the light, and how far a shadow ray from
 * p may look (INFINITY for a directional light). For a point light the ray
 * stops short of the light by its own tnear (sl_point_ray, arealight.h),
 * computed here exactly as the truth computes it. */
void sl_frame_toward(const struct sl_light_frame *f, const float p[3], float dir[3], float *tmax);

/* Depth along the light (world units from the light for a point light,
 * from the box's zero for a directional one) of a window depth. */
static inline double sl_frame_depth_of(const struct sl_light_frame *f, double z)
{
    double n = f->box.lo[2], fa = f->box.hi[2];
    if (!f->box.persp)
        return n + z * (fa - n);
    return fa * n / (fa - (fa - n) * z);
}

/* World units along the light per unit of window depth at window depth z:
 * the constant depth_range of a box, d^2 / B of a perspective frustum. */
static inline double sl_frame_world_per_depth(const struct sl_light_frame *f, double z)
{
    if (!f->box.persp)
        return f->depth_range;
    double n = f->box.lo[2], fa = f->box.hi[2], d = sl_frame_depth_of(f, z);
    return d * d * (fa - n) / (fa * n);
}

/* World units across one texel at window depth z (the larger side). */
static inline double sl_frame_texel_world_at(const struct sl_light_frame *f, double z)
{
    return f->box.persp ? f->texel_world * sl_frame_depth_of(f, z) : f->texel_world;
}

/* Whether texel coordinates fall inside the map: always so for a
 * directional light's receivers, not for those a point light's frustum
 * leaves outside (lightfit.c), whose lookups read the map's border. */
static inline int sl_frame_inside(const struct sl_light_frame *f, float u, float v)
{
    return u >= 0.0f && v >= 0.0f && u < (float)f->size && v < (float)f->size;
}

/* Texel index of texel coordinates, clamped to the map. */
static inline uint32_t sl_frame_texel(const struct sl_light_frame *f, float u, float v)
{
    int i = (int)floorf(u), j = (int)floorf(v);
    if (i < 0) i = 0;
    if (j < 0) j = 0;
    if (i >= f->size) i = f->size - 1;
    if (j >= f->size) j = f->size - 1;
    return (uint32_t)j * (uint32_t)f->size + (uint32_t)i;
}

/* Layer l (rendered) replaced by its values at each pixel's own texel:
 * for every pixel of v that a method decides (neither background nor
 * PnFL), depth[i] and id[i] (id when the layer has one) are those of
 * texel sl_frame_texel(sl_frame_project(pos[i])), the very texel every
 * per-pixel reader computes (clamped to the map); other pixels hold 1 and
 * 0, read by no one. The dense arrays go back to f->pool, the
 * new ones come from f->pix_pool. Only for readers that look a layer up at
 * the pixel's own texel and nowhere else (method.h: at_pixel): at a big map
 * size a view's pixels are far fewer than the map's texels (1920x1080
 * against 4096^2: 8 MB against 64 MiB an array). SL_E_NOMEM when out of
 * memory (the layer then stays dense). */
struct sl_view;
enum sl_err sl_frame_gather(struct sl_light_frame *f, int l, const struct sl_view *v, int threads,
                            struct sl_diag *d);

/* Percentage-closer count at texel coordinates (u, v) and window depth z
 * in a depth array of S x S texels: how many of the texels light the
 * point (z <= depth), over the 2x2 of its bilinear footprint (texels 4:
 * from floor(u - 1/2), floor(v - 1/2)) or the 3x3 around its texel
 * (texels 9), each texel clamped to the map at its border. */
static inline int sl_frame_pcf_lit(const float *depth, int S, float u, float v, float z, int texels)
{
    int x0, y0, n;
    if (texels == 4) {
        x0 = (int)floorf(u - 0.5f);
        y0 = (int)floorf(v - 0.5f);
        n = 2;
    } else {
        x0 = (int)floorf(u) - 1;
        y0 = (int)floorf(v) - 1;
        n = 3;
    }
    int lit = 0;
    if (x0 >= 0 && y0 >= 0 && x0 + n <= S && y0 + n <= S) {
        /* the footprint inside the map (all but the border texels): no clamps */
        const float *row = depth + (size_t)y0 * (size_t)S + (size_t)x0;
        for (int j = 0; j < n; j++, row += S)
            for (int i = 0; i < n; i++)
                lit += z <= row[i];
        return lit;
    }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int tx = x0 + i, ty = y0 + j;
            tx = tx < 0 ? 0 : tx >= S ? S - 1 : tx;
            ty = ty < 0 ? 0 : ty >= S ? S - 1 : ty;
            lit += z <= depth[(size_t)ty * (size_t)S + (size_t)tx];
        }
    return lit;
}

/* Each pixel's lookup in dense layer l for view v (struct sl_pix_look),
 * made here once per (frame, view, layer) and kept in f->look, for the
 * methods that look the layer up around each pixel's texel (Moderno's,
 * method.h: looks): each computed the same projection, texel and depth
 * test per pixel, and the depth test's load, a cache miss in a map of
 * 4-16 MiB, was a quarter of their time. The same inline code as theirs,
 * so the same bits. Arrays from f->pix_pool. SL_E_NOMEM when out of
 * memory; SL_E_INTERNAL when the layer is not dense. */
enum sl_err sl_frame_look(struct sl_light_frame *f, int l, const struct sl_view *v, int threads,
                          unsigned parts, struct sl_diag *d);
/* parts: also each pixel's percentage-closer counts (sl_frame_pcf_lit, 4
 * and 9 texels), for the methods that test the texels around the pixel's
 * (Moderno's coherence and its chain): added to lookups made without them */
#define SL_LOOK_PCF 1u
/* f's lookups in layer l for view v, NULL when sl_frame_look did not make them. */
static inline const struct sl_frame_look *sl_frame_look_of(const struct sl_light_frame *f, int l,
                                                           uint64_t serial, size_t n)
{
    const struct sl_frame_look *k = &f->look;
    return k->px && k->layer == l && k->serial == serial && k->n == n && (f->have & SL_NEED(l)) &&
           !f->layer[l].per_pixel ? k : NULL;
}

/* Give one layer's arrays back (to the pool, or free) and mark it not rendered. */
void sl_frame_drop_layer(struct sl_light_frame *f, int layer);
/* Every layer dropped; the frame is zeroed (its pool pointer too). */
void sl_frame_free(struct sl_light_frame *f);

#endif
