/* raytri::* — the reference ray-triangle tests and distances. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "sl_test.h"
#include <stdint.h>
#include "raytri.h"
#include "arealight.h"   /* sl_rt_tnear */

static const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0};

static void raytri_hit_inside(void **st)
{
    (void)st;
    double o[3] = {0.25, 0.25, 5}, d[3] = {0, 0, -1}, t = -1;
    assert_int_equal(sl_ray_tri_d(o, d, A, B, C, 0.0, &t), 1);
    assert_true(fabs(t - 5.0) < 1e-12);
    /* from below, facing the back: no culling */
    double o2[3] = {0.25, 0.25, -2}, d2[3] = {0, 0, 1};
    assert_int_equal(sl_ray_tri_d(o2, d2, A, B, C, 0.0, &t), 1);
    assert_true(fabs(t - 2.0) < 1e-12);
}

static void raytri_miss_outside_and_behind(void **st)
{
    (void)st;
    double t;
    double o[3] = {0.75, 0.75, 5}, d[3] = {0, 0, -1};
    assert_int_equal(sl_ray_tri_d(o, d, A, B, C, 0.0, &t), 0);      /* beyond the hypotenuse */
    double o2[3] = {0.25, 0.25, 5}, d2[3] = {0, 0, 1};
    assert_int_equal(sl_ray_tri_d(o2, d2, A, B, C, 0.0, &t), 0);    /* triangle behind */
    double o3[3] = {0.25, 0.25, 1}, d3[3] = {1, 0, 0};
    assert_int_equal(sl_ray_tri_d(o3, d3, A, B, C, 0.0, &t), 0);    /* parallel */
}

static void raytri_edges_closed_and_tmin(void **st)
{
    (void)st;
    double t;
    double o[3] = {0.5, 0.5, 3}, d[3] = {0, 0, -1};                  /* exactly on the hypotenuse */
    assert_int_equal(sl_ray_tri_d(o, d, A, B, C, 0.0, &t), 1);
    double o2[3] = {0.25, 0.25, 0.5};
    assert_int_equal(sl_ray_tri_d(o2, d, A, B, C, 0.5, &t), 0);     /* t == tmin is not a hit */
    assert_int_equal(sl_ray_tri_d(o2, d, A, B, C, 0.49, &t), 1);
}

static void raytri_distances(void **st)
{
    (void)st;
    double p[3] = {0.25, 0.25, 2};
    assert_true(fabs(sl_point_tri_dist_d(p, A, B, C) - 2.0) < 1e-12);
    double q[3] = {2, 0, 0};                      /* 1 beyond vertex B along x */
    assert_true(fabs(sl_point_tri_dist_d(q, A, B, C) - 1.0) < 1e-12);
    double r[3] = {0.25, -0.5, 0};                /* 0.5 below edge AB */
    assert_true(fabs(sl_point_tri_dist_d(r, A, B, C) - 0.5) < 1e-12);
    double s[3] = {0.25, 0.1, 0};                 /* inside, 0.1 from AB */
    assert_true(fabs(sl_point_tri_edge_dist_d(s, A, B, C) - 0.1) < 1e-12);
}

/* The sure test along a ray toward a point light: a triangle between the
 * pixel and the light is a sure hit, the same triangle beyond the light a
 * sure miss (the ray ends there), one right at the light too close to call;
 * with no end (a directional light) the far one is a hit as well. */
static void raytri_sure_until_the_light(void **st)
{
    (void)st;
    const float p[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    const float a[3] = {-1, 5, -1}, b[3] = {1, 5, -1}, c[3] = {0, 5, 1};        /* at y = 5 */
    const float a2[3] = {-1, 12, -1}, b2[3] = {1, 12, -1}, c2[3] = {0, 12, 1};  /* at y = 12 */
    float tnear = 1e-5f;
    assert_int_equal(sl_shadow_ray_tri_sure(p, up, 10.0f, tnear, a, b, c), 1);
    assert_int_equal(sl_shadow_ray_tri_sure(p, up, 10.0f, tnear, a2, b2, c2), -1);
    assert_int_equal(sl_shadow_ray_tri_sure(p, up, 12.0f, tnear, a2, b2, c2), 0);
    assert_int_equal(sl_shadow_ray_tri_sure(p, up, INFINITY, tnear, a2, b2, c2), 1);
    /* a triangle below the pixel: behind the ray, whatever its end */
    const float a3[3] = {-1, -3, -1}, b3[3] = {1, -3, -1}, c3[3] = {0, -3, 1};
    assert_int_equal(sl_shadow_ray_tri_sure(p, up, INFINITY, tnear, a3, b3, c3), -1);
}

static uint64_t rng_state = 0x9e3779b97f4a7c15u;
static double rnd(void)     /* xorshift64*, in [0, 1) */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 0x2545f4914f6cdd1du) >> 11) * 0x1p-53;
}

