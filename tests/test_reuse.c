/* Reuse instead of churn (issue 20): the layer-array pool hands arrays out
 * again and replaces the ones too small; the shadow-map pass keeps one
 * render target per map size; the G-buffer pass keeps its own. What is
 * reused must not change a single texel or pixel: layers rendered into a
 * pooled frame through kept targets (arrays dirty from a larger size
 * before) are compared bit for bit with layers from a fresh pass into
 * calloc'd arrays. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>
#include "sl_test.h"
#include "adjacency.h"
#include "fixture.h"
#include "lightfit.h"
#include "method.h"
#include "shadowmap.h"
#include "test_params.h"

static void reuse_pool_serves_and_replaces(void **st)
{
    (void)st;
    struct sl_layer_pool p;
    memset(&p, 0, sizeof p);
    void *a = sl_layer_pool_get(&p, 1000), *b = sl_layer_pool_get(&p, 1000);
    assert_non_null(a);
    assert_non_null(b);
    assert_ptr_not_equal(a, b);
    assert_int_equal(p.allocs, 2);
    sl_layer_pool_put(&p, a);
    /* an idle array serves a smaller request: no allocation */
    assert_ptr_equal(sl_layer_pool_get(&p, 500), a);
    assert_int_equal(p.allocs, 2);
    sl_layer_pool_put(&p, a);
    sl_layer_pool_put(&p, b);
    /* a larger request replaces an idle array that is too small, in its slot */
    size_t big = (size_t)8 << 20;
    void *c = sl_layer_pool_get(&p, big);
    assert_non_null(c);
    assert_int_equal(p.allocs, 3);
    assert_int_equal(p.n, 2);
    assert_int_equal(p.bytes, 1000 + big);
    /* large arrays are aligned for huge pages */
    assert_int_equal((uintptr_t)c % ((uintptr_t)2 << 20), 0);
    memset(c, 0xab, big);
    /* with the large one busy, a small request takes the small idle one */
    void *s = sl_layer_pool_get(&p, 800);
    assert_true(s == a || s == b);
    sl_layer_pool_put(&p, s);
    sl_layer_pool_put(&p, c);
    /* and now the large one is the only idle one that fits */
    assert_ptr_equal(sl_layer_pool_get(&p, big - 1), c);
    sl_layer_pool_put(&p, c);
    /* every slot busy: arrays outside the pool, freed when given back */
    void *held[SL_POOL_SLOTS + 2];
    for (int i = 0; i < SL_POOL_SLOTS + 2; i++)
        assert_non_null(held[i] = sl_layer_pool_get(&p, 64));
    assert_int_equal(p.n, SL_POOL_SLOTS);
    for (int i = 0; i < SL_POOL_SLOTS + 2; i++)
        sl_layer_pool_put(&p, held[i]);
    sl_layer_pool_free(&p);
    assert_int_equal(p.n, 0);
}

static void fit(const struct fixture *f, const struct sl_view *v, int size, struct sl_light_frame *fr)
{
    fr->size = size;
    memcpy(fr->dir, f->scene.light_dir, sizeof fr->dir);
    sl_light_fit(&f->scene, v, &fr->box);
    fr->texel_world = fmaxf(fr->box.hi[0] - fr->box.lo[0], fr->box.hi[1] - fr->box.lo[1]) / (float)size;
    fr->depth_range = fr->box.hi[2] - fr->box.lo[2];
}

/* Every layer, sizes 1024, 512, 1024 (the pooled arrays and the kept
 * 1024^2 target come back dirty), each rendered twice in a row into the
 * pooled frame as run.c's repetitions do, against a fresh pass per size
 * rendering into calloc'd arrays, BGSM2 there through the upload of BGSM's ids. */
