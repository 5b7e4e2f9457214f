/* lightfit::* — the fitted light box holds every receiver and every caster. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "gen.h"
#include "fixture.h"
#include "lightfit.h"
#include "raytri.h"

static void project(const struct sl_light_box *b, const float p[3], float out[3])
{
    vec4 w = {p[0], p[1], p[2], 1.0f}, c;
    glm_mat4_mulv((vec4 *)b->vp, w, c);
    out[0] = c[0] / c[3] * 0.5f + 0.5f;
    out[1] = c[1] / c[3] * 0.5f + 0.5f;
    out[2] = c[2] / c[3];
}

static int inside(const float q[3])
{
    return q[0] >= 0.0f && q[0] <= 1.0f && q[1] >= 0.0f && q[1] <= 1.0f && q[2] >= 0.0f && q[2] <= 1.0f;
}

/* The world point where the ray from p along the unit dir first meets a
 * triangle other than the pixel's own (own = triangle + 1) before tmax:
 * brute force in double; 0 if none. */
static int nearest_hit(const struct sl_scene *s, const float p[3], const double dir[3], uint32_t own, double tmax,
                       float hit[3])
{
    double o[3] = {p[0], p[1], p[2]}, best = INFINITY;
    for (uint32_t t = 0; t < s->nt; t++) {
        double a[3], b[3], c[3], th;
        for (int k = 0; k < 3; k++) {
            a[k] = s->pos[3 * s->idx[3 * t] + k];
            b[k] = s->pos[3 * s->idx[3 * t + 1] + k];
            c[k] = s->pos[3 * s->idx[3 * t + 2] + k];
        }
        if (t + 1 != own && sl_ray_tri_d(o, dir, a, b, c, 1e-4, &th) && th < best && th < tmax)
            best = th;
    }
    for (int k = 0; k < 3; k++)
        hit[k] = (float)(o[k] + best * dir[k]);
    return isfinite(best);
}

/* A hand-made view: four receivers on y = 0, light straight down. A triangle
 * hanging over them must be inside, one off to the side must not count as a
 * caster, one below the receivers must not move the near plane. */
static void lightfit_synthetic(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    uint32_t a = sl_mesh_vertex(&m, -1, 5, -1), b = sl_mesh_vertex(&m, 1, 5, -1), c = sl_mesh_vertex(&m, 0, 9, 1);
    sl_mesh_tri(&m, a, b, c);                                  /* caster, up to y = 9 */
    a = sl_mesh_vertex(&m, 50, 20, 0); b = sl_mesh_vertex(&m, 52, 20, 0); c = sl_mesh_vertex(&m, 51, 30, 1);
    sl_mesh_tri(&m, a, b, c);                                  /* far to the side, higher */
    a = sl_mesh_vertex(&m, -1, -5, -1); b = sl_mesh_vertex(&m, 1, -5, -1); c = sl_mesh_vertex(&m, 0, -5, 1);
    sl_mesh_tri(&m, a, b, c);                                  /* below the receivers */
    struct sl_scene s;
    memset(&s, 0, sizeof s);
    struct sl_diag d;
    assert_int_equal(sl_scene_from_mesh(&s, &m, &d), SL_OK);
    sl_mesh_free(&m);
    s.light_dir[1] = -1.0f;
    float pos[4 * 3] = {-2, 0, -2, 2, 0, -2, -2, 0, 2, 2, 0, 2};
    uint8_t cls[4] = {SL_C_PFL, SL_C_PFL, SL_C_PFL, SL_C_PFL};
    struct sl_view v;
    memset(&v, 0, sizeof v);
    v.w = 2; v.h = 2; v.pos = pos; v.cls = cls;
    struct sl_light_box box;
    sl_light_fit(&s, &v, &box);
    assert_int_equal(box.n_receivers, 4);
    assert_int_equal(box.n_casters, 1);          /* the one below lies beyond every receiver */
    float q[3];
    for (int i = 0; i < 4; i++) {
        project(&box, pos + 3 * i, q);
        assert_true(inside(q));
        assert_true(q[2] > 0.99f);               /* receivers are the farthest */
    }
    for (int k = 0; k < 3; k++) {
        project(&box, s.pos + 3 * s.idx[k], q);
        assert_true(inside(q));
    }
    project(&box, s.pos + 3 * s.idx[5], q);      /* apex of the side triangle */
    assert_false(inside(q));
    /* the near plane is set by the caster's top (y = 9), not by the side one (y = 30) */
    float top[3] = {0, 9, 1};
    project(&box, top, q);
    assert_true(q[2] >= 0.0f && q[2] < 0.01f);
    sl_scene_free(&s);
}

