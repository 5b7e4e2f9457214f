/* contour::* — contour widths and neighbourhood on synthetic result images. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "contour.h"

#define W 32
#define H 16

/* count of pixels in row y inside the contour of thickness t */
static int row_count(const uint8_t *band, int y, int t)
{
    int n = 0;
    for (int x = 0; x < W; x++)
        n += band[y * W + x] && sl_in_contour(band[y * W + x], t);
    return n;
}

static void contour_vertical_edge_widths(void **st)
{
    (void)st;
    uint8_t s[W * H], b[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            s[y * W + x] = x < 16 ? 1 : 2;   /* lit | shadow */
    sl_contour_bands(W, H, s, 2, b);
    for (int y = 0; y < H; y++) {
        assert_int_equal(row_count(b, y, 2), 2);
        assert_int_equal(row_count(b, y, 4), 4);
        assert_int_equal(row_count(b, y, 6), 6);
    }
    /* balanced: as many lit as shadowed pixels on each side */
    assert_int_equal(b[5 * W + 15], 1);
    assert_int_equal(b[5 * W + 16], 1);
    assert_int_equal(b[5 * W + 14], 2);
    assert_int_equal(b[5 * W + 17], 2);
    assert_int_equal(b[5 * W + 13], 3);
    assert_int_equal(b[5 * W + 18], 3);
    assert_int_equal(b[5 * W + 12], 0);
}

static void contour_uniform_image_has_none(void **st)
{
    (void)st;
    uint8_t s[W * H], b[W * H];
    memset(s, 2, sizeof s);
    sl_contour_bands(W, H, s, 2, b);
    for (int i = 0; i < W * H; i++)
        assert_int_equal(b[i], 0);
}

static void contour_background_never_enters(void **st)
{
    (void)st;
    uint8_t s[W * H], b[W * H];
    /* left third background, then lit, then shadow */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            s[y * W + x] = x < 10 ? 0 : (x < 20 ? 1 : 2);
    sl_contour_bands(W, H, s, 4, b);
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < 10; x++)
            assert_int_equal(b[y * W + x], 0);
        /* the silhouette lit|background makes no contour */
        assert_int_equal(b[y * W + 10], 0);
        /* the lit|shadow change at 19|20 does, dilated up to 5 bands */
        assert_int_equal(b[y * W + 19], 1);
        assert_int_equal(b[y * W + 15], 5);
        assert_int_equal(b[y * W + 14], 0);
    }
}

static void contour_single_pixel_diamond(void **st)
{
    (void)st;
    uint8_t s[W * H], b[W * H];
    memset(s, 1, sizeof s);
    s[8 * W + 16] = 2;     /* one shadowed pixel */
    sl_contour_bands(W, H, s, 1, b);
    int n1 = 0, n2 = 0;
    for (int i = 0; i < W * H; i++) {
        n1 += b[i] == 1;
        n2 += b[i] == 2;
    }
    assert_int_equal(n1, 5);     /* the pixel and its 4 neighbours */
    assert_int_equal(n2, 8);     /* the 4-neighbour ring around that cross */
}

static void contour_whole_image_region(void **st)
{
    (void)st;
    assert_true(sl_in_contour(0, 0));
    assert_false(sl_in_contour(0, 2));
    assert_true(sl_in_contour(1, 2));
    assert_false(sl_in_contour(2, 2));
    assert_true(sl_in_contour(3, 6));
}

/* The rows-in-parallel bands equal the plain loop's, whatever the size
 * (down to one row or column, and blocks of three rows), the states
 * (background among them), the dilations and the thread count. */
static void contour_parallel_matches_plain(void **st)
{
    (void)st;
    /* the last two cut into blocks of rows (~64 K pixels each) drawn apart */
    static const int sz[][2] = {{1, 1},   {1, 9},      {9, 1},      {2, 2},    {5, 7},
                                {64, 3},  {301, 203},  {1000, 37},  {1024, 300}, {7, 30000}};
    uint32_t r = 7u;
    int banded = 0;
    for (int s = 0; s < 10; s++) {
        int w = sz[s][0], h = sz[s][1];
        size_t n = (size_t)w * (size_t)h;
        uint8_t *state = malloc(n), *a = malloc(n), *b = malloc(n);
        assert_true(state && a && b);
        for (int pass = 0; pass < 2; pass++) {
            /* pass 0: noise; pass 1: blobs (runs of one state) */
            for (size_t i = 0; i < n; i++) {
                r ^= r << 13, r ^= r >> 17, r ^= r << 5;
                state[i] = pass == 0 || i == 0 || r % 23 == 0 ? (uint8_t)(r % 4) : state[i - 1];
            }
            for (int dil = 0; dil <= 4; dil++) {
                sl_contour_bands_plain(w, h, state, dil, a);
                for (int th = 1; th <= 5; th++) {
                    memset(b, 0xCD, n);
                    sl_contour_bands_mt(w, h, state, dil, b, th);
                    assert_memory_equal(a, b, n);
                }
                for (size_t i = 0; i < n; i++)
                    banded += a[i] == dil + 1 && dil >= 2;
            }
        }
        free(state);
        free(a);
        free(b);
    }
    assert_true(banded > 1000);   /* the dilations reached far */
}