static void reuse_layers_identical(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "primitives", 2));
    struct sl_diag d;
    struct sl_adjacency adj;
    assert_true(fixture_adjacency(&f, &adj));
    struct sl_view v;
    assert_true(fixture_view(&f, 0, 256, 256, &v));
    struct sl_shadowmap_pass kept;
    assert_int_equal(sl_shadowmap_init(&kept, &d), SL_OK);
    const unsigned all = (1u << SL_LAYER_COUNT) - 1u;
    const int sizes[3] = {1024, 512, 1024};
    uint64_t allocs_after_first = 0;
    for (int si = 0; si < 3; si++) {
        struct sl_light_frame a, b;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        a.pool = &kept.pool;
        fit(&f, &v, sizes[si], &a);
        fit(&f, &v, sizes[si], &b);
        for (int rep = 0; rep < 2; rep++) {
            if (rep)
                for (int l = 0; l < SL_LAYER_COUNT; l++)
                    sl_frame_drop_layer(&a, l);
            assert_int_equal(sl_shadowmap_render(&kept, &f.mesh, &a, all, &d), SL_OK);
        }
        /* the fresh pass draws SGSM between BGSM and BGSM2, so BGSM2 finds
         * SGSM's ids in the target and uploads BGSM's from the frame */
        struct sl_shadowmap_pass fresh;
        assert_int_equal(sl_shadowmap_init(&fresh, &d), SL_OK);
        fresh.chunk = 5;   /* and in draws of 5 triangles, flushed between: the same layers */
        const unsigned first = SL_NEED(SL_LAYER_BGSM) | SL_NEED(SL_LAYER_SGSM);
        assert_int_equal(sl_shadowmap_render(&fresh, &f.mesh, &b, first, &d), SL_OK);
        assert_int_equal(sl_shadowmap_render(&fresh, &f.mesh, &b, SL_NEED(SL_LAYER_BGSM2), &d), SL_OK);
        assert_int_equal(sl_shadowmap_render(&fresh, &f.mesh, &b, all, &d), SL_OK);
        assert_int_equal(fresh.targets_made, 1);
        assert_int_equal(fresh.ids_uploads, 1);
        sl_shadowmap_free(&fresh);
        size_t n = (size_t)sizes[si] * (size_t)sizes[si];
        for (int l = 0; l < SL_LAYER_COUNT; l++) {
            assert_memory_equal(a.layer[l].depth, b.layer[l].depth, n * sizeof(float));
            if (l == SL_LAYER_BGSM2) {
                /* read by no one, so not read back (shadowmap.h) */
                assert_null(a.layer[l].id);
                assert_null(b.layer[l].id);
            } else {
                assert_memory_equal(a.layer[l].id, b.layer[l].id, n * sizeof(uint32_t));
            }
            assert_int_equal(a.layer[l].fragments, b.layer[l].fragments);
            assert_int_equal(a.layer[l].gs_prims, b.layer[l].gs_prims);
        }
        /* eleven arrays at once (BGSM2 has no id array); the first size's are the largest */
        assert_int_equal(kept.pool.n, 2 * SL_LAYER_COUNT - 1);
        if (si == 0)
            allocs_after_first = kept.pool.allocs;
        else
            assert_int_equal(kept.pool.allocs, allocs_after_first);
        sl_light_box_free(&a.box);
        sl_light_box_free(&b.box);
        sl_frame_free(&a);
        sl_frame_free(&b);
    }
    /* one target per size, made once; BGSM2 read BGSM's ids where BGSM left them */
    assert_int_equal(kept.targets_made, 2);
    assert_int_equal(kept.ids_uploads, 0);
    sl_shadowmap_free(&kept);
    sl_view_free(&v);
    sl_adjacency_free(&adj);
    fixture_close(&f);
}

/* The G-buffer through a kept target (after another size) equals a fresh
 * pass's. */
static void reuse_gbuffer_identical(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "primitives", 2));
    struct sl_diag d;
    struct sl_view a, b, c;
    assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 0, 200, 100, &a, NULL, NULL, NULL, &d), SL_OK);
    sl_view_free(&a);
    assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 1, 320, 240, &a, NULL, NULL, NULL, &d), SL_OK);
    assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 1, 320, 240, &b, NULL, NULL, NULL, &d), SL_OK);
    struct sl_gbuffer_pass fresh;
    assert_int_equal(sl_gbuffer_init(&fresh, &f.scene, &d), SL_OK);
    assert_int_equal(sl_gbuffer_render(&fresh, &f.mesh, &f.scene, 1, 320, 240, &c, NULL, NULL, NULL, &d), SL_OK);
    sl_gbuffer_free(&fresh);
    size_t n = 320 * 240;
    const struct sl_view *kept[2] = {&a, &b};
    for (int i = 0; i < 2; i++) {
        assert_memory_equal(kept[i]->pos, c.pos, n * 3 * sizeof(float));
        assert_memory_equal(kept[i]->nrm, c.nrm, n * 3 * sizeof(float));
        assert_memory_equal(kept[i]->tri, c.tri, n * sizeof(uint32_t));
        assert_memory_equal(kept[i]->cls, c.cls, n);
    }
    assert_int_equal(f.gp.w, 320);
    sl_view_free(&a);
    sl_view_free(&b);
    sl_view_free(&c);
    fixture_close(&f);
}

/* A view rendered into arrays given back (sl_gbuffer_give_back), which
 * hold another viewpoint's pixels, equals a fresh pass's view in every
 * array and count; the arrays are the ones given back; a timed-only render
 * (no view) between them changes nothing. Under a spot light too, whose
 * outside-the-cone array must be rewritten where the pixel is inside. */
