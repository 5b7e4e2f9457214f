/*
 * truth.c — Embree ground truth.
 *
 * Self-intersection policy, and why: a PFL pixel lies on its own triangle and
 * the shadow ray leaves that triangle's plane on its front side (the PFL test
 * uses the same face normal), so the own triangle can only be "hit" at t ~ 0
 * through rounding of the GL-interpolated position: the filter rejects it by
 * id, whatever t. A neighbouring triangle sharing an edge with the pixel's
 * triangle can also be grazed at t ~ 0 when the pixel sits on that edge; a
 * tnear of 2^-16 (1.5e-5) relative to the coordinates (128 float ulps, above
 * GL's interpolation error, far below any feature of our scenes: 7.6e-4
 * units at 50 units from the origin) skips those. No other offset is applied:
 * the origin is not pushed along the normal, so contact shadows stay exact.
 * tests/test_truth.c checks this policy against a double-precision brute
 * force over every triangle.
 */
#include "truth.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <omp.h>
#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#include <pmmintrin.h>
#endif
#include "arealight.h"
#include "packet.h"
#include "util.h"

void sl_rt_thread_init(void)
{
#if defined(__SSE__) || defined(__x86_64__)
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
#endif
}

/* Embree's RTCRayN_id / RTCHitN_primID accessors are C++ only; these read the
 * same SOA layout that rtcore_ray.h defines (id is the 11th ray field, primID
 * the 6th hit field, N lanes each). */
static unsigned rayn_id(const struct RTCRayN *r, unsigned N, unsigned i)
{
    return ((const unsigned *)r)[10 * N + i];
}
static unsigned hitn_prim(const struct RTCHitN *h, unsigned N, unsigned i)
{
    return ((const unsigned *)h)[5 * N + i];
}

/* Reject the hit when it is the ray's own triangle (ray.id = triangle + 1). */
static void own_triangle_filter(const struct RTCFilterFunctionNArguments *args)
{
    for (unsigned i = 0; i < args->N; i++) {
        if (args->valid[i] != -1)
            continue;
        unsigned prim = hitn_prim(args->hit, args->N, i);
        unsigned own = rayn_id(args->ray, args->N, i);
        if (prim + 1u == own)
            args->valid[i] = 0;
    }
}

/* The packet width the device runs natively (packet.h): 16, 8 or 4, as
 * log2; -1 when it has none (an Embree built without packets). */
static int native_shift(RTCDevice dev)
{
    if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED))
        return 4;
    if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED))
        return 3;
    if (rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED))
        return 2;
    return -1;
}

const char *sl_rt_env_config(void)
{
    const char *env = getenv("SHADOWLAB_EMBREE_CONFIG");
    return env && *env ? env : NULL;
}

/* rtcNewDevice(3)'s configuration, Embree 3.13: the keys it documents and
 * the ISA names it takes. Embree itself ignores a key it does not know and
 * reads an ISA name it does not know as sse2, so a typo (isa=avx-2) would
 * silently trace with other kernels than asked: refused here instead. */
static const char *const rtc_keys[] = {"threads", "user_threads", "set_affinity", "start_threads", "isa",
                                       "max_isa", "hugepages", "enable_selockmemoryprivilege", "verbose",
                                       "frequency_level", NULL};
static const char *const rtc_isas[] = {"sse2", "sse4.2", "avx", "avx2", "avx512", NULL};

static int in_list(const char *const *list, const char *s, size_t n)
{
    for (int i = 0; list[i]; i++)
        if (strlen(list[i]) == n && strncmp(list[i], s, n) == 0)
            return 1;
    return 0;
}

/* Whether this CPU runs Embree's kernels for `isa` (n bytes). Embree 3
 * takes 'isa=' as given, without asking the CPU: kernels it lacks would
 * stop the program on an illegal instruction. Its AVX-512 kernels are
 * Skylake-X's (F, CD, BW, DQ, VL). Only x86 is asked; elsewhere any name
 * passes to Embree. */
