/*
 * overlay.c — see overlay.h. The grey is Lambert on the face normal:
 * 0.12 ambient, plus 0.5 * dot(n, l) where the method says lit.
 *
 * Invariant: a pixel is wrong here exactly when figures.c counts it wrong
 * (said lit while not lit in truth, or said shadowed while lit), so the
 * overlay's error colours add up to the cell's wrong pixels.
 */
#include "overlay.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "contour.h"

const uint8_t sl_overlay_colour[SL_OV_CLASSES][3] = {
    [SL_OV_LIT_WRONG] = {213, 94, 0},       /* vermillion */
    [SL_OV_SHADOW_WRONG] = {240, 228, 66},  /* yellow */
    [SL_OV_WRONG_OUTSIDE] = {0, 114, 178},  /* blue */
    [SL_OV_UNCERTAIN] = {204, 121, 167},    /* reddish purple */
    [SL_OV_CONTOUR] = {0, 158, 115},        /* bluish green, blended */
    [SL_OV_OUTSIDE_CONE] = {56, 56, 56},    /* the hatching's light stripe */
};

/* The colour of a pixel drawn right: grey shaded by n.l where the method
 * says lit, the ambient alone where it says shadowed; the faint tint inside
 * the contour. */
static void right_colour(const struct sl_view *v, const float light_dir[3], const float *light_pos, int lit,
                         int tint, size_t i, uint8_t *o)
{
    /* n.l only where the method says lit (the shadowed grey is the
     * ambient alone): most of this loop's time was reading the normals */
    float ndl = 0.0f;
    if (lit) {
        const float *nn = v->nrm + 3 * i;
        ndl = -(nn[0] * light_dir[0] + nn[1] * light_dir[1] + nn[2] * light_dir[2]);
        if (light_pos) {
            const float *p = v->pos + 3 * i;
            float l[3] = {light_pos[0] - p[0], light_pos[1] - p[1], light_pos[2] - p[2]};
            float len = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            ndl = len > 0.0f ? (nn[0] * l[0] + nn[1] * l[1] + nn[2] * l[2]) / len : 0.0f;
        }
    }
    float g = 255.0f * (0.12f + (ndl > 0.0f ? 0.5f * ndl : 0.0f));
    if (tint) {
        /* the faint tint: 65% grey, 35% bluish green */
        const uint8_t *c = sl_overlay_colour[SL_OV_CONTOUR];
        for (int j = 0; j < 3; j++)
            o[j] = (uint8_t)(0.65f * g + 0.35f * (float)c[j] + 0.5f);
        return;
    }
    o[0] = o[1] = o[2] = (uint8_t)(g + 0.5f);
}

/* The codes of build's first pass: the error classes (SL_OV_LIT_WRONG ..
 * SL_OV_UNCERTAIN, 0-3) and how a pixel drawn right gets its colour. */
enum {
    CODE_BACKGROUND = SL_OV_UNCERTAIN + 1,   /* black */
    CODE_DARK,                              /* right, not said lit: the ambient grey */
    CODE_DARK_TINT,                         /* the same inside the contour */
    CODE_LIT,                               /* right, said lit: n.l (the shade's, or computed) */
    CODE_LIT_TINT,
    CODE_CONE,                              /* right, outside a spot's cone: hatched */
    CODES
};
/* Pixels per chunk: the codes stay in L1 between the two passes. */
enum { CHUNK = 4096 };

/* lit: the lit colours of the view's pixels (a shade's, 3 bytes a pixel
 * and every byte written), or NULL: each computed where needed.
 *
 * Two passes per chunk (issue 20: the one branchy loop that decided and
 * drew each pixel was 4% of the Moderno study's samples): the first gives
 * each pixel a code with byte compares and selects only, which vectorise,
 * and counts the codes; the second draws each code's colour, a constant
 * of the code or the shade's lit colour, as one 4-byte store a pixel (its
 * fourth byte overwritten by the next pixel's). */
