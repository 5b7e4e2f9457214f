/* slices::* — the sweep cut into tasks (plan.h, sl_plan_slices): every cell
 * in exactly one slice, in order, none empty; each slice within half an even
 * share of it; cuts on view boundaries wherever the views allow, and the
 * count of views a cut lands inside (the sharing a split loses) exact. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "plan.h"

static int view_starts(const struct sl_config *c, int i)
{
    if (i == 0)
        return 1;
    struct sl_cell_key a, b;
    sl_plan_cell(c, i - 1, &a);
    sl_plan_cell(c, i, &b);
    return a.scene != b.scene || a.viewport != b.viewport || a.vp != b.vp;
}

/* The invariants of any split; returns the cuts that land inside a view. */
static int check_split(const struct sl_config *c, int want, const int *b, int n)
{
    int total = sl_plan_count(c);
    assert_true(n >= 1 && n <= want);
    assert_int_equal(b[0], 0);
    assert_int_equal(b[n], total);
    double share = (double)total / (want < total ? want : total);
    int inside = 0;
    for (int i = 0; i < n; i++) {
        assert_true(b[i + 1] > b[i]);
        assert_true(b[i + 1] - b[i] <= (int)(1.5 * share) + 2);
        inside += !view_starts(c, b[i]);
    }
    return inside;
}

static void slices_morais(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/morais-2015.yaml", &c, &d), SL_OK);
    int b[65], nviews = 0;
    for (int want = 1; want <= 64; want++) {
        int n = sl_plan_slices(&c, want, b);
        int inside = check_split(&c, want, b, n);
        assert_int_equal(sl_plan_split_views(&c, b, n, &nviews), inside);
        assert_int_equal(nviews, 27);
        assert_int_equal(n, want);
        /* Morais's views hold 32 cells each: while a slice is at least two
         * views long, a view boundary is always within a quarter of it */
        if (864 / want >= 128)
            assert_int_equal(inside, 0);
    }
    sl_config_free(&c);
}

static void slices_ci_by_view(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/ci.yaml", &c, &d), SL_OK);
    int b[8], nviews = 0;
    int n = sl_plan_slices(&c, 4, b);
    assert_int_equal(n, 4);   /* 4 views of 34 to 44 cells: one view a task */
    assert_int_equal(check_split(&c, 4, b, n), 0);
    assert_int_equal(sl_plan_split_views(&c, b, n, &nviews), 0);
    assert_int_equal(nviews, 4);
    /* more tasks than cells: one cell each, every view but the first cut */
    int total = sl_plan_count(&c);
    int *many = calloc((size_t)total + 2, sizeof *many);
    assert_non_null(many);
    n = sl_plan_slices(&c, total + 5, many);
    assert_int_equal(n, total);
    for (int i = 0; i <= n; i++)
        assert_int_equal(many[i], i);
    assert_int_equal(sl_plan_split_views(&c, many, n, NULL), total - 4);
    free(many);
    sl_config_free(&c);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(slices, morais),
        SL_CASE(slices, ci_by_view),
    };
    return sl_run_group(argc, argv, "slices", tests, NULL, NULL);
}