static void reuse_gbuffer_given_back(void **st)
{
    (void)st;
    const char *scenes[2] = {"primitives", "scenes/lamp.yaml"};
    for (int si = 0; si < 2; si++) {
        struct fixture f;
        assert_true(fixture_open(&f, scenes[si], 2));
        struct sl_diag d;
        struct sl_view a, b, c;
        const int W = 160, H = 120;
        /* the reference: viewpoint 1 by a fresh pass */
        struct sl_gbuffer_pass fresh;
        assert_int_equal(sl_gbuffer_init(&fresh, &f.scene, &d), SL_OK);
        assert_int_equal(sl_gbuffer_render(&fresh, &f.mesh, &f.scene, 1, W, H, &c, NULL, NULL, NULL, &d), SL_OK);
        sl_gbuffer_free(&fresh);
        /* viewpoint 0 fills the arrays, given back, then viewpoint 1 into them */
        assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 0, W, H, &a, NULL, NULL, NULL, &d), SL_OK);
        const void *was[3] = {a.pos, a.tri, a.cls};
        sl_gbuffer_give_back(&f.gp, &a);
        assert_null(a.pos);
        assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 1, W, H, NULL, NULL, NULL, NULL, &d), SL_OK);
        assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 1, W, H, &b, NULL, NULL, NULL, &d), SL_OK);
        assert_ptr_equal(b.pos, was[0]);
        assert_ptr_equal(b.tri, was[1]);
        assert_ptr_equal(b.cls, was[2]);
        size_t n = (size_t)W * H;
        assert_memory_equal(b.pos, c.pos, n * 3 * sizeof(float));
        assert_memory_equal(b.nrm, c.nrm, n * 3 * sizeof(float));
        assert_memory_equal(b.tri, c.tri, n * sizeof(uint32_t));
        assert_memory_equal(b.cls, c.cls, n);
        assert_memory_equal(b.truth, c.truth, n);
        assert_int_equal(b.outside != NULL, si == 1);
        if (b.outside) {
            assert_memory_equal(b.outside, c.outside, n);
            assert_true(c.n_outside_cone > 0 && c.n_outside_cone < n);
        }
        assert_int_equal(b.n_background, c.n_background);
        assert_int_equal(b.n_pfl, c.n_pfl);
        assert_int_equal(b.n_pnfl, c.n_pnfl);
        assert_int_equal(b.n_outside_cone, c.n_outside_cone);
        assert_true(c.n_pfl > 0 && c.n_background + c.n_pnfl > 0);   /* more than one class to rewrite */
        assert_true(b.serial != c.serial);
        /* another size: new arrays, the spare ones freed */
        sl_gbuffer_give_back(&f.gp, &b);
        assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 1, W / 2, H / 2, &a, NULL, NULL, NULL, &d),
                         SL_OK);
        assert_null(f.gp.spare.pos);
        sl_view_free(&a);
        sl_view_free(&c);
        fixture_close(&f);
    }
}

/* Layers gathered per pixel (frame.h, sl_frame_gather; run.c does it for
 * layers every remaining reader reads at the pixel's own texel) give the
 * conservative methods the very values of the dense layers: every verdict,
 * how it was reached, the tests per pixel and the counts are the same, on
 * two scenes and two map sizes. And BGSM2 refuses to be drawn once BGSM is
 * gathered and its ids are gone from the target. */
