/*
 * frame.c — see frame.h: a frame's rays toward the light, the layer-array
 * pool, the frees and the layers' names.
 */
#define _GNU_SOURCE
#include "frame.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include "arealight.h"
#include "util.h"
#include "view.h"

const char *const sl_layer_names[SL_LAYER_COUNT] = {
#define SL_LAYER_NAME(id, name, title) name,
    SL_LAYERS(SL_LAYER_NAME)
#undef SL_LAYER_NAME
};

const char *const sl_layer_titles[SL_LAYER_COUNT] = {
#define SL_LAYER_TITLE(id, name, title) title,
    SL_LAYERS(SL_LAYER_TITLE)
#undef SL_LAYER_TITLE
};

void sl_frame_toward(const struct sl_light_frame *f, const float p[3], float dir[3], float *tmax)
{
    if (!f->box.persp) {
        for (int k = 0; k < 3; k++)
            dir[k] = -f->dir[k];
        *tmax = INFINITY;
    } else if (!sl_point_ray(f->box.eye, p, dir, tmax)) {
        dir[0] = dir[1] = 0.0f;   /* at the light itself: no ray */
        dir[2] = 1.0f;
        *tmax = 0.0f;
    }
}

/* Arrays from 4 MiB up are aligned to the 2 MiB of a huge page and advised
 * as such; smaller ones are not worth a huge page's zeroing. */
#define HUGE_FROM ((size_t)4 << 20)
#define HUGE_ALIGN ((size_t)2 << 20)

static void *pool_alloc(size_t bytes)
{
    if (bytes < HUGE_FROM)
        return malloc(bytes);
    void *p = NULL;
    size_t n = (bytes + HUGE_ALIGN - 1) & ~(HUGE_ALIGN - 1);
    if (posix_memalign(&p, HUGE_ALIGN, n))
        return NULL;
#ifdef MADV_HUGEPAGE
    madvise(p, n, MADV_HUGEPAGE);   /* advice only: a kernel without THP ignores it */
#endif
    return p;
}

void *sl_layer_pool_get(struct sl_layer_pool *p, size_t bytes)
{
    if (!bytes)
        bytes = 1;
    /* the smallest idle array that is large enough */
    int best = -1, small = -1;
    for (int i = 0; i < p->n; i++) {
        if (p->slot[i].busy)
            continue;
        if (p->slot[i].bytes >= bytes) {
            if (best < 0 || p->slot[i].bytes < p->slot[best].bytes)
                best = i;
        } else if (small < 0 || p->slot[i].bytes < p->slot[small].bytes) {
            small = i;
        }
    }
    if (best >= 0) {
        p->slot[best].busy = 1;
        return p->slot[best].p;
    }
    /* none: replace an idle one that is too small, else take a new slot */
    int s = small >= 0 ? small : p->n < SL_POOL_SLOTS ? p->n : -1;
    void *a = pool_alloc(bytes);
    if (!a)
        return NULL;
    p->allocs++;
    if (s < 0)
        return a;   /* every slot busy: an array outside the pool, freed on return */
    if (s == p->n)
        p->n++;
    else {
        free(p->slot[s].p);
        p->bytes -= p->slot[s].bytes;
    }
    p->slot[s].p = a;
    p->slot[s].bytes = bytes;
    p->slot[s].busy = 1;
    p->bytes += bytes;
    return a;
}

void sl_layer_pool_put(struct sl_layer_pool *p, void *ptr)
{
    if (!ptr)
        return;
    for (int i = 0; i < p->n; i++)
        if (p->slot[i].p == ptr) {
            p->slot[i].busy = 0;
            return;
        }
    free(ptr);
}

void sl_layer_pool_free(struct sl_layer_pool *p)
{
    for (int i = 0; i < p->n; i++)
        free(p->slot[i].p);
    memset(p, 0, sizeof *p);
}

/* One array of a layer handed back: to the pool it came from, else freed. */
static void layer_put(struct sl_layer_pool *pool, void *a)
{
    if (pool)
        sl_layer_pool_put(pool, a);
    else
        free(a);
}

/* No texel: a pixel the methods do not decide (frame.h: sl_frame_gather). */
#define NO_TEXEL UINT32_MAX

