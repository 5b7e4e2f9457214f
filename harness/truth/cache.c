/*
 * cache.c — see cache.h.
 *
 * Invariants: a file is read only when every header field, its length and
 * its checksum are the expected ones and its values agree with the view's
 * classes; a file is written under a temporary name and renamed into place.
 */
#define _GNU_SOURCE   /* O_NOFOLLOW, O_CLOEXEC */
#include "cache.h"
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "arealight.h"
#include "util.h"

/* Bump when anything that determines the truth changes (tnear, filter, PFL
 * rule), so cached truths of older code are never read. */
#define SL_TRUTH_VERSION "truth-v1 own-triangle-filter tnear=2^-16|p|+2^-24 face-normal-pfl"

/* Bump when the layout of a cache file changes. */
#define SL_CACHE_FORMAT 2u

/* What a scene's truths depend on besides the view: hashed once per scene
 * (the geometry is the bulk of it). */
unsigned long long sl_cache_scene_key(const struct sl_scene *s, const char *gl_backend, const char *gl_renderer,
                                      const char *gl_version,
                                      const struct sl_rt *rt)
{
    unsigned long long k = SL_FNV_SEED;
    k = sl_fnv1a(k, SL_TRUTH_VERSION, strlen(SL_TRUTH_VERSION));
    k = sl_fnv1a(k, s->pos, (size_t)s->nv * 3 * sizeof(float));
    k = sl_fnv1a(k, s->idx, (size_t)s->nt * 3 * sizeof(uint32_t));
    k = sl_fnv1a(k, &s->light, sizeof s->light);
    /* the G-buffer positions come from GL: another renderer, another truth */
    k = sl_fnv1a(k, gl_backend, strlen(gl_backend));
    k = sl_fnv1a(k, gl_renderer, strlen(gl_renderer));
    k = sl_fnv1a(k, gl_version, strlen(gl_version));
    k = sl_fnv1a(k, rt->version, strlen(rt->version));
    return k;
}

unsigned long long sl_cache_view_key(unsigned long long scene, const struct sl_viewpoint *vp, int w, int h)
{
    unsigned long long k = sl_fnv1a(scene, vp, sizeof *vp);
    k = sl_fnv1a(k, &w, sizeof w);
    return sl_fnv1a(k, &h, sizeof h);
}

/* An area truth adds to the view's truth key its rules, the cache format,
 * its samples per side (resolved, so 0 and 32 share a file) and its seed,
 * and a few of its sample points: the sample pattern is shared with soft_mc
 * (arealight.h), so a change made there for soft_mc is a new key here. */
unsigned long long sl_cache_area_key(unsigned long long view, int side, uint32_t seed)
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

static void cache_path(char *path, size_t size, const char *dir, const char *kind, unsigned long long key)
{
    snprintf(path, size, "%s/%s-%016llx.bin", dir, kind, key);
}

/* The payload of the file of (kind, key) into *out (malloc'd, `bytes`
 * long): SL_CACHE_HIT when its header, length and checksum are all as
 * expected; SL_CACHE_MISS when there is no file; SL_CACHE_REJECTED otherwise. */
static enum sl_cache_read cache_load(const char *dir, const char *kind, const char magic[8], unsigned long long key,
                                  int w, int h, uint32_t parts, size_t bytes, void **out)
{
    char path[1200];
    cache_path(path, sizeof path, dir, kind, key);
    *out = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return SL_CACHE_MISS;
    struct cache_head hd;
    void *buf = malloc(bytes ? bytes : 1);
    int ok = buf && fread(&hd, sizeof hd, 1, f) == 1 && memcmp(hd.magic, magic, 8) == 0 &&
             hd.format == SL_CACHE_FORMAT && hd.parts == parts && hd.key == key && hd.w == w && hd.h == h &&
             hd.bytes == bytes && fread(buf, 1, bytes, f) == bytes && fgetc(f) == EOF && !ferror(f) &&
             sl_fnv1a(SL_FNV_SEED, buf, bytes) == hd.sum;
    fclose(f);
    if (!ok) {
        free(buf);
        return SL_CACHE_REJECTED;
    }
    *out = buf;
    return SL_CACHE_HIT;
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
    int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);   /* never through a link */
    FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (!f) {
        if (fd >= 0)
            close(fd);
        return;   /* a cache that cannot be written is only a lost speed-up */
    }
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

/* SL_CACHE_HIT and v->truth filled when a valid cache entry exists and agrees
 * with the view's classes; otherwise v->truth is untouched (then it is
 * traced). */
enum sl_cache_read sl_cache_truth_read(const char *dir, unsigned long long key, struct sl_view *v)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    void *buf;
    uint64_t lit, shadow;
    enum sl_cache_read r = cache_load(dir, "truth", truth_magic, key, v->w, v->h, 1, n, &buf);
    if (r == SL_CACHE_HIT && !truth_agrees(v, buf, &lit, &shadow))
        r = SL_CACHE_REJECTED;
    if (r == SL_CACHE_HIT) {
        memcpy(v->truth, buf, n);
        v->n_lit = lit;
        v->n_shadow = shadow;
    }
    free(buf);
    return r;
}

void sl_cache_truth_write(const char *dir, unsigned long long key, const struct sl_view *v)
{
    struct cache_part part = {v->truth, (size_t)v->w * (size_t)v->h};
    cache_store(dir, "truth", truth_magic, key, v->w, v->h, &part, 1);
}

/* V2: the rays the area truth traced (a fourth part), so a cell whose truth
 * comes from the cache stores the count of the one that traced it */
static const char area_magic[8] = {'S', 'L', 'A', 'R', 'E', 'A', 'V', '2'};

/* SL_CACHE_HIT with the visible fraction, its standard error and the centre's
 * hard truth filled when a valid entry exists: its fractions and errors in
 * [0, 1], 0 on the background, and the point truth agreeing with the view's
 * classes. Otherwise nothing is written. */
enum sl_cache_read sl_cache_area_read(const char *dir, unsigned long long key, struct sl_view *v, float *visible,
                                       float *se, uint64_t *rays)
{
    size_t n = (size_t)v->w * (size_t)v->h, nf = n * sizeof(float);
    void *buf;
    enum sl_cache_read r = cache_load(dir, "area", area_magic, key, v->w, v->h, 4, 2 * nf + n + sizeof *rays, &buf);
    if (r != SL_CACHE_HIT)
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
        memcpy(rays, truth + n, sizeof *rays);
        v->n_lit = lit;
        v->n_shadow = shadow;
    }
    free(buf);
    return ok ? SL_CACHE_HIT : SL_CACHE_REJECTED;
}

void sl_cache_area_write(const char *dir, unsigned long long key, const struct sl_view *v, const float *visible,
                             const float *se, uint64_t rays)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    struct cache_part part[4] = {{visible, n * sizeof(float)}, {se, n * sizeof(float)}, {v->truth, n},
                                 {&rays, sizeof rays}};
    cache_store(dir, "area", area_magic, key, v->w, v->h, part, 4);
}

