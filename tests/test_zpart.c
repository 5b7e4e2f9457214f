/* zpart::* — z-partitioned shadow maps (seed 004): the split planes, the
 * slices, each slice's fit, k = 1 against NSM, and on the deep street scene
 * fewer wrong pixels with a smaller aliasing error than one map. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "aliasing.h"
#include "fixture.h"
#include "gen.h"
#include "lightfit.h"
#include "method.h"
#include "raytri.h"
#include "shadowmap.h"
#include "zpart.h"
#include "test_params.h"

/* eq. 62 at lambda = 1 is eq. 63 (appendix B); lambda = 0 is the uniform
 * split; every blend is increasing from n to f and lies between the two. */
static void zpart_split_planes(void **st)
{
    (void)st;
    const double ranges[][2] = {{1.0, 100.0}, {0.5, 300.0}, {20.0, 250.0}, {3.0, 3.5}};
    for (size_t r = 0; r < sizeof ranges / sizeof ranges[0]; r++)
        for (int k = 1; k <= 8; k++) {
            double n = ranges[r][0], f = ranges[r][1], it[9], cl[9], un[9];
            sl_zsplit_iterative(n, f, k, 1.0, it);
            sl_zsplit_closed(n, f, k, cl);
            for (int i = 0; i <= k; i++)
                assert_float_equal(it[i], cl[i], 1e-12 * f);
            /* eq. 63 by hand: n (f/n)^(i/k) */
            for (int i = 0; i <= k; i++)
                assert_float_equal(cl[i], n * pow(f / n, (double)i / k), 1e-12 * f);
            sl_zsplit_iterative(n, f, k, 0.0, un);
            for (int i = 0; i <= k; i++)
                assert_float_equal(un[i], n + (f - n) * i / k, 1e-12 * f);
            for (double l = 0.25; l < 1.0; l += 0.25) {
                double b[9];
                sl_zsplit_iterative(n, f, k, l, b);
                assert_float_equal(b[0], n, 0.0);
                assert_float_equal(b[k], f, 0.0);
                for (int i = 1; i <= k; i++)
                    assert_true(b[i] > b[i - 1]);
                for (int i = 1; i < k; i++)
                    assert_true(b[i] >= cl[i] - 1e-9 && b[i] <= un[i] + 1e-9);
            }
        }
}

/* The world point where the ray from p toward the light first meets a
 * triangle other than the pixel's own: brute force in double. */
static int nearest_hit(const struct sl_scene *s, const float p[3], const float *L, uint32_t own, float hit[3])
{
    double o[3] = {p[0], p[1], p[2]}, dir[3] = {-L[0], -L[1], -L[2]}, best = INFINITY;
    for (uint32_t t = 0; t < s->nt; t++) {
        double a[3], b[3], c[3], th;
        for (int k = 0; k < 3; k++) {
            a[k] = s->pos[3 * s->idx[3 * t] + k];
            b[k] = s->pos[3 * s->idx[3 * t + 1] + k];
            c[k] = s->pos[3 * s->idx[3 * t + 2] + k];
        }
        if (t + 1 != own && sl_ray_tri_d(o, dir, a, b, c, 1e-4, &th) && th < best)
            best = th;
    }
    for (int k = 0; k < 3; k++)
        hit[k] = (float)(o[k] + best * dir[k]);
    return isfinite(best);
}

static int inside(const struct sl_light_box *b, const float p[3])
{
    vec4 w = {p[0], p[1], p[2], 1.0f}, c;
    glm_mat4_mulv((vec4 *)b->vp, w, c);
    float q[3] = {c[0] / c[3] * 0.5f + 0.5f, c[1] / c[3] * 0.5f + 0.5f, c[2] / c[3]};
    return q[0] >= 0.0f && q[0] <= 1.0f && q[1] >= 0.0f && q[1] <= 1.0f && q[2] >= 0.0f && q[2] <= 1.0f;
}

