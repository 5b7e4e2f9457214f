/*
 * packet.h — sixteen shadow rays handed to Embree in packets of the width
 * its device runs natively, every lane written.
 *
 * Why: rtcOccluded16 is native only where Embree runs AVX-512. Elsewhere
 * Embree 3 emulates it through its ray-stream path, which ignores the valid
 * mask and traces every lane whose tnear <= tfar (a ray stream's only
 * notion of an inactive ray), so a lane left unwritten is traced as
 * whatever the memory holds, and Debian's assertion-enabled libembree3
 * aborts on it. The documented contract, followed to the letter here:
 *   - the packet width is one the device supports natively
 *     (rtcGetDeviceProperty(RTC_DEVICE_PROPERTY_NATIVE_RAY16/8/4_SUPPORTED),
 *     chosen once in sl_rt_build: 16 where native, else 8, else 4);
 *   - every lane of every packet is written; an inactive lane is a dead
 *     ray (finite origin and direction, tnear 1 > tfar 0, time 0, mask 0,
 *     flags 0) that every path Embree may take skips, valid mask or not;
 *   - packets are aligned to 64 bytes (16: 64, 8: 32, 4: 16 required).
 *
 * Layout: a tile is 16 lanes (a 4x4 pixel tile of the truth, or 16 samples
 * of one pixel of the area truth). Its memory is 16 / width packets of
 * `width` lanes, each one Embree SOA packet (struct RTCRay4/8/16: twelve
 * fields of `width` values), back to back: lane k is lane k % width of
 * packet k / width. So the same tile is one RTCRay16, two RTCRay8 or four
 * RTCRay4, and a lane's ray is the same bits whichever width the device
 * takes; each ray is traced alone (packets do not share answers), so the
 * answers are the same ray for ray on every ISA (portability::isa_figures).
 *
 * Owns: nothing (a tile is a plain value). Does not: choose the rays.
 */
#ifndef SL_PACKET_H
#define SL_PACKET_H
#include <stddef.h>
#include <embree3/rtcore.h>

#define SL_RT_LANES 16

/* the fields of Embree's ray, in struct RTCRayN's order (rtcore_ray.h) */
enum sl_ray_field {
    SL_RAY_ORG_X, SL_RAY_ORG_Y, SL_RAY_ORG_Z, SL_RAY_TNEAR,
    SL_RAY_DIR_X, SL_RAY_DIR_Y, SL_RAY_DIR_Z, SL_RAY_TIME,
    SL_RAY_TFAR,  SL_RAY_MASK,  SL_RAY_ID,    SL_RAY_FLAGS,
    SL_RAY_FIELDS
};

_Static_assert(sizeof(struct RTCRay16) == SL_RAY_FIELDS * 16 * sizeof(float), "RTCRay16 is 12 fields of 16");
_Static_assert(sizeof(struct RTCRay8) == SL_RAY_FIELDS * 8 * sizeof(float), "RTCRay8 is 12 fields of 8");
_Static_assert(sizeof(struct RTCRay4) == SL_RAY_FIELDS * 4 * sizeof(float), "RTCRay4 is 12 fields of 4");
_Static_assert(offsetof(struct RTCRay4, flags) == SL_RAY_FLAGS * 4 * sizeof(float), "field order");

union sl_ray_word {
    float    f;
    unsigned u;
};

struct sl_rt_tile {
    _Alignas(64) union sl_ray_word w[SL_RAY_FIELDS * SL_RT_LANES];
    _Alignas(64) int valid[SL_RT_LANES];
};

/* Index of field `f` of lane k (0..15) for packets of 1 << shift lanes. */
static inline size_t sl_tile_at(int shift, int f, int k)
{
    return (((size_t)(k >> shift) * SL_RAY_FIELDS + (size_t)f) << shift) + (size_t)(k & ((1 << shift) - 1));
}

static inline void sl_tile_set(struct sl_rt_tile *t, int shift, int f, int k, float v)
{
    t->w[sl_tile_at(shift, f, k)].f = v;
}

static inline float sl_tile_get(const struct sl_rt_tile *t, int shift, int f, int k)
{
    return t->w[sl_tile_at(shift, f, k)].f;
}

/* A dead ray's fields: origin 0, tnear 1, direction +z, time 0, tfar 0,
 * every mask bit, id 0, flags 0. tnear > tfar is what makes it dead on
 * every path; the mask is the active rays' so that a lane turned active
 * by sl_tile_start need not write it again. */
static const union sl_ray_word sl_dead_ray[SL_RAY_FIELDS] = {
    {.f = 0.0f}, {.f = 0.0f}, {.f = 0.0f}, {.f = 1.0f}, {.f = 0.0f}, {.f = 0.0f},
    {.f = 1.0f}, {.f = 0.0f}, {.f = 0.0f}, {.u = 0xffffffffu}, {.u = 0u}, {.u = 0u}};