static int cpu_runs(const char *isa, size_t n)
{
    if (!isa)
        return 0;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    if (n == 6 && strncmp(isa, "sse4.2", 6) == 0)
        return __builtin_cpu_supports("sse4.2");
    if (n == 3 && strncmp(isa, "avx", 3) == 0)
        return __builtin_cpu_supports("avx");
    if (n == 4 && strncmp(isa, "avx2", 4) == 0)
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (n == 6 && strncmp(isa, "avx512", 6) == 0)
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vl");
#endif
    (void)isa, (void)n;
    return 1;
}

int sl_rt_cpu_runs(const char *isa)
{
    return isa && cpu_runs(isa, strlen(isa));
}

enum sl_err sl_rt_check_env(struct sl_diag *d)
{
    const char *user = sl_rt_env_config();
    if (!user)
        return SL_OK;
    const size_t max = sizeof((struct sl_rt *)0)->config - 16;
    if (strlen(user) > max)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EMBREE_CONFIG",
                       "'%.40s...': at most %zu characters of Embree's device config (e.g. isa=avx2)", user, max);
    for (const char *t = user; *t;) {
        const size_t len = strcspn(t, ","), key = strcspn(t, "=,");
        if (key == len || key == 0 || !in_list(rtc_keys, t, key))
            return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EMBREE_CONFIG",
                           "'%.*s' in '%s': Embree's device config is key=value pairs separated by commas, the "
                           "keys threads, user_threads, set_affinity, start_threads, isa, max_isa, hugepages, "
                           "verbose, frequency_level (rtcNewDevice(3))", (int)len, t, user);
        const char *val = t + key + 1;
        const size_t vlen = len - key - 1;
        const int isa = (key == 3 && strncmp(t, "isa", 3) == 0) || (key == 7 && strncmp(t, "max_isa", 7) == 0);
        if (isa && !in_list(rtc_isas, val, vlen))
            return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EMBREE_CONFIG",
                           "'%.*s' in '%s': the ISA is sse2, sse4.2, avx, avx2 or avx512", (int)len, t, user);
        if (isa && key == 3 && !cpu_runs(val, vlen))
            return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EMBREE_CONFIG",
                           "'%.*s' in '%s': this CPU does not run Embree's %.*s kernels (max_isa= caps the "
                           "choice instead)", (int)len, t, user, (int)vlen, val);
        for (size_t i = 0; i < vlen; i++)
            if (!(val[i] == '.' || val[i] == '_' || (val[i] >= '0' && val[i] <= '9') ||
                  (val[i] >= 'a' && val[i] <= 'z')))
                return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EMBREE_CONFIG",
                               "'%.*s' in '%s': a value is a number or a lower-case name", (int)len, t, user);
        t += len + (t[len] == ',');
    }
    return SL_OK;
}

enum sl_err sl_rt_build(struct sl_rt *rt, const struct sl_scene *s, int threads, int own_filter,
                        struct sl_diag *d)
{
    return sl_rt_build_isa(rt, s, threads, own_filter, NULL, d);
}

