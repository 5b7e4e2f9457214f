/*
 * run.c — see run.h.
 *
 * Invariants: cells are visited in sweep order, so the cells sharing a scene,
 * a view and a map size are contiguous and each shared stage is computed once
 * for them (the caches below hold the current scene, view and frame); the
 * layers rendered for a (view, map size) are the union of what the methods of
 * the selected cells in that group declare; methods see the view without
 * its truth.
 */
#define _XOPEN_SOURCE 700
#include "run.h"
#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <limits.h>
#include <signal.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "adjacency.h"
#include "arealight.h"
#include "softfig.h"
#include "softmap.h"
#include "softmc.h"
#include "softtruth.h"
#include "contour.h"
#include "gbuffer.h"
#include "glctx.h"
#include "image.h"
#include "lightfit.h"
#include "outputs.h"
#include "overlay.h"
#include "shadowmap.h"
#include "scenefile.h"
#include "store.h"
#include "table.h"
#include "truth.h"
#include "util.h"

/* Bump when anything that determines the truth changes (tnear, filter, PFL
 * rule), so cached truths of older code are never read. */
#define SL_TRUTH_VERSION "truth-v1 own-triangle-filter tnear=2^-16|p|+2^-24 face-normal-pfl"

void sl_run_result_free(struct sl_run_result *r)
{
    if (!r)
        return;
    free(r->cells);
    memset(r, 0, sizeof *r);
}

static int popcount(unsigned m)
{
    int n = 0;
    for (; m; m &= m - 1)
        n++;
    return n;
}

/* The j-th set bit of mask (j < popcount(mask)). */
static int nth_bit(unsigned mask, int j)
{
    int b = 0;
    while (!(mask & (1u << b)) || j-- > 0)
        b++;
    return b;
}

int sl_plan_count(const struct sl_config *c)
{
    int n = 0;
    for (int s = 0; s < c->nscenes; s++)
        n += c->nviewports * c->scenes[s].nviewpoints * popcount(c->scenes[s].map_mask) *
             popcount(c->scenes[s].method_mask);
    return n;
}

void sl_plan_cell(const struct sl_config *c, int index, struct sl_cell_key *k)
{
    memset(k, 0, sizeof *k);
    for (int s = 0; s < c->nscenes; s++) {
        const struct sl_config_scene *cs = &c->scenes[s];
        int nm = popcount(cs->map_mask), nl = popcount(cs->method_mask);
        int per = c->nviewports * cs->nviewpoints * nm * nl;
        if (index < per) {
            k->scene = s;
            k->method = nth_bit(cs->method_mask, index % nl);
            index /= nl;
            k->map = nth_bit(cs->map_mask, index % nm);
            index /= nm;
            k->vp = index % cs->nviewpoints;
            k->viewport = index / cs->nviewpoints;
            return;
        }
        index -= per;
    }
}

static int rm_cb(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb; (void)flag; (void)ftw;
    return remove(p);
}

static void rm_tree(const char *path)
{
    nftw(path, rm_cb, 16, FTW_DEPTH | FTW_PHYS);
}

/* ---- truth cache ----
 *
 * One file per view and kind of truth in the cache folder, named by its key:
 * truth-<key>.bin (the hard truth) and area-<key>.bin (an area light's
 * visible fraction, its standard error and the hard truth of its centre).
 * Every file is a fixed header then the payload:
 *   magic[8] (the kind), format version, number of parts, key, width,
 *   height, payload length, FNV-1a 64 of the payload
 * in the machine's byte order (the keys hash native floats, so a cache is
 * the machine's own anyway). A file is used only when every header field is
 * the expected one, the payload has exactly the expected length with
 * nothing after it, its checksum matches and its values agree with the
 * view's classes; anything else (a write cut short, another format, a key
 * collision, a damaged disk) is ignored, the truth recomputed and the file
 * replaced. Files are written to a temporary name and renamed into place,
 * so a reader never sees a half-written one. */

/* Bump when the layout of a cache file changes. */
#define SL_CACHE_FORMAT 2u

/* What a scene's truths depend on besides the view: hashed once per scene
 * (the geometry is the bulk of it). */
static unsigned long long scene_key(const struct sl_scene *s, const struct sl_gl *gl, const struct sl_rt *rt)
{
    unsigned long long k = SL_FNV_SEED;
    k = sl_fnv1a(k, SL_TRUTH_VERSION, strlen(SL_TRUTH_VERSION));
    k = sl_fnv1a(k, s->pos, (size_t)s->nv * 3 * sizeof(float));
    k = sl_fnv1a(k, s->idx, (size_t)s->nt * 3 * sizeof(uint32_t));
    k = sl_fnv1a(k, &s->light, sizeof s->light);
    /* the G-buffer positions come from GL: another renderer, another truth */
    k = sl_fnv1a(k, gl->renderer, strlen(gl->renderer));
    k = sl_fnv1a(k, gl->version, strlen(gl->version));
    k = sl_fnv1a(k, rt->version, strlen(rt->version));
    return k;
}

static unsigned long long truth_key(unsigned long long scene, const struct sl_viewpoint *vp, int w, int h)
{
    unsigned long long k = sl_fnv1a(scene, vp, sizeof *vp);
    k = sl_fnv1a(k, &w, sizeof w);
    return sl_fnv1a(k, &h, sizeof h);
}

/* An area truth adds to the view's truth key its rules, the cache format,
 * its samples per side (resolved, so 0 and 32 share a file) and its seed,
 * and a few of its sample points: the sample pattern is shared with soft_mc
 * (arealight.h), so a change made there for soft_mc is a new key here. */
static unsigned long long area_key(unsigned long long view, int side, uint32_t seed)
{
    const uint32_t format = SL_CACHE_FORMAT, n = (uint32_t)side;
    unsigned long long k = sl_fnv1a(view, SL_SOFT_TRUTH_VERSION, strlen(SL_SOFT_TRUTH_VERSION));
    k = sl_fnv1a(k, &format, sizeof format);
    k = sl_fnv1a(k, &side, sizeof side);
    k = sl_fnv1a(k, &seed, sizeof seed);
    for (uint32_t i = 0; i < 8; i++) {
        double uv[2];
        sl_area_jitter(37 * i, 11 * i, (5 * i) % (n * n), n, seed, &uv[0], &uv[1]);
        k = sl_fnv1a(k, uv, sizeof uv);
    }
    return k;
}

struct cache_head {
    char     magic[8];
    uint32_t format, parts;
    uint64_t key;
    int32_t  w, h;
    uint64_t bytes, sum;
};
_Static_assert(sizeof(struct cache_head) == 48, "the cache header is written as it lies in memory");

/* One array of a cache file's payload. */
struct cache_part {
    const void *p;
    size_t      n;   /* bytes */
};

enum cache_read { CACHE_MISS, CACHE_REJECTED, CACHE_HIT };

static void cache_path(char *path, size_t size, const char *dir, const char *kind, unsigned long long key)
{
    snprintf(path, size, "%s/%s-%016llx.bin", dir, kind, key);
}

/* The payload of the file of (kind, key) into *out (malloc'd, `bytes`
 * long): CACHE_HIT when its header, length and checksum are all as
 * expected; CACHE_MISS when there is no file; CACHE_REJECTED otherwise. */