static void build(const uint8_t *lit, const struct sl_view *v, const float light_dir[3], const float *light_pos,
                  const struct sl_verdicts *vd, const uint8_t *band, int thickness, uint8_t *rgb, uint8_t *err,
                  uint64_t count[SL_OV_CLASSES])
{
    _Static_assert(SL_OV_LIT_WRONG == 0 && SL_OV_SHADOW_WRONG == 1 && SL_OV_WRONG_OUTSIDE == 2 &&
                       SL_OV_UNCERTAIN == 3,
                   "the error classes are codes 0-3");
    _Static_assert(CODES <= 16, "the codes' counters");
    const size_t n = (size_t)v->w * (size_t)v->h;
    /* sl_in_contour(b, thickness) as byte compares: every pixel when the
     * thickness is 0, else a band b with 0 < b <= thickness / 2 */
    const uint8_t all_in = thickness == 0, tint_ok = thickness > 0;
    const int hi = thickness / 2 > 255 ? 255 : thickness / 2 < 0 ? 0 : thickness / 2;
    const uint8_t hi8 = (uint8_t)hi;
    /* each constant code's colour, packed as a little-endian 4-byte word */
    uint32_t pal[CODES] = {0};
    for (int k = 0; k <= SL_OV_UNCERTAIN; k++)
        pal[k] = (uint32_t)sl_overlay_colour[k][0] | (uint32_t)sl_overlay_colour[k][1] << 8 |
                 (uint32_t)sl_overlay_colour[k][2] << 16;
    for (int c = CODE_DARK; c <= CODE_DARK_TINT; c++) {
        uint8_t o[3];
        right_colour(v, light_dir, light_pos, 0, c == CODE_DARK_TINT, 0, o);
        pal[c] = (uint32_t)o[0] | (uint32_t)o[1] << 8 | (uint32_t)o[2] << 16;
    }
    uint64_t tally[CODES] = {0};
    uint8_t code[CHUNK];
    for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
        const size_t m = n - i0 < CHUNK ? n - i0 : CHUNK;
        const uint8_t *t = v->truth + i0, *vv = vd->v + i0, *b = band + i0;
        /* counts of the codes, one counter each (a counter array indexed
         * by the code would not vectorise) */
        uint32_t c0 = 0, c1 = 0, c2 = 0, c3 = 0, ct = 0;
        for (size_t j = 0; j < m; j++) {
            const uint8_t tj = t[j], vj = vv[j], bj = b[j];
            const uint8_t in = all_in | ((bj != 0) & (bj <= hi8));
            const uint8_t bg = tj == SL_T_BACKGROUND, tl = tj == SL_T_LIT;
            const uint8_t said_lit = vj == SL_V_LIT;
            const uint8_t wrong_lit = said_lit & !tl & !bg, wrong_shadow = (vj == SL_V_SHADOW) & tl;
            const uint8_t unc = (vj == SL_V_UNCERTAIN) & !bg;
            const uint8_t tint = in & tint_ok;
            uint8_t k = (uint8_t)((said_lit ? CODE_LIT : CODE_DARK) + tint);
            k = unc ? (uint8_t)SL_OV_UNCERTAIN : k;
            k = wrong_shadow ? (in ? (uint8_t)SL_OV_SHADOW_WRONG : (uint8_t)SL_OV_WRONG_OUTSIDE) : k;
            k = wrong_lit ? (in ? (uint8_t)SL_OV_LIT_WRONG : (uint8_t)SL_OV_WRONG_OUTSIDE) : k;
            k = bg ? (uint8_t)CODE_BACKGROUND : k;
            code[j] = k;
            c0 += k == SL_OV_LIT_WRONG;
            c1 += k == SL_OV_SHADOW_WRONG;
            c2 += k == SL_OV_WRONG_OUTSIDE;
            c3 += k == SL_OV_UNCERTAIN;
            ct += (k == CODE_DARK_TINT) | (k == CODE_LIT_TINT);
        }
        if (v->outside) {
            /* outside the spot's cone, right (said shadowed or PnFL):
             * diagonal stripes, 2 of every 8 px at 56, the rest at 12, so
             * the cone's footprint reads apart from the background (0),
             * the shadowed grey (31) and the lit grey (31-158); not a
             * contour pixel then */
            const uint8_t *out = v->outside + i0;
            for (size_t j = 0; j < m; j++)
                if (out[j] && code[j] >= CODE_DARK && code[j] != CODE_BACKGROUND) {
                    ct -= code[j] == CODE_DARK_TINT || code[j] == CODE_LIT_TINT;
                    code[j] = CODE_CONE;
                    tally[CODE_CONE]++;
                }
        }
        tally[SL_OV_LIT_WRONG] += c0;
        tally[SL_OV_SHADOW_WRONG] += c1;
        tally[SL_OV_WRONG_OUTSIDE] += c2;
        tally[SL_OV_UNCERTAIN] += c3;
        tally[CODE_DARK_TINT] += ct;
        if (err)
            for (size_t j = 0; j < m; j++)
                err[i0 + j] = code[j] <= SL_OV_UNCERTAIN ? 255 : 0;
        uint8_t *o = rgb + 3 * i0;
        if (lit) {
            /* all but the chunk's last pixel as 4-byte stores; the shade's
             * word read over the next pixel's first byte, in the buffer */
            const uint8_t *l = lit + 3 * i0;
            for (size_t j = 0; j + 1 < m; j++) {
                uint32_t w;
                memcpy(&w, l + 3 * j, 4);
                w = code[j] >= CODE_LIT ? w : pal[code[j]];
                memcpy(o + 3 * j, &w, 4);
            }
        } else {
            for (size_t j = 0; j + 1 < m; j++)
                memcpy(o + 3 * j, &pal[code[j]], 4);
        }
        /* the chunk's last pixel, 3 bytes; without a shade, each lit
         * colour computed; the hatching */
        memcpy(o + 3 * (m - 1), &pal[code[m - 1]], 3);
        if (lit && code[m - 1] >= CODE_LIT)
            memcpy(o + 3 * (m - 1), lit + 3 * (i0 + m - 1), 3);
        if (!lit)
            for (size_t j = 0; j < m; j++)
                if (code[j] == CODE_LIT || code[j] == CODE_LIT_TINT)
                    right_colour(v, light_dir, light_pos, 1, code[j] == CODE_LIT_TINT, i0 + j, o + 3 * j);
        if (v->outside)
            for (size_t j = 0; j < m; j++)
                if (code[j] == CODE_CONE) {
                    const size_t x = (i0 + j) % (size_t)v->w, y = (i0 + j) / (size_t)v->w;
                    const uint8_t g8 = (x + y) % 8 < 2 ? sl_overlay_colour[SL_OV_OUTSIDE_CONE][0] : 12;
                    o[3 * j] = o[3 * j + 1] = o[3 * j + 2] = g8;
                }
    }
    if (count) {
        for (int k = 0; k <= SL_OV_UNCERTAIN; k++)
            count[k] = tally[k];
        count[SL_OV_CONTOUR] = tally[CODE_DARK_TINT];
        count[SL_OV_OUTSIDE_CONE] = tally[CODE_CONE];
    }
}

