/*
 * softmc::* — Curtis 2009's soft shadows (harness/render/softmap.c, methods/softmc.c) on
 * tests/scenes/softbox.yaml: an elongated box floating over a ground that is
 * a pure receiver, under a 4 x 4 area light. The frame holds the view and
 * the light, the layers bound the box; output in [0, 1] and bit-identical
 * for a seed (also across thread counts); lit far from the box, umbra under
 * it, strictly partial on the penumbra's middle; the hierarchical search
 * finds every hit the linear one does (never more light); one layer never
 * gives more light than two, and gives none where a conventional shadow map
 * shadows; the shortcuts never change the hierarchical result (strict
 * umbra); the layers against Embree on the very same rays; the blur; a
 * fixed fov; bad input; the third layer (the camera's G-buffer, 3.4) never
 * gives less light than two layers. Then the guarantees again on
 * softmix.yaml (tilted rectangular light, leaf, sphere, torus, box on the
 * ground), and the third layer on scenes/curtis_box.yaml and
 * scenes/soft_wuson.yaml (a model that shadows itself: legs under the
 * body, horns over the head) against two layers and against the area
 * truth. Each case prints what it measured.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "scenefile.h"
#include "sl_test.h"
#include "arealight.h"
#include "gbuffer.h"
#include "glctx.h"
#include "softmap.h"
#include "softmc.h"
#include "softtruth.h"
#include "truth.h"
#include "util.h"

#define MAP 512
#define VW 256
#define VH 192

/* A scene with its view, layers, N-buffer and BVH. The GL context and the
 * layers' program are shared. */
struct env {
    struct sl_scene scene;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gp;
    struct sl_view view;
    struct sl_softmap map;
    struct sl_softmap_nbuf nb;
    struct sl_rt rt;
    uint8_t receiver[16];
    /* bounds, % of the pixels: linear vs hier, linear with vs without
     * shortcuts; % equal to Embree: receivers, everything */
    double lin_pct, lin_short_pct, rt_ground_pct, rt_all_pct;
    int ok;
};

static struct sl_gl GL;
static struct sl_softmap_pass SP;
static struct env BOX, MIX, AREA;
static struct env *E = &BOX;   /* the scene the cases below look at */

static int env_open(struct env *e, const char *path, const char *vp_name)
{
    struct sl_diag d;
    memset(e, 0, sizeof *e);
    if (sl_scene_build(path, &e->scene, &d) || sl_gl_mesh_upload(&e->mesh, &e->scene, &d) ||
        sl_gbuffer_init(&e->gp, &e->scene, &d)) {
        fprintf(stderr, "%s: %s\n", path, d.msg);
        return 0;
    }
    if (e->scene.nranges > 16 || sl_softmap_receivers_named(&e->scene, "ground", e->receiver) != 1)
        return 0;
    int vp = sl_scene_find_viewpoint(&e->scene, vp_name);
    double t0 = sl_now();
    struct sl_softmap_desc md = {.size = MAP, .receiver = e->receiver};
    if (sl_gbuffer_render(&e->gp, &e->mesh, &e->scene, vp, VW, VH, &e->view, NULL, NULL, NULL, &d) ||
        sl_softmap_render(&SP, &e->mesh, &e->scene, &e->view, &md, &e->map, &d) ||
        sl_softmap_nbuf_build(&e->map, 0, &e->nb, &d) || sl_rt_build(&e->rt, &e->scene, 2, 1, &d)) {
        fprintf(stderr, "%s: %s\n", path, d.msg);
        return 0;
    }
    printf("softmc: %s: map %d, fov %.1f deg, light depth %.3f, planes [%.3f, %.3f]; layers %.1f + %.1f ms, "
           "readback %.1f ms, N-buffer %.1f ms (%d levels, first build); setup %.0f ms\n", e->scene.name,
           MAP, e->map.fov_deg, e->map.light_depth, e->map.znear, e->map.zfar, e->map.ms_near, e->map.ms_far,
           e->map.ms_readback, e->nb.ms_build, e->nb.levels, 1e3 * (sl_now() - t0));
    e->ok = 1;
    return 1;
}

static void env_close(struct env *e)
{
    sl_rt_free(&e->rt);
    sl_softmap_nbuf_free(&e->nb);
    sl_softmap_free(&e->map);
    sl_view_free(&e->view);
    sl_gbuffer_free(&e->gp);
    sl_gl_mesh_free(&e->mesh);
    sl_scene_free(&e->scene);
}

static int group_setup(void **st)
{
    struct sl_diag d;
    if (sl_test_setup(st))
        return -1;
    if (sl_gl_init(&GL, &d) || sl_softmap_init(&SP, &d)) {
        fprintf(stderr, "setup: %s\n", d.msg);
        return -1;
    }
    env_open(&BOX, "tests/scenes/softbox.yaml", "low");
    BOX.lin_pct = 1.0;
    BOX.lin_short_pct = 2.0;
    BOX.rt_ground_pct = 98.0;
    BOX.rt_all_pct = 90.0;
    return 0;
}

static int group_teardown(void **st)
{
    env_close(&BOX);
    sl_softmap_pass_free(&SP);
    sl_gl_free(&GL);
    return sl_test_teardown(st);
}

