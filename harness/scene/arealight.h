/*
 * arealight.h — rectangular area lights (Curtis 2009 uses square ones), their
 * sample points and the stateless per-pixel random source both the area
 * truth and the `soft_mc` method draw from.
 *
 * A scene's area light (scene.h, SL_LIGHT_AREA) has a centre, the unit
 * normal of the side that emits, an up direction and a size (width across
 * up x normal, height along up). sl_area_of turns it into an orthonormal
 * frame in double; sl_area_point maps the unit square onto the rectangle.
 *
 * Random numbers: Curtis hashes each fragment's screen coordinates with a
 * 16-round MD5 so that every pixel draws independently on the GPU. We keep
 * the idea (a stateless hash of pixel, sample index and seed, so any pixel's
 * samples can be recomputed alone, in any order, on any thread: fixed seeds
 * give bit-identical images) with a cheaper integer hash (Wellons'
 * "lowbias32" finaliser, applied in a chain), since MD5's rounds buy
 * nothing a CPU needs here.
 * Does not: trace, render or own anything.
 */
#ifndef SL_AREALIGHT_H
#define SL_AREALIGHT_H
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include "scene.h"

struct sl_area {
    double c[3];     /* centre */
    double n[3];     /* unit normal, the side that emits */
    double ex[3];    /* unit, along the width: up x normal, orthogonal to n */
    double ey[3];    /* unit, along the height: n x ex (up made orthogonal to n) */
    double w, h;     /* width and height */
};

/* The frame of an SL_LIGHT_AREA light. */
void sl_area_of(const struct sl_light *l, struct sl_area *a);

/* The point at (u, v) in [0, 1]^2 of the rectangle: c + (u - 1/2) w ex + (v - 1/2) h ey. */
void sl_area_point(const struct sl_area *a, double u, double v, double out[3]);

/* Distance along the ray (the truth's and every method's) at which shadow rays start: 2^-16 (about 1.5e-5) of
 * the origin's largest coordinate magnitude, plus 2^-24 absolute. */
static inline float sl_rt_tnear(const float p[3])
{
    /* plain comparisons: fmaxf is a libm call when NaNs must be honoured */
    float x = p[0] < 0.0f ? -p[0] : p[0];
    float y = p[1] < 0.0f ? -p[1] : p[1];
    float z = p[2] < 0.0f ? -p[2] : p[2];
    float m = x > y ? x : y;
    m = m > z ? m : z;
    return m * 0x1p-16f + 0x1p-24f;
}

/* The shadow ray from p to a point light at c, as every user of a point
 * light casts it (the point truth, hard_point, the methods' sure tests):
 * unit direction (c - p) / |c - p| computed in double, and its end tfar =
 * |c - p| minus the tnear of c (truth.h), so a ray never meets the light's
 * own surroundings. Returns 0 when p coincides with c (no direction). */
int sl_point_ray(const float c[3], const float p[3], float dir[3], float *tfar);

/* Whether a point p with unit normal n (turned toward the camera) is lit at
 * all by a light at a point (an area light's centre, a spot or a point
 * light): it faces the light's position, and
 *   - area: lies on the emitting side of the light's plane (a PFL pixel of
 *     the point approximation);
 *   - spot: lies inside the cone (sl_spot_inside);
 *   - point: nothing more.
 * Double, so the G-buffer's classes, hard_point and the methods agree. */
static inline int sl_spot_inside(const struct sl_light *l, const float p[3]);
static inline int sl_point_faces(const struct sl_light *l, const float p[3], const float n[3])
{
    double facing = 0.0, emitting = 0.0;
    for (int k = 0; k < 3; k++) {
        double to = (double)l->pos[k] - (double)p[k];
        facing += (double)n[k] * to;
        emitting -= (double)l->normal[k] * to;
    }
    if (!(facing > 0.0))
        return 0;
    if (l->type == SL_LIGHT_AREA)
        return emitting > 0.0;
    if (l->type == SL_LIGHT_SPOT)
        return sl_spot_inside(l, p);
    return 1;
}

/* Whether p lies inside a spot light's cone: the angle between the light's
 * direction and p - pos at most fov / 2 (fov < 180 degrees, scenefile.c),
 * in double: dot > 0 and dot^2 >= cos^2(fov / 2) |p - pos|^2. A point at
 * the light itself is outside (no direction). */
static inline int sl_spot_inside(const struct sl_light *l, const float p[3])
{
    double dot = 0.0, len2 = 0.0;
    for (int k = 0; k < 3; k++) {
        double d = (double)p[k] - (double)l->pos[k];
        dot += d * (double)l->dir[k];
        len2 += d * d;
    }
    double c = cos(0.5 * (double)l->fov_deg * (3.14159265358979323846 / 180.0));
    return dot > 0.0 && dot * dot >= c * c * len2;
}

/* A light's words for the tables' and the report's headings:
 * "directional light", "spot light, 70°" (", penumbra 5° ignored" when it
 * has one: the hard methods ignore it), "point light", "area light" (UTF-8).
 * Always NUL-terminated, cut to n. */
void sl_light_heading(const struct sl_light *l, char *buf, size_t n);

/* 32 random bits for (x, y, k) under seed: pixel x, y, sample k. */
uint32_t sl_hash4(uint32_t x, uint32_t y, uint32_t k, uint32_t seed);

/* A 32-bit hash as a double in [0, 1). */
static inline double sl_unit(uint32_t h) { return (double)h * (1.0 / 4294967296.0); }

/* Sample k of an n x n jittered grid (stratified) over the unit square for
 * pixel (x, y): cell (k mod n, k div n), a random point inside it. */
void sl_area_jitter(uint32_t x, uint32_t y, uint32_t k, uint32_t n, uint32_t seed, double *u, double *v);

#endif
