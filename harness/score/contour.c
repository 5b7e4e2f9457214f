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

/* band of a pixel from the states: 1 on a change of state, else 0 */
static inline uint8_t edge_px(uint8_t c, uint8_t l, uint8_t r, uint8_t u, uint8_t d)
{
    const int e = (l != 0 && l != c) | (r != 0 && r != c) | (u != 0 && u != c) | (d != 0 && d != c);
    return (uint8_t)((c != 0) & e);
}

/* one dilation of a pixel: band 0 on a state next to band k becomes k + 1 */
static inline uint8_t dil_px(uint8_t k, uint8_t c, uint8_t s, uint8_t l, uint8_t r, uint8_t u, uint8_t d)
{
    const int touch = (l == k) | (r == k) | (u == k) | (d == k);
    return (uint8_t)(c | ((c == 0) & (s != 0) & touch ? k + 1 : 0));
}

/* Segments of SEG pixels of a row (one cache line; the last one of a row
 * may be shorter). Most segments of an image lie inside one state, away
 * from any change: their edges are 0 and no dilation reaches them. So a
 * segment is tested first (a few word operations) and drawn only where
 * something can happen; nz[] keeps, per segment of each scratch row,
 * whether it holds any band yet (an over-estimate is harmless: the segment
 * is then drawn, and drawing is exact). Measured on the bench's side view
 * (bench --only scoring), one thread: 0.45 ms per 1 M pixels for the
 * bands before, drawn pixel by pixel in vector registers. */
#define SEG 64

/* SEG is the 64 bytes sl_bytes64_dev (contour.h) tests at once */
_Static_assert(SEG == 64, "segments are sl_bytes64_dev's 64 bytes");

static inline uint8_t any_n(const uint8_t *p, int n)
{
    if (n == SEG)
        return sl_bytes64_dev(p, 0) != 0;
    uint8_t a = 0;
    for (int x = 0; x < n; x++)
        a |= p[x];
    return a != 0;
}

/* the edges of row pixels [x0, x1); a neighbour outside the image counts
 * as background (state 0), which is what the plain loop's bounds checks
 * meant: it neither makes an edge nor passes a band on */
static void edge_seg(int w, const uint8_t *restrict up, const uint8_t *restrict s, const uint8_t *restrict dn,
                     uint8_t *restrict b, int x0, int x1)
{
    if (x0 > 0 && x1 < w && x1 - x0 == SEG) {
        /* an inner segment: a fixed count, no bounds, vector registers */
        up += x0, s += x0, dn += x0, b += x0;
        for (int x = 0; x < SEG; x++)
            b[x] = edge_px(s[x], s[x - 1], s[x + 1], up[x], dn[x]);
        return;
    }
    for (int x = x0; x < x1; x++)
        b[x] = edge_px(s[x], x > 0 ? s[x - 1] : 0, x + 1 < w ? s[x + 1] : 0, up[x], dn[x]);
}

static void edge_row(int w, const uint8_t *restrict up, const uint8_t *restrict s, const uint8_t *restrict dn,
                     uint8_t *restrict b, uint8_t *restrict nz)
{
    for (int x0 = 0, j = 0; x0 < w; x0 += SEG, j++) {
        const int x1 = x0 + SEG < w ? x0 + SEG : w;
        const uint8_t c = s[x0];
        /* one state over the segment, its neighbours left and right, and
         * the rows above and below (or all background): no change, no edge */
        if (x1 - x0 == SEG && !sl_bytes64_dev(s + x0, c) &&
            (c == 0 || (!sl_bytes64_dev(up + x0, c) && !sl_bytes64_dev(dn + x0, c) && (x0 == 0 || s[x0 - 1] == c) &&
                        (x1 == w || s[x1] == c)))) {
            memset(b + x0, 0, SEG);
            nz[j] = 0;
            continue;
        }
        edge_seg(w, up, s, dn, b, x0, x1);
        nz[j] = any_n(b + x0, x1 - x0);
    }
}

