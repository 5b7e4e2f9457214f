/*
 * softfig::* — the soft-shadow figures on hand-made images whose every
 * number can be worked out on paper.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include "sl_test.h"
#include "softfig.h"

/* 2 x 4 pixels, one background:
 * truth   1    1    0    0.5 | 0.25  0   (bg)  1
 * method  1    0.92 0    0.46| 0.5   0.02 (bg) 1      */
static void softfig_worked_example(void **st)
{
    (void)st;
    const uint32_t tri[8] = {1, 1, 1, 1, 1, 1, 0, 1};
    const float t[8] = {1, 1, 0, 0.5f, 0.25f, 0, 0.7f, 1};
    const float v[8] = {1, 0.92f, 0, 0.46f, 0.5f, 0.02f, 0.1f, 1};
    const float se[8] = {0, 0, 0, 0.1f, 0.2f, 0, 9, 0};
    struct sl_soft_figures f;
    sl_soft_figures_compute(4, 2, tri, v, t, se, 0.0, &f);
    assert_int_equal(f.n[SL_SFIG_soft_pixels], 7);
    /* errors 0, -0.08, 0, -0.04, +0.25, +0.02, 0 */
    assert_true(fabs(f.pct[SL_SFIG_soft_mae] - 100.0 * 0.39 / 7) < 1e-4);
    assert_true(fabs(f.pct[SL_SFIG_soft_rmse] - 100.0 * sqrt((0.0064 + 0.0016 + 0.0625 + 0.0004) / 7)) < 1e-4);
    assert_true(fabs(f.pct[SL_SFIG_soft_bias] - 100.0 * 0.15 / 7) < 1e-4);
    assert_int_equal(f.n[SL_SFIG_soft_within_005], 5);   /* 0, 0, -0.04, +0.02, 0 */
    assert_int_equal(f.n[SL_SFIG_soft_within_010], 6);
    assert_int_equal(f.n[SL_SFIG_soft_truth_lit], 3);
    assert_int_equal(f.n[SL_SFIG_soft_truth_umbra], 2);
    assert_int_equal(f.n[SL_SFIG_soft_truth_penumbra], 2);
    assert_int_equal(f.n[SL_SFIG_soft_lit_right], 2);      /* 0.92 is penumbra */
    assert_int_equal(f.n[SL_SFIG_soft_umbra_right], 1);    /* 0.02 is penumbra */
    assert_int_equal(f.n[SL_SFIG_soft_penumbra_right], 2);
    assert_int_equal(f.n[SL_SFIG_soft_class_right], 5);
    assert_true(fabs(f.pct[SL_SFIG_soft_class_right] - 100.0 * 5 / 7) < 1e-9);
    assert_true(fabs(f.pct[SL_SFIG_soft_lit_right] - 100.0 * 2 / 3) < 1e-9);
    assert_true(fabs(f.pct[SL_SFIG_soft_truth_stderr] - 100.0 * 0.3 / 7) < 1e-4);   /* background's 9 left out */
    assert_true(isnan(f.pct[SL_SFIG_soft_pixels]));
}

/* No pixel: no division by zero, NaN percentages. */
static void softfig_empty(void **st)
{
    (void)st;
    const uint32_t tri[2] = {0, 0};
    const float z[2] = {0, 0};
    struct sl_soft_figures f;
    sl_soft_figures_compute(2, 1, tri, z, z, NULL, 0.0, &f);
    assert_int_equal(f.n[SL_SFIG_soft_pixels], 0);
    for (int k = 0; k < SL_SFIG_COUNT; k++)
        assert_true(isnan(f.pct[k]));
}

/* A hard light's 0/1 truth and a filtered visibility that is never exactly
 * 0 or 1: exact classes call every pixel penumbra (0 right of 6); within
 * SL_SOFT_HARD_TOL a class is right exactly when |v - t| <= 0.05, so class
 * right equals within 0.05 and the lit and umbra shares say what is
 * over-darkened and what leaks by more than the tolerance.
 * truth   1     1     1    0     0     0
 * method  0.97  0.96  0.6  0.01  0.04  0.3  */
static void softfig_hard_tolerance(void **st)
{
    (void)st;
    const uint32_t tri[6] = {1, 1, 1, 1, 1, 1};
    const float t[6] = {1, 1, 1, 0, 0, 0};
    const float v[6] = {0.97f, 0.96f, 0.6f, 0.01f, 0.04f, 0.3f};
    struct sl_soft_figures f;
    sl_soft_figures_compute(3, 2, tri, v, t, NULL, 0.0, &f);
    assert_int_equal(f.n[SL_SFIG_soft_class_right], 0);
    sl_soft_figures_compute(3, 2, tri, v, t, NULL, SL_SOFT_HARD_TOL, &f);
    assert_int_equal(f.n[SL_SFIG_soft_truth_lit], 3);
    assert_int_equal(f.n[SL_SFIG_soft_truth_umbra], 3);
    assert_int_equal(f.n[SL_SFIG_soft_truth_penumbra], 0);
    assert_int_equal(f.n[SL_SFIG_soft_lit_right], 2);     /* 0.6: over-darkened by 0.4 */
    assert_int_equal(f.n[SL_SFIG_soft_umbra_right], 2);   /* 0.3: leaks 0.3 */
    assert_int_equal(f.n[SL_SFIG_soft_penumbra_right], 0);
    assert_true(isnan(f.pct[SL_SFIG_soft_penumbra_right]));
    assert_int_equal(f.n[SL_SFIG_soft_class_right], 4);
    assert_int_equal(f.n[SL_SFIG_soft_class_right], f.n[SL_SFIG_soft_within_005]);
    assert_true(fabs(f.pct[SL_SFIG_soft_class_right] - 100.0 * 4 / 6) < 1e-9);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(softfig, worked_example),
        SL_CASE(softfig, empty),
        SL_CASE(softfig, hard_tolerance),
    };
    return sl_run_group(argc, argv, "softfig", tests, NULL, NULL);
}