static enum cache_read cache_load(const char *dir, const char *kind, const char magic[8], unsigned long long key,
                                  int w, int h, uint32_t parts, size_t bytes, void **out)
{
    char path[1200];
    cache_path(path, sizeof path, dir, kind, key);
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return CACHE_MISS;
    struct cache_head hd;
    void *buf = malloc(bytes ? bytes : 1);
    int ok = buf && fread(&hd, sizeof hd, 1, f) == 1 && memcmp(hd.magic, magic, 8) == 0 &&
             hd.format == SL_CACHE_FORMAT && hd.parts == parts && hd.key == key && hd.w == w && hd.h == h &&
             hd.bytes == bytes && fread(buf, 1, bytes, f) == bytes && fgetc(f) == EOF && !ferror(f) &&
             sl_fnv1a(SL_FNV_SEED, buf, bytes) == hd.sum;
    fclose(f);
    if (!ok) {
        free(buf);
        return CACHE_REJECTED;
    }
    *out = buf;
    return CACHE_HIT;
}

/* Write the file of (kind, key): a temporary file renamed into place. */
static void cache_store(const char *dir, const char *kind, const char magic[8], unsigned long long key, int w,
                        int h, const struct cache_part *part, uint32_t parts)
{
    char path[1200], tmp[1300];
    cache_path(path, sizeof path, dir, kind, key);
    snprintf(tmp, sizeof tmp, "%s.tmp-%ld", path, (long)getpid());
    struct cache_head hd;
    memset(&hd, 0, sizeof hd);
    memcpy(hd.magic, magic, 8);
    hd.format = SL_CACHE_FORMAT;
    hd.parts = parts;
    hd.key = key;
    hd.w = w;
    hd.h = h;
    hd.sum = SL_FNV_SEED;
    for (uint32_t i = 0; i < parts; i++) {
        hd.bytes += part[i].n;
        hd.sum = sl_fnv1a(hd.sum, part[i].p, part[i].n);   /* FNV runs on: the parts hash as one */
    }
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return;   /* a cache that cannot be written is only a lost speed-up */
    int ok = fwrite(&hd, sizeof hd, 1, f) == 1;
    for (uint32_t i = 0; ok && i < parts; i++)
        ok = fwrite(part[i].p, 1, part[i].n, f) == part[i].n;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0)
        remove(tmp);
}

/* 1 when a truth image agrees with the view's classes (then *lit and
 * *shadow are its counts), 0 otherwise. */
static int truth_agrees(const struct sl_view *v, const uint8_t *truth, uint64_t *lit_out, uint64_t *shadow_out)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    uint64_t lit = 0, shadow = 0;
    for (size_t i = 0; i < n; i++) {
        uint8_t t = truth[i], c = v->cls[i];
        if (!((c == SL_C_BACKGROUND && t == SL_T_BACKGROUND) || (c == SL_C_PNFL && t == SL_T_PNFL) ||
              (c == SL_C_PFL && (t == SL_T_LIT || t == SL_T_SHADOW))))
            return 0;
        lit += t == SL_T_LIT;
        shadow += t == SL_T_SHADOW;
    }
    *lit_out = lit;
    *shadow_out = shadow;
    return 1;
}

static const char truth_magic[8] = {'S', 'L', 'T', 'R', 'U', 'T', 'H', '2'};

/* CACHE_HIT and v->truth filled when a valid cache entry exists and agrees
 * with the view's classes; otherwise v->truth is untouched (then it is
 * traced). */
static enum cache_read truth_cache_read(const char *dir, unsigned long long key, struct sl_view *v)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    void *buf;
    uint64_t lit, shadow;
    enum cache_read r = cache_load(dir, "truth", truth_magic, key, v->w, v->h, 1, n, &buf);
    if (r == CACHE_HIT && !truth_agrees(v, buf, &lit, &shadow))
        r = CACHE_REJECTED;
    if (r == CACHE_HIT) {
        memcpy(v->truth, buf, n);
        v->n_lit = lit;
        v->n_shadow = shadow;
    }
    free(buf);
    return r;
}

static void truth_cache_write(const char *dir, unsigned long long key, const struct sl_view *v)
{
    struct cache_part part = {v->truth, (size_t)v->w * (size_t)v->h};
    cache_store(dir, "truth", truth_magic, key, v->w, v->h, &part, 1);
}

static const char area_magic[8] = {'S', 'L', 'A', 'R', 'E', 'A', 'V', '1'};

/* CACHE_HIT with the visible fraction, its standard error and the centre's
 * hard truth filled when a valid entry exists: its fractions and errors in
 * [0, 1], 0 on the background, and the point truth agreeing with the view's
 * classes. Otherwise nothing is written. */
static enum cache_read area_cache_read(const char *dir, unsigned long long key, struct sl_view *v, float *visible,
                                       float *se)
{
    size_t n = (size_t)v->w * (size_t)v->h, nf = n * sizeof(float);
    void *buf;
    enum cache_read r = cache_load(dir, "area", area_magic, key, v->w, v->h, 3, 2 * nf + n, &buf);
    if (r != CACHE_HIT)
        return r;
    const float *fv = buf, *fs = fv + n;   /* malloc'd: aligned for float */
    const uint8_t *truth = (const uint8_t *)buf + 2 * nf;
    uint64_t lit, shadow;
    int ok = truth_agrees(v, truth, &lit, &shadow);
    for (size_t i = 0; ok && i < n; i++)
        ok = v->tri[i] ? (fv[i] >= 0.0f && fv[i] <= 1.0f && fs[i] >= 0.0f && fs[i] <= 1.0f)
                       : (fv[i] == 0.0f && fs[i] == 0.0f);
    if (ok) {
        memcpy(visible, fv, nf);
        memcpy(se, fs, nf);
        memcpy(v->truth, truth, n);
        v->n_lit = lit;
        v->n_shadow = shadow;
    }
    free(buf);
    return ok ? CACHE_HIT : CACHE_REJECTED;
}

static void area_cache_write(const char *dir, unsigned long long key, const struct sl_view *v, const float *visible,
                             const float *se)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    struct cache_part part[3] = {{visible, n * sizeof(float)}, {se, n * sizeof(float)}, {v->truth, n}};
    cache_store(dir, "area", area_magic, key, v->w, v->h, part, 3);
}

/* ---- the run ---- */

/* Repetitions of a timed stage: the config's warm-up runs, then its timed
 * runs; the stage's real computation is repetition 0, so a config with one
 * run and no warm-up times each stage once and repeats nothing. */
#define SL_MAX_REPS 1100   /* config: warm-up <= 100, runs <= 1000 */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* {median, min, max} of n >= 1 times (sorted in place). */
static void med_min_max(double *t, int n, double out[3])
{
    qsort(t, (size_t)n, sizeof t[0], cmp_double);
    out[SL_MED] = n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
    out[SL_MIN] = t[0];
    out[SL_MAX] = t[n - 1];
}