/* Every visible pixel lies in exactly one slice, the one its view depth
 * falls in; each slice's box holds its receivers and, for each shadowed
 * one, the occluder its ray meets first. */
static void zpart_slices_fit(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "primitives", 2));
    struct sl_view v;
    assert_true(fixture_view(&f, 0, 96, 96, &v));
    size_t n = (size_t)v.w * (size_t)v.h;
    uint8_t *slice = malloc(n);
    const int ks[] = {1, 3, 4, 8};
    for (size_t kk = 0; kk < sizeof ks / sizeof ks[0]; kk++) {
        int k = ks[kk];
        double planes[9];
        sl_zpart_slices(&v, k, 0.5, planes, slice);
        long per[8] = {0}, pfl = 0, checked = 0;
        for (size_t i = 0; i < n; i++) {
            if (v.cls[i] == SL_C_BACKGROUND) {
                assert_int_equal(slice[i], 255);
                continue;
            }
            assert_true(slice[i] < k);
            float z = sl_view_depth(&v, v.pos + 3 * i);
            assert_true(z >= planes[slice[i]] * (1 - 1e-6) && z <= planes[slice[i] + 1] * (1 + 1e-6));
            per[slice[i]]++;
            pfl += v.cls[i] == SL_C_PFL;
        }
        long sum = 0, recv = 0;
        for (int s = 0; s < k; s++) {
            sum += per[s];
            struct sl_light_box box;
            assert_true(sl_light_fit_slice(&f.scene, &v, slice, (uint8_t)s, &box));
            recv += box.n_receivers;
            for (size_t i = 0; i < n; i++) {
                if (v.cls[i] != SL_C_PFL || slice[i] != s)
                    continue;
                assert_true(inside(&box, v.pos + 3 * i));
                float hit[3];
                if (v.truth[i] == SL_T_SHADOW && checked % 7 == 0) {
                    assert_true(nearest_hit(&f.scene, v.pos + 3 * i, f.scene.light_dir, v.tri[i], hit));
                    assert_true(inside(&box, hit));
                }
                checked += v.truth[i] == SL_T_SHADOW;
            }
        }
        assert_int_equal(sum, (long)(n - v.n_background));
        assert_int_equal(recv, pfl);
        assert_true(checked > 50);
    }
    /* with every PFL pixel in one slice the fit is sl_light_fit's */
    sl_zpart_slices(&v, 1, 0.5, (double[2]){0}, slice);
    struct sl_light_box a, b;
    sl_light_fit(&f.scene, &v, &a);
    sl_light_fit_slice(&f.scene, &v, slice, 0, &b);
    assert_memory_equal(a.vp, b.vp, sizeof a.vp);
    free(slice);
    sl_view_free(&v);
    fixture_close(&f);
}

struct bench {
    struct fixture f;
    struct sl_view v, mv;
    struct sl_shadowmap_pass sp;
    struct sl_light_frame fr;
    struct sl_verdicts vd;
};

static void bench_open(struct bench *g, const char *scene, int w, int map)
{
    memset(g, 0, sizeof *g);
    assert_true(fixture_open(&g->f, scene, 2));
    assert_true(fixture_view(&g->f, 0, w, w, &g->v));
    g->mv = g->v;
    g->mv.truth = NULL;
    struct sl_diag d;
    assert_int_equal(sl_shadowmap_init(&g->sp, &d), SL_OK);
    /* the cell's frame, as the driver builds it (run.c, ensure_frame) */
    sl_light_fit(&g->f.scene, &g->v, &g->fr.box);
    g->fr.size = map;
    memcpy(g->fr.dir, g->f.scene.light_dir, sizeof g->fr.dir);
    g->fr.texel_world = fmaxf(g->fr.box.hi[0] - g->fr.box.lo[0], g->fr.box.hi[1] - g->fr.box.lo[1]) / (float)map;
    g->fr.depth_range = g->fr.box.hi[2] - g->fr.box.lo[2];
    assert_int_equal(sl_shadowmap_render(&g->sp, &g->f.mesh, &g->fr,
                                         SL_NEED(SL_LAYER_DEPTH_ID) | SL_NEED(SL_LAYER_DEPTH_ID_BACK), &d), SL_OK);
    size_t n = (size_t)w * (size_t)w;
    g->vd.w = g->vd.h = w;
    g->vd.v = calloc(n, 1);
    g->vd.how = calloc(n, 1);
    g->vd.base = calloc(n, 1);
    g->vd.detail = calloc(n, 1);
    g->vd.tests = calloc(n, 1);
}