/* Images of a few large areas (rectangles of states 1..3 over background,
 * some reaching the image's borders), where most 64-pixel segments of a
 * row lie inside one state: those are skipped by the edge and dilation
 * passes (contour.c, SEG). Widths around multiples of the segment, so
 * short last segments and segments at both borders are drawn too; the
 * bands equal the plain loop's for every dilation and thread count. */
static void contour_segments_match_plain(void **st)
{
    (void)st;
    static const int ws[] = {1, 63, 64, 65, 127, 128, 129, 200, 1000};
    static const int hs[] = {1, 2, 3, 50, 301};
    uint32_t r = 99u;
    long skipped = 0, drawn = 0;
    for (int wi = 0; wi < 9; wi++)
        for (int hi = 0; hi < 5; hi++) {
            const int w = ws[wi], h = hs[hi];
            const size_t n = (size_t)w * (size_t)h;
            uint8_t *state = calloc(n, 1), *a = malloc(n), *b = malloc(n);
            assert_true(state && a && b);
            for (int q = 0; q < 12; q++) {
                r ^= r << 13, r ^= r >> 17, r ^= r << 5;
                const int x0 = (int)(r % (unsigned)w) - w / 8, y0 = (int)((r >> 8) % (unsigned)h) - h / 8;
                const int x1 = x0 + 1 + (int)((r >> 16) % (unsigned)(w / 2 + 1));
                const int y1 = y0 + 1 + (int)((r >> 20) % (unsigned)(h / 2 + 1));
                const uint8_t v = q == 0 ? 2 : (uint8_t)(r % 4);   /* 0: a hole of background */
                for (int y = y0 < 0 ? 0 : y0; y < y1 && y < h; y++)
                    for (int x = x0 < 0 ? 0 : x0; x < x1 && x < w; x++)
                        state[(size_t)y * (size_t)w + (size_t)x] = v;
            }
            /* segments the edge pass can skip: one state over 64 pixels and the rows around */
            for (int y = 1; y + 1 < h; y++)
                for (int x0 = 0; x0 + 64 <= w; x0 += 64) {
                    int one = 1;
                    const uint8_t c = state[(size_t)y * (size_t)w + (size_t)x0];
                    for (int dy = -1; dy <= 1; dy++)
                        for (int x = x0; x < x0 + 64; x++)
                            one &= state[(size_t)(y + dy) * (size_t)w + (size_t)x] == c;
                    skipped += one;
                    drawn += !one;
                }
            for (int dil = 0; dil <= 4; dil++) {
                sl_contour_bands_plain(w, h, state, dil, a);
                for (int th = 1; th <= 3; th++) {
                    memset(b, 0xCD, n);
                    sl_contour_bands_mt(w, h, state, dil, b, th);
                    assert_memory_equal(a, b, n);
                }
            }
            /* one state over the whole image: no band at all */
            memset(state, 3, n);
            memset(b, 0xCD, n);
            sl_contour_bands_mt(w, h, state, 2, b, 2);
            sl_contour_bands_plain(w, h, state, 2, a);
            assert_memory_equal(a, b, n);
            free(state);
            free(a);
            free(b);
        }
    assert_true(skipped > 1000 && drawn > 100);   /* both kinds of segment were there */
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(contour, vertical_edge_widths),
        SL_CASE(contour, uniform_image_has_none),
        SL_CASE(contour, background_never_enters),
        SL_CASE(contour, single_pixel_diamond),
        SL_CASE(contour, whole_image_region),
        SL_CASE(contour, parallel_matches_plain),
        SL_CASE(contour, segments_match_plain),
    };
    return sl_run_group(argc, argv, "contour", tests, NULL, NULL);
}
