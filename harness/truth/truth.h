/*
 * truth.h — the exact answer: Embree 3, one shadow ray per PFL pixel.
 *
 * Owns: the Embree device and BVH of a scene (built once per scene, robust
 * flag, high build quality). Does not: render, or know about methods; methods
 * that trace (raytrace, csm, chain) use sl_rt_occluded16 on the same BVH.
 *
 * Self-intersection: each ray carries the id of the pixel's own triangle
 * (ray.id) and an occlusion filter rejects hits on it; the ray also starts a
 * small distance off the surface (tnear, see sl_rt_tnear). See truth.c.
 */
#ifndef SL_TRUTH_H
#define SL_TRUTH_H
#include <stdint.h>
#include <embree3/rtcore.h>
#include "rtload.h"   /* Embree through dlopen: rtc* are pointers */
#include "scene.h"
#include "view.h"
#include "arealight.h" /* sl_rt_tnear: where the truth's shadow rays start */

struct sl_rt {
    RTCDevice device;
    RTCScene  scene;
    int       threads;
    int       shift;        /* packets of 1 << shift rays: the device's native width (packet.h) */
    double    ms_build;
    char      version[32];
    char      config[160];  /* the device config given to rtcNewDevice ("threads=N[,SHADOWLAB_EMBREE_CONFIG]") */
};

struct sl_rt_tile;

/* SHADOWLAB_EMBREE_CONFIG when set and not empty, else NULL: appended to
 * the device config of every BVH (sl_rt_build), e.g. isa=sse4.2 to run
 * Embree's SSE kernels on any CPU; recorded in the run's provenance. */
const char *sl_rt_env_config(void);
/* SL_E_USAGE naming SHADOWLAB_EMBREE_CONFIG when it is not a device config
 * Embree documents (rtcNewDevice(3): key=value pairs, known keys, known ISA
 * names); loads nothing, so a verb checks it before it writes anything. */
enum sl_err sl_rt_check_env(struct sl_diag *d);
/* Whether this CPU runs Embree's kernels for isa (sse4.2, avx, avx2,
 * avx512): an isa= the CPU lacks is refused (Embree would take it and stop
 * on an illegal instruction). */
int sl_rt_cpu_runs(const char *isa);

/* Trace the 16 rays of a tile (packet.h) in packets of the device's native
 * width; active lanes come back with tfar = -inf where occluded. */
void sl_rt_occluded_tile(const struct sl_rt *rt, struct RTCIntersectContext *ctx, struct sl_rt_tile *t);

enum sl_err sl_rt_build(struct sl_rt *rt, const struct sl_scene *s, int threads, int own_filter,
                        struct sl_diag *d);
/* The same with Embree's kernels for `isa` (sse2, sse4.2, avx, avx2, avx512;
 * NULL = as sl_rt_build), after SHADOWLAB_EMBREE_CONFIG: the bench's truth
 * stage measures each packet width the CPU runs on one machine. */
enum sl_err sl_rt_build_isa(struct sl_rt *rt, const struct sl_scene *s, int threads, int own_filter,
                            const char *isa, struct sl_diag *d);
void        sl_rt_free(struct sl_rt *rt);

struct sl_truth_stats {
    uint64_t rays;
    double   ms_trace;   /* wall clock of the whole pass */
    /* thread time, summed over the tracing threads (sl_rt_times) */
    double   ms_setup, ms_rays;
};

/* Trace every PFL pixel of v toward the light; fills v->truth with
 * SL_T_LIT / SL_T_SHADOW and v->n_lit / n_shadow. An area light is traced as
 * a point at its centre (sl_point_ray): the hard truth the hard-shadow
 * methods answer to under it; its own truth is the visible fraction
 * (softtruth.h). */
enum sl_err sl_truth_trace(const struct sl_rt *rt, const struct sl_scene *s, struct sl_view *v,
                           struct sl_truth_stats *st, struct sl_diag *d);

/* Trace the PFL pixels of v that `select` marks (NULL = all) toward the
 * light, writing SL_T_SHADOW or SL_T_LIT into out[i] for each traced pixel
 * (others untouched): the very rays of the truth, so a method that traces
 * a pixel gets the truth's answer for it. Counts of rays and occluded rays. */
enum sl_err sl_rt_trace(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                        const uint8_t *select, uint8_t *out, uint64_t *rays, uint64_t *shadow,
                        struct sl_diag *d);

/* The same with a per-pixel end of ray (tfar[i], world units; NULL =
 * infinity): Hertel's RT_opt, where nothing can occlude beyond a known
 * distance and shorter rays are cheaper. */
enum sl_err sl_rt_trace_until(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                              const uint8_t *select, const float *tfar, uint8_t *out, uint64_t *rays,
                              uint64_t *shadow, struct sl_diag *d);

/* Where a trace's time went, summed over its threads (each thread's clock
 * around its own chunks, so on one thread these add up to the pass less its
 * start and end): ms_setup fills packets from the G-buffer and writes the
 * answers back, ms_rays is rtcOccluded4/8/16 with the own-triangle filter (what
 * a plain loop over prebuilt packets does), in packets of the device's
 * native width (packet.h). */
struct sl_rt_times {
    double ms_setup, ms_rays;
};

/* sl_rt_trace_until, also saying where the time went (tm may be NULL). */
enum sl_err sl_rt_trace_timed(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                              const uint8_t *select, const float *tfar, uint8_t *out, uint64_t *rays,
                              uint64_t *shadow, struct sl_rt_times *tm, struct sl_diag *d);

/* Turn on flush-to-zero / denormals-are-zero in the calling thread (Embree's
 * advice; tracing threads call it). */
void sl_rt_thread_init(void);

#endif