enum sl_err sl_rt_build_isa(struct sl_rt *rt, const struct sl_scene *s, int threads, int own_filter,
                            const char *isa, struct sl_diag *d)
{
    memset(rt, 0, sizeof *rt);
    rt->threads = threads;
    /* the user's SHADOWLAB_EMBREE_CONFIG after ours, then the caller's ISA:
     * Embree reads the string left to right, the last value of a key wins */
    const char *user = sl_rt_env_config();
    enum sl_err ce = sl_rt_check_env(d);
    if (ce)
        return ce;
    if (isa && !in_list(rtc_isas, isa, strlen(isa)))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "sl_rt_build_isa: no ISA '%s'", isa);
    int len = snprintf(rt->config, sizeof rt->config, "threads=%d%s%s", threads, user ? "," : "", user ? user : "");
    if (isa && len > 0 && (size_t)len < sizeof rt->config)
        snprintf(rt->config + len, sizeof rt->config - (size_t)len, ",isa=%s", isa);
    char why[300];
    if (sl_rtc_load(why, sizeof why))
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "%s", why);
    double t0 = sl_now();
    rt->device = rtcNewDevice(rt->config);
    if (!rt->device) {
        if (user)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "SHADOWLAB_EMBREE_CONFIG",
                           "'%s': Embree refused the device config '%s' (error %d; e.g. isa=sse4.2, isa=avx2, "
                           "threads=1)", user, rt->config, (int)rtcGetDeviceError(NULL));
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "rtcNewDevice failed (error %d)",
                       (int)rtcGetDeviceError(NULL));
    }
    snprintf(rt->version, sizeof rt->version, "%d.%d.%d",
             (int)rtcGetDeviceProperty(rt->device, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
             (int)rtcGetDeviceProperty(rt->device, RTC_DEVICE_PROPERTY_VERSION_MINOR),
             (int)rtcGetDeviceProperty(rt->device, RTC_DEVICE_PROPERTY_VERSION_PATCH));
    rt->shift = native_shift(rt->device);
    if (rt->shift < 0) {
        sl_rt_free(rt);
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "this Embree has no native ray packets (4, 8 or 16 wide)");
    }
    rt->scene = rtcNewScene(rt->device);
    rtcSetSceneFlags(rt->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(rt->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(rt->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    /* Embree-allocated buffers carry the padding its SIMD loads need. */
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), s->nv);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), s->nt);
    if (!vb || !ib) {
        rtcReleaseGeometry(g);
        sl_rt_free(rt);
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "Embree buffers for %u triangles", s->nt);
    }
    memcpy(vb, s->pos, (size_t)s->nv * 3 * sizeof(float));
    memcpy(ib, s->idx, (size_t)s->nt * 3 * sizeof(unsigned));
    if (own_filter)
        rtcSetGeometryOccludedFilterFunction(g, own_triangle_filter);
    rtcCommitGeometry(g);
    rtcAttachGeometry(rt->scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(rt->scene);
    rt->ms_build = 1e3 * (sl_now() - t0);
    enum RTCError err = rtcGetDeviceError(rt->device);
    if (err != RTC_ERROR_NONE) {
        sl_rt_free(rt);
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "Embree scene build failed (error %d)", (int)err);
    }
    return SL_OK;
}

void sl_rt_free(struct sl_rt *rt)
{
    if (rt->scene) rtcReleaseScene(rt->scene);
    if (rt->device) rtcReleaseDevice(rt->device);
    memset(rt, 0, sizeof *rt);
}

enum sl_err sl_rt_trace(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                        const uint8_t *select, uint8_t *out, uint64_t *rays_out, uint64_t *shadow_out,
                        struct sl_diag *d)
{
    return sl_rt_trace_timed(rt, s, v, select, NULL, out, rays_out, shadow_out, NULL, d);
}

enum sl_err sl_rt_trace_until(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                              const uint8_t *select, const float *tfar, uint8_t *out, uint64_t *rays_out,
                              uint64_t *shadow_out, struct sl_diag *d)
{
    return sl_rt_trace_timed(rt, s, v, select, tfar, out, rays_out, shadow_out, NULL, d);
}

/* Tiles per chunk: a thread fills the rays of SL_RT_CHUNK 4x4 tiles side
 * by side (a 4-row strip, 4*SL_RT_CHUNK pixels wide), traces them, then
 * writes their answers back. 32 tiles are 26 KiB: they stay in L1/L2
 * between set-up and trace, where rays built for the whole view (48 MB
 * at 1024x1024) go out to memory and back. Filling a strip row by row reads
 * the G-buffer in address order. The chunk is also what the set-up and
 * trace clocks time: ~4 clock reads per 512 pixels. */
#define SL_RT_CHUNK 32

struct rt_chunk {
    struct sl_rt_tile t[SL_RT_CHUNK];
    int any[SL_RT_CHUNK];
};