void sl_overlay_build(const struct sl_view *v, const float light_dir[3], const float *light_pos,
                      const struct sl_verdicts *vd,
                      const uint8_t *band, int thickness, uint8_t *rgb, uint8_t *err,
                      uint64_t count[SL_OV_CLASSES])
{
    build(NULL, v, light_dir, light_pos, vd, band, thickness, rgb, err, count);
}

void sl_overlay_shade_free(struct sl_overlay_shade *sh)
{
    free(sh->lit);
    free(sh->band);
    memset(sh, 0, sizeof *sh);
}

/* The shade's lit colours for this view, light, bands and thickness: kept,
 * or drawn afresh. 0: no memory. */
static int shade_ready(struct sl_overlay_shade *sh, const struct sl_view *v, const float light_dir[3],
                       const float *light_pos, const uint8_t *band, int thickness)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    if (sh->lit && sh->serial == v->serial && sh->n == n && sh->thickness == thickness &&
        !memcmp(sh->light_dir, light_dir, sizeof sh->light_dir) && sh->has_pos == (light_pos != NULL) &&
        (!light_pos || !memcmp(sh->light_pos, light_pos, sizeof sh->light_pos)) && !memcmp(sh->band, band, n))
        return 1;
    if (sh->n < n) {
        sl_overlay_shade_free(sh);
        /* lit zeroed: build reads a word of it at every pixel, background too */
        if (!(sh->lit = calloc(3 * n, 1)) || !(sh->band = malloc(n))) {
            sl_overlay_shade_free(sh);
            return 0;
        }
    }
    sh->n = n;
    for (size_t i = 0; i < n; i++)
        if (v->truth[i] != SL_T_BACKGROUND)
            right_colour(v, light_dir, light_pos, 1, sl_in_contour(band[i], thickness) && thickness > 0, i,
                         sh->lit + 3 * i);
    memcpy(sh->band, band, n);
    memcpy(sh->light_dir, light_dir, sizeof sh->light_dir);
    sh->has_pos = light_pos != NULL;
    if (light_pos)
        memcpy(sh->light_pos, light_pos, sizeof sh->light_pos);
    sh->serial = v->serial;
    sh->thickness = thickness;
    return 1;
}