struct run_ctx {
    struct sl_gl gl;
    struct sl_rt rt;
    /* current scene */
    int scene_i;
    struct sl_scene scene;
    unsigned long long scene_key;      /* truth cache key of the scene */
    struct sl_adjacency adj;
    int have_adj;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gpass;
    struct sl_shadowmap_pass spass;
    /* current view */
    int view_scene, view_vp, view_viewport;
    struct sl_view view;
    struct sl_light_box box;
    struct sl_stage_ms vms;
    int truth_cached;
    uint64_t truth_rays;
    /* current frame */
    int frame_map;
    struct sl_light_frame frame;
    double layer_ms[SL_LAYER_COUNT][3];   /* render time of each layer: median, min, max */
    uint64_t view_bad, layer_bad[SL_LAYER_COUNT];   /* values that are not finite or out of range */
    /* per-pixel scratch */
    int W, H;
    uint8_t *state, *band, *rgb;
    struct sl_verdicts vd;
    /* an area light's scene: its truth is the visible fraction (softtruth.h) */
    int area;
    float *soft_truth, *soft_se;
    /* its layers for soft_mc (softmap.h) and their N-buffer, per (view, map size) */
    struct sl_softmap_pass softpass;
    struct sl_softmap softmap;
    struct sl_softmc_nbuf nbuf;
    int soft_map;                        /* map index the layers are for, -1 none */
    uint8_t *receivers;                  /* per scene range: a pure receiver */
};

static void drop_frame(struct run_ctx *x)
{
    sl_frame_free(&x->frame);
    x->frame_map = -1;
}

static void drop_view(struct run_ctx *x)
{
    drop_frame(x);
    sl_light_box_free(&x->box);
    sl_softmap_free(&x->softmap);
    memset(&x->softmap, 0, sizeof x->softmap);
    x->soft_map = -1;
    sl_view_free(&x->view);
    x->view_scene = x->view_vp = x->view_viewport = -1;
}

static void drop_scene(struct run_ctx *x)
{
    drop_view(x);
    sl_rt_free(&x->rt);
    if (x->have_adj)
        sl_adjacency_free(&x->adj);
    x->have_adj = 0;
    if (x->gl.ctx) {
        sl_gbuffer_free(&x->gpass);
        sl_gl_mesh_free(&x->mesh);
    }
    sl_scene_free(&x->scene);
    x->scene_i = -1;
}

static void ctx_free(struct run_ctx *x)
{
    drop_scene(x);
    free(x->state);
    free(x->band);
    free(x->rgb);
    free(x->vd.v);
    free(x->vd.how);
    free(x->vd.base);
    free(x->vd.detail);
    free(x->vd.tests);
    free(x->vd.vis);
    free(x->soft_truth);
    free(x->soft_se);
    free(x->receivers);
    sl_softmc_nbuf_free(&x->nbuf);
    if (x->gl.ctx) {
        sl_softmap_pass_free(&x->softpass);
        sl_shadowmap_free(&x->spass);
        sl_gl_free(&x->gl);
    }
}

static enum sl_err ensure_scene(struct run_ctx *x, const struct sl_config *c, int si,
                                struct sl_run_result *res, struct sl_diag *d)
{
    if (x->scene_i == si)
        return SL_OK;
    drop_scene(x);
    double t0 = sl_now();
    enum sl_err e = sl_scene_load(c->scenes[si].path, &x->scene, d);
    if (e)
        return e;
    res->ms_scene += 1e3 * (sl_now() - t0);
    if ((e = sl_gl_mesh_upload(&x->mesh, &x->scene, d)) || (e = sl_gbuffer_init(&x->gpass, &x->scene, d)) ||
        (e = sl_rt_build(&x->rt, &x->scene, c->threads, 1, d)))
        return e;
    res->ms_bvh += x->rt.ms_build;
    res->passes.scenes++;
    x->area = x->scene.light.type == SL_LIGHT_AREA;
    free(x->receivers);
    x->receivers = sl_calloc((size_t)(x->scene.nranges ? x->scene.nranges : 1), 1);
    if (!x->receivers)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "receiver flags");
    for (int r = 0; r < x->scene.nranges; r++)
        x->receivers[r] = (uint8_t)x->scene.ranges[r].receiver;
    x->scene_key = scene_key(&x->scene, &x->gl, &x->rt);
    unsigned needs = 0;
    for (int m = 0; m < c->nmethods; m++)
        if (c->scenes[si].method_mask & (1u << m))
            needs |= c->methods[m].method->needs(&c->methods[m].params);
    if (needs & SL_NEED_ADJACENCY) {
        if ((e = sl_adjacency_build(&x->scene, &x->adj, d)))
            return e;
        x->have_adj = 1;
        if ((e = sl_gl_mesh_upload_adjacency(&x->mesh, &x->scene, &x->adj, d)))
            return e;
        res->passes.adjacency++;
    }
    x->scene_i = si;
    return SL_OK;
}

static enum sl_err ensure_buffers(struct run_ctx *x, int W, int H, struct sl_diag *d)
{
    if (x->W == W && x->H == H)
        return SL_OK;
    size_t npx = (size_t)W * (size_t)H;
    free(x->state); free(x->band); free(x->rgb); free(x->vd.v); free(x->vd.how); free(x->vd.base);
    free(x->vd.detail);
    free(x->vd.tests);
    free(x->vd.vis);
    free(x->soft_truth);
    free(x->soft_se);
    x->vd.vis = sl_calloc(npx, sizeof(float));
    x->soft_truth = sl_calloc(npx, sizeof(float));
    x->soft_se = sl_calloc(npx, sizeof(float));
    x->vd.tests = sl_calloc(npx, 1);
    x->vd.base = sl_calloc(npx, 1);
    x->vd.detail = sl_calloc(npx, 1);
    x->state = sl_calloc(npx, 1);
    x->band = sl_calloc(npx, 1);
    x->rgb = sl_calloc(npx, 3);
    x->vd.v = sl_calloc(npx, 1);
    x->vd.how = sl_calloc(npx, 1);
    x->W = x->vd.w = W;
    x->H = x->vd.h = H;
    if (!x->state || !x->band || !x->rgb || !x->vd.v || !x->vd.how || !x->vd.base || !x->vd.detail || !x->vd.tests ||
        !x->vd.vis || !x->soft_truth || !x->soft_se) {
        x->W = x->H = 0;
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "per-pixel buffers %dx%d", W, H);
    }
    return SL_OK;
}

/* G-buffer values that are not finite (positions, normals of non-background
 * pixels). A hard case must never produce one (tests/test_hard.c). */
static uint64_t view_bad(const struct sl_view *v)
{
    uint64_t n = 0;
    size_t np = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < np; i++)
        if (v->cls[i] != SL_C_BACKGROUND)
            for (int k = 0; k < 3; k++)
                n += !isfinite(v->pos[3 * i + k]) + !isfinite(v->nrm[3 * i + k]);
    return n;
}

/* Shadow-map depths outside [0, 1] or not finite. */
static uint64_t layer_bad(const struct sl_depth_layer *l, int size)
{
    uint64_t n = 0;
    size_t nt = (size_t)size * (size_t)size;
    for (size_t i = 0; i < nt; i++)
        n += !(l->depth[i] >= 0.0f && l->depth[i] <= 1.0f);
    return n;
}

/* The view's truth is in place: its light frustum (lightfit.h), timed (a
 * point light's says what it could not map), its count of bad G-buffer
 * values, and the key it is kept under. */