void sl_rt_occluded_tile(const struct sl_rt *rt, struct RTCIntersectContext *ctx, struct sl_rt_tile *t)
{
    switch (rt->shift) {
    case 4:
        rtcOccluded16(t->valid, rt->scene, ctx, (struct RTCRay16 *)t->w);
        break;
    case 3:
        /* a packet with no active lane is not handed to Embree at all */
        for (int p = 0; p < 2; p++)
            if (t->valid[8 * p] | t->valid[8 * p + 1] | t->valid[8 * p + 2] | t->valid[8 * p + 3] |
                t->valid[8 * p + 4] | t->valid[8 * p + 5] | t->valid[8 * p + 6] | t->valid[8 * p + 7])
                rtcOccluded8(t->valid + 8 * p, rt->scene, ctx, (struct RTCRay8 *)(t->w + 8 * SL_RAY_FIELDS * p));
        break;
    default:
        for (int p = 0; p < 4; p++)
            if (t->valid[4 * p] | t->valid[4 * p + 1] | t->valid[4 * p + 2] | t->valid[4 * p + 3])
                rtcOccluded4(t->valid + 4 * p, rt->scene, ctx, (struct RTCRay4 *)(t->w + 4 * SL_RAY_FIELDS * p));
        break;
    }
}

/* Fill the packets of tiles [t0, t0+n) of tile row ty0 (4-pixel tiles):
 * every lane disarmed first (packet.h: a lane outside the image or not
 * traced is a dead ray, never garbage; the chunk's tiles were written whole
 * when the thread began), then each traced pixel's ray in its lane,
 * (row, x & 3) of its tile. What an active lane holds is the same ray on
 * every packet width, so each ray and its answer are too. */
static void chunk_fill(struct rt_chunk *c, int shift, const struct sl_scene *s, const struct sl_view *v,
                       const uint8_t *select, const float *tfar, int point, int ty0, int t0, int n)
{
    const int W = v->w, H = v->h;
    const int y0 = ty0 * 4, ny = H - y0 < 4 ? H - y0 : 4;
    const int x0 = t0 * 4, x1 = (t0 + n) * 4 < W ? (t0 + n) * 4 : W;
    for (int pk = 0; pk < n; pk++) {
        sl_tile_disarm(&c->t[pk], shift);
        c->any[pk] = 0;
    }
    for (int row = 0; row < ny; row++) {
        const size_t base = (size_t)(y0 + row) * (size_t)W;
        const uint8_t *cls = v->cls + base;
        for (int x = x0; x < x1; x++) {
            if (cls[x] != SL_C_PFL || (select && !select[base + (size_t)x]))
                continue;
            const size_t i = base + (size_t)x;
            const int pk = (x - x0) >> 2, k = row * 4 + (x & 3);
            const float *p = v->pos + 3 * i;
            float end = tfar ? tfar[i] : INFINITY;
            if (point) {
                float dir[3], to = 0.0f;   /* a pixel at the light itself: an empty ray */
                if (!sl_point_ray(s->light.pos, p, dir, &to))
                    dir[0] = dir[1] = 0.0f, dir[2] = 1.0f;
                end = to < end ? to : end;
                for (int a = 0; a < 3; a++)
                    sl_tile_set(&c->t[pk], shift, SL_RAY_DIR_X + a, k, dir[a]);
            }
            sl_tile_start(&c->t[pk], shift, k, p, sl_rt_tnear(p), end, v->tri[i]);
            c->any[pk] = 1;
        }
    }
}

enum sl_err sl_rt_trace_timed(const struct sl_rt *rt, const struct sl_scene *s, const struct sl_view *v,
                              const uint8_t *select, const float *tfar, uint8_t *out, uint64_t *rays_out,
                              uint64_t *shadow_out, struct sl_rt_times *tm, struct sl_diag *d)
{
    const int W = v->w, H = v->h;
    const int tx = (W + 3) / 4, ty = (H + 3) / 4;
    const int cx = (tx + SL_RT_CHUNK - 1) / SL_RT_CHUNK;   /* chunks per tile row */
    const int shift = rt->shift;
    /* spot and point lights are traced to their position, an area light as
     * a point at its centre (arealight.h) */
    const int point = s->light.type != SL_LIGHT_DIRECTIONAL;
    uint64_t rays = 0, shadow = 0;
    double set_s = 0.0, trace_s = 0.0;
    struct rt_chunk *chunks = aligned_alloc(64, sizeof *chunks * (size_t)(rt->threads > 0 ? rt->threads : 1));
    if (!chunks)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "ray packets for %d threads", rt->threads);
    /* 4x4 tiles as 16 rays (one to four packets, packet.h); rays are
     * independent, so the result does not depend on the thread count or
     * schedule, nor on which other pixels are traced with it: a method
     * tracing a subset gets, ray for ray, the truth's answer. */