static void bench_close(struct bench *g)
{
    sl_verdicts_drop_frames(&g->vd);
    free(g->vd.v);
    free(g->vd.how);
    free(g->vd.base);
    free(g->vd.detail);
    free(g->vd.tests);
    sl_frame_free(&g->fr);
    sl_shadowmap_free(&g->sp);
    sl_view_free(&g->v);
    fixture_close(&g->f);
}

/* Run a method into g->vd (nframes reset first, as the driver does). */
static void bench_run(struct bench *g, const char *method, const char *spec)
{
    const struct sl_method *m = sl_method_find(method);
    assert_non_null(m);
    struct sl_method_params p;
    struct sl_diag d;
    sl_test_params(m, &p, spec);
    struct sl_method_args a = {.scene = &g->f.scene, .view = &g->mv, .frame = &g->fr, .params = &p,
                               .rt = &g->f.rt, .threads = 2, .spass = &g->sp, .mesh = &g->f.mesh};
    struct sl_cost c = {0};
    g->vd.has_base = g->vd.nframes = 0;
    assert_int_equal(m->run(&a, &g->vd, &c, &d), SL_OK);
}

/* k = 1 is NSM pixel for pixel, under each self-shadow policy. */
static void zpart_one_is_nsm(void **st)
{
    (void)st;
    struct bench g;
    bench_open(&g, "primitives", 160, 512);
    size_t n = (size_t)g.v.w * (size_t)g.v.h;
    uint8_t *nv = malloc(n), *nh = malloc(n);
    const char *const pol[] = {"front_faces", "none", "slope"};
    for (size_t k = 0; k < sizeof pol / sizeof pol[0]; k++) {
        char spec[64];
        snprintf(spec, sizeof spec, "self_shadow=%s", pol[k]);
        bench_run(&g, "nsm", spec);
        memcpy(nv, g.vd.v, n);
        memcpy(nh, g.vd.how, n);
        snprintf(spec, sizeof spec, "self_shadow=%s partitions=1", pol[k]);
        bench_run(&g, "zpart", spec);
        assert_int_equal(g.vd.nframes, 1);
        assert_memory_equal(nv, g.vd.v, n);
        assert_memory_equal(nh, g.vd.how, n);
        long shadowed = 0;
        for (size_t i = 0; i < n; i++)
            shadowed += g.vd.v[i] == SL_V_SHADOW;
        assert_true(shadowed > 100);   /* not an empty comparison */
        /* and its slice frame is the cell's */
        assert_memory_equal(g.vd.frames[0].box.vp, g.fr.box.vp, sizeof g.fr.box.vp);
    }
    free(nv);
    free(nh);
    bench_close(&g);
}