static void view_ready(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k)
{
    double t0 = sl_now();
    sl_light_fit(&x->scene, &x->view, &x->box);
    x->vms.fit = 1e3 * (sl_now() - t0);
    if (x->box.n_outside || x->box.n_unmapped)
        fprintf(stderr, "shadowlab: note: %s/%s: the point frustum of the area light's centre leaves %u PFL "
                        "pixel(s) outside its map (the exact methods trace them) and %u triangle(s) out of the "
                        "conservative layers (tested on the CPU instead)\n",
                x->scene.name, c->scenes[k->scene].viewpoints[k->vp], x->box.n_outside, x->box.n_unmapped);
    x->view_bad = view_bad(&x->view);
    x->view_scene = k->scene;
    x->view_vp = k->vp;
    x->view_viewport = k->viewport;
}

/* The truths of a view under an area light: the visible fraction of the
 * light per pixel from the config's samples and seed, and the hard truth of
 * the point at its centre (one ray per PFL pixel, truth.h), which the
 * hard-shadow methods' figures and exactness are measured against; then the
 * point's perspective frustum (lightfit.h). The soft layers fit their own.
 * Both truths are timed together as the view's truth; the point's adds one
 * ray per pixel to the area's area_samples^2. Both come from the cache
 * (area_key) when it holds them, timed as the read, as a hard truth is. */
static enum sl_err area_view(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                             unsigned long long view_key, const char *cache_dir, int reps, double *times,
                             struct sl_run_result *res, struct sl_diag *d)
{
    const int cache = cache_dir && cache_dir[0];
    const unsigned long long key = area_key(view_key, sl_soft_truth_side(c->area_samples), c->seed);
    double t0 = sl_now();
    enum cache_read got = cache ? area_cache_read(cache_dir, key, &x->view, x->soft_truth, x->soft_se) : CACHE_MISS;
    x->truth_cached = got == CACHE_HIT;
    x->truth_rays = 0;
    res->passes.cache_rejected += got == CACHE_REJECTED;
    if (x->truth_cached) {
        res->passes.truths_cached++;
        res->passes.soft_truths_cached++;
        x->vms.truth[SL_MED] = x->vms.truth[SL_MIN] = x->vms.truth[SL_MAX] = 1e3 * (sl_now() - t0);
    } else {
        struct sl_soft_truth_stats st;
        struct sl_truth_stats ts;
        for (int r = 0; r < reps; r++) {
            enum sl_err e = sl_soft_truth(&x->rt, &x->scene, &x->view, c->area_samples, c->seed, x->soft_truth,
                                          x->soft_se, &st, d);
            if (!e)
                e = sl_truth_trace(&x->rt, &x->scene, &x->view, &ts, d);
            if (e)
                return e;
            times[r] = st.ms_trace + ts.ms_trace;
        }
        med_min_max(times + c->warmup, c->runs, x->vms.truth);
        res->passes.truths_traced++;
        res->passes.soft_truths++;
        x->truth_rays = st.rays + ts.rays;
        if (cache)
            area_cache_write(cache_dir, key, &x->view, x->soft_truth, x->soft_se);
    }
    view_ready(x, c, k);
    return SL_OK;
}

static enum sl_err ensure_view(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                               const char *cache_dir, struct sl_run_result *res, struct sl_diag *d)
{
    if (x->view_scene == k->scene && x->view_vp == k->vp && x->view_viewport == k->viewport)
        return SL_OK;
    drop_view(x);
    int W = c->viewport_w[k->viewport], H = c->viewport_h[k->viewport];
    int vp = sl_scene_find_viewpoint(&x->scene, c->scenes[k->scene].viewpoints[k->vp]);
    if (vp < 0)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "viewpoint vanished from the scene");
    memset(&x->vms, 0, sizeof x->vms);
    int reps = c->warmup + c->runs;
    double times[SL_MAX_REPS];
    enum sl_err e = sl_gbuffer_render(&x->gpass, &x->mesh, &x->scene, vp, W, H, &x->view, &times[0],
                                      &x->vms.gbuffer_readback, d);
    if (e)
        return e;
    res->passes.gbuffers++;
    for (int r = 1; r < reps; r++) {
        /* the same pass again, timed only */
        struct sl_view again;
        e = sl_gbuffer_render(&x->gpass, &x->mesh, &x->scene, vp, W, H, &again, &times[r], NULL, d);
        sl_view_free(&again);
        if (e)
            return e;
    }
    med_min_max(times + c->warmup, c->runs, x->vms.gbuffer_render);
    unsigned long long key = truth_key(x->scene_key, &x->scene.vp[vp], W, H);
    if (x->area)
        return area_view(x, c, k, key, cache_dir, reps, times, res, d);
    double t0 = sl_now();
    enum cache_read got = cache_dir && cache_dir[0] ? truth_cache_read(cache_dir, key, &x->view) : CACHE_MISS;
    x->truth_cached = got == CACHE_HIT;
    x->truth_rays = 0;
    res->passes.cache_rejected += got == CACHE_REJECTED;
    if (x->truth_cached) {
        res->passes.truths_cached++;
        x->vms.truth[SL_MED] = x->vms.truth[SL_MIN] = x->vms.truth[SL_MAX] = 1e3 * (sl_now() - t0);
    } else {
        struct sl_truth_stats ts;
        for (int r = 0; r < reps; r++) {
            /* repetitions trace the same rays into the same answer */
            if ((e = sl_truth_trace(&x->rt, &x->scene, &x->view, &ts, d)))
                return e;
            times[r] = ts.ms_trace;
        }
        med_min_max(times + c->warmup, c->runs, x->vms.truth);
        res->passes.truths_traced++;
        x->truth_rays = ts.rays;
        if (cache_dir && cache_dir[0])
            truth_cache_write(cache_dir, key, &x->view);
    }
    view_ready(x, c, k);
    return SL_OK;
}

/* The layers wanted by the selected cells of the (view, map) group that
 * starts at cell `from` (the group's cells are contiguous in sweep order),
 * leaving out cells a resumed run will skip. */
static unsigned group_needs(const struct sl_config *c, int from, int last, struct sl_store *st, int resume)
{
    struct sl_cell_key k0, k;
    sl_plan_cell(c, from, &k0);
    unsigned needs = 0;
    for (int i = from; i < last; i++) {
        sl_plan_cell(c, i, &k);
        if (k.scene != k0.scene || k.viewport != k0.viewport || k.vp != k0.vp || k.map != k0.map)
            break;
        const struct sl_config_scene *cs = &c->scenes[k.scene];
        if (resume && sl_store_has_cell(st, c->hash, cs->name, cs->viewpoints[k.vp], c->viewport_w[k.viewport],
                                        c->viewport_h[k.viewport], c->maps[k.map], c->methods[k.method].label))
            continue;
        needs |= c->methods[k.method].method->needs(&c->methods[k.method].params);
    }
    return needs;
}