/* Each pixel's texel under f, computed once per frame and view: every
 * gathered layer of the frame reads the same ones (projecting each pixel
 * once, not once per layer). */
static const uint32_t *pixel_texels(struct sl_light_frame *f, const struct sl_view *v, int threads)
{
    const size_t n = (size_t)v->w * (size_t)v->h;
    if (f->pix_texel && f->pix_serial == v->serial && f->pix_n == n)
        return f->pix_texel;
    layer_put(f->pix_pool, f->pix_texel);
    f->pix_texel = NULL;
    uint32_t *k = f->pix_pool ? sl_layer_pool_get(f->pix_pool, n * 4) : malloc(n * 4);
    if (!k)
        return NULL;
    /* the pixels sl_verdict_fixed (method.h) leaves to the method, and the
     * projection and texel the methods compute (frame.h): the same inline
     * code, so the same texel; inside the map or not (clamped), as a reader
     * that looks before it checks (cell.c's violation report) reads */
#pragma omp parallel for num_threads(threads > 0 ? threads : 1) schedule(static)
    for (long i = 0; i < (long)n; i++) {
        uint32_t t = NO_TEXEL;
        if (v->cls[i] != SL_C_BACKGROUND && v->cls[i] != SL_C_PNFL) {
            float u, w, z;
            sl_frame_project(f, v->pos + 3 * (size_t)i, &u, &w, &z);
            t = sl_frame_texel(f, u, w);
        }
        k[i] = t;
    }
    f->pix_texel = k;
    f->pix_serial = v->serial;
    f->pix_n = n;
    return k;
}

/* The lookups' arrays back to the pool; none kept. */
static void look_drop(struct sl_light_frame *f)
{
    layer_put(f->pix_pool, f->look.px);
    layer_put(f->pix_pool, f->look.id);
    layer_put(f->pix_pool, f->look.pcf);
    memset(&f->look, 0, sizeof f->look);
}

enum sl_err sl_frame_gather(struct sl_light_frame *f, int l, const struct sl_view *v, int threads,
                            struct sl_diag *d)
{
    struct sl_depth_layer *L = &f->layer[l];
    if (L->per_pixel || !L->depth)
        return SL_OK;
    const size_t n = (size_t)v->w * (size_t)v->h;
    const uint32_t *tex = pixel_texels(f, v, threads);
    float *depth = !tex ? NULL : f->pix_pool ? sl_layer_pool_get(f->pix_pool, n * 4) : malloc(n * 4);
    uint32_t *id = NULL;
    if (depth && L->id && !(id = f->pix_pool ? sl_layer_pool_get(f->pix_pool, n * 4) : malloc(n * 4))) {
        layer_put(f->pix_pool, depth);
        depth = NULL;
    }
    if (!depth)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "layer gathered per pixel (%dx%d)", v->w, v->h);
    const float *dd = L->depth;
    const uint32_t *di = L->id;
#pragma omp parallel for num_threads(threads > 0 ? threads : 1) schedule(static)
    for (long i = 0; i < (long)n; i++) {
        const uint32_t k = tex[i];
        depth[i] = k == NO_TEXEL ? 1.0f : dd[k];
        if (id)
            id[i] = k == NO_TEXEL ? 0u : di[k];
    }
    if (f->look.px && f->look.layer == l)
        look_drop(f);   /* made on the dense arrays given back here */
    layer_put(f->pool, L->depth);
    layer_put(f->pool, L->id);
    L->depth = depth;
    L->id = id;
    L->per_pixel = 1;
    return SL_OK;
}

/* The percentage-closer counts added to f's lookups (sl_frame_look). */
static enum sl_err look_pcf(struct sl_light_frame *f, const struct sl_view *v, int threads, struct sl_diag *d)
{
    struct sl_frame_look *k = &f->look;
    const double t0 = sl_now();
    uint8_t *pcf = f->pix_pool ? sl_layer_pool_get(f->pix_pool, k->n) : malloc(k->n);
    if (!pcf)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "percentage-closer counts per pixel (%dx%d)", v->w, v->h);
    const float *dd = f->layer[k->layer].depth;
    const struct sl_pix_look *px = k->px;
    const int S = f->size;