#pragma omp parallel num_threads(rt->threads) reduction(+ : rays, shadow, set_s, trace_s)
    {
        sl_rt_thread_init();
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        /* Embree loads the packet and its mask with aligned vector loads
         * (packet.h). Every lane written whole once per thread; what is
         * the same for every ray of a directional light (its direction) is
         * written here too, not once per chunk. */
        struct rt_chunk *c = &chunks[omp_get_thread_num()];
        const float ldir[3] = {-s->light_dir[0], -s->light_dir[1], -s->light_dir[2]};
        for (int pk = 0; pk < SL_RT_CHUNK; pk++) {
            sl_tile_kill_all(&c->t[pk], shift);
            if (!point)
                sl_tile_dir_all(&c->t[pk], shift, ldir);
        }
#pragma omp for schedule(dynamic, 1)
        for (int ch = 0; ch < cx * ty; ch++) {
            const int ty0 = ch / cx, t0 = (ch % cx) * SL_RT_CHUNK;
            const int n = tx - t0 < SL_RT_CHUNK ? tx - t0 : SL_RT_CHUNK;
            const double a = sl_now();
            chunk_fill(c, shift, s, v, select, tfar, point, ty0, t0, n);
            const double b = sl_now();
            for (int pk = 0; pk < n; pk++)
                if (c->any[pk])
                    sl_rt_occluded_tile(rt, &ctx, &c->t[pk]);
            const double e = sl_now();
            const int y0 = ty0 * 4, ny = H - y0 < 4 ? H - y0 : 4;
            const int x0 = t0 * 4, x1 = (t0 + n) * 4 < W ? (t0 + n) * 4 : W;
            for (int row = 0; row < ny; row++) {
                uint8_t *o = out + (size_t)(y0 + row) * (size_t)W;
                for (int x = x0; x < x1; x++) {
                    const int pk = (x - x0) >> 2, k = row * 4 + (x & 3);
                    if (!c->t[pk].valid[k])
                        continue;
                    const int occluded = sl_tile_occluded(&c->t[pk], shift, k);
                    o[x] = occluded ? SL_T_SHADOW : SL_T_LIT;
                    shadow += (uint64_t)occluded;
                    rays++;
                }
            }
            set_s += (b - a) + (sl_now() - e);
            trace_s += e - b;
        }
    }
    free(chunks);
    if (rays_out)
        *rays_out = rays;
    if (shadow_out)
        *shadow_out = shadow;
    if (tm) {
        tm->ms_setup = 1e3 * set_s;
        tm->ms_rays = 1e3 * trace_s;
    }
    enum RTCError err = rtcGetDeviceError(rt->device);
    if (err != RTC_ERROR_NONE)
        return sl_fail(d, SL_E_EMBREE, NULL, 0, NULL, "Embree trace failed (error %d)", (int)err);
    return SL_OK;
}

enum sl_err sl_truth_trace(const struct sl_rt *rt, const struct sl_scene *s, struct sl_view *v,
                           struct sl_truth_stats *st, struct sl_diag *d)
{
    double t0 = sl_now();
    uint64_t rays = 0, shadow = 0;
    struct sl_rt_times tm = {0, 0};
    enum sl_err e = sl_rt_trace_timed(rt, s, v, NULL, NULL, v->truth, &rays, &shadow, &tm, d);
    v->n_lit = rays - shadow;
    v->n_shadow = shadow;
    if (st) {
        st->rays = rays;
        st->ms_trace = 1e3 * (sl_now() - t0);
        st->ms_setup = tm.ms_setup;
        st->ms_rays = tm.ms_rays;
    }
    return e;
}
