/*
 * contour.c — see contour.h. Invariant: bands only grow outward one 4-step per
 * dilation and never onto background.
 *
 * Rows in parallel, without branches in the inner loops (the compiler
 * vectorises them): a neighbour outside the image counts as background
 * (state 0, band 0), which is what the bounds checks of the plain loop
 * meant — it neither makes an edge nor passes a band on. A dilation only
 * turns band 0 into k + 1 while it reads band == k, so the order pixels
 * are visited in does not change the result. Blocks of rows are
 * independent: each is drawn in a scratch of its own with `dilations` rows
 * of halo above and below (recomputed by both neighbours: 2 * 2 rows per
 * 64 at 1024 wide, 6%), so threads share nothing and wait for nothing
 * between blocks — on a shared machine a barrier waits for a descheduled
 * thread's whole time slice.
 */
#include "contour.h"
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* band of row y from the states: 1 on a change of state, else 0. The
 * first and last pixels apart, so the inner loop has no bounds checks. */
static inline uint8_t edge_px(uint8_t c, uint8_t l, uint8_t r, uint8_t u, uint8_t d)
{
    const int e = (l != 0 && l != c) | (r != 0 && r != c) | (u != 0 && u != c) | (d != 0 && d != c);
    return (uint8_t)((c != 0) & e);
}

static void edge_row(int w, const uint8_t *restrict up, const uint8_t *restrict s, const uint8_t *restrict dn,
                     uint8_t *restrict b)
{
    if (w == 1) {
        b[0] = edge_px(s[0], 0, 0, up[0], dn[0]);
        return;
    }
    b[0] = edge_px(s[0], 0, s[1], up[0], dn[0]);
    for (int x = 1; x < w - 1; x++)
        b[x] = edge_px(s[x], s[x - 1], s[x + 1], up[x], dn[x]);
    b[w - 1] = edge_px(s[w - 1], s[w - 2], 0, up[w - 1], dn[w - 1]);
}

/* one dilation of row y: band 0 on a state next to band k becomes k + 1.
 * It reads the row as it was (old: a copy), which gives the same answer as
 * reading it as it is being written (a pixel written turns 0 into k + 1,
 * never into k) and lets the loop run in vector registers. */
static inline uint8_t dil_px(uint8_t k, uint8_t c, uint8_t s, uint8_t l, uint8_t r, uint8_t u, uint8_t d)
{
    const int touch = (l == k) | (r == k) | (u == k) | (d == k);
    return (uint8_t)(c | ((c == 0) & (s != 0) & touch ? k + 1 : 0));
}

static void dilate_row(int w, uint8_t k, const uint8_t *restrict up, const uint8_t *restrict s,
                       const uint8_t *restrict old, uint8_t *restrict b, const uint8_t *restrict dn)
{
    if (w == 1) {
        b[0] = dil_px(k, old[0], s[0], 0, 0, up[0], dn[0]);
        return;
    }
    b[0] = dil_px(k, old[0], s[0], 0, old[1], up[0], dn[0]);
    for (int x = 1; x < w - 1; x++)
        b[x] = dil_px(k, old[x], s[x], old[x - 1], old[x + 1], up[x], dn[x]);
    b[w - 1] = dil_px(k, old[w - 1], s[w - 1], old[w - 2], 0, up[w - 1], dn[w - 1]);
}

void sl_contour_bands_rows(int w, int h, const uint8_t *state, int dilations, int y0, int y1, uint8_t *band,
                           uint8_t *scratch)
{
    if (w <= 0 || y0 >= y1)
        return;
    const size_t W = (size_t)w;
    /* the rows' bands depend on edges up to `dilations` rows away, and
     * those on the states one row further: edges of the rows [a, b) into
     * the scratch (row 0: a zero row; row 1 + (b - a): another; a copy row
     * after them), then the dilations there; a wrong guess at the scratch's
     * cut (a row beyond it taken as band 0) travels one row per dilation,
     * so it never reaches [y0, y1) */
    const int a = y0 - dilations > 0 ? y0 - dilations : 0, b = y1 + dilations < h ? y1 + dilations : h;
    const int n = b - a;
    uint8_t *zero = scratch, *rows = scratch + W, *old = scratch + W * (size_t)(n + 1);
    memset(zero, 0, W);
    for (int y = a; y < b; y++)
        edge_row(w, y > 0 ? state + (size_t)(y - 1) * W : zero, state + (size_t)y * W,
                 y + 1 < h ? state + (size_t)(y + 1) * W : zero, rows + (size_t)(y - a) * W);
    for (int k = 1; k <= dilations; k++)
        for (int y = a; y < b; y++) {
            uint8_t *r = rows + (size_t)(y - a) * W;
            memcpy(old, r, W);
            dilate_row(w, (uint8_t)k, y > a ? r - W : zero, state + (size_t)y * W, old, r, y + 1 < b ? r + W : zero);
        }
    memcpy(band + (size_t)y0 * W, rows + (size_t)(y0 - a) * W, W * (size_t)(y1 - y0));
}

size_t sl_contour_scratch(int w, int rows, int dilations)
{
    return (size_t)(w > 0 ? w : 0) * (size_t)(rows + 2 * dilations + 2);
}

void sl_contour_bands_mt(int w, int h, const uint8_t *state, int dilations, uint8_t *band, int threads)
{
    if (w <= 0 || h <= 0)
        return;
    if (threads <= 0)
        threads = omp_get_max_threads();
    /* blocks of ~64 K pixels, each with its halo, no barrier between them */
    const int rows = (65536 + w - 1) / w, nblk = (h + rows - 1) / rows;
    const size_t need = sl_contour_scratch(w, rows, dilations);
    uint8_t *scratch = malloc(need * (size_t)threads);
    if (!scratch) {
        sl_contour_bands_plain(w, h, state, dilations, band);
        return;
    }
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (int bi = 0; bi < nblk; bi++) {
        const int y0 = bi * rows, y1 = y0 + rows < h ? y0 + rows : h;
        sl_contour_bands_rows(w, h, state, dilations, y0, y1, band,
                              scratch + need * (size_t)omp_get_thread_num());
    }
    free(scratch);
}

void sl_contour_bands(int w, int h, const uint8_t *state, int dilations, uint8_t *band)
{
    sl_contour_bands_mt(w, h, state, dilations, band, 0);
}

void sl_contour_bands_plain(int w, int h, const uint8_t *state, int dilations, uint8_t *band)
{
    memset(band, 0, (size_t)w * (size_t)h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            uint8_t s = state[i];
            if (!s)
                continue;
            int edge = (x > 0 && state[i - 1] && state[i - 1] != s) ||
                       (x + 1 < w && state[i + 1] && state[i + 1] != s) ||
                       (y > 0 && state[i - (size_t)w] && state[i - (size_t)w] != s) ||
                       (y + 1 < h && state[i + (size_t)w] && state[i + (size_t)w] != s);
            if (edge)
                band[i] = 1;
        }
    for (int k = 1; k <= dilations; k++) {
        uint8_t nb = (uint8_t)(k + 1);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                if (band[i] || !state[i])
                    continue;
                int touch = (x > 0 && band[i - 1] == k) || (x + 1 < w && band[i + 1] == k) ||
                            (y > 0 && band[i - (size_t)w] == k) ||
                            (y + 1 < h && band[i + (size_t)w] == k);
                if (touch)
                    band[i] = nb;
            }
    }
}