static enum sl_err ensure_frame(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                                unsigned needs, struct sl_run_result *res, struct sl_diag *d)
{
    needs &= (1u << SL_LAYER_COUNT) - 1u;   /* the frame's layers; adjacency is per scene */
    if (x->frame_map == k->map && (x->frame.have & needs) == needs)
        return SL_OK;
    if (x->frame_map != k->map) {
        drop_frame(x);
        memset(&x->frame, 0, sizeof x->frame);
        x->frame.size = c->maps[k->map];
        memcpy(x->frame.dir, x->scene.light_dir, sizeof x->frame.dir);
        x->frame.box = x->box;
        x->frame.texel_world = fmaxf(x->box.hi[0] - x->box.lo[0], x->box.hi[1] - x->box.lo[1]) /
                               (float)x->frame.size;
        x->frame.depth_range = x->box.hi[2] - x->box.lo[2];
        x->frame_map = k->map;
    }
    unsigned before = x->frame.have;
    enum sl_err e = sl_shadowmap_render(&x->spass, &x->mesh, &x->frame, needs, d);
    int reps = c->warmup + c->runs;
    for (int l = 0; l < SL_LAYER_COUNT && !e; l++) {
        if (!((x->frame.have & ~before) & SL_NEED(l)))
            continue;
        res->passes.layers[l]++;
        x->layer_bad[l] = layer_bad(&x->frame.layer[l], x->frame.size);
        double times[SL_MAX_REPS];
        times[0] = x->frame.layer[l].ms_render;
        for (int r = 1; r < reps && !e; r++) {
            /* the same layer again into a scratch copy of the frame (which
             * shares the other layers, e.g. BGSM for BGSM2), timed only */
            struct sl_light_frame again = x->frame;
            again.have &= ~SL_NEED(l);
            memset(&again.layer[l], 0, sizeof again.layer[l]);
            e = sl_shadowmap_render(&x->spass, &x->mesh, &again, SL_NEED(l), d);
            times[r] = again.layer[l].ms_render;
            free(again.layer[l].depth);
            free(again.layer[l].id);
        }
        if (!e)
            med_min_max(times + c->warmup, c->runs, x->layer_ms[l]);
    }
    return e;
}

/* Every PFL pixel against the guarantee the method declares. */
static void check_exact(const struct run_ctx *x, const struct sl_method *m, struct sl_cell *cell)
{
    const struct sl_view *v = &x->view;
    for (int y = 0; y < v->h; y++)
        for (int xx = 0; xx < v->w; xx++) {
            size_t i = (size_t)y * (size_t)v->w + (size_t)xx;
            if (v->cls[i] != SL_C_PFL)
                continue;
            uint8_t how = x->vd.how[i];
            int proved = how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ || how == SL_HOW_CORRECT ||
                         how == SL_HOW_TRACED;
            int right = (x->vd.v[i] == SL_V_LIT) == (v->truth[i] == SL_T_LIT);
            int bad = ((m->exact & SL_EXACT_LIT) && x->vd.v[i] == SL_V_LIT && v->truth[i] != SL_T_LIT) ||
                      ((m->exact & SL_EXACT_SHADOW) && x->vd.v[i] == SL_V_SHADOW && v->truth[i] != SL_T_SHADOW) ||
                      ((m->exact & SL_EXACT_PROVED) && proved && !right);
            if (!bad)
                continue;
            if (cell->violations < SL_MAX_VIOLATIONS) {
                struct sl_violation *o = &cell->violation[cell->violations];
                memset(o, 0, sizeof *o);
                o->x = xx;
                o->y = y;
                o->truth = v->truth[i];
                o->verdict = x->vd.v[i];
                o->how = x->vd.how[i];
                o->own_tri = v->tri[i];
                float u, w, z;
                sl_frame_project(&x->frame, v->pos + 3 * i, &u, &w, &z);
                uint32_t k = sl_frame_texel(&x->frame, u, w);
                o->tx = (int)(k % (uint32_t)x->frame.size);
                o->ty = (int)(k / (uint32_t)x->frame.size);
                for (int l = 0; l < SL_LAYER_COUNT; l++)
                    if (x->frame.have & SL_NEED(l))
                        o->layer_tri[l] = x->frame.layer[l].id[k] & ~SL_FULL;
            }
            cell->violations++;
        }
}

static void report_violations(const struct sl_config *c, const struct sl_cell *cl)
{
    static const char *const layer_names[SL_LAYER_COUNT] = {"depth", "depth_back", "bgsm", "bgsm2", "sgsm",
                                                            "sgsm_adj"};
    fprintf(stderr, "shadowlab: VIOLATION: %s/%s %dx%d map %d '%s': %llu pixel(s) break its exactness\n",
            cl->scene, cl->viewpoint, c->viewport_w[cl->key.viewport], c->viewport_h[cl->key.viewport],
            c->maps[cl->key.map], c->methods[cl->key.method].label, (unsigned long long)cl->violations);
    for (uint64_t k = 0; k < cl->violations && k < SL_MAX_VIOLATIONS; k++) {
        const struct sl_violation *o = &cl->violation[k];
        fprintf(stderr, "  pixel (%d, %d): truth %d, verdict %d, how %d, own triangle %u, texel (%d, %d):",
                o->x, o->y, o->truth, o->verdict, o->how, o->own_tri ? o->own_tri - 1 : 0, o->tx, o->ty);
        for (int l = 0; l < SL_LAYER_COUNT; l++)
            if (o->layer_tri[l])
                fprintf(stderr, " %s triangle %u", layer_names[l], o->layer_tri[l] - 1);
        fputc('\n', stderr);
    }
}

/* The area light's near and far layers at the cell's map size, and their
 * N-buffer, once per (view, map size) and only when a soft method of the
 * group reads them. */
static enum sl_err ensure_soft(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                               unsigned needs, struct sl_run_result *res, struct sl_diag *d)
{
    if (!(needs & SL_NEED_SOFT) || x->soft_map == k->map)
        return SL_OK;
    if (!x->softpass.prog) {
        enum sl_err e = sl_softmap_init(&x->softpass, d);
        if (e)
            return e;
    }
    sl_softmap_free(&x->softmap);
    memset(&x->softmap, 0, sizeof x->softmap);
    x->soft_map = -1;
    struct sl_softmap_desc sd = {.size = c->maps[k->map], .receiver = x->receivers};
    enum sl_err e = sl_softmap_render(&x->softpass, &x->mesh, &x->scene, &x->view, &sd, &x->softmap, d);
    if (!e)
        e = sl_softmc_nbuf_build(&x->softmap, c->threads, &x->nbuf, d);
    if (e)
        return e;
    res->passes.soft_layers++;
    x->soft_map = k->map;
    return SL_OK;
}

/* An area light's cell: the soft figures of the method's visible fraction
 * against the area truth, and an error heat map as its overlay (a hard
 * method's cell also has its hard figures against the point truth). */