#pragma omp parallel for num_threads(threads > 0 ? threads : 1) schedule(static)
    for (long i = 0; i < (long)k->n; i++) {
        uint8_t c = 0;
        if (v->cls[i] != SL_C_BACKGROUND && v->cls[i] != SL_C_PNFL) {
            const struct sl_pix_look q = px[i];
            c = (uint8_t)(sl_frame_pcf_lit(dd, S, q.u, q.v, q.z, 4) | sl_frame_pcf_lit(dd, S, q.u, q.v, q.z, 9) << 4);
        }
        pcf[i] = c;
    }
    k->pcf = pcf;
    k->ms_pcf = 1e3 * (sl_now() - t0);
    return SL_OK;
}

enum sl_err sl_frame_look(struct sl_light_frame *f, int l, const struct sl_view *v, int threads,
                          unsigned parts, struct sl_diag *d)
{
    const size_t n = (size_t)v->w * (size_t)v->h;
    if (sl_frame_look_of(f, l, v->serial, n))
        return (parts & SL_LOOK_PCF) && !f->look.pcf ? look_pcf(f, v, threads, d) : SL_OK;
    const struct sl_depth_layer *L = &f->layer[l];
    if (!(f->have & SL_NEED(l)) || L->per_pixel || !L->depth || !L->id)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "lookups: layer %d is not a dense depth + id layer", l);
    double t0 = sl_now();
    look_drop(f);
    struct sl_pix_look *px = f->pix_pool ? sl_layer_pool_get(f->pix_pool, n * sizeof *px) : malloc(n * sizeof *px);
    uint32_t *id = !px ? NULL : f->pix_pool ? sl_layer_pool_get(f->pix_pool, n * 4) : malloc(n * 4);
    if (!id) {
        layer_put(f->pix_pool, px);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "lookups per pixel (%dx%d)", v->w, v->h);
    }
    const float *dd = L->depth;
    const uint32_t *di = L->id;
    /* the pixels sl_verdict_fixed leaves to the methods; the projection,
     * texel and depth test of theirs (moderno.c), inline here as there */
#pragma omp parallel for num_threads(threads > 0 ? threads : 1) schedule(static)
    for (long i = 0; i < (long)n; i++) {
        struct sl_pix_look q = {0};
        uint32_t t = 0;
        if (v->cls[i] != SL_C_BACKGROUND && v->cls[i] != SL_C_PNFL) {
            sl_frame_project(f, v->pos + 3 * (size_t)i, &q.u, &q.v, &q.z);
            const uint32_t k = sl_frame_texel(f, q.u, q.v);
            q.k = k | (q.z <= dd[k] ? 0u : SL_LOOK_SHADOW);
            t = di[k];
        }
        px[i] = q;
        id[i] = t;
    }
    f->look = (struct sl_frame_look){.px = px, .id = id, .layer = l, .serial = v->serial, .n = n,
                                     .ms = 1e3 * (sl_now() - t0)};
    return (parts & SL_LOOK_PCF) ? look_pcf(f, v, threads, d) : SL_OK;
}

void sl_frame_drop_layer(struct sl_light_frame *f, int l)
{
    if (f->look.px && f->look.layer == l)
        look_drop(f);
    struct sl_depth_layer *L = &f->layer[l];
    struct sl_layer_pool *pool = L->per_pixel ? f->pix_pool : f->pool;
    if (pool) {
        sl_layer_pool_put(pool, L->depth);
        sl_layer_pool_put(pool, L->id);
    } else {
        free(L->depth);
        free(L->id);
    }
    memset(L, 0, sizeof *L);
    f->have &= ~SL_NEED(l);
}

void sl_frame_free(struct sl_light_frame *f)
{
    if (!f)
        return;
    for (int i = 0; i < SL_LAYER_COUNT; i++)
        sl_frame_drop_layer(f, i);
    look_drop(f);
    layer_put(f->pix_pool, f->pix_texel);
    memset(f, 0, sizeof *f);
}

void sl_light_box_free(struct sl_light_box *b)
{
    free(b->unmapped);
    b->unmapped = NULL;
    b->n_unmapped = 0;
}
