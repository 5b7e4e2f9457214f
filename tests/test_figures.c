/*
 * figures::* — the fused, multithreaded figure pass (figures.c: a histogram
 * of each pixel's classes) against the pixel-by-pixel reference, on inputs
 * drawn at random so that every combination of truth, verdict, how, NSM's
 * verdict and band turns up, with values outside the enums (which the
 * counting rules treat as "anything else") among them; and its exactness
 * count against a plain count of the guarantees, pixel by pixel.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "contour.h"
#include "figures.h"

struct rnd_cell {
    struct sl_view v;
    struct sl_verdicts vd;
    uint8_t *band;
};

static uint32_t rng = 12345u;
static uint32_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

/* a value of 0..n-1, or now and then any byte */
static uint8_t pick(unsigned n) { return next() % 50 == 0 ? (uint8_t)next() : (uint8_t)(next() % n); }

static void make(struct rnd_cell *c, int w, int h, int has_base)
{
    memset(c, 0, sizeof *c);
    size_t n = (size_t)w * (size_t)h;
    c->v.w = c->vd.w = w;
    c->v.h = c->vd.h = h;
    c->v.truth = malloc(n);
    c->v.cls = malloc(n);
    c->vd.v = malloc(n);
    c->vd.how = malloc(n);
    c->vd.base = malloc(n);
    c->vd.tests = malloc(n);
    c->band = malloc(n);
    assert_true(c->v.truth && c->v.cls && c->vd.v && c->vd.how && c->vd.base && c->vd.tests && c->band);
    c->vd.has_base = has_base;
    for (size_t i = 0; i < n; i++) {
        c->v.truth[i] = (uint8_t)(next() % 4);   /* enum sl_truth: nothing else is ever written */
        c->v.cls[i] = pick(3);
        c->vd.v[i] = pick(4);
        c->vd.how[i] = pick(SL_HOW_COUNT);
        c->vd.base[i] = pick(4);
        c->vd.tests[i] = (uint8_t)next();
        c->band[i] = pick(next() % 2 ? 6 : 24);
    }
}

static void drop(struct rnd_cell *c)
{
    free(c->v.truth);
    free(c->v.cls);
    free(c->vd.v);
    free(c->vd.how);
    free(c->vd.base);
    free(c->vd.tests);
    free(c->band);
}

static void same(const struct sl_figures *a, const struct sl_figures *b)
{
    assert_int_equal(a->background, b->background);
    assert_int_equal(a->wrong_image, b->wrong_image);
    assert_int_equal(a->nregions, b->nregions);
    for (int r = 0; r < a->nregions; r++) {
        assert_int_equal(a->r[r].thickness, b->r[r].thickness);
        for (int f = 0; f < SL_FIG_COUNT; f++) {
            if (a->r[r].n[f] != b->r[r].n[f])
                fprintf(stderr, "region %d figure %s: %llu vs %llu\n", r, sl_figure_name((enum sl_figure)f),
                        (unsigned long long)a->r[r].n[f], (unsigned long long)b->r[r].n[f]);
            assert_int_equal(a->r[r].n[f], b->r[r].n[f]);
            assert_true(isnan(a->r[r].pct[f]) ? isnan(b->r[r].pct[f]) : a->r[r].pct[f] == b->r[r].pct[f]);
        }
    }
}

