/* raytri::* — the reference ray-triangle tests and distances. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "sl_test.h"
#include "raytri.h"

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

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(raytri, hit_inside),
        SL_CASE(raytri, miss_outside_and_behind),
        SL_CASE(raytri, edges_closed_and_tmin),
        SL_CASE(raytri, distances),
        SL_CASE(raytri, sure_until_the_light),
    };
    return sl_run_group(argc, argv, "raytri", tests, NULL, NULL);
}