static enum sl_err soft_cell(struct run_ctx *x, const struct sl_config *c, struct sl_cell *cell, const char *ovdir,
                             struct sl_diag *d)
{
    int W = x->view.w, H = x->view.h;
    size_t npx = (size_t)W * (size_t)H;
    double t0 = sl_now();
    sl_soft_figures_compute(W, H, x->view.tri, x->vd.vis, x->soft_truth, x->soft_se, &cell->soft);
    cell->has_soft = 1;
    for (size_t i = 0; i < npx; i++)
        cell->nonfinite += x->view.tri[i] && !(x->vd.vis[i] >= 0.0f && x->vd.vis[i] <= 1.0f);
    cell->ms.figures += 1e3 * (sl_now() - t0);
    if (!ovdir)
        return SL_OK;
    t0 = sl_now();
    /* the visible fraction as grey; where the method is off by more than 0.05,
     * red where it is too dark and blue where too light, stronger with the error */
    for (size_t i = 0; i < npx; i++) {
        uint8_t *p = x->rgb + 3 * i;
        if (!x->view.tri[i]) {
            p[0] = p[1] = p[2] = 0;
            continue;
        }
        float e = x->vd.vis[i] - x->soft_truth[i], g = 40.0f + 180.0f * x->vd.vis[i];
        float a = fabsf(e) > 0.05f ? fminf(1.0f, 0.3f + fabsf(e)) : 0.0f;
        p[0] = (uint8_t)((1 - a) * g + a * (e < 0 ? 255.0f : 0.0f));
        p[1] = (uint8_t)((1 - a) * g);
        p[2] = (uint8_t)((1 - a) * g + a * (e > 0 ? 255.0f : 0.0f));
    }
    char name[400], path[1600];
    sl_out_overlay_name(c, cell, name, sizeof name);
    snprintf(path, sizeof path, "%s/%s", ovdir, name);
    enum sl_err e = sl_image_write_rgb8(path, W, H, x->rgb, d);
    cell->ms.overlay = 1e3 * (sl_now() - t0);
    return e;
}

static enum sl_err run_cell(struct run_ctx *x, const struct sl_config *c, const struct sl_cell_key *k,
                            struct sl_cell *cell, const char *ovdir, const char *exrdir,
                            struct sl_run_result *res, struct sl_diag *d)
{
    const struct sl_config_method *cm = &c->methods[k->method];
    int W = c->viewport_w[k->viewport], H = c->viewport_h[k->viewport];
    size_t npx = (size_t)W * (size_t)H;
    cell->key = *k;
    snprintf(cell->scene, sizeof cell->scene, "%s", x->scene.name);
    snprintf(cell->viewpoint, sizeof cell->viewpoint, "%s", c->scenes[k->scene].viewpoints[k->vp]);
    cell->ms = x->vms;
    cell->truth_cached = x->truth_cached;
    cell->truth_rays = x->truth_rays;
    cell->nonfinite = x->view_bad;
    cell->n_pfl = x->view.n_pfl;
    cell->n_pnfl = x->view.n_pnfl;
    cell->n_background = x->view.n_background;
    cell->n_truth_lit = x->view.n_lit;
    cell->n_truth_shadow = x->view.n_shadow;
    unsigned mneeds = cm->method->needs(&cm->params);
    for (int l = 0; l < SL_LAYER_COUNT; l++)
        if (mneeds & SL_NEED(l)) {
            for (int j = 0; j < 3; j++)
                cell->ms.map_render[j] += x->layer_ms[l][j];
            cell->nonfinite += x->layer_bad[l];
            cell->ms.map_readback += x->frame.layer[l].ms_readback;
            cell->gs_prims += x->frame.layer[l].gs_prims;
            cell->fragments += x->frame.layer[l].fragments;
        }
    /* methods get the view without its truth */
    struct sl_view mview = x->view;
    mview.truth = NULL;
    struct sl_method_args a = {
        .scene = &x->scene, .view = &mview, .frame = &x->frame, .params = &cm->params,
        .rt = &x->rt, .adj = x->have_adj ? &x->adj : NULL, .threads = c->threads,
        .softmap = x->soft_map >= 0 ? &x->softmap : NULL, .nbuf = x->soft_map >= 0 ? &x->nbuf : NULL,
        .seed = c->seed,
    };
    int reps = c->warmup + c->runs;
    double times[SL_MAX_REPS];
    enum sl_err e = SL_OK;
    for (int r = 0; r < reps && !e; r++) {
        struct sl_cost cost = {0};
        x->vd.has_base = 0;
        x->vd.has_detail = 0;
        memset(x->vd.tests, 0, npx);
        e = cm->method->run(&a, &x->vd, &cost, d);
        res->passes.method_runs++;
        if (r >= c->warmup)
            times[r - c->warmup] = cost.ms_method;
        cell->cost = cost;   /* counters are the same every run */
    }
    if (e)
        return e;
    med_min_max(times, c->runs, cell->ms.method);
    cell->cost.ms_method = cell->ms.method[SL_MED];

    const int soft = (cm->method->lights & SL_LIGHTS_AREA) != 0;
    if (soft) {
        memset(&cell->fig, 0, sizeof cell->fig);
        cell->fig.background = x->view.n_background;
        return soft_cell(x, c, cell, ovdir, d);
    }
    double t0 = sl_now();
    for (size_t i = 0; i < npx; i++)
        x->state[i] = x->vd.v[i];   /* 0 background, else the verdict */
    /* regions are the increasing contours, then 0 (whole image) */
    int maxt = c->regions[c->nregions - 2];
    sl_contour_bands(W, H, x->state, maxt / 2 - 1, x->band);
    cell->ms.contours = 1e3 * (sl_now() - t0);
    t0 = sl_now();
    sl_figures_compute(&x->view, &x->vd, x->band, c->regions, c->nregions, &cell->fig);
    cell->ms.figures = 1e3 * (sl_now() - t0);
    if (cm->method->exact)
        check_exact(x, cm->method, cell);
    if (x->vd.has_detail) {
        cell->has_patterns = 1;
        for (size_t i = 0; i < npx; i++) {
            if (x->view.cls[i] != SL_C_PFL)
                continue;
            uint8_t k = x->vd.detail[i] < 10 ? x->vd.detail[i] : 9;
            for (int r = 0; r < cell->fig.nregions; r++)
                if (sl_in_contour(x->band[i], cell->fig.r[r].thickness)) {
                    cell->pattern[r][k][0]++;
                    cell->pattern[r][k][1] += x->view.truth[i] == SL_T_SHADOW;
                }
        }
    }
    if (x->area) {
        /* a hard method under an area light: its verdicts as a visible
         * fraction, scored against the area truth. A pixel it leaves
         * uncertain counts as half lit: the method says neither, and 0.5 is
         * the guess whose worst error is smallest. */
        for (size_t i = 0; i < npx; i++)
            x->vd.vis[i] = x->vd.v[i] == SL_V_LIT ? 1.0f : x->vd.v[i] == SL_V_UNCERTAIN ? 0.5f : 0.0f;
        e = soft_cell(x, c, cell, ovdir, d);
        ovdir = NULL;   /* the overlay is the soft one: the error against the area truth */
    }
    if (ovdir && !e) {
        t0 = sl_now();
        char name[400], path[1600];
        sl_out_overlay_name(c, cell, name, sizeof name);
        snprintf(path, sizeof path, "%s/%s", ovdir, name);
        sl_overlay_build(&x->view, x->scene.light_dir, &x->vd, x->band, c->overlay_contour, x->rgb);
        e = sl_image_write_rgb8(path, W, H, x->rgb, d);
        cell->ms.overlay = 1e3 * (sl_now() - t0);
    }
    if (exrdir && !e) {
        /* the per-pixel layers behind the figures, for anyone who wants to
         * recount: truth (enum sl_truth), verdict (enum sl_verdict), how
         * (enum sl_how) and contour band (k: inside the 2k-px contour) */
        char path[1400];
        snprintf(path, sizeof path, "%s/%s-%s-%dx%d-%d-%s.exr", exrdir, cell->scene, cell->viewpoint, W, H,
                 c->maps[k->map], cm->label);
        static const char *const names[] = {"truth", "verdict", "how", "contour"};
        const unsigned char *layers[] = {x->view.truth, x->vd.v, x->vd.how, x->band};
        e = sl_image_write_layers(path, W, H, 4, names, layers, d);
    }
    return e;
}