static void figures_fused_matches_pixelwise(void **st)
{
    (void)st;
    /* the last two are thicker than a band class can be clamped to: the
     * region sets are then looked up, not computed */
    static const int regs[][5] = {{2, 4, 6, 0}, {0}, {6, 2, 0, 4}, {16, 0, 2}, {4}, {40, 2, 0}, {30}};
    static const int nregs[] = {4, 1, 4, 3, 1, 3, 1};
    static const int sizes[][2] = {{1, 1}, {7, 5}, {333, 211}, {1024, 97}};
    int nonzero = 0;
    for (int s = 0; s < 4; s++)
        for (int hb = 0; hb < 2; hb++) {
            struct rnd_cell c;
            make(&c, sizes[s][0], sizes[s][1], hb);
            /* a cell without hints: the Moderno PnFL rule turns on them */
            if (s == 2)
                for (size_t i = 0; i < (size_t)c.v.w * (size_t)c.v.h; i++)
                    if (c.vd.how[i] == SL_HOW_HINT)
                        c.vd.how[i] = SL_HOW_MAP;
            for (int g = 0; g < 7; g++) {
                struct sl_figures ref, got;
                sl_figures_compute_pixelwise(&c.v, &c.vd, c.band, regs[g], nregs[g], &ref);
                for (int th = 1; th <= 3; th++) {
                    memset(&got, 0xAB, sizeof got);
                    assert_int_equal(sl_figures_fused(&c.v, &c.vd, c.band, regs[g], nregs[g], 0, th, &got), 0);
                    same(&ref, &got);
                }
                memset(&got, 0xAB, sizeof got);
                sl_figures_compute(&c.v, &c.vd, c.band, regs[g], nregs[g], &got);
                same(&ref, &got);
                nonzero += ref.r[0].n[SL_FIG_pixels] > 0 && ref.r[0].n[SL_FIG_hinted_moderno] > 0;
            }
            drop(&c);
        }
    assert_true(nonzero >= 6);   /* the comparison saw real counts (of 10 cells with hints and NSM) */
}

/* the exactness check's count, pixel by pixel, as cell.c counted it */
static uint64_t plain_bad(const struct rnd_cell *c, unsigned exact)
{
    uint64_t want = 0;
    for (size_t i = 0; i < (size_t)c->v.w * (size_t)c->v.h; i++) {
        if (c->v.cls[i] != SL_C_PFL)
            continue;
        uint8_t how = c->vd.how[i], x = c->vd.v[i], t = c->v.truth[i];
        int proved = how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ || how == SL_HOW_CORRECT ||
                     how == SL_HOW_TRACED;
        int right = (x == SL_V_LIT) == (t == SL_T_LIT);
        want += ((exact & SL_EXACT_LIT) && x == SL_V_LIT && t != SL_T_LIT) ||
                ((exact & SL_EXACT_SHADOW) && x == SL_V_SHADOW && t != SL_T_SHADOW) ||
                ((exact & SL_EXACT_PROVED) && proved && !right);
    }
    return want;
}

static void figures_fused_exactness_count(void **st)
{
    (void)st;
    struct rnd_cell c;
    make(&c, 257, 131, 1);
    const int reg[] = {2, 0};
    for (unsigned exact = 0; exact < 8; exact++) {
        const uint64_t want = plain_bad(&c, exact);
        struct sl_figures f;
        for (int th = 1; th <= 2; th++)
            assert_int_equal(sl_figures_fused(&c.v, &c.vd, c.band, reg, 2, exact, th, &f), want);
        assert_true(exact == 0 ? want == 0 : want > 100);
    }
    drop(&c);
}

/* Bands drawn block by block inside the figure pass: the same bands as the
 * plain contour loop, every row of them, and the same figures and
 * violations, whatever the threads; verdicts in runs, so contours are
 * lines, and sizes that cut into several blocks. */
static void figures_score_fused_matches(void **st)
{
    (void)st;
    static const int sizes[][2] = {{5, 3}, {1024, 300}, {333, 611}};
    static const int regs[][4] = {{2, 4, 6, 0}, {8, 0}, {40, 2, 0}};
    static const int nregs[] = {4, 2, 3};
    for (int s = 0; s < 3; s++) {
        struct rnd_cell c;
        make(&c, sizes[s][0], sizes[s][1], 1);
        size_t n = (size_t)c.v.w * (size_t)c.v.h;
        for (size_t i = 1; i < n; i++)
            if (next() % 17)
                c.vd.v[i] = c.vd.v[i - 1];
        uint8_t *want = malloc(n), *got = malloc(n);
        assert_true(want && got);
        for (int g = 0; g < 3; g++) {
            int maxt = 0;
            for (int r = 0; r < nregs[g]; r++)
                maxt = regs[g][r] > maxt ? regs[g][r] : maxt;
            const int dil = maxt / 2 - 1;
            sl_contour_bands_plain(c.v.w, c.v.h, c.vd.v, dil, want);
            struct sl_figures ref, f;
            sl_figures_compute_pixelwise(&c.v, &c.vd, want, regs[g], nregs[g], &ref);
            uint64_t bad = sl_figures_fused(&c.v, &c.vd, want, regs[g], nregs[g], SL_EXACT_LIT | SL_EXACT_PROVED, 1,
                                            &f);
            for (int th = 1; th <= 3; th++) {
                memset(got, 0xCD, n);
                assert_int_equal(sl_score_fused(&c.v, &c.vd, c.vd.v, dil, got, regs[g], nregs[g],
                                                SL_EXACT_LIT | SL_EXACT_PROVED, th, &f), bad);
                assert_memory_equal(want, got, n);
                same(&ref, &f);
            }
            assert_true(bad > 0);
        }
        free(want);
        free(got);
        drop(&c);
    }
}