static void run(const struct sl_softmc_desc *o, struct sl_softmc_result *r)
{
    struct sl_diag d;
    enum sl_err e = sl_softmc_run(&E->map, &E->view, o, r, &d);
    if (e)
        fprintf(stderr, "run: %s\n", d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(r->st.capped, 0);
}

static const float *P(size_t i) { return E->view.pos + 3 * i; }
/* World coordinates (the scene is kept in a local frame around its centre). */
static double wx(size_t i) { return P(i)[0] + E->scene.origin[0]; }
static double wz(size_t i) { return P(i)[2] + E->scene.origin[2]; }
static void local(double x, double y, double z, double out[3])
{
    out[0] = x - E->scene.origin[0];
    out[1] = y - E->scene.origin[1];
    out[2] = z - E->scene.origin[2];
}
/* On a pure receiver. */
static int ground(size_t i)
{
    uint32_t t = E->view.tri[i];
    for (int r = 0; t && r < E->scene.nranges; r++)
        if (E->receiver[r] && t - 1 >= E->scene.ranges[r].first &&
            t - 1 < E->scene.ranges[r].first + E->scene.ranges[r].count)
            return 1;
    return 0;
}

static void report(const char *label, const struct sl_softmc_result *r)
{
    const struct sl_softmc_stats *s = &r->st;
    printf("softmc: %-22s %6.1f ms; px %llu: lit %llu umbra %llu endpoint %llu; rays %llu: backface %llu "
           "region %llu searched %llu (hit %llu); lookups %llu (search %llu)\n",
           label, s->ms_trace, (unsigned long long)s->pixels, (unsigned long long)s->px_lit,
           (unsigned long long)s->px_umbra, (unsigned long long)s->px_endpoint, (unsigned long long)s->rays,
           (unsigned long long)s->rays_backface, (unsigned long long)s->rays_region,
           (unsigned long long)s->rays_searched, (unsigned long long)s->rays_hit,
           (unsigned long long)s->lookups, (unsigned long long)s->lookups_search);
}

/* The frame holds every visible point in front of the light and the light
 * itself; the layers bound the box. */
static void softmc_frame(void **st)
{
    (void)st;
    assert_true(E->ok);
    const struct sl_softmap *m = &E->map;
    assert_int_equal(m->n_outside, 0);
    assert_true(m->n_fit > 0);
    assert_int_equal(m->n_receiver_ranges, 1);
    const size_t n = (size_t)VW * VH;
    for (size_t i = 0; i < n; i++) {
        if (!E->view.tri[i])
            continue;
        double p[3] = {P(i)[0], P(i)[1], P(i)[2]}, u, v, z;
        sl_softmap_project(m, p, &u, &v, &z);
        assert_true(u > 0.0 && u < MAP && v > 0.0 && v < MAP);
        assert_true(z > m->light_depth && z < m->zfar);
    }
    for (int k = 0; k < 4; k++) {
        double p[3], u, v, z;
        sl_area_point(&m->area, k & 1, k >> 1, p);
        sl_softmap_project(m, p, &u, &v, &z);
        assert_true(u > -1e-6 && u < MAP + 1e-6 && v > -1e-6 && v < MAP + 1e-6);
        assert_true(fabs(z - m->light_depth) < 1e-9);
    }
    /* eq. 3.1 */
    assert_true(fabs(m->light_depth * 2.0 * m->tan_half - 4.0) < 1e-9);
    /* under the box's middle: near = its top (y = 3), far = its bottom (y = 2);
     * the light looks down from y = 10 */
    double c[3], u, v, z;
    local(0.3, 2.5, 0.2, c);
    sl_softmap_project(m, c, &u, &v, &z);
    size_t t = (size_t)floor(v) * MAP + (size_t)floor(u);
    assert_true(fabs(m->near[t] - (m->light_depth + 7.0)) < 1e-3);
    assert_true(fabs(m->far[t] - (m->light_depth + 8.0)) < 1e-3);
    /* beside the box: empty (the ground is a pure receiver): Curtis's clears */
    double g[3];
    local(0.0, 0.0, 6.0, g);
    sl_softmap_project(m, g, &u, &v, &z);
    t = (size_t)floor(v) * MAP + (size_t)floor(u);
    assert_true(m->near[t] == (float)m->zfar && m->far[t] == (float)m->znear);
    /* the N-buffer's top level is the whole map */
    const struct sl_softmap_texel *top = E->nb.t + (size_t)(E->nb.levels - 1) * MAP * MAP;
    assert_true(fabs(top->near_min - (m->light_depth + 7.0)) < 1e-3);
    assert_true(top->far_max == (float)m->zfar || fabs(top->far_max - (m->light_depth + 8.0)) < 1e-3);
}

/* Output in [0, 1]; the same seed gives the same bits, on 1 and 2 threads
 * (three layers too); another seed does not. */
static void softmc_range_deterministic(void **st)
{
    (void)st;
    assert_true(E->ok);
    const size_t n = (size_t)VW * VH;
    /* hier/linear x two/one layer, then linear with three layers */
    for (int variant = 0; variant < 5; variant++) {
        struct sl_softmc_desc o = {.seed = 7, .search = variant & 1, .layers = variant & 2 ? 1 : 2};
        if (variant == 4) {
            o.search = SL_SOFTMC_LINEAR;
            o.layers = 3;
        }
        struct sl_softmc_result a, b;
        o.threads = 2;
        run(&o, &a);
        o.threads = 1;
        run(&o, &b);
        for (size_t i = 0; i < n; i++)
            assert_true(a.vis[i] >= 0.0f && a.vis[i] <= 1.0f);
        assert_memory_equal(a.vis, b.vis, n * sizeof(float));
        sl_softmc_result_free(&b);
        o.seed = 8;
        run(&o, &b);
        assert_true(memcmp(a.vis, b.vis, n * sizeof(float)) != 0);
        sl_softmc_result_free(&a);
        sl_softmc_result_free(&b);
    }
}

/* Lit far from the box, umbra under its middle, partial in the penumbra's
 * middle (ground, 3 x 3 rays: the third of the light with z < -2/3 is
 * always hidden there, the third with z > 2/3 always seen). */
static void softmc_shadow_regions(void **st)
{
    (void)st;
    assert_true(E->ok);
    for (int variant = 0; variant < 3; variant++) {
        struct sl_softmc_desc o = {.seed = 1, .search = variant == 1, .layers = variant == 2 ? 1 : 2};
        struct sl_softmc_result r;
        run(&o, &r);
        int nfar = 0, numbra = 0, nedge = 0;
        for (size_t i = 0; i < (size_t)VW * VH; i++) {
            if (!ground(i))
                continue;
            double x = wx(i), z = wz(i);
            if (fabs(z) > 4.0 || fabs(x) > 9.0) {
                assert_true(r.vis[i] == 1.0f);
                nfar++;
            }
            if (fabs(x) < 3.0 && fabs(z) < 0.5) {
                assert_true(r.vis[i] == 0.0f);
                numbra++;
            }
            if (fabs(x) < 3.0 && fabs(fabs(z) - 1.5) < 0.15) {
                assert_true(r.vis[i] > 0.0f && r.vis[i] < 1.0f);
                nedge++;
            }
        }
        report(variant == 0 ? "hier" : variant == 1 ? "linear" : "hier, one layer", &r);
        printf("softmc: variant %d: %d far pixels lit, %d umbra pixels dark, %d penumbra pixels partial\n",
               variant, nfar, numbra, nedge);
        assert_true(nfar > 1000 && numbra > 100 && nedge > 50);
        sl_softmc_result_free(&r);
    }
}

/* Per pixel: the number of pixels where a gives more light than b, where
 * they differ, and the largest difference. */
static void compare(const float *a, const float *b, uint64_t *more, uint64_t *differ, float *maxdiff)
{
    *more = *differ = 0;
    *maxdiff = 0.0f;
    for (size_t i = 0; i < (size_t)VW * VH; i++) {
        if (!E->view.tri[i])
            continue;
        *more += a[i] > b[i];
        *differ += a[i] != b[i];
        float dd = fabsf(a[i] - b[i]);
        if (dd > *maxdiff)
            *maxdiff = dd;
    }
}

static uint64_t pixels(void)
{
    uint64_t n = 0;
    for (size_t i = 0; i < (size_t)VW * VH; i++)
        n += E->view.tri[i] != 0;
    return n;
}

/* The hierarchical search finds every hit a linear sample finds (it tests
 * whole texels, the linear search points), so it never gives more light;
 * the two agree on most pixels. Both with every shortcut off, so that the
 * rays are the same. */
static void softmc_hier_vs_linear(void **st)
{
    (void)st;
    assert_true(E->ok);
    const uint64_t npx = pixels();
    struct sl_softmc_desc o = {.seed = 3, .no_classify = 1, .no_accel = 1};
    struct sl_softmc_result h;
    run(&o, &h);
    report("hier, all rays", &h);
    /* the defaults (4-texel steps, 4 binary steps), then coarse steps with
     * one binary step, then no refinement at all */
    const double step[3] = {0.0, 8.0, 8.0};
    const int refine[3] = {0, 1, -1};
    uint64_t differ_default = 0;
    for (int k = 0; k < 3; k++) {
        struct sl_softmc_desc l = o;
        l.search = SL_SOFTMC_LINEAR;
        l.step_texels = step[k];
        l.refine = refine[k];
        struct sl_softmc_result r;
        run(&l, &r);
        uint64_t more, differ;
        float md;
        compare(h.vis, r.vis, &more, &differ, &md);
        printf("softmc: hier vs linear (step %.0f texels, %d binary steps): %llu of %llu pixels differ "
               "(%.2f%%), largest %.3f; hier lighter on %llu; linear %.1f ms, %llu lookups\n",
               k ? 8.0 : 4.0, k == 0 ? 4 : k == 1 ? 1 : 0, (unsigned long long)differ, (unsigned long long)npx,
               100.0 * (double)differ / (double)npx, md, (unsigned long long)more, r.st.ms_trace,
               (unsigned long long)r.st.lookups);
        assert_int_equal(more, 0);
        if (k == 0)
            differ_default = differ;
        sl_softmc_result_free(&r);
    }
    assert_true((double)differ_default <= E->lin_pct * 0.01 * (double)npx);
    sl_softmc_result_free(&h);
}

/* One layer (3.2): anything behind the near layer occludes, a superset of
 * "between near and far", so per ray it blocks at least what two layers
 * block (hierarchical search: every pixel, exactly). And where a
 * conventional shadow map shadows (the end q' behind the near layer) every
 * ray ends behind it: 0, only outer penumbrae. */
static void softmc_single_layer(void **st)
{
    (void)st;
    assert_true(E->ok);
    struct sl_softmc_desc o = {.seed = 5, .no_classify = 1, .no_accel = 1};
    struct sl_softmc_result two, one;
    run(&o, &two);
    o.layers = 1;
    run(&o, &one);
    uint64_t more, differ;
    float md;
    compare(one.vis, two.vis, &more, &differ, &md);
    assert_int_equal(more, 0);
    /* the conventional test, with softmc.h's bias (eq. 3.2, defaults) */
    const struct sl_softmap *m = &E->map;
    uint64_t sm_shadow = 0, lit_there = 0, inner = 0;
    for (size_t i = 0; i < (size_t)VW * VH; i++) {
        if (!E->view.tri[i])
            continue;
        double q[3] = {P(i)[0], P(i)[1], P(i)[2]}, u, v, z, rel[3], rl = 0.0, ndl = 0.0;
        for (int k = 0; k < 3; k++) {
            rel[k] = q[k] - m->area.c[k];
            rl += rel[k] * rel[k];
            ndl -= E->view.nrm[3 * i + k] * rel[k];
        }
        ndl = fmax(ndl / sqrt(rl), 0.1);
        sl_softmap_project(m, q, &u, &v, &z);
        double ze = z - 1.4142135623730951 * z * m->tan_half / (MAP * ndl);
        size_t t = (size_t)floor(v) * MAP + (size_t)floor(u);
        if (m->near[t] < ze) {
            sm_shadow++;
            lit_there += one.vis[i] > 0.0f;
        }
        inner += two.vis[i] > 0.0f && two.vis[i] < 1.0f && one.vis[i] == 0.0f;
    }
    printf("softmc: one layer vs two: %llu pixels differ, largest %.3f; conventional map shadows %llu "
           "pixels, one layer lights %llu of them; %llu penumbra pixels of two layers are 0 with one\n",
           (unsigned long long)differ, md, (unsigned long long)sm_shadow, (unsigned long long)lit_there,
           (unsigned long long)inner);
    assert_true(sm_shadow > 100);
    assert_int_equal(lit_there, 0);
    sl_softmc_result_free(&two);
    sl_softmc_result_free(&one);
}

/* The shortcuts (3.6 classification, 3.7 endpoint / region / shortening)
 * against every ray searched. With the hierarchical search they only prove
 * what it would find: not one pixel changes with the strict umbra test.
 * Curtis's umbra test (z >= z_near_max alone) assumes the near layer hides
 * a solid reaching the far one: it holds on softbox (0 pixels) and not on
 * softmix (rays passing under the leaf or through the torus's hole):
 * bounded at 1%. With the linear search shortened rays move the samples and
 * proven hits may lie between samples, so pixels change (measured, bounded
 * with two layers; one layer, which cannot refine, is only reported); but
 * every linear hit is still a hierarchical one, so with or without the
 * shortcuts the linear search never gives less light than the
 * hierarchical. */
static void softmc_classification(void **st)
{
    (void)st;
    assert_true(E->ok);
    const uint64_t npx = pixels();
    for (int layers = 1; layers <= 2; layers++) {
        struct sl_softmc_desc h = {.seed = 11, .layers = layers};
        struct sl_softmc_result ref;
        run(&h, &ref);
        for (int search = 0; search < 2; search++) {
            struct sl_softmc_desc o = {.seed = 11, .search = search, .layers = layers, .no_classify = 1,
                                       .no_accel = 1};
            struct sl_softmc_result all, r;
            run(&o, &all);
            uint64_t differ[4], more;
            float md;
            const char *name[4] = {"classify", "accel", "both", "both, Curtis's umbra"};
            printf("softmc: shortcuts, %s, %d layer(s), pixels changed:", search ? "linear" : "hier", layers);
            for (int k = 0; k < 4; k++) {
                struct sl_softmc_desc f = o;
                f.no_classify = k == 1;
                f.no_accel = k == 0;
                f.curtis_umbra = k == 3;
                run(&f, &r);
                compare(r.vis, all.vis, &more, &differ[k], &md);
                printf(" %s %llu (largest %.3f);", name[k], (unsigned long long)differ[k], md);
                if (k < 3) {
                    uint64_t from_ref;
                    compare(ref.vis, r.vis, &more, &from_ref, &md);   /* hier lighter: never */
                    assert_int_equal(more, 0);
                    if (search && k == 2) {
                        compare(ref.vis, all.vis, &more, &from_ref, &md);
                        printf(" (from hier: all rays %llu,", (unsigned long long)from_ref);
                        compare(ref.vis, r.vis, &more, &from_ref, &md);
                        printf(" shortcuts %llu);", (unsigned long long)from_ref);
                    }
                }
                if (k == 2) {
                    printf(" rays searched %llu -> %llu, lookups %llu -> %llu, %.1f -> %.1f ms;",
                           (unsigned long long)all.st.rays_searched, (unsigned long long)r.st.rays_searched,
                           (unsigned long long)all.st.lookups, (unsigned long long)r.st.lookups,
                           all.st.ms_trace, r.st.ms_trace);
                    assert_true(r.st.rays_searched * 2 < all.st.rays_searched);
                }
                sl_softmc_result_free(&r);
            }
            printf("\n");
            for (int k = 0; k < 4; k++) {
                if (search == SL_SOFTMC_HIER && k < 3)
                    assert_int_equal(differ[k], 0);
                else if (search == SL_SOFTMC_HIER)
                    assert_true(differ[k] * 100 <= npx);
                else if (layers == 2)
                    assert_true((double)differ[k] <= E->lin_short_pct * 0.01 * (double)npx);
            }
            sl_softmc_result_free(&all);
        }
        sl_softmc_result_free(&ref);
    }
}

/* The same jittered rays traced exactly by Embree (origin on the surface,
 * the own triangle filtered, the back-face rule shared). */
static void softmc_embree(void **st)
{
    (void)st;
    assert_true(E->ok);
    const int r = 3;
    const uint32_t seed = 13;
    const size_t n = (size_t)VW * VH;
    float *ex = calloc(n, sizeof(float));
    assert_non_null(ex);
    double t0 = sl_now();
    uint64_t rays = 0;
    sl_rt_thread_init();
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (int y = 0; y < VH; y++)
        for (int x = 0; x < VW; x++) {
            size_t i = (size_t)y * VW + (size_t)x;
            if (!E->view.tri[i])
                continue;
            const float *q = P(i), *nr = E->view.nrm + 3 * i;
            int seen = 0;
            for (int k = 0; k < r * r; k++) {
                double u, v, p[3];
                sl_area_jitter((uint32_t)x, (uint32_t)y, (uint32_t)k, (uint32_t)r, seed, &u, &v);
                sl_area_point(&E->map.area, u, v, p);
                double dd[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
                if (nr[0] * dd[0] + nr[1] * dd[1] + nr[2] * dd[2] <= 0.0)
                    continue;
                struct RTCRay ray = {.org_x = q[0], .org_y = q[1], .org_z = q[2], .tnear = sl_rt_tnear(q),
                                     .dir_x = (float)dd[0], .dir_y = (float)dd[1], .dir_z = (float)dd[2],
                                     .tfar = 1.0f, .mask = 0xffffffffu, .id = E->view.tri[i]};
                rtcOccluded1(E->rt.scene, &ctx, &ray);
                rays++;
                seen += ray.tfar != -INFINITY;
            }
            ex[i] = (float)seen / (float)(r * r);
        }
    double ms_rt = 1e3 * (sl_now() - t0);
    struct sl_softmc_desc o = {.grid = r, .seed = seed};
    uint64_t eq_lin[2] = {0, 0};   /* pixels equal to Embree, linear with two and three layers */
    for (int variant = 0; variant < 4; variant++) {
        o.search = variant == 1 || variant == 3 ? SL_SOFTMC_LINEAR : SL_SOFTMC_HIER;
        o.layers = variant == 2 ? 1 : variant == 3 ? 3 : 2;
        struct sl_softmc_result s;
        run(&o, &s);
        uint64_t np = 0, eq = 0, near = 0, gp = 0, geq = 0, gnear = 0;
        double sum = 0.0, gsum = 0.0;
        for (size_t i = 0; i < n; i++) {
            if (!E->view.tri[i])
                continue;
            float dd = fabsf(s.vis[i] - ex[i]);
            np++;
            eq += dd == 0.0f;
            near += dd <= 1.0f / 9.0f + 1e-6f;
            sum += dd;
            if (ground(i)) {
                gp++;
                geq += dd == 0.0f;
                gnear += dd <= 1.0f / 9.0f + 1e-6f;
                gsum += dd;
            }
        }
        printf("softmc: vs Embree (%s): all %llu px: %.2f%% equal, %.2f%% within one ray, mean |diff| %.4f; "
               "ground %llu px: %.2f%% equal, %.2f%% within one ray, mean %.4f (layers %.1f ms, Embree "
               "%.1f ms for %llu rays)\n",
               variant == 0   ? "hier"
               : variant == 1 ? "linear"
               : variant == 2 ? "hier, one layer"
                              : "linear, three layers",
               (unsigned long long)np,
               100.0 * eq / np, 100.0 * near / np, sum / np, (unsigned long long)gp, 100.0 * geq / gp,
               100.0 * gnear / gp, gsum / gp, s.st.ms_trace, ms_rt, (unsigned long long)rays);
        if (variant == 1 || variant == 3)
            eq_lin[variant == 3] = eq;
        if (variant == 0) {
            /* softbox: the ground (receivers only) 98% equal, everything 90%
             * (the box's own faces: rays ending inside the layers' solid are
             * blocked, Curtis 3.4) */
            assert_true((double)geq >= E->rt_ground_pct * 0.01 * (double)gp);
            assert_true((double)eq >= E->rt_all_pct * 0.01 * (double)np);
        }
        sl_softmc_result_free(&s);
    }
    /* the third layer on the very same rays: it can also miss what two
     * layers blocked only by accident (a leaf's edge that no texel centre of
     * the near layer holds, inside the hull of a deeper object), so this is
     * measured, not guaranteed: equal to Embree on 30045 -> 30050 pixels
     * (softbox), 25468 -> 25573 (softmix), 40113 -> 40116 and 31244 ->
     * 31270 (curtis_box above, low), 32843 -> 33095 and 46875 -> 46914
     * (soft_wuson front, above) */
    printf("softmc: vs Embree, linear: %llu pixels equal with two layers, %llu with three\n",
           (unsigned long long)eq_lin[0], (unsigned long long)eq_lin[1]);
    assert_true(eq_lin[1] >= eq_lin[0]);
    free(ex);
}

/* The blur: a weighted mean, so inside the range of the values it mixes
 * (hence in [0, 1]); it smooths the penumbra; and its depth weights keep
 * values from crossing depth edges: where the neighbourhood spans a depth
 * jump, it moves values less than a depth-blind blur does. */
static void softmc_blur(void **st)
{
    (void)st;
    assert_true(E->ok);
    const int R = 4;
    struct sl_softmc_desc o = {.seed = 2, .grid = 2, .blur_radius = R};
    struct sl_softmc_result r;
    run(&o, &r);
    assert_non_null(r.vis_blur);
    const size_t n = (size_t)VW * VH;
    float *blind = calloc(n, sizeof(float));
    assert_non_null(blind);
    struct sl_diag d;
    assert_int_equal(sl_softmc_blur(&E->view, r.vis, blind, R, 0.5 * R, 1e-9, &d), SL_OK);
    uint64_t changed = 0, edge = 0;
    double move_k = 0.0, move_blind = 0.0;
    for (int y = 0; y < VH; y++)
        for (int x = 0; x < VW; x++) {
            size_t i = (size_t)y * VW + (size_t)x;
            if (!E->view.tri[i]) {
                assert_true(r.vis_blur[i] == 0.0f);
                continue;
            }
            float lo = 1.0f, hi = 0.0f;
            int jump = 0;
            for (int yy = y - R; yy <= y + R; yy++)
                for (int xx = x - R; xx <= x + R; xx++) {
                    size_t j = (size_t)yy * VW + (size_t)xx;
                    if (xx < 0 || yy < 0 || xx >= VW || yy >= VH || !E->view.tri[j])
                        continue;
                    lo = r.vis[j] < lo ? r.vis[j] : lo;
                    hi = r.vis[j] > hi ? r.vis[j] : hi;
                    jump |= fabs(wz(j) - wz(i)) > 2.0;   /* the box's edge over the ground */
                }
            assert_true(r.vis_blur[i] >= lo - 1e-6f && r.vis_blur[i] <= hi + 1e-6f);
            changed += r.vis_blur[i] != r.vis[i];
            if (jump && hi > lo) {
                edge++;
                move_k += fabs(r.vis_blur[i] - r.vis[i]);
                move_blind += fabs(blind[i] - r.vis[i]);
            }
        }
    printf("softmc: blur (2x2 rays, radius %d): %llu pixels changed, %.1f ms; across %llu depth-edge pixels "
           "values move %.1f (depth-blind: %.1f)\n", R, (unsigned long long)changed, r.st.ms_blur,
           (unsigned long long)edge, move_k, move_blind);
    assert_true(changed > 100 && edge > 10);
    assert_true(move_k < move_blind);
    free(blind);
    sl_softmc_result_free(&r);
}

/* A fixed fov (the caller's, as Curtis has it) narrower than the view
 * needs: eq. 3.1 with that fov, the points outside counted, and their rays
 * clipped to the map: results still in [0, 1], searches never capped. */
static void softmc_fixed_fov(void **st)
{
    (void)st;
    assert_true(E->ok);
    struct sl_diag d;
    struct sl_softmap m;
    struct sl_softmap_nbuf nb;
    memset(&nb, 0, sizeof nb);
    struct sl_softmap_desc md = {.size = 256, .fov_deg = 60.0, .receiver = E->receiver};
    assert_int_equal(sl_softmap_render(&SP, &E->mesh, &E->scene, &E->view, &md, &m, &d), SL_OK);
    assert_true(fabs(m.fov_deg - 60.0) < 1e-9);
    assert_true(fabs(m.light_depth - 2.0 / tan(30.0 * 3.14159265358979323846 / 180.0)) < 1e-9);
    assert_true(m.n_outside > 1000);
    assert_int_equal(sl_softmap_nbuf_build(&m, 0, &nb, &d), SL_OK);
    struct sl_softmc_desc o = {.seed = 4};
    struct sl_softmc_result r;
    for (int search = 0; search < 2; search++) {
        o.search = search;
        assert_int_equal(sl_softmc_run(&m, &E->view, &o, &r, &d), SL_OK);
        assert_int_equal(r.st.capped, 0);
        for (size_t i = 0; i < (size_t)VW * VH; i++)
            assert_true(r.vis[i] >= 0.0f && r.vis[i] <= 1.0f);
        sl_softmc_result_free(&r);
    }
    printf("softmc: fixed fov 60 deg: light depth %.3f, %u of %u points outside the frustum\n", m.light_depth,
           m.n_outside, m.n_fit);
    sl_softmap_nbuf_free(&nb);
    sl_softmap_free(&m);
}

/* Bad input comes back as an error id: a scene without an area light, a
 * map size that is not a power of two, an N-buffer of another map, a grid
 * too large. */
static void softmc_bad_input(void **st)
{
    (void)st;
    assert_true(E->ok);
    struct sl_diag d;
    struct sl_scene dir;
    struct sl_view none;
    struct sl_softmap m;
    memset(&none, 0, sizeof none);
    assert_int_equal(sl_scene_build("tests/scenes/leaf.yaml", &dir, &d), SL_OK);
    struct sl_softmap_desc md = {0};
    assert_int_equal(sl_softmap_fit(&dir, &none, &md, &m, &d), SL_E_SCENE);
    sl_scene_free(&dir);
    md.size = 500;
    assert_int_equal(sl_softmap_fit(&E->scene, &E->view, &md, &m, &d), SL_E_METHOD);
    md.size = 256;
    assert_int_equal(sl_softmap_fit(&E->scene, &E->view, &md, &m, &d), SL_OK);
    struct sl_softmc_desc o = {0};
    struct sl_softmc_result r;
    m.nbuf = &E->nb;   /* the N-buffer of another map (its size) */
    assert_int_equal(sl_softmc_run(&m, &E->view, &o, &r, &d), SL_E_INTERNAL);
    o.grid = 65;
    assert_int_equal(sl_softmc_run(&E->map, &E->view, &o, &r, &d), SL_E_METHOD);
    /* the third layer with the hierarchical search (the default search) is
     * refused, not run linear; four layers do not exist */
    o.grid = 0;
    o.layers = 3;
    assert_int_equal(sl_softmc_run(&E->map, &E->view, &o, &r, &d), SL_E_METHOD);
    assert_non_null(strstr(d.msg, "linear"));
    o.search = SL_SOFTMC_LINEAR;
    o.layers = 4;
    assert_int_equal(sl_softmc_run(&E->map, &E->view, &o, &r, &d), SL_E_METHOD);
    sl_softmc_result_free(&r);
}

/* Curtis's third layer (3.4). With the same samples three layers never
 * give less light than two, per pixel: a sample between the layers that
 * the camera sees is no hit, and a ray with no sample between the layers
 * takes the same samples and refinements either way (softmc.c); the umbra
 * classification is off and the endpoint test asks the camera, both only
 * ever lighter. Checked with every shortcut and with none. Output in
 * [0, 1], bit-identical on a second run and on 1 thread. Returns the
 * pixels changed with the shortcuts on, and with both out pointers given
 * hands that pair of results to the caller. */
static uint64_t third_layer_checks(uint32_t seed, struct sl_softmc_result *two_out,
                                   struct sl_softmc_result *three_out)
{
    const size_t n = (size_t)VW * VH;
    const uint64_t npx = pixels();
    uint64_t changed_default = 0;
    for (int shortcuts = 1; shortcuts >= 0; shortcuts--) {
        struct sl_softmc_desc o = {.seed = seed, .search = SL_SOFTMC_LINEAR, .no_classify = !shortcuts,
                                   .no_accel = !shortcuts, .threads = 2};
        struct sl_softmc_result two, three, again;
        run(&o, &two);
        o.layers = 3;
        run(&o, &three);
        run(&o, &again);
        assert_memory_equal(three.vis, again.vis, n * sizeof(float));
        sl_softmc_result_free(&again);
        o.threads = 1;
        run(&o, &again);
        assert_memory_equal(three.vis, again.vis, n * sizeof(float));
        sl_softmc_result_free(&again);
        uint64_t darker, changed;
        float md;
        compare(two.vis, three.vis, &darker, &changed, &md);   /* two layers lighter */
        for (size_t i = 0; i < n; i++)
            assert_true(three.vis[i] >= 0.0f && three.vis[i] <= 1.0f);
        const struct sl_softmc_stats *s3 = &three.st;
        printf("softmc: three layers vs two (%s, seed %u): %llu of %llu pixels lighter (%.2f%%), largest "
               "+%.3f, none darker: %s; rays hit %llu -> %llu; eye tests %llu: seen %llu, outside the view "
               "%llu; endpoint %llu -> %llu, umbra %llu -> %llu; %.1f -> %.1f ms\n",
               shortcuts ? "shortcuts" : "every ray searched", seed, (unsigned long long)changed,
               (unsigned long long)npx, 100.0 * (double)changed / (double)npx, md, darker ? "NO" : "yes",
               (unsigned long long)two.st.rays_hit, (unsigned long long)s3->rays_hit,
               (unsigned long long)s3->eye_tests, (unsigned long long)s3->eye_seen,
               (unsigned long long)s3->eye_outside, (unsigned long long)two.st.px_endpoint,
               (unsigned long long)s3->px_endpoint, (unsigned long long)two.st.px_umbra,
               (unsigned long long)s3->px_umbra, two.st.ms_trace, s3->ms_trace);
        assert_int_equal(darker, 0);
        assert_int_equal(s3->px_umbra, 0);
        assert_true(s3->eye_seen + s3->eye_outside <= s3->eye_tests);
        assert_int_equal(two.st.eye_tests, 0);
        if (shortcuts) {
            changed_default = changed;
            if (two_out && three_out) {
                *two_out = two;
                *three_out = three;
                continue;
            }
        }
        sl_softmc_result_free(&two);
        sl_softmc_result_free(&three);
    }
    return changed_default;
}

/* Outside the camera's view the G-buffer says nothing and the two-layer
 * answer stands: with the camera's projection negated every point falls
 * behind it (clip w < 0), so every eye test is "outside" and three layers
 * give two layers' image bit for bit (the umbra classification off for
 * both: three layers have none). */
static void third_layer_out_of_view(void)
{
    const size_t n = (size_t)VW * VH;
    struct sl_view turned = E->view;   /* shares the G-buffer's arrays */
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++)
            turned.proj[col][row] = -E->view.proj[col][row];
    struct sl_softmc_desc o = {.seed = 19, .search = SL_SOFTMC_LINEAR, .no_classify = 1};
    struct sl_softmc_result two, three;
    struct sl_diag d;
    run(&o, &two);
    o.layers = 3;
    assert_int_equal(sl_softmc_run(&E->map, &turned, &o, &three, &d), SL_OK);
    printf("softmc: three layers, camera turned away: %llu eye tests, %llu outside the view\n",
           (unsigned long long)three.st.eye_tests, (unsigned long long)three.st.eye_outside);
    assert_true(three.st.eye_tests > 0);
    assert_int_equal(three.st.eye_outside, three.st.eye_tests);
    assert_memory_equal(two.vis, three.vis, n * sizeof(float));
    sl_softmc_result_free(&two);
    sl_softmc_result_free(&three);
}

static void softmc_third_layer(void **st)
{
    (void)st;
    assert_true(E->ok);
    third_layer_checks(17, NULL, NULL);
    third_layer_out_of_view();
}

/* The guarantees again, on softmix.yaml: a tilted rectangular light, a
 * box on the ground, a sphere, a zero-thickness leaf, a torus, a frustum of
 * about 150 degrees. The linear search misses more there (the leaf has no
 * "between" and the wide frustum packs each ray's occluder crossing into a
 * few texels): looser measured bounds. */
static void softmc_mixed_scene(void **st)
{
    assert_true(env_open(&MIX, "tests/scenes/softmix.yaml", "low"));
    assert_int_equal(MIX.map.n_outside, 0);
    MIX.lin_pct = 10.0;
    MIX.lin_short_pct = 10.0;
    MIX.rt_ground_pct = 0.0;
    MIX.rt_all_pct = 0.0;
    E = &MIX;
    softmc_range_deterministic(st);
    softmc_hier_vs_linear(st);
    softmc_single_layer(st);
    softmc_classification(st);
    softmc_embree(st);
    softmc_third_layer(st);
    E = &BOX;
    env_close(&MIX);
}

/* The third layer on the area-light scenes of scenes/: per pixel, the
 * guarantees above on both views of each, the MAE against the area truth
 * (16 x 16 samples, seed 1; soft_mc draws seed 2, the same samples with two
 * and three layers) printed, and on the very same rays three layers agree
 * with Embree at least as often (softmc_embree).
 * Wuson is where the third layer is meant to matter: the model shadows
 * itself (legs under the body, horns over the head), and with two layers
 * every point of it inside the two-layer hull is in umbra (3.4: only outer
 * penumbrae). Three layers must strictly light some pixels there, and must
 * not look worse than two by more than the truth's own noise allows: only
 * the changed pixels differ, and a truth off by d moves |a - t| - |b - t|
 * by at most 2|d|, so the bound is 2 x the sum of the truth's standard
 * errors over the changed pixels / all pixels. Measured (this build,
 * 256x192, 512^2): front 1.966% -> 1.797% (bound 0.018), above 1.137% ->
 * 1.124% (bound 0.004): better beyond the bound on both, which is asserted
 * too; on the changed pixels alone the mean error drops from 0.25 to 0.08
 * (front) and 0.17 to 0.09 (above).
 * Curtis's box is convex: the two-layer hull is the box, and three layers
 * change only a few pixels where a sample beside the box falls in a texel
 * the box covers (7 and 42 pixels, 0.02% and 0.13%; bounded at 0.2%). Those
 * agree with Embree's same rays more often (40113 -> 40116, 31244 ->
 * 31270 pixels), but against the area truth they move the MAE by soft_mc's
 * own sampling noise, which the bound above does not hold (9 rays: an
 * exact ray can take a pixel away from the area's fraction): 1.137% ->
 * 1.136% (above), 1.391% -> 1.394% (low, bound 0.0024); so there the MAE
 * is only printed. */
static void softmc_third_layer_scenes(void **st)
{
    static const struct { const char *path, *view; int concave; } cases[] = {
        {"scenes/curtis_box.yaml", "above", 0}, {"scenes/curtis_box.yaml", "low", 0},
        {"scenes/soft_wuson.yaml", "front", 1}, {"scenes/soft_wuson.yaml", "above", 1},
    };
    for (size_t ci = 0; ci < sizeof cases / sizeof cases[0]; ci++) {
        assert_true(env_open(&AREA, cases[ci].path, cases[ci].view));
        E = &AREA;
        const size_t n = (size_t)VW * VH;
        struct sl_softmc_result two, three;
        const uint64_t changed = third_layer_checks(2, &two, &three);
        float *truth = calloc(n, sizeof(float)), *se = calloc(n, sizeof(float));
        assert_true(truth && se);
        struct sl_diag d;
        assert_int_equal(sl_soft_truth(&E->rt, &E->scene, &E->view, 16, 1, truth, se, NULL, &d), SL_OK);
        double s2 = 0.0, s3 = 0.0, c2 = 0.0, c3 = 0.0, noise = 0.0;
        uint64_t np = 0;
        for (size_t i = 0; i < n; i++) {
            if (!E->view.tri[i])
                continue;
            const double e2 = fabs((double)two.vis[i] - (double)truth[i]);
            const double e3 = fabs((double)three.vis[i] - (double)truth[i]);
            np++;
            s2 += e2;
            s3 += e3;
            if (two.vis[i] != three.vis[i]) {
                c2 += e2;
                c3 += e3;
                noise += 2.0 * (double)se[i];
            }
        }
        const double m2 = 100.0 * s2 / (double)np, m3 = 100.0 * s3 / (double)np;
        const double bound = 100.0 * noise / (double)np;
        printf("softmc: %s %s: three layers change %llu of %llu pixels; MAE vs area truth (16x16): two "
               "layers %.3f%%, three %.3f%% (truth noise bound on the difference %.4f); on the changed pixels "
               "mean |err| %.3f -> %.3f\n", E->scene.name, cases[ci].view, (unsigned long long)changed,
               (unsigned long long)np, m2, m3, bound, changed ? c2 / (double)changed : 0.0,
               changed ? c3 / (double)changed : 0.0);
        if (cases[ci].concave) {
            assert_true(changed > 0);
            assert_true(m3 <= m2 + bound);
            assert_true(m3 < m2 - bound);
            assert_true(c3 < c2);
        } else
            assert_true(changed * 500 < np);   /* under 0.2% */
        free(truth);
        free(se);
        sl_softmc_result_free(&two);
        sl_softmc_result_free(&three);
        softmc_embree(st);
        E = &BOX;
        env_close(&AREA);
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(softmc, frame),
        SL_CASE(softmc, range_deterministic),
        SL_CASE(softmc, shadow_regions),
        SL_CASE(softmc, hier_vs_linear),
        SL_CASE(softmc, single_layer),
        SL_CASE(softmc, classification),
        SL_CASE(softmc, embree),
        SL_CASE(softmc, blur),
        SL_CASE(softmc, fixed_fov),
        SL_CASE(softmc, bad_input),
        SL_CASE(softmc, third_layer),
        SL_CASE(softmc, mixed_scene),
        SL_CASE(softmc, third_layer_scenes),
    };
    return sl_run_group(argc, argv, "softmc", tests, group_setup, group_teardown);
}
