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
/* Pixels per chunk: the codes stay in L1 between the two passes, and a
 * byte counter per lane (16 pixels a step, 128 steps) cannot wrap. */
enum { CHUNK = 2048 };

/* 16 bytes as one value (GCC's vector extension: SSE2 on x86-64, NEON on
 * arm64); a comparison gives 0xff or 0 per byte. */
typedef uint8_t u8x16 __attribute__((vector_size(16)));

/* The code of one pixel (the vector loop's tail), the same expressions. */
static inline uint8_t code_of(uint8_t t, uint8_t v, uint8_t b, uint8_t all_in, uint8_t hi, uint8_t tint_ok)
{
    const int in = all_in || (b != 0 && b <= hi);
    if (t == SL_T_BACKGROUND)
        return CODE_BACKGROUND;
    if (v == SL_V_LIT && t != SL_T_LIT)
        return in ? SL_OV_LIT_WRONG : SL_OV_WRONG_OUTSIDE;
    if (v == SL_V_SHADOW && t == SL_T_LIT)
        return in ? SL_OV_SHADOW_WRONG : SL_OV_WRONG_OUTSIDE;
    if (v == SL_V_UNCERTAIN)
        return SL_OV_UNCERTAIN;
    return (uint8_t)((v == SL_V_LIT ? CODE_LIT : CODE_DARK) + (in && tint_ok));
}

static inline u8x16 sel(u8x16 m, u8x16 a, u8x16 b) { return (m & a) | (~m & b); }

/* Bytes equal to k from code[j] on, up to m. */
static size_t run_end(const uint8_t *code, size_t j, size_t m, uint8_t k)
{
    const uint64_t kw = (uint64_t)k * 0x0101010101010101ull;
    while (j + 8 <= m) {
        uint64_t w;
        memcpy(&w, code + j, 8);
        if (w != kw)
            break;
        j += 8;
    }
    while (j < m && code[j] == k)
        j++;
    return j;
}

/* lit: the lit colours of the view's pixels (a shade's), or NULL: each
 * computed where needed.
 *
 * Two passes per chunk (issue 20: the one branchy loop that decided and
 * drew each pixel was 4% of the Moderno study's samples): the first gives
 * 16 pixels at a time a code with byte compares and selects and counts
 * the codes in byte lanes; the second draws runs of one code, which in a
 * render are long: the shade's colours copied, a grey set, another
 * constant colour repeated. */