static void wrong_and_median(struct bench *g, long *wrong, double *median_m)
{
    size_t n = (size_t)g->v.w * (size_t)g->v.h;
    float *m = malloc(n * sizeof *m);
    uint8_t *band = calloc(n, 1);
    sl_alias_image(&g->v, &g->fr, &g->vd, 2, m);
    const int regions[1] = {0};
    struct sl_alias_figures af;
    sl_alias_figures_compute(&g->v, &g->vd, m, band, regions, 1, &af);
    *wrong = 0;
    for (size_t i = 0; i < n; i++)
        *wrong += g->v.cls[i] == SL_C_PFL && ((g->vd.v[i] == SL_V_LIT) != (g->v.truth[i] == SL_T_LIT));
    uint64_t byband = 0;
    for (int b = 0; b < SL_ALIAS_BANDS; b++)
        byband += af.n[0][SL_AFIG_wrong_m_le1 + b];
    assert_int_equal(byband + 0, (uint64_t)*wrong);   /* every wrong pixel has a finite m here */
    *median_m = af.n[0][SL_AFIG_wrong_m_median_milli] / 1000.0;
    free(m);
    free(band);
}

/* On the deep street, four slices at one map size beat one map: fewer
 * wrong pixels, and the wrong pixels that remain have a smaller m. */
static void zpart_deep_scene(void **st)
{
    (void)st;
    struct bench g;
    bench_open(&g, "street", 256, 1024);
    long w_nsm, w_z;
    double m_nsm, m_z;
    bench_run(&g, "nsm", NULL);
    wrong_and_median(&g, &w_nsm, &m_nsm);
    bench_run(&g, "zpart", "partitions=4 lambda=0.5");
    wrong_and_median(&g, &w_z, &m_z);
    print_message("street 256^2, map 1024: nsm %ld wrong (median m %.3f), zpart k=4 %ld (median m %.3f)\n", w_nsm,
                  m_nsm, w_z, m_z);
    assert_true(w_nsm > 200);
    assert_true(w_z < w_nsm);
    assert_true(m_z < m_nsm);
    bench_close(&g);
}


/* A hand-made view of a receiver plane y = 0 seen by a camera at height 2
 * looking along -z (tilted down a little), the plane's points at depths 2
 * to 40; one pole stands on it. */
struct handmade {
    struct sl_scene s;
    struct sl_view v;
    float pos[3 * 64];
    uint8_t cls[64];
};

static void handmade_open(struct handmade *h, const float light[3])
{
    memset(h, 0, sizeof *h);
    struct sl_mesh m = {0};
    uint32_t a = sl_mesh_vertex(&m, -0.2f, 0, -10), b = sl_mesh_vertex(&m, 0.2f, 0, -10),
             c = sl_mesh_vertex(&m, 0, 3, -10);
    sl_mesh_tri(&m, a, b, c);   /* the pole */
    struct sl_diag d;
    assert_int_equal(sl_scene_from_mesh(&h->s, &m, &d), SL_OK);
    sl_mesh_free(&m);
    memcpy(h->s.light_dir, light, sizeof h->s.light_dir);
    vec3 eye = {0, 2, 0}, dir = {0, -0.05f, -1}, up = {0, 1, 0};
    glm_look(eye, dir, up, h->v.view);
    h->v.w = 8;
    h->v.h = 8;
    for (int i = 0; i < 64; i++) {
        h->pos[3 * i] = (float)(i % 8) - 3.5f;
        h->pos[3 * i + 1] = 0.0f;
        h->pos[3 * i + 2] = -2.0f - 38.0f * (float)(i / 8) / 7.0f;
        h->cls[i] = SL_C_PFL;
    }
    h->v.pos = h->pos;
    h->v.cls = h->cls;
}

/* n_opt = (z_n + sqrt(z_n z_f)) / sin gamma at known angles; the light
 * along the view direction (gamma = 0) falls back to the uniform box. */