/* The overlay's path as the store keeps it: relative to the database's
 * folder when the results folder lies under it (the usual layout,
 * results/shadowlab.db beside results/<name>/), else absolute. The file is in
 * place once the run ends (the staging folder is renamed then). */
static void overlay_store_path(const char *store_path, const char *final, const char *name, char *out,
                               size_t n)
{
    char dbdir[PATH_MAX], fin[PATH_MAX], tmp[1200];
    snprintf(tmp, sizeof tmp, "%s", store_path);
    char *slash = strrchr(tmp, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(tmp, sizeof tmp, ".");
    if (!realpath(tmp, dbdir) || !realpath(final, fin)) {
        /* the results folder does not exist yet on a first run: resolve its parent */
        char parent[1200];
        snprintf(parent, sizeof parent, "%s", final);
        char *ps = strrchr(parent, '/');
        const char *base = ps ? ps + 1 : final;
        if (ps)
            *ps = '\0';
        else
            snprintf(parent, sizeof parent, ".");
        char rp[PATH_MAX];
        if (!realpath(tmp, dbdir) || !realpath(parent, rp)) {
            snprintf(out, n, "%s/overlays/%s", final, name);
            return;
        }
        snprintf(fin, sizeof fin, "%.*s/%s", (int)(sizeof fin - 300), rp, base);
    }
    size_t k = strlen(dbdir);
    if (strncmp(fin, dbdir, k) == 0 && fin[k] == '/')
        snprintf(out, n, "%s/overlays/%s", fin + k + 1, name);
    else
        snprintf(out, n, "%s/overlays/%s", fin, name);
}

static enum sl_err store_cell(struct sl_store *st, int64_t run_id, const struct sl_config *c,
                              const struct sl_cell *cl, const char *store_path, const char *final,
                              struct sl_diag *d)
{
    struct sl_cell_record sc;
    sl_out_record(c, cl, &sc);
    if (final && final[0] && c->overlays) {
        char name[400];
        sl_out_overlay_name(c, cl, name, sizeof name);
        overlay_store_path(store_path, final, name, sc.overlay, sizeof sc.overlay);
    }
    return sl_store_put_cell(st, run_id, c->hash, &sc, d);
}

/* Move the files of <from>/<sub> into <to>/<sub> where <to> has no file of that name. */
static void carry_files(const char *from, const char *to, const char *sub)
{
    char src[1400], dst[1400];
    snprintf(src, sizeof src, "%s/%s", from, sub);
    DIR *dir = opendir(src);
    if (!dir)
        return;
    snprintf(dst, sizeof dst, "%s/%s", to, sub);
    mkdir(dst, 0777);
    struct dirent *e;
    while ((e = readdir(dir))) {
        /* a killed run may have left a half-written image under its
         * temporary name (image.cpp writes name.tmp.ext, then renames) */
        if (e->d_name[0] == '.' || strstr(e->d_name, ".tmp."))
            continue;
        char a[1800], b[1800];
        snprintf(a, sizeof a, "%s/%s", src, e->d_name);
        snprintf(b, sizeof b, "%s/%s", dst, e->d_name);
        if (access(b, F_OK) != 0)
            rename(a, b);
    }
    closedir(dir);
}

static void carry_previous(const char *root, const char *name, const char *final, const char *stage)
{
    carry_files(final, stage, "overlays");
    carry_files(final, stage, "exr");
    DIR *dir = opendir(root);
    if (!dir)
        return;
    char prefix[200], own[1200];
    snprintf(prefix, sizeof prefix, ".%s.partial-", name);
    struct dirent *e;
    while ((e = readdir(dir))) {
        if (strncmp(e->d_name, prefix, strlen(prefix)) != 0)
            continue;
        snprintf(own, sizeof own, "%s/%s", root, e->d_name);
        if (strcmp(own, stage) == 0)
            continue;
        /* only a dead run's folder: another run of this config may be writing
         * its own right now (a pid that cannot be parsed counts as dead) */
        char *end;
        long pid = strtol(e->d_name + strlen(prefix), &end, 10);
        if (*end == '\0' && pid > 0 && (kill((pid_t)pid, 0) == 0 || errno == EPERM))
            continue;
        carry_files(own, stage, "overlays");
        carry_files(own, stage, "exr");
        rm_tree(own);   /* a killed run's leftovers: its cells are in the store */
    }
    closedir(dir);
}

/* A run row carrying the filled-in config, so a number in the store can be
 * reproduced from the store alone. */
static enum sl_err begin_run(struct sl_store *st, const struct sl_config *c, const struct sl_provenance *p,
                             int64_t *run_id, struct sl_diag *d)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "config text");
    sl_config_write(c, f);
    fclose(f);
    enum sl_err e = sl_store_begin_run(st, p, c->name, c->path, c->hash, text, run_id, d);
    free(text);
    return e;
}

static void progress(int done, int total, const struct sl_cell *cl, const struct sl_config *c, double t_start)
{
    double el = sl_now() - t_start;
    double eta = done ? el * (double)(total - done) / (double)done : 0.0;
    fprintf(stderr, "\r[%d/%d] %s/%s %d² %-16s %6.1fs elapsed, ~%.0fs left   ", done, total, cl->scene,
            cl->viewpoint, c->maps[cl->key.map], c->methods[cl->key.method].label, el, eta);
    if (done == total)
        fputc('\n', stderr);
    fflush(stderr);
}

