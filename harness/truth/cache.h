/*
 * cache.h — the truth cache: the exact answers of a view kept on disk, so a
 * study run again (or resumed) traces each view once.
 *
 * One file per view and kind of truth in the cache folder, named by its key:
 * truth-<key>.bin (the hard truth) and area-<key>.bin (an area light's
 * visible fraction, its standard error, the hard truth of its centre and
 * the number of rays its area samples traced: a cell whose truth is read
 * stores the counts of one that traced it; the hard truth's rays are its
 * lit and shadowed pixels, n_lit + n_shadow, one ray each).
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
 * so a reader never sees a half-written one.
 *
 * Owns: nothing between calls (files only). Does not: decide where the
 * cache lives (the driver), trace (truth.c, softtruth.c) or render.
 */
#ifndef SL_CACHE_H
#define SL_CACHE_H
#include <stdint.h>
#include "softtruth.h"
#include "truth.h"
#include "view.h"

enum sl_cache_read { SL_CACHE_MISS, SL_CACHE_REJECTED, SL_CACHE_HIT };

/* What a scene's truths depend on besides the view: the truth's rules, the
 * geometry, the light, the GL backend and renderer that made the G-buffer and Embree's
 * version; hashed once per scene. */
unsigned long long sl_cache_scene_key(const struct sl_scene *s, const char *gl_backend, const char *gl_renderer,
                                      const char *gl_version,
                                      const struct sl_rt *rt);
/* A view's key: the scene's, its viewpoint and its viewport. */
unsigned long long sl_cache_view_key(unsigned long long scene, const struct sl_viewpoint *vp, int w, int h);
/* An area truth's key: the view's, the area truth's rules, the cache format,
 * its samples per side (resolved), its seed and a few of its sample points. */
unsigned long long sl_cache_area_key(unsigned long long view, int side, uint32_t seed);

/* SL_CACHE_HIT and v->truth (with n_lit, n_shadow) filled when a valid
 * entry agrees with the view's classes; otherwise v is untouched. */
enum sl_cache_read sl_cache_truth_read(const char *dir, unsigned long long key, struct sl_view *v);
void               sl_cache_truth_write(const char *dir, unsigned long long key, const struct sl_view *v);

/* SL_CACHE_HIT with the visible fraction, its standard error, the
 * centre's hard truth and *rays (the area samples traced, the centre's rays
 * not included) filled when a valid entry exists; otherwise nothing is
 * written. A cache that cannot be written is only a lost speed-up: the
 * writers report nothing. */
enum sl_cache_read sl_cache_area_read(const char *dir, unsigned long long key, struct sl_view *v, float *visible,
                                      float *se, uint64_t *rays);
void               sl_cache_area_write(const char *dir, unsigned long long key, const struct sl_view *v,
                                       const float *visible, const float *se, uint64_t rays);

#endif