void sl_overlay_build_shaded(struct sl_overlay_shade *sh, const struct sl_view *v, const float light_dir[3],
                             const float *light_pos, const struct sl_verdicts *vd, const uint8_t *band,
                             int thickness, uint8_t *rgb, uint8_t *err, uint64_t count[SL_OV_CLASSES])
{
    int kept = sh && shade_ready(sh, v, light_dir, light_pos, band, thickness);
    build(kept ? sh->lit : NULL, v, light_dir, light_pos, vd, band, thickness, rgb, err, count);
}

static int any8(const uint8_t *a, const uint8_t *b, int x)
{
    uint64_t wa, wb = 0;
    memcpy(&wa, a + x, 8);
    if (b)
        memcpy(&wb, b + x, 8);
    return (wa | wb) != 0;
}

/* The first and last x < n where a[x] or b[x] (b may be NULL) is nonzero,
 * -1 when none: eight bytes at a time from each end (these scans, a byte
 * and a branch per pixel, were most of the crop's and the insets' time:
 * issue 20). */
static void row_span(const uint8_t *a, const uint8_t *b, int n, int *first, int *last)
{
    *first = *last = -1;
    int x = 0;
    while (x + 8 <= n && !any8(a, b, x))
        x += 8;
    for (; x < n; x++)
        if (a[x] || (b && b[x])) {
            *first = x;
            break;
        }
    if (*first < 0)
        return;
    int y = n;
    while (y - 8 >= *first && !any8(a, b, y - 8))
        y -= 8;
    for (y--; y >= *first; y--)
        if (a[y] || (b && b[y])) {
            *last = y;
            return;
        }
}

/* Bounding box of the pixels with keep(i) true, or x1 < 0 when none. */
static void bbox(const struct sl_view *v, const uint8_t *band, const uint8_t *err, int *x0, int *y0, int *x1, int *y1)
{
    _Static_assert(SL_T_BACKGROUND == 0, "the truth's background is the zero byte");
    *x0 = v->w, *y0 = v->h, *x1 = -1, *y1 = -1;
    for (int y = 0; y < v->h; y++) {
        size_t r = (size_t)y * (size_t)v->w;
        int first, last;
        if (band)
            row_span(band + r, err ? err + r : NULL, v->w, &first, &last);
        else
            row_span(v->truth + r, NULL, v->w, &first, &last);
        if (first < 0)
            continue;
        *x0 = first < *x0 ? first : *x0;
        *x1 = last > *x1 ? last : *x1;
        *y0 = y < *y0 ? y : *y0;
        *y1 = y;
    }
}