/* Lane k as a dead ray, inactive (see above). */
static inline void sl_tile_kill(struct sl_rt_tile *t, int shift, int k)
{
    for (int f = 0; f < SL_RAY_FIELDS; f++)
        t->w[sl_tile_at(shift, f, k)] = sl_dead_ray[f];
    t->valid[k] = 0;
}

/* Every lane dead: the tile's memory in order, packet by packet, field by
 * field (contiguous stores). */
static inline void sl_tile_kill_all(struct sl_rt_tile *t, int shift)
{
    const int width = 1 << shift;
    union sl_ray_word *w = t->w;
    for (int p = 0; p < SL_RT_LANES >> shift; p++)
        for (int f = 0; f < SL_RAY_FIELDS; f++)
            for (int l = 0; l < width; l++)
                *w++ = sl_dead_ray[f];
    for (int k = 0; k < SL_RT_LANES; k++)
        t->valid[k] = 0;
}

/* Every lane dead again, cheaply: tnear 1 > tfar 0 and not valid, the other
 * fields left as they are. Only for a tile every lane of which was written
 * whole since it was made (sl_tile_kill_all, then rays): its origins and
 * directions are finite and its time, mask and flags a ray's. */
static inline void sl_tile_disarm(struct sl_rt_tile *t, int shift)
{
    const int width = 1 << shift;
    for (int p = 0; p < SL_RT_LANES >> shift; p++) {
        union sl_ray_word *w = t->w + (size_t)p * SL_RAY_FIELDS * (size_t)width;
        for (int l = 0; l < width; l++) {
            w[SL_RAY_TNEAR * width + l].f = 1.0f;
            w[SL_RAY_TFAR * width + l].f = 0.0f;
        }
    }
    for (int k = 0; k < SL_RT_LANES; k++)
        t->valid[k] = 0;
}

/* The same direction in every lane (a directional light's). */
static inline void sl_tile_dir_all(struct sl_rt_tile *t, int shift, const float dir[3])
{
    for (int k = 0; k < SL_RT_LANES; k++)
        for (int c = 0; c < 3; c++)
            t->w[sl_tile_at(shift, SL_RAY_DIR_X + c, k)].f = dir[c];
}

/* Lane k active with origin o, segment [tnear, tfar] and the own
 * triangle's id; its direction, time (0), mask (every bit) and flags (0)
 * are the ones the lane holds (sl_tile_kill_all, sl_tile_dir_all). */
static inline void sl_tile_start(struct sl_rt_tile *t, int shift, int k, const float o[3], float tnear, float tfar,
                                 unsigned id)
{
    union sl_ray_word *w = t->w + sl_tile_at(shift, 0, k);   /* field f is w[f << shift] */
    w[SL_RAY_ORG_X << shift].f = o[0];
    w[SL_RAY_ORG_Y << shift].f = o[1];
    w[SL_RAY_ORG_Z << shift].f = o[2];
    w[SL_RAY_TNEAR << shift].f = tnear;
    w[SL_RAY_TFAR << shift].f = tfar;
    w[SL_RAY_ID << shift].u = id;
    t->valid[k] = -1;
}

/* Lane k as an active ray: origin o, direction dir, [tnear, tfar], the own
 * triangle's id (truth.c's filter), time 0, every mask bit, flags 0. */
static inline void sl_tile_ray(struct sl_rt_tile *t, int shift, int k, const float o[3], const float dir[3],
                               float tnear, float tfar, unsigned id)
{
    t->w[sl_tile_at(shift, SL_RAY_ORG_X, k)].f = o[0];
    t->w[sl_tile_at(shift, SL_RAY_ORG_Y, k)].f = o[1];
    t->w[sl_tile_at(shift, SL_RAY_ORG_Z, k)].f = o[2];
    t->w[sl_tile_at(shift, SL_RAY_TNEAR, k)].f = tnear;
    t->w[sl_tile_at(shift, SL_RAY_DIR_X, k)].f = dir[0];
    t->w[sl_tile_at(shift, SL_RAY_DIR_Y, k)].f = dir[1];
    t->w[sl_tile_at(shift, SL_RAY_DIR_Z, k)].f = dir[2];
    t->w[sl_tile_at(shift, SL_RAY_TIME, k)].f = 0.0f;
    t->w[sl_tile_at(shift, SL_RAY_TFAR, k)].f = tfar;
    t->w[sl_tile_at(shift, SL_RAY_MASK, k)].u = 0xffffffffu;
    t->w[sl_tile_at(shift, SL_RAY_ID, k)].u = id;
    t->w[sl_tile_at(shift, SL_RAY_FLAGS, k)].u = 0u;
    t->valid[k] = -1;
}

/* An active lane after tracing: occluded rays come back with tfar = -inf. */
static inline int sl_tile_occluded(const struct sl_rt_tile *t, int shift, int k)
{
    return t->w[sl_tile_at(shift, SL_RAY_TFAR, k)].f == -__builtin_inff();
}

#endif