enum sl_err sl_run(const struct sl_config *c, const struct sl_run_opts *o, struct sl_run_result *res,
                   struct sl_diag *d)
{
    memset(res, 0, sizeof *res);
    double t_start = sl_now();
    const char *root = o->out_root ? o->out_root : "results";
    int total = sl_plan_count(c);
    int first = o->first > 0 ? o->first : 0;
    int last = o->last > 0 ? o->last : total;
    if (first >= total || last > total || first >= last)
        return sl_fail(d, SL_E_USAGE, c->path, 0, "--cells", "cells %d:%d outside the sweep of %d cells",
                       first, last, total);
    char stage[1100] = "", final[1100] = "", ovdir[1200] = "", exrdir[1200] = "", store_path[1100] = "",
         cache[1100] = "";
    if (o->store)
        snprintf(store_path, sizeof store_path, "%s", o->store);
    else if (c->store[0])
        snprintf(store_path, sizeof store_path, "%s", c->store);
    else if (o->write_files)
        snprintf(store_path, sizeof store_path, "%s/shadowlab.db", root);
    if (o->cache_dir)
        snprintf(cache, sizeof cache, "%s", o->cache_dir);
    else if (o->write_files)
        snprintf(cache, sizeof cache, "%s/cache", root);
    if (o->resume && !store_path[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--resume", "--resume needs a results store");

    enum sl_err e = SL_OK;
    if (o->write_files) {
        /* fail on an unwritable output before any GL or Embree work */
        if ((e = sl_mkdirs(root, d)))
            return e;
        snprintf(final, sizeof final, "%s/%s", root, c->name);
        snprintf(stage, sizeof stage, "%s/.%s.partial-%ld", root, c->name, (long)getpid());
        rm_tree(stage);
        if ((e = sl_mkdirs(stage, d)))
            return e;
        snprintf(ovdir, sizeof ovdir, "%s/overlays", stage);
        snprintf(exrdir, sizeof exrdir, "%s/exr", stage);
        if ((c->overlays && (e = sl_mkdirs(ovdir, d))) || (c->exr && (e = sl_mkdirs(exrdir, d)))) {
            rm_tree(stage);
            return e;
        }
        snprintf(res->out_dir, sizeof res->out_dir, "%s", final);
    }
    if (cache[0] && sl_mkdirs(cache, NULL) != SL_OK)
        cache[0] = '\0';   /* no cache is only slower */

    struct run_ctx x;
    memset(&x, 0, sizeof x);
    x.scene_i = x.view_scene = x.view_vp = x.view_viewport = x.frame_map = x.soft_map = -1;
    struct sl_store *st = NULL;
    int64_t run_id = 0;
    int show = o->progress && isatty(2);
    if ((e = sl_gl_init(&x.gl, d)) || (e = sl_shadowmap_init(&x.spass, d)))
        goto out;
    snprintf(res->prov.gl_renderer, sizeof res->prov.gl_renderer, "%s", x.gl.renderer);
    snprintf(res->prov.gl_version, sizeof res->prov.gl_version, "%s", x.gl.version);
    snprintf(res->prov.embree, sizeof res->prov.embree, "%d.%d.%d", RTC_VERSION_MAJOR, RTC_VERSION_MINOR,
             RTC_VERSION_PATCH);
    res->prov.threads = c->threads;
    sl_provenance_fill(&res->prov);
    if (store_path[0]) {
        if ((e = sl_store_open(store_path, &st, d)) ||
            (e = begin_run(st, c, &res->prov, &run_id, d)))
            goto out;
        snprintf(res->store_path, sizeof res->store_path, "%s", store_path);
    }

    res->cells = sl_calloc((size_t)(last - first), sizeof *res->cells);
    if (!res->cells) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cell table");
        goto out;
    }
    for (int idx = first; idx < last && !e; idx++) {
        struct sl_cell_key k;
        sl_plan_cell(c, idx, &k);
        if (o->resume) {
            const struct sl_config_scene *cs = &c->scenes[k.scene];
            if (sl_store_has_cell(st, c->hash, cs->name, cs->viewpoints[k.vp], c->viewport_w[k.viewport],
                                  c->viewport_h[k.viewport], c->maps[k.map], c->methods[k.method].label)) {
                res->skipped++;
                continue;
            }
        }
        if ((e = ensure_scene(&x, c, k.scene, res, d)) ||
            (e = ensure_buffers(&x, c->viewport_w[k.viewport], c->viewport_h[k.viewport], d)) ||
            (e = ensure_view(&x, c, &k, cache, res, d)))
            break;
        const unsigned needs = group_needs(c, idx, last, st, o->resume);
        if ((e = ensure_frame(&x, c, &k, needs, res, d)) || (x.area && (e = ensure_soft(&x, c, &k, needs, res, d))))
            break;
        struct sl_cell *cell = &res->cells[res->ncells];
        cell->index = idx;
        if ((e = run_cell(&x, c, &k, cell, o->write_files && c->overlays ? ovdir : NULL,
                          o->write_files && c->exr ? exrdir : NULL, res, d)))
            break;
        if (cell->violations)
            report_violations(c, cell);
        if (cell->nonfinite)
            fprintf(stderr, "shadowlab: NON-FINITE: %s/%s map %d '%s': %llu G-buffer or shadow-map value(s) "
                            "not finite or out of range\n", cell->scene, cell->viewpoint, c->maps[k.map],
                    c->methods[k.method].label, (unsigned long long)cell->nonfinite);
        if (st && (e = store_cell(st, run_id, c, cell, store_path, o->write_files ? final : NULL, d)))
            break;
        res->ncells++;
        if (show)
            progress(res->ncells + res->skipped, last - first, cell, c, t_start);
    }
    res->ms_total = 1e3 * (sl_now() - t_start);
    if (e || !o->write_files)
        goto out;

    {
        struct { const char *name; int kind; } files[] = {
            {"figures.csv", 0}, {"table.md", 1}, {"table.tex", 2}, {"costs.csv", 3},
            {"config.yaml", 4}, {"run.yaml", 5}, {"patterns.csv", 6},
        };
        for (size_t f = 0; f < sizeof files / sizeof files[0] && !e; f++) {
            if (!c->tables && files[f].kind <= 2)
                continue;
            struct sl_outfile of;
            char path[1300];
            snprintf(path, sizeof path, "%s/%s", stage, files[f].name);
            if ((e = sl_out_open(&of, path, d)))
                break;
            switch (files[f].kind) {
            case 0: e = sl_out_write_tables(of.f, SL_TABLE_CSV, c, res, d); break;
            case 1:
                e = sl_out_write_tables(of.f, SL_TABLE_MD, c, res, d);
                sl_out_write_costs_md(of.f, c, res);
                sl_out_write_patterns_md(of.f, c, res);
                break;
            case 2: e = sl_out_write_tables(of.f, SL_TABLE_LATEX, c, res, d); break;
            case 3: sl_out_write_costs_csv(of.f, c, res); break;
            case 4:
                fprintf(of.f, "# from %s (hash %016llx), git %s\n", c->path, c->hash, res->prov.git_sha);
                sl_config_write(c, of.f);
                break;
            case 5: sl_out_write_run_yaml(of.f, c, res); break;
            case 6: sl_out_write_patterns_csv(of.f, c, res); break;
            }
            if (e)
                sl_out_abort(&of);
            else
                e = sl_out_commit(&of, d);
        }
        if (e)
            goto out;
    }
    /* a resumed run computed only the missing cells: the overlays and EXR
     * files of the cells it skipped come from the previous results folder, or
     * from the staging folder of a run that was killed, so what the store
     * points at is in place */
    if (o->resume)
        carry_previous(root, c->name, final, stage);
    /* swap the finished folder into place */
    {
        char old[1200];
        snprintf(old, sizeof old, "%s/.%s.old-%ld", root, c->name, (long)getpid());
        struct stat sb;
        int had = stat(final, &sb) == 0;
        if (had && rename(final, old) != 0) {
            e = sl_fail(d, SL_E_OUTPUT, final, 0, NULL, "cannot replace the previous results: %s", strerror(errno));
            goto out;
        }
        if (rename(stage, final) != 0) {
            if (had)
                rename(old, final);
            e = sl_fail(d, SL_E_OUTPUT, final, 0, NULL, "cannot move results into place: %s", strerror(errno));
            goto out;
        }
        if (had)
            rm_tree(old);
    }
    if (o->table_out && c->tables) {
        e = sl_out_write_tables(o->table_out, SL_TABLE_MD, c, res, d);
        sl_out_write_costs_md(o->table_out, c, res);
        sl_out_write_patterns_md(o->table_out, c, res);
        fprintf(o->table_out, "\nwritten to %s/%s%s\n", final, store_path[0] ? " and " : "", store_path);
    }
out:
    if (e && stage[0])
        rm_tree(stage);
    sl_store_close(st);
    ctx_free(&x);
    return e;
}
