/* lightfit::* — the fitted light box holds every receiver and every caster. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
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

/* A point into the light view as lightfit.c's to_light puts it (depth
 * grows away from the light). */
static void plain_to_light(mat4 view, const float p[3], float q[3])
{
    vec4 w = {p[0], p[1], p[2], 1.0f}, c;
    glm_mat4_mulv(view, w, c);
    q[0] = c[0];
    q[1] = c[1];
    q[2] = -c[2];
}

/* The directional box as one plain loop over the pixels and one over the
 * triangles, as lightfit.c fitted it before its loops ran in blocks: the
 * reference the blocked fit must equal bit for bit. */
static void plain_dir_fit(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                          struct sl_light_box *out)
{
    memset(out, 0, sizeof *out);
    sl_light_view(s->light_dir, out->view);
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    for (size_t i = 0; i < (size_t)v->w * (size_t)v->h; i++) {
        if (v->cls[i] != SL_C_PFL || (mask && mask[i] != value))
            continue;
        float q[3];
        plain_to_light(out->view, v->pos + 3 * i, q);
        for (int k = 0; k < 3; k++) {
            if (q[k] < lo[k]) lo[k] = q[k];
            if (q[k] > hi[k]) hi[k] = q[k];
        }
        out->n_receivers++;
    }
    float near = lo[2];
    for (uint32_t t = 0; t < s->nt; t++) {
        float tl[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, th[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
        for (int c = 0; c < 3; c++) {
            float q[3];
            plain_to_light(out->view, s->pos + 3 * s->idx[3 * t + c], q);
            for (int k = 0; k < 3; k++) {
                if (q[k] < tl[k]) tl[k] = q[k];
                if (q[k] > th[k]) th[k] = q[k];
            }
        }
        if (th[0] < lo[0] || tl[0] > hi[0] || th[1] < lo[1] || tl[1] > hi[1] || tl[2] > hi[2])
            continue;
        out->n_casters++;
        if (tl[2] < near)
            near = tl[2];
    }
    lo[2] = near;
    for (int k = 0; k < 3; k++) {
        float ext = hi[k] - lo[k];
        float mag = fmaxf(fabsf(lo[k]), fabsf(hi[k]));
        float m = fmaxf(1e-4f * ext, 1e-6f * mag + 1e-6f);
        lo[k] -= m;
        hi[k] += m;
    }
    memcpy(out->lo, lo, sizeof lo);
    memcpy(out->hi, hi, sizeof hi);
}

/* A perspective box's receivers and the pixels it leaves outside, counted
 * plainly (lightfit.c, fit_point: in front, tangents within 8), and its
 * unmapped triangles listed in increasing order, as one loop listed them. */
static void plain_persp_checks(const struct sl_view *v, const uint8_t *mask, uint8_t value,
                               const struct sl_light_box *b)
{
    mat4 view;
    memcpy(view, b->view, sizeof view);
    uint32_t in = 0, out = 0;
    for (size_t i = 0; i < (size_t)v->w * (size_t)v->h; i++) {
        if (v->cls[i] != SL_C_PFL || (mask && mask[i] != value))
            continue;
        float q[3];
        plain_to_light(view, v->pos + 3 * i, q);
        const int ok = q[2] > 0.0f && fabsf(q[0] / q[2]) <= 8.0f && fabsf(q[1] / q[2]) <= 8.0f;
        in += (uint32_t)ok;
        out += (uint32_t)!ok;
    }
    assert_int_equal(b->n_receivers, in);
    assert_int_equal(b->n_outside, out);
    for (uint32_t k = 1; b->unmapped && k < b->n_unmapped; k++)
        assert_true(b->unmapped[k - 1] < b->unmapped[k]);
}

/* Two boxes bit for bit the same: matrices, bounds, counts, and the
 * unmapped triangles listed in the same order. */
static void same_box(const struct sl_light_box *a, const struct sl_light_box *b)
{
    assert_memory_equal(a->view, b->view, sizeof a->view);
    assert_memory_equal(a->proj, b->proj, sizeof a->proj);
    assert_memory_equal(a->vp, b->vp, sizeof a->vp);
    assert_memory_equal(a->lo, b->lo, sizeof a->lo);
    assert_memory_equal(a->hi, b->hi, sizeof a->hi);
    assert_memory_equal(a->eye, b->eye, sizeof a->eye);
    assert_memory_equal(&a->wmin, &b->wmin, sizeof a->wmin);
    assert_memory_equal(&a->guard, &b->guard, sizeof a->guard);
    assert_int_equal(a->persp, b->persp);
    assert_int_equal(a->n_receivers, b->n_receivers);
    assert_int_equal(a->n_outside, b->n_outside);
    assert_int_equal(a->n_casters, b->n_casters);
    assert_int_equal(a->n_unmapped, b->n_unmapped);
    assert_int_equal(a->unmapped == NULL, b->unmapped == NULL);
    if (a->unmapped)
        assert_memory_equal(a->unmapped, b->unmapped, a->n_unmapped * sizeof *a->unmapped);
}

/* The fit on 2, 3, 4 and 7 threads equals the one-thread fit bit for bit
 * (lightfit.c, "blocks"), and the one-thread fit equals the plain loops it
 * replaced (the directional box bit for bit; a perspective box's counts and
 * its unmapped list's order): a directional light over the bench scene's 54,200
 * triangles (its slices and stabilised boxes too), an area light, a spot
 * light and point lights (the summary box, each cube face with its guard
 * band alone and the six at once, and the faces' selection itself), on views of 640 x 480 (ten blocks
 * of pixels). Unmapped triangles (the lamp's pole, the room's walls across
 * the cube's planes) are among them, so their lists' joining is checked. */
static void lightfit_threads_bit_identical(void **st)
{
    (void)st;
    static const char *const scenes[] = {"bench", "curtis_box", "scenes/lamp.yaml", "room",
                                         "tests/scenes/cube_six.yaml"};
    static const int threads[] = {2, 3, 4, 7};
    uint64_t unmapped = 0, faces = 0, blocks_of_tris = 0;
    for (int sc = 0; sc < 5; sc++) {
        struct fixture f;
        assert_true(fixture_open(&f, scenes[sc], 2));
        blocks_of_tris += f.scene.nt > 8192;
        for (int vp = 0; vp < f.scene.nvp && vp < 2; vp++) {
            struct sl_view v;
            assert_true(fixture_view(&f, vp, 640, 480, &v));
            const size_t n = (size_t)v.w * (size_t)v.h;
            struct sl_light_box a, b;
            sl_light_fit(&f.scene, &v, &a);
            unmapped += a.n_unmapped;
            if (f.scene.light.type == SL_LIGHT_DIRECTIONAL) {
                struct sl_light_box p;
                plain_dir_fit(&f.scene, &v, NULL, 0, &p);
                assert_memory_equal(a.lo, p.lo, sizeof a.lo);
                assert_memory_equal(a.hi, p.hi, sizeof a.hi);
                assert_int_equal(a.n_receivers, p.n_receivers);
                assert_int_equal(a.n_casters, p.n_casters);
            } else if (f.scene.light.type != SL_LIGHT_POINT) {
                plain_persp_checks(&v, NULL, 0, &a);
            }
            for (int t = 0; t < 4; t++) {
                sl_light_fit_mt(&f.scene, &v, &b, threads[t]);
                same_box(&a, &b);
                sl_light_box_free(&b);
            }
            sl_light_box_free(&a);
            if (f.scene.light.type == SL_LIGHT_POINT) {
                uint8_t *face = malloc(n), *face2 = malloc(n);
                assert_true(face && face2);
                for (size_t i = 0; i < n; i++)
                    face[i] = (uint8_t)sl_cube_face_of(f.scene.light.pos, v.pos + 3 * i);
                for (int t = 0; t < 4; t++) {
                    memset(face2, 0xEE, n);
                    sl_cube_faces(f.scene.light.pos, &v, face2, threads[t]);
                    assert_memory_equal(face, face2, n);
                }
                struct sl_light_box six[5][6];   /* the six faces at once, on 1, 2, 3, 4, 7 threads */
                sl_light_fit_cube_mt(&f.scene, &v, f.scene.light.pos, face, 512, 2, six[0], 1);
                for (int t = 0; t < 4; t++)
                    sl_light_fit_cube_mt(&f.scene, &v, f.scene.light.pos, face, 512, 2, six[1 + t], threads[t]);
                for (int fc = 0; fc < 6; fc++) {
                    float axis[3];
                    sl_cube_axis(fc, axis);
                    sl_light_fit_face(&f.scene, &v, f.scene.light.pos, axis, face, (uint8_t)fc, 512, 2, &a);
                    plain_persp_checks(&v, face, (uint8_t)fc, &a);
                    unmapped += a.n_unmapped;
                    for (int t = 0; t < 5; t++) {
                        same_box(&a, &six[t][fc]);
                        sl_light_box_free(&six[t][fc]);
                    }
                    faces += a.n_receivers > 0;
                    for (int t = 0; t < 4; t++) {
                        sl_light_fit_face_mt(&f.scene, &v, f.scene.light.pos, axis, face, (uint8_t)fc, 512, 2, &b,
                                             threads[t]);
                        same_box(&a, &b);
                        sl_light_box_free(&b);
                    }
                    sl_light_box_free(&a);
                }
                free(face);
                free(face2);
            }
            if (f.scene.light.type == SL_LIGHT_DIRECTIONAL) {
                /* three slices of rows (a mask), and the stabilised boxes */
                uint8_t *slice = malloc(n);
                assert_non_null(slice);
                for (size_t i = 0; i < n; i++)
                    slice[i] = (uint8_t)(3 * (i / (size_t)v.w) / (size_t)v.h);
                for (int k = 0; k < 3; k++) {
                    assert_int_equal(sl_light_fit_slice(&f.scene, &v, slice, (uint8_t)k, &a), 1);
                    assert_true(a.n_receivers > 0);
                    struct sl_light_box p;
                    plain_dir_fit(&f.scene, &v, slice, (uint8_t)k, &p);
                    assert_memory_equal(a.lo, p.lo, sizeof a.lo);
                    assert_memory_equal(a.hi, p.hi, sizeof a.hi);
                    assert_int_equal(a.n_casters, p.n_casters);
                    for (int t = 0; t < 4; t++) {
                        assert_int_equal(sl_light_fit_slice_mt(&f.scene, &v, slice, (uint8_t)k, &b, threads[t]), 1);
                        same_box(&a, &b);
                        sl_light_box_free(&b);
                    }
                    sl_light_box_free(&a);
                }
                free(slice);
                for (int snap = 0; snap < 2; snap++) {
                    const struct sl_fit_opts o = {.fit = SL_FIT_SPHERE, .snap = snap};
                    sl_light_fit_stable(&f.scene, &v, &o, 1024, &a);
                    for (int t = 0; t < 4; t++) {
                        sl_light_fit_stable_mt(&f.scene, &v, &o, 1024, &b, threads[t]);
                        same_box(&a, &b);
                        sl_light_box_free(&b);
                    }
                    sl_light_box_free(&a);
                }
            }
            sl_view_free(&v);
        }
        fixture_close(&f);
    }
    assert_true(unmapped > 0);        /* lists were joined from blocks */
    assert_true(faces >= 6);          /* cube faces with receivers were compared */
    assert_true(blocks_of_tris > 0);  /* a scene with many blocks of triangles */
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(lightfit, synthetic),
        SL_CASE(lightfit, primitives_occluders_inside),
        SL_CASE(lightfit, point_occluders_inside),
        SL_CASE(lightfit, threads_bit_identical),
    };
    return sl_run_group(argc, argv, "lightfit", tests, NULL, NULL);
}