/* One dilation of a row, in place: band 0 on a state next to band k
 * becomes k + 1. Each drawn segment reads a copy of itself and of its two
 * neighbour pixels (old), so the loop runs in vector registers. Reading
 * the row above as this pass left it, and the left neighbour as this pass
 * left it, gives the same answer as reading them as they were: a pixel
 * written turns 0 into k + 1, never into k. A segment is left as it is
 * when neither it, its neighbours in the row, nor the segments above and
 * below hold any band: then no neighbour of its pixels is k. */
static void dilate_row(int w, uint8_t k, const uint8_t *restrict up, const uint8_t *restrict s,
                       uint8_t *restrict b, const uint8_t *restrict dn, const uint8_t *restrict nz_up,
                       uint8_t *restrict nz, const uint8_t *restrict nz_dn)
{
    const int nseg = (w + SEG - 1) / SEG;
    for (int j = 0; j < nseg; j++) {
        if (!(nz[j] | nz_up[j] | nz_dn[j] | (j > 0 ? nz[j - 1] : 0) | (j + 1 < nseg ? nz[j + 1] : 0)))
            continue;
        const int x0 = j * SEG, x1 = x0 + SEG < w ? x0 + SEG : w, n = x1 - x0;
        uint8_t old[SEG + 2];
        old[0] = x0 > 0 ? b[x0 - 1] : 0;
        memcpy(old + 1, b + x0, (size_t)n);
        old[n + 1] = x1 < w ? b[x1] : 0;
        if (n == SEG) {
            const uint8_t *u = up + x0, *st = s + x0, *dd = dn + x0;
            uint8_t *o = b + x0;
            for (int x = 0; x < SEG; x++)
                o[x] = dil_px(k, old[x + 1], st[x], old[x], old[x + 2], u[x], dd[x]);
        } else {
            for (int x = 0; x < n; x++)
                b[x0 + x] = dil_px(k, old[x + 1], s[x0 + x], old[x], old[x + 2], up[x0 + x], dn[x0 + x]);
        }
        nz[j] = any_n(b + x0, n);
    }
}

void sl_contour_bands_rows(int w, int h, const uint8_t *state, int dilations, int y0, int y1, uint8_t *band,
                           uint8_t *scratch)
{
    if (w <= 0 || y0 >= y1)
        return;
    const size_t W = (size_t)w, nseg = (W + SEG - 1) / SEG;
    /* the rows' bands depend on edges up to `dilations` rows away, and
     * those on the states one row further: edges of the rows [a, b) into
     * the scratch (row 0: a zero row, then the rows), then the dilations
     * there, a row beyond the scratch taken as band 0; such a wrong guess
     * at the scratch's cut travels one row per dilation, so it never
     * reaches [y0, y1). After the rows, their segments' flags (nz), with a
     * zero row of flags first. */
    const int a = y0 - dilations > 0 ? y0 - dilations : 0, b = y1 + dilations < h ? y1 + dilations : h;
    const int n = b - a;
    uint8_t *zero = scratch, *rows = scratch + W;
    uint8_t *nzero = scratch + W * (size_t)(n + 1), *nz = nzero + nseg;
    memset(zero, 0, W);
    memset(nzero, 0, nseg);
    for (int y = a; y < b; y++)
        edge_row(w, y > 0 ? state + (size_t)(y - 1) * W : zero, state + (size_t)y * W,
                 y + 1 < h ? state + (size_t)(y + 1) * W : zero, rows + (size_t)(y - a) * W,
                 nz + (size_t)(y - a) * nseg);
    for (int k = 1; k <= dilations; k++)
        for (int y = a; y < b; y++) {
            uint8_t *r = rows + (size_t)(y - a) * W, *f = nz + (size_t)(y - a) * nseg;
            dilate_row(w, (uint8_t)k, y > a ? r - W : zero, state + (size_t)y * W, r, y + 1 < b ? r + W : zero,
                       y > a ? f - nseg : nzero, f, y + 1 < b ? f + nseg : nzero);
        }
    memcpy(band + (size_t)y0 * W, rows + (size_t)(y0 - a) * W, W * (size_t)(y1 - y0));
}

size_t sl_contour_scratch(int w, int rows, int dilations)
{
    /* a zero row and up to rows + 2 dilations rows, each with its flags */
    const size_t W = (size_t)(w > 0 ? w : 0), nseg = (W + SEG - 1) / SEG;
    return (W + nseg) * (size_t)(rows + 2 * dilations + 1);
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