/* On a real view: every receiver, and the point where each shadowed pixel's
 * ray meets its nearest occluder, lies inside the box. */
static void lightfit_primitives_occluders_inside(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "primitives", 2));
    for (int vp = 0; vp < f.scene.nvp; vp++) {
        struct sl_view v;
        assert_true(fixture_view(&f, vp, 128, 128, &v));
        struct sl_light_box box;
        sl_light_fit(&f.scene, &v, &box);
        assert_int_equal(box.n_receivers, v.n_pfl);
        long checked = 0;
        const float *L = f.scene.light_dir;
        for (int i = 0; i < v.w * v.h; i++) {
            if (v.cls[i] != SL_C_PFL)
                continue;
            float q[3];
            project(&box, v.pos + 3 * i, q);
            assert_true(inside(q));
            if (v.truth[i] != SL_T_SHADOW)
                continue;
            const double dir[3] = {-L[0], -L[1], -L[2]};
            float hit[3];
            assert_true(nearest_hit(&f.scene, v.pos + 3 * i, dir, v.tri[i], INFINITY, hit));
            project(&box, hit, q);
            assert_true(inside(q));
            checked++;
        }
        assert_true(checked > 100);
        sl_view_free(&v);
    }
    fixture_close(&f);
}

/* An area light as a point at its centre: a perspective frustum that holds
 * every receiver and the nearest occluder on each shadowed pixel's ray to
 * the centre; its window depths turn back into depths along the axis, and
 * the depth scale is the derivative of that map. */
static void lightfit_point_occluders_inside(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "curtis_box", 2));
    assert_int_equal(f.scene.light.type, SL_LIGHT_AREA);
    const float *c = f.scene.light.pos, *nl = f.scene.light.normal;
    for (int vp = 0; vp < f.scene.nvp; vp++) {
        struct sl_view v;
        assert_true(fixture_view(&f, vp, 96, 96, &v));
        struct sl_light_frame fr;
        memset(&fr, 0, sizeof fr);
        sl_light_fit(&f.scene, &v, &fr.box);
        assert_true(fr.box.persp);
        assert_int_equal(fr.box.n_receivers, v.n_pfl);
        assert_int_equal(fr.box.n_unmapped, 0);
        assert_true(fr.box.lo[2] > 0.0f && fr.box.lo[2] < fr.box.hi[2]);
        fr.size = 1024;
        fr.depth_range = fr.box.hi[2] - fr.box.lo[2];
        long checked = 0;
        for (int i = 0; i < v.w * v.h; i++) {
            if (v.cls[i] != SL_C_PFL)
                continue;
            const float *p = v.pos + 3 * i;
            float q[3];
            project(&fr.box, p, q);
            assert_true(inside(q));
            /* depth along the light's normal, back from window depth */
            double axis = 0.0;
            for (int k = 0; k < 3; k++)
                axis += ((double)p[k] - c[k]) * nl[k];
            assert_true(fabs(sl_frame_depth_of(&fr, q[2]) - axis) <= 1e-4 * axis);
            double h = 1e-4, dd = sl_frame_depth_of(&fr, q[2] + h) - sl_frame_depth_of(&fr, q[2] - h);
            assert_true(fabs(dd / (2 * h) - sl_frame_world_per_depth(&fr, q[2])) <=
                        1e-3 * sl_frame_world_per_depth(&fr, q[2]));
            if (v.truth[i] != SL_T_SHADOW)
                continue;
            double dir[3], len = 0.0;
            for (int k = 0; k < 3; k++) {
                dir[k] = (double)c[k] - p[k];
                len += dir[k] * dir[k];
            }
            len = sqrt(len);
            for (int k = 0; k < 3; k++)
                dir[k] /= len;
            float hit[3];
            assert_true(nearest_hit(&f.scene, p, dir, v.tri[i], len, hit));
            project(&fr.box, hit, q);
            assert_true(inside(q));
            checked++;
        }
        assert_true(checked > 100);
        sl_view_free(&v);
    }
    fixture_close(&f);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(lightfit, synthetic),
        SL_CASE(lightfit, primitives_occluders_inside),
        SL_CASE(lightfit, point_occluders_inside),
    };
    return sl_run_group(argc, argv, "lightfit", tests, NULL, NULL);
}