static void build(const uint8_t *lit, const struct sl_view *v, const float light_dir[3], const float *light_pos,
                  const struct sl_verdicts *vd, const uint8_t *band, int thickness, uint8_t *rgb, uint8_t *err,
                  uint64_t count[SL_OV_CLASSES])
{
    _Static_assert(SL_OV_LIT_WRONG == 0 && SL_OV_SHADOW_WRONG == 1 && SL_OV_WRONG_OUTSIDE == 2 &&
                       SL_OV_UNCERTAIN == 3,
                   "the error classes are codes 0-3");
    const size_t n = (size_t)v->w * (size_t)v->h;
    /* sl_in_contour(b, thickness) as byte compares: every pixel when the
     * thickness is 0, else a band b with 0 < b <= thickness / 2 */
    const uint8_t all_in = thickness == 0, tint_ok = thickness > 0;
    const uint8_t hi = (uint8_t)(thickness / 2 > 255 ? 255 : thickness / 2 < 0 ? 0 : thickness / 2);
    /* each constant code's colour */
    uint8_t pal[CODES][3] = {{0}};
    for (int k = 0; k <= SL_OV_UNCERTAIN; k++)
        memcpy(pal[k], sl_overlay_colour[k], 3);
    right_colour(v, light_dir, light_pos, 0, 0, 0, pal[CODE_DARK]);
    right_colour(v, light_dir, light_pos, 0, 1, 0, pal[CODE_DARK_TINT]);
    const u8x16 z = {0}, one = z + 1, v_hi = z + hi, v_all = all_in ? ~z : z, v_tint = tint_ok ? ~z : z;
    uint64_t tally[CODES] = {0};
    uint8_t code[CHUNK];
    for (size_t i0 = 0; i0 < n; i0 += CHUNK) {
        const size_t m = n - i0 < CHUNK ? n - i0 : CHUNK;
        const uint8_t *t = v->truth + i0, *vv = vd->v + i0, *b = band + i0;
        u8x16 n0 = z, n1 = z, n2 = z, n3 = z, nt = z;   /* per-lane counts, at most 128 */
        size_t j = 0;
        for (; j + 16 <= m; j += 16) {
            u8x16 T, V, B;
            memcpy(&T, t + j, 16);
            memcpy(&V, vv + j, 16);
            memcpy(&B, b + j, 16);
            const u8x16 in = v_all | ((u8x16)(B != z) & (u8x16)(B <= v_hi));
            const u8x16 bg = (u8x16)(T == z), tl = (u8x16)(T == z + SL_T_LIT);
            const u8x16 said_lit = (u8x16)(V == z + SL_V_LIT);
            const u8x16 wrong_lit = said_lit & ~tl, wrong_shadow = (u8x16)(V == z + SL_V_SHADOW) & tl;
            const u8x16 unc = (u8x16)(V == z + SL_V_UNCERTAIN);
            u8x16 k = sel(said_lit, z + CODE_LIT, z + CODE_DARK) + (in & v_tint & one);
            k = sel(unc, z + SL_OV_UNCERTAIN, k);
            k = sel(wrong_shadow, sel(in, z + SL_OV_SHADOW_WRONG, z + SL_OV_WRONG_OUTSIDE), k);
            k = sel(wrong_lit, sel(in, z + SL_OV_LIT_WRONG, z + SL_OV_WRONG_OUTSIDE), k);
            k = sel(bg, z + CODE_BACKGROUND, k);
            memcpy(code + j, &k, 16);
            n0 -= (u8x16)(k == z + SL_OV_LIT_WRONG);
            n1 -= (u8x16)(k == z + SL_OV_SHADOW_WRONG);
            n2 -= (u8x16)(k == z + SL_OV_WRONG_OUTSIDE);
            n3 -= (u8x16)(k == z + SL_OV_UNCERTAIN);
            nt -= (u8x16)(k == z + CODE_DARK_TINT) | (u8x16)(k == z + CODE_LIT_TINT);
        }
        for (int l = 0; l < 16; l++) {
            tally[SL_OV_LIT_WRONG] += n0[l];
            tally[SL_OV_SHADOW_WRONG] += n1[l];
            tally[SL_OV_WRONG_OUTSIDE] += n2[l];
            tally[SL_OV_UNCERTAIN] += n3[l];
            tally[CODE_DARK_TINT] += nt[l];
        }
        for (; j < m; j++) {
            const uint8_t k = code_of(t[j], vv[j], b[j], all_in, hi, tint_ok);
            code[j] = k;
            tally[k <= SL_OV_UNCERTAIN ? k : CODE_DARK_TINT] += k <= SL_OV_UNCERTAIN || k == CODE_DARK_TINT ||
                                                               k == CODE_LIT_TINT;
        }
        if (v->outside) {
            /* outside the spot's cone, right (said shadowed or PnFL): not a
             * contour pixel then, hatched below */
            const uint8_t *out = v->outside + i0;
            for (j = 0; j < m; j++)
                if (out[j] && code[j] >= CODE_DARK && code[j] != CODE_BACKGROUND) {
                    tally[CODE_DARK_TINT] -= code[j] == CODE_DARK_TINT || code[j] == CODE_LIT_TINT;
                    code[j] = CODE_CONE;
                    tally[CODE_CONE]++;
                }
        }
        if (err)
            for (j = 0; j < m; j++)
                err[i0 + j] = code[j] <= SL_OV_UNCERTAIN ? 255 : 0;
        uint8_t *o = rgb + 3 * i0;
        for (j = 0; j < m;) {
            const uint8_t k = code[j];
            const size_t e = run_end(code, j + 1, m, k);
            uint8_t *p = o + 3 * j;
            if (k == CODE_LIT || k == CODE_LIT_TINT) {
                if (lit)
                    memcpy(p, lit + 3 * (i0 + j), 3 * (e - j));
                else
                    for (size_t q = j; q < e; q++, p += 3)
                        right_colour(v, light_dir, light_pos, 1, k == CODE_LIT_TINT, i0 + q, p);
            } else if (k == CODE_CONE) {
                /* diagonal stripes, 2 of every 8 px at 56, the rest at 12,
                 * so the cone's footprint reads apart from the background
                 * (0), the shadowed grey (31) and the lit grey (31-158) */
                for (size_t q = j; q < e; q++, p += 3) {
                    const size_t x = (i0 + q) % (size_t)v->w, y = (i0 + q) / (size_t)v->w;
                    p[0] = p[1] = p[2] = (x + y) % 8 < 2 ? sl_overlay_colour[SL_OV_OUTSIDE_CONE][0] : 12;
                }
            } else if (pal[k][0] == pal[k][1] && pal[k][1] == pal[k][2]) {
                memset(p, pal[k][0], 3 * (e - j));   /* black, the ambient grey */
            } else {
                for (size_t q = j; q < e; q++, p += 3)
                    memcpy(p, pal[k], 3);
            }
            j = e;
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
        if (!(sh->lit = malloc(3 * n)) || !(sh->band = malloc(n))) {
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


/* The intervals of window corners in row y that overlap one of the got
 * windows chosen (s x s), as [a, b) in x - X0 clamped to [0, cw): in a
 * row, the windows overlapping a chosen one are an interval of x. */
static int row_cuts(const struct sl_ov_box *out, int got, int y, int s, int X0, int cw, int (*cut)[2])
{
    int ncut = 0;
    for (int k = 0; k < got; k++)
        if (y < out[k].y + out[k].h && out[k].y < y + s) {
            int a = out[k].x - s + 1 - X0, b = out[k].x + out[k].w - X0;
            cut[ncut][0] = a < 0 ? 0 : a;
            cut[ncut][1] = b > cw ? cw : b;
            ncut++;
        }
    return ncut;
}

/* The largest of c[0..cw) outside the cuts, scanned as the segments
 * between them; with want > 0, *at: the first x outside them where
 * c[x] == want (-1 when none). */
static uint32_t row_allowed(const uint32_t *c, int cw, const int (*cut)[2], int ncut, uint32_t want, int *at)
{
    uint32_t best = 0;
    if (at)
        *at = -1;
    for (int x = 0; x < cw;) {
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
        int end = cw;
        for (int k = 0; k < ncut; k++)
            if (cut[k][0] > x && cut[k][0] < end)
                end = cut[k][0];
        if (x >= end)
            break;
        if (want) {
            for (int i = x; i < end; i++)
                if (c[i] == want) {
                    *at = i;
                    return want;
                }
        } else {
            uint32_t m = 0;
            for (int i = x; i < end; i++)
                m = c[i] > m ? c[i] : m;
            best = m > best ? m : best;
        }
        x = end;
    }
    return best;
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
    /* window corners x in [X0, XL], y in [Y0, YL]; their pixels lie in
     * [X0, XL + s) x [Y0, YL + s) */
    const int X0 = ex0 - s + 1 > 0 ? ex0 - s + 1 : 0, Y0 = ey0 - s + 1 > 0 ? ey0 - s + 1 : 0;
    const int XL = ex1 < w - s ? ex1 : w - s, YL = ey1 < h - s ? ey1 : h - s;
    const int rw = XL + s - X0;
    /* every window's count, once: the n greedy passes below then read
     * this table (three scans of four summed-area reads each were most of
     * this function's time: issue 20); cnt[y][x] for the window at
     * (X0 + x, Y0 + y). Each row of it from the column sums of the rows
     * [y, y + s), slid along x; the column sums moved down a row by adding
     * the row below and taking off the row above (a summed-area table of
     * the region, written and read again, was as costly as the rest). */
    const size_t cw = (size_t)(XL - X0 + 1), ch = (size_t)(YL - Y0 + 1);
    uint32_t *cnt = malloc(cw * ch * sizeof *cnt);
    uint32_t *col = calloc((size_t)rw, sizeof *col);   /* errors in column X0 + x, rows [y, y + s) */
    uint32_t *rmax = malloc(ch * sizeof *rmax);         /* each row's largest count */
    int (*cut)[2] = malloc((size_t)n * sizeof *cut);   /* a row's intervals no window may start in */
    if (!cnt || !col || !rmax || !cut) {
        free(cnt);
        free(col);
        free(rmax);
        free(cut);
        return -1;
    }
    for (int y = 0; y < s - 1; y++) {
        const uint8_t *e = err + (size_t)(Y0 + y) * (size_t)w + (size_t)X0;
        for (int x = 0; x < rw; x++)
            col[x] += e[x] != 0;
    }
    for (size_t y = 0; y < ch; y++) {
        const uint8_t *in = err + (Y0 + y + (size_t)s - 1) * (size_t)w + (size_t)X0;
        for (int x = 0; x < rw; x++)
            col[x] += in[x] != 0;
        uint32_t *c = cnt + y * cw, sum = 0, m;
        for (int x = 0; x < s; x++)
            sum += col[x];
        c[0] = m = sum;
        for (size_t x = 1; x < cw; x++) {
            sum += col[x + (size_t)s - 1] - col[x - 1];
            c[x] = sum;
            m = sum > m ? sum : m;
        }
        rmax[y] = m;
        const uint8_t *outr = err + (Y0 + y) * (size_t)w + (size_t)X0;
        for (int x = 0; x < rw; x++)
            col[x] -= outr[x] != 0;
    }
    free(col);
    int got = 0;
    for (; got < n; got++) {
        /* the first window in scan order (rows, then columns) holding more
         * than every window before it, among those overlapping none chosen:
         * the first of the largest. A row whose largest count is no more
         * than the best so far cannot hold it, and a row no chosen window
         * cuts holds its largest count: only the rows a chosen window cuts
         * are scanned (issue 20: n scans of the whole table were most of
         * this function's time), and only the best row again for where its
         * largest count first lies. */
        uint32_t best = 0;
        int by = -1;
        for (int y = Y0; y <= YL; y++) {
            if (rmax[y - Y0] <= best)
                continue;
            int ncut = row_cuts(out, got, y, s, X0, (int)cw, cut);
            uint32_t m = ncut ? row_allowed(cnt + (size_t)(y - Y0) * cw, (int)cw, cut, ncut, 0, NULL)
                              : rmax[y - Y0];
            if (m > best) {
                best = m;
                by = y;
            }
        }
        if (by < 0)
            break;
        int bx;
        row_allowed(cnt + (size_t)(by - Y0) * cw, (int)cw, cut, row_cuts(out, got, by, s, X0, (int)cw, cut), best,
                    &bx);
        out[got] = (struct sl_ov_box){X0 + bx, by, s, s};
        count[got] = best;
    }
    free(rmax);
    free(cut);
    free(cnt);
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