static void reuse_gathered_same_verdicts(void **st)
{
    (void)st;
    const char *scenes[2] = {"primitives", "bench"};
    const char *methods[5] = {"bgsm", "sgsm", "sgsm_adj", "csm", "csm_adj"};
    const int cons[4] = {SL_LAYER_BGSM2, SL_LAYER_SGSM, SL_LAYER_SGSM_ADJ, SL_LAYER_BGSM};
    const unsigned all = SL_NEED(SL_LAYER_BGSM) | SL_NEED(SL_LAYER_BGSM2) | SL_NEED(SL_LAYER_SGSM) |
                         SL_NEED(SL_LAYER_SGSM_ADJ);
    int decided_lit = 0, decided_shadow = 0, gathered_checked = 0;
    for (int sc = 0; sc < 2; sc++)
        for (int size = 256; size <= 1024; size *= 4) {
            struct fixture f;
            assert_true(fixture_open(&f, scenes[sc], 2));
            struct sl_diag d;
            struct sl_adjacency adj;
            assert_true(fixture_adjacency(&f, &adj));
            struct sl_view v;
            assert_true(fixture_view(&f, 0, 192, 160, &v));
            struct sl_view mv = v;
            mv.truth = NULL;
            const size_t n = (size_t)v.w * (size_t)v.h, nt = (size_t)size * (size_t)size;
            struct sl_shadowmap_pass sp;
            assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
            struct sl_light_frame fr, dense;
            memset(&fr, 0, sizeof fr);
            memset(&dense, 0, sizeof dense);
            fr.pool = &sp.pool;
            fr.pix_pool = &sp.pix_pool;
            fit(&f, &v, size, &fr);
            fit(&f, &v, size, &dense);
            assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &fr, all, &d), SL_OK);
            assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &dense, all, &d), SL_OK);
            uint8_t *vv[2][5], *how[2][5], *tests[2][5];
            struct sl_cost cost[2][5];
            for (int pass = 0; pass < 2; pass++) {
                if (pass == 1)
                    for (int i = 0; i < 4; i++) {
                        assert_int_equal(sl_frame_gather(&fr, cons[i], &v, 2, &d), SL_OK);
                        assert_true(fr.layer[cons[i]].per_pixel);
                    }
                for (int m = 0; m < 5; m++) {
                    const struct sl_method *me = sl_method_find(methods[m]);
                    assert_non_null(me);
                    struct sl_method_params p;
                    sl_test_params(me, &p, NULL);
                    struct sl_method_args a = {.scene = &f.scene, .view = &mv, .frame = pass ? &fr : &dense,
                                               .params = &p, .rt = &f.rt, .adj = &adj, .threads = 2};
                    struct sl_verdicts vd = {.w = v.w, .h = v.h, .v = calloc(n, 1), .how = calloc(n, 1),
                                             .tests = calloc(n, 1)};
                    assert_non_null(vd.v);
                    assert_non_null(vd.how);
                    assert_non_null(vd.tests);
                    memset(&cost[pass][m], 0, sizeof cost[pass][m]);
                    assert_int_equal(me->run(&a, &vd, &cost[pass][m], &d), SL_OK);
                    vv[pass][m] = vd.v;
                    how[pass][m] = vd.how;
                    tests[pass][m] = vd.tests;
                }
            }
            for (int m = 0; m < 5; m++) {
                assert_memory_equal(vv[0][m], vv[1][m], n);
                assert_memory_equal(how[0][m], how[1][m], n);
                assert_memory_equal(tests[0][m], tests[1][m], n);
                assert_int_equal(cost[0][m].lookups, cost[1][m].lookups);
                assert_int_equal(cost[0][m].tri_tests, cost[1][m].tri_tests);
                assert_int_equal(cost[0][m].rays, cost[1][m].rays);
                for (size_t i = 0; i < n; i++) {
                    decided_lit += how[0][m][i] == SL_HOW_MAP && vv[0][m][i] == SL_V_LIT;
                    decided_shadow += how[0][m][i] == SL_HOW_MAP && vv[0][m][i] == SL_V_SHADOW;
                }
                for (int pass = 0; pass < 2; pass++) {
                    free(vv[pass][m]);
                    free(how[pass][m]);
                    free(tests[pass][m]);
                }
            }
            /* the gathered values are the dense ones at each decided pixel's texel */
            for (size_t i = 0; i < n; i++) {
                if (v.cls[i] != SL_C_PFL)
                    continue;
                float u, w, z;
                sl_frame_project(&dense, v.pos + 3 * i, &u, &w, &z);
                const uint32_t k = sl_frame_texel(&dense, u, w);
                assert_true(k < nt);
                for (int l = 0; l < 4; l++) {
                    const struct sl_depth_layer *G = &fr.layer[cons[l]], *D = &dense.layer[cons[l]];
                    assert_memory_equal(&G->depth[i], &D->depth[k], sizeof(float));
                    if (D->id)
                        assert_int_equal(G->id[i], D->id[k]);
                    else
                        assert_null(G->id);
                }
                gathered_checked++;
            }
            /* BGSM2 again: the target now holds the dense frame's last ids, not BGSM's */
            sl_frame_drop_layer(&fr, SL_LAYER_BGSM2);
            assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &fr, SL_NEED(SL_LAYER_BGSM2), &d), SL_E_INTERNAL);
            sl_light_box_free(&fr.box);
            sl_light_box_free(&dense.box);
            sl_frame_free(&fr);
            sl_frame_free(&dense);
            sl_shadowmap_free(&sp);
            sl_view_free(&v);
            sl_adjacency_free(&adj);
            fixture_close(&f);
        }
    /* the layers decided pixels both ways: the comparison is not vacuous */
    assert_true(decided_lit > 1000);
    assert_true(decided_shadow > 1000);
    assert_true(gathered_checked > 1000);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(reuse, pool_serves_and_replaces),
        SL_CASE(reuse, layers_identical),
        SL_CASE(reuse, gbuffer_identical),
        SL_CASE(reuse, gbuffer_given_back),
        SL_CASE(reuse, gathered_same_verdicts),
    };
    return sl_run_group(argc, argv, "reuse", tests, sl_test_setup, sl_test_teardown);
}