/* The box padded, clamped; 1 when it covers less than half the frame. */
static int small_box(const struct sl_view *v, int x0, int y0, int x1, int y1, int pad, struct sl_ov_box *out)
{
    if (x1 < 0)
        return 0;
    x0 = x0 - pad > 0 ? x0 - pad : 0;
    y0 = y0 - pad > 0 ? y0 - pad : 0;
    x1 = x1 + pad < v->w - 1 ? x1 + pad : v->w - 1;
    y1 = y1 + pad < v->h - 1 ? y1 + pad : v->h - 1;
    struct sl_ov_box b = {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
    /* half the frame: below it, a crop shows the scene noticeably larger in
     * a report's fixed-width figure */
    if (2 * (uint64_t)b.w * (uint64_t)b.h >= (uint64_t)v->w * (uint64_t)v->h)
        return 0;
    *out = b;
    return 1;
}

int sl_overlay_crop(const struct sl_view *v, const uint8_t *band, const uint8_t *err, int pad, struct sl_ov_box *out)
{
    int x0, y0, x1, y1;
    *out = (struct sl_ov_box){0, 0, v->w, v->h};
    bbox(v, NULL, NULL, &x0, &y0, &x1, &y1);
    if (x1 < 0)
        return 0;   /* nothing but background: show the frame as it is */
    if (small_box(v, x0, y0, x1, y1, pad, out))
        return 1;
    if (!band)
        return 0;
    /* a ground filling the frame (Bench, Trees): the shadows' boundaries and
     * the errors instead, with a wider margin so the casters' lit sides
     * beside them stay in view */
    int m = (v->w < v->h ? v->w : v->h) / 16;
    bbox(v, band, err, &x0, &y0, &x1, &y1);
    return small_box(v, x0, y0, x1, y1, pad > m ? pad : m, out);
}


int sl_overlay_insets(int w, int h, const uint8_t *err, int s, int n, struct sl_ov_box *out, uint64_t *count)
{
    if (s > w)
        s = w;
    if (s > h)
        s = h;
    if (s <= 0 || n <= 0)
        return 0;
    /* only windows holding an error pixel can be chosen (one holding none
     * never beats best = 0), and those lie within s of the errors' bounding
     * box: the table covers that box, not the frame (a 1024² frame's table
     * was 4 MiB of fresh pages per cell, most of them around no error).
     * The windows are scanned in the same order as over the whole frame, so
     * the same ones are chosen. */
    int ex0 = w, ey0 = h, ex1 = -1, ey1 = -1;
    for (int y = 0; y < h; y++) {
        int first, last;
        row_span(err + (size_t)y * (size_t)w, NULL, w, &first, &last);
        if (first < 0)
            continue;
        ex0 = first < ex0 ? first : ex0;
        ex1 = last > ex1 ? last : ex1;
        ey0 = y < ey0 ? y : ey0;
        ey1 = y;
    }
    if (ex1 < 0)
        return 0;
    /* window corners x in [X0, XL], y in [Y0, YL]; the table covers
     * [X0, XL + s) x [Y0, YL + s) */
    const int X0 = ex0 - s + 1 > 0 ? ex0 - s + 1 : 0, Y0 = ey0 - s + 1 > 0 ? ey0 - s + 1 : 0;
    const int XL = ex1 < w - s ? ex1 : w - s, YL = ey1 < h - s ? ey1 : h - s;
    const int rw = XL + s - X0, rh = YL + s - Y0;
    /* summed-area table, (rw+1) x (rh+1), sat[y][x] = errors in [X0, X0+x) x [Y0, Y0+y) */
    size_t sw = (size_t)rw + 1;
    uint32_t *sat = calloc(sw * ((size_t)rh + 1), sizeof *sat);
    if (!sat)
        return -1;
    for (int y = 0; y < rh; y++) {
        uint32_t run = 0;
        const uint8_t *e = err + (size_t)(Y0 + y) * (size_t)w + (size_t)X0;
        uint32_t *above = sat + (size_t)y * sw, *row = above + sw;
        for (int x = 0; x < rw; x++) {
            run += e[x] != 0;
            row[x + 1] = above[x + 1] + run;
        }
    }
    /* every window's count, once: the n greedy passes below then scan
     * this table (three scans of four table reads each were most of this
     * function's time: issue 20); cnt[y][x] for the window at (X0 + x, Y0 + y) */
    const size_t cw = (size_t)(XL - X0 + 1), ch = (size_t)(YL - Y0 + 1);
    uint32_t *cnt = malloc(cw * ch * sizeof *cnt);
    int (*cut)[2] = malloc((size_t)n * sizeof *cut);   /* a row's intervals no window may start in */
    if (!cnt || !cut) {
        free(cnt);
        free(cut);
        free(sat);
        return -1;
    }
    for (size_t y = 0; y < ch; y++) {
        const uint32_t *lo = sat + y * sw, *hi = lo + (size_t)s * sw;
        uint32_t *c = cnt + y * cw;
        for (size_t x = 0; x < cw; x++)
            c[x] = hi[x + (size_t)s] - hi[x] - lo[x + (size_t)s] + lo[x];
    }
    int got = 0;
    for (; got < n; got++) {
        /* the first window in scan order (rows, then columns) holding more
         * than every window before it, among those overlapping none chosen:
         * the first of the largest. In a row, the windows overlapping a
         * chosen one are an interval of x, so each row is scanned as the
         * segments between those intervals. */
        uint32_t best = 0;
        int bx = -1, by = -1;
        for (int y = Y0; y <= YL; y++) {
            const uint32_t *c = cnt + (size_t)(y - Y0) * cw;
            /* the intervals this row may not use, as [a, b) in x - X0 */
            int ncut = 0;
            for (int k = 0; k < got; k++)
                if (y < out[k].y + out[k].h && out[k].y < y + s) {
                    int a = out[k].x - s + 1 - X0, b = out[k].x + out[k].w - X0;
                    cut[ncut][0] = a < 0 ? 0 : a;
                    cut[ncut][1] = b > (int)cw ? (int)cw : b;
                    ncut++;
                }
            for (int x = 0; x < (int)cw;) {
                /* skip any cut that covers x; then run to the next cut's start */
                int moved = 1;
                while (moved) {
                    moved = 0;
                    for (int k = 0; k < ncut; k++)
                        if (cut[k][0] <= x && x < cut[k][1]) {
                            x = cut[k][1];
                            moved = 1;
                        }
                }
                int end = (int)cw;
                for (int k = 0; k < ncut; k++)
                    if (cut[k][0] > x && cut[k][0] < end)
                        end = cut[k][0];
                if (x >= end)
                    break;
                uint32_t m = 0;
                for (int i = x; i < end; i++)
                    m = c[i] > m ? c[i] : m;
                if (m > best) {
                    int i = x;
                    while (c[i] != m)
                        i++;
                    best = m;
                    bx = X0 + i;
                    by = y;
                }
                x = end;
            }
        }
        if (bx < 0)
            break;
        out[got] = (struct sl_ov_box){bx, by, s, s};
        count[got] = best;
    }
    free(cut);
    free(cnt);
    free(sat);
    return got;
}

void sl_overlay_soft(int w, int h, const uint32_t *tri, const float *vis, const float *truth, uint8_t *rgb)
{
    static const float dark[3] = {213, 94, 0}, light[3] = {0, 114, 178};   /* vermillion, blue */
    size_t npx = (size_t)w * (size_t)h;
    for (size_t i = 0; i < npx; i++) {
        uint8_t *p = rgb + 3 * i;
        if (!tri[i]) {
            p[0] = p[1] = p[2] = 0;
            continue;
        }
        float e = vis[i] - truth[i], g = 40.0f + 180.0f * vis[i];
        float a = fabsf(e) > 0.05f ? fminf(1.0f, 0.3f + fabsf(e)) : 0.0f;
        const float *c = e < 0 ? dark : light;
        for (int j = 0; j < 3; j++)
            p[j] = (uint8_t)((1 - a) * g + a * c[j]);
    }
}
