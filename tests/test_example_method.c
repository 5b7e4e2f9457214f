/*
 * The worked example of doc/adding-a-method.md (tests/example_method/pcf3.c,
 * the doc's own code: doc::adding_a_method checks they are the same) built
 * with the project's flags and run on a view, outside the shipped registry:
 * a flat plane lit everywhere gets every PFL pixel lit, its lookups counted
 * 9 a pixel, and configure's defaults and checks hold.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <cglm/clipspace/ortho_rh_zo.h>
#include "fixture.h"
#include "lightfit.h"
#include "method.h"
#include "shadowmap.h"
#include "sl_test.h"

extern const struct sl_method sl_method_pcf3;

static void example_method_pcf3_configure(void **state)
{
    (void)state;
    const struct sl_method *m = &sl_method_pcf3;
    struct sl_diag d;
    struct sl_method_params p;
    sl_method_params_init(m, &p);
    assert_int_equal(sl_method_configure(m, &p, &d), SL_OK);
    assert_true(sl_method_param(&p, "bias") == 1.0);   /* its declared default */
    assert_int_equal(p.values.given, 0);
    assert_int_equal(sl_method_param_put(&p, "bias", -1.0, &d), SL_E_METHOD);   /* below its range */
    assert_string_equal(d.key, "bias");
    assert_int_equal(sl_method_param_put(&p, "kernel", 3, &d), SL_E_METHOD);    /* not declared */
    assert_int_equal(sl_method_param_put(&p, "bias", 2.5, &d), SL_OK);
    assert_true(sl_method_param(&p, "bias") == 2.5 && p.values.given == 1u);
    /* no fast path: the driver hands its layer dense */
    assert_int_equal(sl_method_at_pixel(m) | sl_method_looks(m) | sl_method_look_parts(m), 0);
    assert_null(sl_method_find("pcf3"));   /* an example, not in the shipped table */
}

static void example_method_pcf3_plane_lit(void **state)
{
    (void)state;
    struct fixture f;
    struct sl_view v;
    struct sl_shadowmap_pass sp;
    struct sl_light_frame fr;
    struct sl_diag d;
    memset(&v, 0, sizeof v);
    memset(&sp, 0, sizeof sp);
    memset(&fr, 0, sizeof fr);
    assert_true(fixture_open(&f, "tests/example_method/plane.yaml", 2));
    assert_true(fixture_view(&f, 0, 128, 128, &v));
    struct sl_view mv = v;
    mv.truth = NULL;
    assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
    /* a 64^2 map over [-10, 10]^2 of light space: the whole plane */
    fr.size = 64;
    memcpy(fr.dir, f.scene.light_dir, sizeof fr.dir);
    sl_light_view(f.scene.light_dir, fr.box.view);
    glm_ortho_rh_zo(-10, 10, -10, 10, -20, 20, fr.box.proj);
    glm_mat4_mul(fr.box.proj, fr.box.view, fr.box.vp);
    fr.texel_world = 20.0f / 64.0f;
    fr.depth_range = 40.0f;
    assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &fr, SL_NEED(SL_LAYER_DEPTH_ID), &d), SL_OK);

    const struct sl_method *m = &sl_method_pcf3;
    struct sl_method_params p;
    sl_method_params_init(m, &p);
    assert_int_equal(sl_method_configure(m, &p, &d), SL_OK);
    assert_int_equal(m->needs(&p) & ~fr.have, 0);
    const size_t n = (size_t)v.w * (size_t)v.h;
    struct sl_verdicts vd = {.w = v.w, .h = v.h, .v = calloc(n, 1), .how = calloc(n, 1), .tests = calloc(n, 1)};
    assert_non_null(vd.v);
    struct sl_method_args a = {.scene = &f.scene, .view = &mv, .frame = &fr, .params = &p, .rt = &f.rt,
                               .threads = 2};
    struct sl_cost c = {0};
    assert_int_equal(m->run(&a, &vd, &c, &d), SL_OK);
    uint64_t pfl = 0, lit = 0, violations = 0;
    for (size_t i = 0; i < n; i++) {
        if (v.cls[i] != SL_C_PFL)
            continue;
        pfl++;
        assert_int_equal(v.truth[i], SL_T_LIT);
        lit += vd.v[i] == SL_V_LIT;
        violations += sl_exact_violated(SL_EXACT_LIT | SL_EXACT_SHADOW, vd.v[i], vd.how[i], v.truth[i]);
    }
    assert_true(pfl > n / 4);
    assert_int_equal(lit, pfl);
    assert_int_equal(violations, 0);
    assert_int_equal(c.lookups, 9 * pfl);
    assert_int_equal(c.rays, 0);
    free(vd.v);
    free(vd.how);
    free(vd.tests);
    sl_frame_free(&fr);
    sl_shadowmap_free(&sp);
    sl_view_free(&v);
    fixture_close(&f);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(example_method, pcf3_configure),
        SL_CASE(example_method, pcf3_plane_lit),
    };
    return sl_run_group(argc, argv, "example_method", tests, sl_test_setup, sl_test_teardown);
}