/* Cells made of areas, as real images are: each array piecewise constant
 * over tiles of its own size (so the arrays' boundaries cross), with a
 * pixel of noise now and then and ray-triangle tests spent over whole
 * areas. Most runs of 64 pixels then hold one value in every array and
 * are counted whole (figures.c, SPAN_RUN); the figures, the tests and the
 * violations equal the pixel-by-pixel ones, on any thread count. */
static void figures_uniform_runs_match(void **st)
{
    (void)st;
    static const int sizes[][2] = {{64, 64}, {1000, 300}, {333, 211}, {130, 1}};
    static const int regs[] = {2, 4, 6, 0};
    int tested = 0;
    for (int s = 0; s < 4; s++)
        for (int hb = 0; hb < 2; hb++) {
            struct rnd_cell c;
            make(&c, sizes[s][0], sizes[s][1], hb);
            const int w = c.v.w, h = c.v.h;
            const size_t n = (size_t)w * (size_t)h;
            uint8_t *arr[7] = {c.v.truth, c.v.cls, c.vd.v, c.vd.how, c.vd.base, c.vd.tests, c.band};
            static const int tw[7] = {640, 576, 900, 1200, 777, 1500, 450}, tht[7] = {40, 33, 61, 90, 17, 45, 29};
            for (int k = 0; k < 7; k++) {
                /* the first pixel of each tile sets the tile (make's value there) */
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++) {
                        const size_t i = (size_t)y * (size_t)w + (size_t)x;
                        const size_t f = (size_t)(y / tht[k] * tht[k]) * (size_t)w + (size_t)(x / tw[k] * tw[k]);
                        if (next() % 20011)
                            arr[k][i] = arr[k][f];
                    }
                if (k == 0)
                    for (size_t i = 0; i < n; i++)
                        arr[0][i] &= 3u;   /* truth stays in its enum */
                if (k == 5)
                    for (size_t i = 0; i < n; i++)
                        arr[5][i] = arr[5][i] % 3 ? 0 : arr[5][i];   /* most areas spend no test */
            }
            long uniform = 0, mixed = 0;
            for (size_t i = 0; i + 64 <= n; i += 64) {
                int one = 1;
                for (int k = 0; k < 7; k++)
                    for (int j = 1; j < 64; j++)
                        one &= arr[k][i + (size_t)j] == arr[k][i];
                uniform += one;
                mixed += !one;
            }
            assert_true(n <= 4096 || (uniform > mixed && mixed > 0));
            struct sl_figures ref, got;
            sl_figures_compute_pixelwise(&c.v, &c.vd, c.band, regs, 4, &ref);
            for (unsigned exact = 0; exact < 8; exact++) {
                const uint64_t want = plain_bad(&c, exact);
                for (int th = 1; th <= 3; th++) {
                    memset(&got, 0xAB, sizeof got);
                    assert_int_equal(sl_figures_fused(&c.v, &c.vd, c.band, regs, 4, exact, th, &got), want);
                    same(&ref, &got);
                }
            }
            tested += ref.r[3].n[SL_FIG_ray_tri_tests] > 0;
            drop(&c);
        }
    assert_true(tested >= 4);   /* the tests' sums were compared where some were spent */
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(figures, fused_matches_pixelwise),
        SL_CASE(figures, fused_exactness_count),
        SL_CASE(figures, score_fused_matches),
        SL_CASE(figures, uniform_runs_match),
    };
    return sl_run_group(argc, argv, "figures", tests, NULL, NULL);
}