/* sl_shadow_ray_tri_hit is sl_shadow_ray_tri_sure > 0 for every input, the
 * hard ones most of all: rays aimed at points within a few margins of an
 * edge (inside and out), crossings near tnear and near the ray's end,
 * nearly grazing rays, at several coordinate sizes. Each outcome of the
 * sure test must come up often, and a 0 from inside the triangle (the
 * edge margin) too, so an order that dropped or changed a condition would
 * show here. */
static void raytri_hit_is_sure_positive(void **st)
{
    (void)st;
    const double scales[] = {1.0, 37.0, 1e3, 1e5};
    int pos = 0, zero = 0, neg = 0, zero_inside = 0, near_end = 0;
    for (int it = 0; it < 400000; it++) {
        double sc = scales[it % 4], off = (it & 4) ? 3.0 * sc : 0.0;
        float a[3], b[3], c[3], p[3], toward[3];
        for (int k = 0; k < 3; k++) {
            a[k] = (float)(off + sc * (rnd() - 0.5));
            b[k] = (float)(off + sc * (rnd() - 0.5));
            c[k] = (float)(off + sc * (rnd() - 0.5));
        }
        /* a target on the triangle's plane: barycentrics that put it near
         * an edge or a corner, by a few of the test's margins either side */
        double margin = 1e-5 * (4.0 * sc + off + 1.0);
        double w1 = rnd(), w2 = rnd() * (1.0 - w1);
        int mode = (int)(rnd() * 4.0);
        if (mode == 1) w1 = (rnd() - 0.5) * 8.0 * margin / sc;            /* near edge ac */
        if (mode == 2) w2 = 1.0 - w1 + (rnd() - 0.5) * 8.0 * margin / sc;  /* near edge bc */
        double tgt[3], dist = (rnd() < 0.25 ? 1e-4 + 1e-3 * rnd() : rnd() + 0.01) * sc, d[3], len = 0.0;
        double dd[3];
        for (int k = 0; k < 3; k++) {
            tgt[k] = a[k] + w1 * ((double)b[k] - a[k]) + w2 * ((double)c[k] - a[k]);
            dd[k] = rnd() - 0.5;
        }
        if (mode == 3)  /* nearly in the plane: grazing */
            for (int k = 0; k < 3; k++)
                dd[k] = (double)b[k] - a[k] + 1e-9 * (rnd() - 0.5);
        for (int k = 0; k < 3; k++)
            len += dd[k] * dd[k];
        len = sqrt(len);
        for (int k = 0; k < 3; k++) {
            d[k] = dd[k] / len;
            p[k] = (float)(tgt[k] - dist * d[k]);
        }
        double tl = 0.0;
        for (int k = 0; k < 3; k++) {
            double e = tgt[k] - (double)p[k];
            tl += e * e;
        }
        tl = sqrt(tl);
        for (int k = 0; k < 3; k++)
            toward[k] = (float)((tgt[k] - (double)p[k]) / tl);
        /* the ray's end: none, well beyond, or within a few margins of the crossing */
        float tmax = it % 3 == 0 ? INFINITY : it % 3 == 1 ? (float)(2.0 * tl)
                                                            : (float)(tl + (rnd() - 0.5) * 6.0 * margin);
        float tnear = (it % 7 == 0) ? (float)(tl * (0.3 + 3.0 * rnd())) : sl_rt_tnear(p);
        int sure = sl_shadow_ray_tri_sure(p, toward, tmax, tnear, a, b, c);
        int hit = sl_shadow_ray_tri_hit(p, toward, tmax, tnear, a, b, c);
        if (hit != (sure > 0))
            fail_msg("iteration %d: hit %d, sure %d", it, hit, sure);
        double o[3] = {p[0], p[1], p[2]}, dir[3] = {toward[0], toward[1], toward[2]};
        double A3[3] = {a[0], a[1], a[2]}, B3[3] = {b[0], b[1], b[2]}, C3[3] = {c[0], c[1], c[2]}, t;
        pos += sure > 0;
        neg += sure < 0;
        zero += sure == 0;
        zero_inside += sure == 0 && sl_ray_tri_d(o, dir, A3, B3, C3, 0.0, &t) && fabs(t - tl) < margin * 10.0 &&
                       tmax == INFINITY && tnear < 0.1f * (float)tl;
        near_end += sure == 0 && it % 3 == 2;
    }
    assert_true(pos > 20000);
    assert_true(neg > 20000);
    assert_true(zero > 20000);
    assert_true(zero_inside > 1000);    /* within the edge margin, inside */
    assert_true(near_end > 1000);       /* within the margin of the ray's end */
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(raytri, hit_inside),
        SL_CASE(raytri, miss_outside_and_behind),
        SL_CASE(raytri, edges_closed_and_tmin),
        SL_CASE(raytri, distances),
        SL_CASE(raytri, sure_until_the_light),
        SL_CASE(raytri, hit_is_sure_positive),
    };
    return sl_run_group(argc, argv, "raytri", tests, NULL, NULL);
}