static void lispsm_nopt_and_fallback(void **st)
{
    (void)st;
    const double zn = 2.0, zf = 40.0;
    const double deg[] = {90.0, 60.0, 30.0, 10.0};
    for (size_t k = 0; k < sizeof deg / sizeof deg[0]; k++) {
        /* the light at angle deg from the camera's forward (0, -0.05, -1), in the y-z plane */
        double g = deg[k] * 3.14159265358979323846 / 180.0, f0 = atan2(-0.05, -1.0);
        float L[3] = {0.0f, (float)sin(f0 - g), (float)cos(f0 - g)};
        struct handmade h;
        handmade_open(&h, L);
        struct sl_light_box b;
        double nopt;
        assert_int_equal(sl_light_fit_lispsm(&h.s, &h.v, NULL, 0, zn, zf, &b, &nopt), 1);
        double want = (zn + sqrt(zn * zf)) / sin(g);
        assert_float_equal(nopt, want, 1e-5 * want);
        /* every receiver inside the warped frame */
        for (int i = 0; i < 64; i++)
            assert_true(inside(&b, h.pos + 3 * i));
        sl_scene_free(&h.s);
    }
    /* gamma = 0: the light travels along the view direction */
    float L[3] = {0.0f, -0.05f, -1.0f};
    struct handmade h;
    handmade_open(&h, L);
    struct sl_light_box b, u;
    double nopt;
    assert_int_equal(sl_light_fit_lispsm(&h.s, &h.v, NULL, 0, zn, zf, &b, &nopt), 0);
    assert_true(nopt > 1e3 * zf || !isfinite(nopt));
    sl_light_fit_slice(&h.s, &h.v, NULL, 0, &u);
    assert_memory_equal(b.vp, u.vp, sizeof u.vp);
    sl_scene_free(&h.s);
}

/* On real views, LiSPSM's frame holds every receiver and each shadowed
 * pixel's first occluder, and on the deep street it has fewer wrong pixels
 * than NSM with a smaller median m; zpart with the warp per slice too. */
static void lispsm_street(void **st)
{
    (void)st;
    struct bench g;
    bench_open(&g, "street", 192, 1024);
    long w_nsm, w_l, w_zl;
    double m_nsm, m_l, m_zl;
    bench_run(&g, "nsm", NULL);
    wrong_and_median(&g, &w_nsm, &m_nsm);
    bench_run(&g, "lispsm", NULL);
    assert_int_equal(g.vd.nframes, 1);
    /* warped (not the uniform fallback): its vp is not the box's */
    assert_true(memcmp(g.vd.frames[0].box.vp, g.fr.box.vp, sizeof g.fr.box.vp) != 0);
    long checked = 0;
    size_t n = (size_t)g.v.w * (size_t)g.v.h;
    for (size_t i = 0; i < n; i++) {
        if (g.v.cls[i] != SL_C_PFL)
            continue;
        assert_true(inside(&g.vd.frames[0].box, g.v.pos + 3 * i));
        float hit[3];
        if (g.v.truth[i] == SL_T_SHADOW && checked++ % 5 == 0) {
            assert_true(nearest_hit(&g.f.scene, g.v.pos + 3 * i, g.f.scene.light_dir, g.v.tri[i], hit));
            assert_true(inside(&g.vd.frames[0].box, hit));
        }
    }
    assert_true(checked > 50);
    wrong_and_median(&g, &w_l, &m_l);
    bench_run(&g, "zpart", "partitions=4 warp=lispsm");
    wrong_and_median(&g, &w_zl, &m_zl);
    print_message("street 192^2, map 1024: nsm %ld (median m %.3f), lispsm %ld (%.3f), zpart 4 lispsm %ld (%.3f)\n",
                  w_nsm, m_nsm, w_l, m_l, w_zl, m_zl);
    assert_true(w_l < w_nsm && m_l < m_nsm);
    assert_true(w_zl < w_nsm && m_zl < m_nsm);
    bench_close(&g);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(zpart, split_planes),
        SL_CASE(zpart, slices_fit),
        SL_CASE(zpart, one_is_nsm),
        SL_CASE(zpart, deep_scene),
        SL_CASE(lispsm, nopt_and_fallback),
        SL_CASE(lispsm, street),
    };
    return sl_run_group(argc, argv, "zpart", tests, sl_test_setup, sl_test_teardown);
}
