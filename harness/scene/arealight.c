/*
 * arealight.c — see arealight.h.
 */
#include "arealight.h"
#include <math.h>
#include <stdio.h>

static void normalise(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

void sl_area_of(const struct sl_light *l, struct sl_area *a)
{
    double up[3];
    for (int k = 0; k < 3; k++) {
        a->c[k] = l->pos[k];
        a->n[k] = l->normal[k];
        up[k] = l->up[k];
    }
    normalise(a->n);
    cross(up, a->n, a->ex);   /* the scene file refuses an up along the normal */
    normalise(a->ex);
    cross(a->n, a->ex, a->ey);
    normalise(a->ey);
    a->w = l->size[0];
    a->h = l->size[1];
}

int sl_point_ray(const float c[3], const float p[3], float dir[3], float *tfar)
{
    double to[3], dist2 = 0.0;
    for (int k = 0; k < 3; k++) {
        to[k] = (double)c[k] - (double)p[k];
        dist2 += to[k] * to[k];
    }
    if (!(dist2 > 0.0))
        return 0;
    double dist = sqrt(dist2);
    for (int k = 0; k < 3; k++)
        dir[k] = (float)(to[k] / dist);
    *tfar = (float)dist - sl_rt_tnear(c);
    return 1;
}

void sl_area_point(const struct sl_area *a, double u, double v, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a->c[k] + (u - 0.5) * a->w * a->ex[k] + (v - 0.5) * a->h * a->ey[k];
}

/* Wellons' lowbias32: a bijection on 32 bits with low bias (avalanche). */
static uint32_t lowbias32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

uint32_t sl_hash4(uint32_t x, uint32_t y, uint32_t k, uint32_t seed)
{
    return lowbias32(lowbias32(lowbias32(lowbias32(seed) ^ x) ^ y) ^ k);
}

void sl_area_jitter(uint32_t x, uint32_t y, uint32_t k, uint32_t n, uint32_t seed, double *u, double *v)
{
    uint32_t cx = k % n, cy = k / n;
    double ju = sl_unit(sl_hash4(x, y, 2 * k, seed)), jv = sl_unit(sl_hash4(x, y, 2 * k + 1, seed));
    *u = ((double)cx + ju) / (double)n;
    *v = ((double)cy + jv) / (double)n;
}

void sl_light_heading(const struct sl_light *l, char *buf, size_t n)
{
    if (!buf || n == 0)
        return;
    switch (l->type) {
    case SL_LIGHT_SPOT:
        /* %g: 70 stays "70", 22.5 "22.5" */
        if (l->penumbra_deg > 0.0f)
            snprintf(buf, n, "spot light, %g\xC2\xB0, penumbra %g\xC2\xB0 ignored", (double)l->fov_deg,
                     (double)l->penumbra_deg);
        else
            snprintf(buf, n, "spot light, %g\xC2\xB0", (double)l->fov_deg);
        break;
    case SL_LIGHT_POINT: snprintf(buf, n, "point light"); break;
    case SL_LIGHT_AREA: snprintf(buf, n, "area light"); break;
    default: snprintf(buf, n, "directional light"); break;
    }
}
