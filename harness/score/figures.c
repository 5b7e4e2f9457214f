/*
 * figures.c — see figures.h. Invariant (tested): in every region
 * pfl + pnfl = pixels and light + shadow + uncertain = pixels.
 */
#include "figures.h"
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include "contour.h"

static const char *const fig_name[] = {
#define F(name, text, of) #name,
    SL_FIGURES(F)
#undef F
};
static const char *const fig_text[] = {
#define F(name, text, of) text,
    SL_FIGURES(F)
#undef F
};
static const char *const fig_of[] = {
#define F(name, text, of) of,
    SL_FIGURES(F)
#undef F
};

const char *sl_figure_name(enum sl_figure f) { return fig_name[f]; }
const char *sl_figure_text(enum sl_figure f) { return fig_text[f]; }
const char *sl_figure_of(enum sl_figure f) { return fig_of[f]; }

/* What one non-background pixel adds to its region's counts, w times over:
 * the counting rules of figures.h in one place, for the pixel-by-pixel
 * reference and for the histogram (each distinct key once, weighted by how
 * many pixels carry it). */
static void count_px(uint64_t *c, uint8_t t, uint8_t verdict, uint8_t how, uint8_t base, int has_base, int hints,
                     uint64_t w)
{
    int truth_lit = t == SL_T_LIT;
    int wrong = (verdict == SL_V_LIT && !truth_lit) || (verdict == SL_V_SHADOW && truth_lit);
    c[SL_FIG_pixels] += w;
    c[t == SL_T_PNFL ? SL_FIG_pnfl : SL_FIG_pfl] += w;
    if (verdict == SL_V_LIT) {
        c[SL_FIG_light] += w;
        c[truth_lit ? SL_FIG_light_correct : SL_FIG_light_incorrect] += w;
    } else if (verdict == SL_V_SHADOW) {
        c[SL_FIG_shadow] += w;
        c[truth_lit ? SL_FIG_shadow_incorrect : SL_FIG_shadow_correct] += w;
    } else {
        c[SL_FIG_uncertain] += w;
    }
    const uint64_t ww = wrong ? w : 0;
    c[SL_FIG_wrong] += ww;
    if (how == SL_HOW_TRACED) {
        c[SL_FIG_traced] += w;
        c[SL_FIG_traced_shadow] += t == SL_T_SHADOW ? w : 0;
    }
    if (how == SL_HOW_HINT) {
        c[SL_FIG_hinted] += w;
        c[SL_FIG_hinted_wrong] += ww;
    }
    c[SL_FIG_confirmed] += how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ ? w : 0;
    c[SL_FIG_confirmed_adj] += how == SL_HOW_CONFIRM_ADJ ? w : 0;
    c[SL_FIG_corrected] += how == SL_HOW_CORRECT ? w : 0;
    if (has_base && t != SL_T_PNFL) {
        int bl = base == SL_V_LIT;
        c[bl ? SL_FIG_nsm_light : SL_FIG_nsm_shadow] += w;
        if (how == SL_HOW_HINT) {
            c[bl ? SL_FIG_hinted_light : SL_FIG_hinted_shadow] += w;
            c[bl ? SL_FIG_hinted_light_wrong : SL_FIG_hinted_shadow_wrong] += ww;
        }
    }
    if (has_base) {
        int pnfl = t == SL_T_PNFL, bl = !pnfl && base == SL_V_LIT;
        int hinted = how == SL_HOW_HINT || (pnfl && hints);
        int conf = how == SL_HOW_HINT || how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ ||
                   how == SL_HOW_CORRECT || pnfl;
        c[SL_FIG_nsm_shadow_moderno] += !bl ? w : 0;
        c[SL_FIG_kept_ss_right_moderno] += pnfl ? w : 0;   /* shadowed by both, always right */
        c[SL_FIG_hinted_moderno] += hinted ? w : 0;
        if (!bl) {
            c[SL_FIG_hinted_shadow_moderno] += hinted ? w : 0;
            c[SL_FIG_hinted_shadow_wrong_moderno] += how == SL_HOW_HINT && wrong ? w : 0;
        }
        c[SL_FIG_conf_moderno] += conf ? w : 0;
        c[SL_FIG_conf_step2_moderno] += conf && how != SL_HOW_CONFIRM_ADJ ? w : 0;
        if (bl)
            c[SL_FIG_conf_light_moderno] += how == SL_HOW_HINT || how == SL_HOW_CORRECT ? w : 0;
        else {
            int cs = how == SL_HOW_HINT || how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ || pnfl;
            c[SL_FIG_conf_shadow_moderno] += cs ? w : 0;
            c[SL_FIG_conf_shadow_step2_moderno] += cs && how != SL_HOW_CONFIRM_ADJ ? w : 0;
        }
    }
    if (has_base && t != SL_T_PNFL && (verdict == SL_V_LIT || verdict == SL_V_SHADOW)) {
        uint8_t b = base;
        if (b == verdict) {
            c[wrong ? SL_FIG_kept_wrong : SL_FIG_kept_right] += w;
            if (b == SL_V_LIT)
                c[wrong ? SL_FIG_kept_ll_wrong : SL_FIG_kept_ll_right] += w;
            else
                c[wrong ? SL_FIG_kept_ss_wrong : SL_FIG_kept_ss_right_moderno] += w;
        }
        else if (b == SL_V_LIT)
            c[wrong ? SL_FIG_broken_ls : SL_FIG_fixed_ls] += w;
        else if (b == SL_V_SHADOW)
            c[wrong ? SL_FIG_broken_sl : SL_FIG_fixed_sl] += w;
    }
}

static void percentages(struct sl_figures *out);

static int regions_init(const int *thickness, int nregions, struct sl_figures *out)
{
    memset(out, 0, sizeof *out);
    if (nregions > SL_MAX_REGIONS)
        nregions = SL_MAX_REGIONS;
    out->nregions = nregions;
    for (int r = 0; r < nregions; r++)
        out->r[r].thickness = thickness[r];
    return nregions;
}

void sl_figures_compute_pixelwise(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                                  const int *thickness, int nregions, struct sl_figures *out)
{
    nregions = regions_init(thickness, nregions, out);
    size_t n = (size_t)v->w * (size_t)v->h;
    /* Moderno's count: PnFL pixels are hinted when the method hints at all */
    int hints = 0;
    for (size_t i = 0; i < n && vd->has_base && !hints; i++)
        hints = vd->how[i] == SL_HOW_HINT;
    for (size_t i = 0; i < n; i++) {
        uint8_t t = v->truth[i];
        if (t == SL_T_BACKGROUND) {
            out->background++;
            continue;
        }
        uint8_t verdict = vd->v[i];
        int truth_lit = t == SL_T_LIT;
        int wrong = (verdict == SL_V_LIT && !truth_lit) || (verdict == SL_V_SHADOW && truth_lit);
        out->wrong_image += (uint64_t)wrong;
        for (int r = 0; r < nregions; r++) {
            if (!sl_in_contour(band[i], thickness[r]))
                continue;
            out->r[r].n[SL_FIG_ray_tri_tests] += vd->tests[i];
            count_px(out->r[r].n, t, verdict, vd->how[i], vd->has_base ? vd->base[i] : 0, vd->has_base, hints, 1);
        }
    }
    percentages(out);
}

/* The fused pass. Every figure of a non-background pixel is a function of
 * five small things: its truth (0..3, enum sl_truth: the truth pass and the
 * checksummed cache write nothing else), its verdict (lit, shadowed, or
 * anything else), its how (hint, confirm, confirm_adj, correct, traced, or
 * anything else: count_px and the exactness check test no other), NSM's
 * verdict (lit, shadowed, anything else) and which regions hold it (a band
 * value's set of regions: bands grow outward, so at most nregions + 2
 * distinct sets). Packed into a 13-bit key, one pass over the pixels only
 * counts keys (a histogram, 32 KiB per thread: it stays in L1/L2), and the
 * counting rules run once per distinct key afterwards, weighted: the same
 * sums, in integers, so the same figures. The ray-triangle tests, the one
 * per-pixel quantity that is not a class, are summed per region set. */
enum { K_T = 0, K_V = 2, K_HOW = 4, K_BASE = 7, K_BAND = 9, K_BITS = 13 };
#define K_N (1u << K_BITS)
#define K_BANDS 16

static const uint8_t how_rep[6] = {SL_HOW_MAP, SL_HOW_HINT, SL_HOW_CONFIRM, SL_HOW_CONFIRM_ADJ,
                                   SL_HOW_CORRECT, SL_HOW_TRACED};
static const uint8_t v_rep[3] = {SL_V_UNCERTAIN, SL_V_LIT, SL_V_SHADOW};

struct fused_tabs {
    uint16_t v[256], how[256], base[256], band[256];   /* pre-shifted key parts */
    unsigned bandmask[K_BANDS];                         /* band class -> regions holding it */
    uint8_t bad[K_N];                                   /* key -> exactness violation */
};

static unsigned cls_v(unsigned x) { return x == SL_V_LIT ? 1u : x == SL_V_SHADOW ? 2u : 0u; }

static void fused_tabs_init(struct fused_tabs *T, const int *thickness, int nregions, int has_base,
                            unsigned exact)
{
    int nb = 0;
    for (int x = 0; x < 256; x++) {
        unsigned h = 0;
        for (unsigned k = 1; k < 6; k++)
            if (x == how_rep[k])
                h = k;
        T->v[x] = (uint16_t)(cls_v((unsigned)x) << K_V);
        T->how[x] = (uint16_t)(h << K_HOW);
        T->base[x] = (uint16_t)((has_base ? cls_v((unsigned)x) : 0u) << K_BASE);
        unsigned m = 0;
        for (int r = 0; r < nregions; r++)
            m |= (unsigned)sl_in_contour((uint8_t)x, thickness[r]) << r;
        int c = 0;
        while (c < nb && T->bandmask[c] != m)
            c++;
        if (c == nb)
            T->bandmask[nb++] = m;   /* at most nregions + 2 <= 10 < K_BANDS */
        T->band[x] = (uint16_t)(c << K_BAND);
    }
    for (unsigned key = 0; key < K_N; key++) {
        const unsigned t = key & 3u, vi = (key >> K_V) & 3u, hi = (key >> K_HOW) & 7u;
        if (vi > 2 || hi > 5) {
            T->bad[key] = 0;   /* no pixel gets this key */
            continue;
        }
        const unsigned vv = v_rep[vi], how = how_rep[hi];
        T->bad[key] = (uint8_t)sl_exact_violated(exact, vv, how, t);
    }
}

/* Runs of SPAN_RUN pixels (one cache line of each array) over which every
 * array the key and the checks read holds one value: most of an image is
 * such runs (inside a lit or shadowed area, away from its contour), and a
 * run's pixels all get one key, so it is counted once, RUN times over. How
 * far the bytes of a run stray from its first one, as one word: 0 when the
 * run is uniform: four 16-byte vectors XORed with the first byte's
 * broadcast and ORed (GCC's vector extension: SSE2 on x86-64, NEON on
 * arm64); a table-free test, so a uniform run costs about 1/8 of a pixel's key. */
#define SPAN_RUN 64   /* sl_bytes64_dev's 64 bytes (contour.h) */

static inline uint64_t run_dev(const uint8_t *p) { return sl_bytes64_dev(p, p[0]); }

/* Pixels [i0, i1) one by one into the histogram (the runs that are not
 * uniform, and the ends); the exactness count reads the G-buffer's class
 * only where the method declares a guarantee; the ray-triangle tests per
 * region set (background pixels' to a slot of their own, left out). */
static inline uint64_t span_px(const struct fused_tabs *T, const uint8_t *tr, const uint8_t *vv,
                               const uint8_t *how, const uint8_t *bs, const uint8_t *band, const uint8_t *tst,
                               const uint8_t *cls, int check, size_t i0, size_t i1, uint32_t *hist,
                               uint64_t *tests)
{
    uint64_t viol = 0;
    unsigned any = 0;
    for (size_t i = i0; i < i1; i++) {
        const unsigned t = tr[i] & 3u;
        const unsigned key = t | T->v[vv[i]] | T->how[how[i]] | T->base[bs[i]] | T->band[band[i]];
        hist[key]++;
        if (check)
            viol += T->bad[key] & (cls[i] == SL_C_PFL);
        any |= tst[i];
    }
    /* most methods spend no ray-triangle test: summed only where some were
     * (in the key loop above they cost a sixth of it for nothing) */
    if (any)
        for (size_t i = i0; i < i1; i++) {
            const unsigned t = tr[i] & 3u;
            tests[t ? T->band[band[i]] >> K_BAND : K_BANDS] += tst[i];
        }
    return viol;
}

/* One span [i0, i1) of pixels into a thread's histogram: uniform runs
 * counted whole, the rest pixel by pixel — the same counts either way (a
 * uniform run's pixels all have the first one's key, class and tests). A
 * key computed with vector arithmetic, then counted, measured slower here
 * than the tables (2.5 vs 2.1 ms per 1 M pixels, one thread), and two
 * interleaved histograms no faster; skipping uniform runs is what pays. */
static uint64_t fused_span(const struct fused_tabs *T, const struct sl_view *v, const struct sl_verdicts *vd,
                           const uint8_t *band, int check, size_t i0, size_t i1, uint32_t *hist,
                           uint64_t *tests)
{
    const uint8_t *tr = v->truth, *vv = vd->v, *how = vd->how, *bs = vd->has_base ? vd->base : vd->v;
    const uint8_t *tst = vd->tests, *cls = check ? v->cls : v->truth;   /* unread without a check */
    uint64_t viol = 0;
    size_t i = i0;
    for (; i + SPAN_RUN <= i1; i += SPAN_RUN) {
        const uint64_t dev = run_dev(tr + i) | run_dev(vv + i) | run_dev(how + i) | run_dev(bs + i) |
                             run_dev(band + i) | run_dev(tst + i) | run_dev(cls + i);
        if (dev) {
            viol += span_px(T, tr, vv, how, bs, band, tst, cls, check, i, i + SPAN_RUN, hist, tests);
            continue;
        }
        const unsigned t = tr[i] & 3u;
        const unsigned key = t | T->v[vv[i]] | T->how[how[i]] | T->base[bs[i]] | T->band[band[i]];
        hist[key] += SPAN_RUN;
        if (check)
            viol += SPAN_RUN * (uint64_t)(T->bad[key] & (cls[i] == SL_C_PFL));
        tests[t ? T->band[band[i]] >> K_BAND : K_BANDS] += SPAN_RUN * (uint64_t)tst[i];
    }
    return viol + span_px(T, tr, vv, how, bs, band, tst, cls, check, i, i1, hist, tests);
}

/* band given (state NULL), or drawn from state block by block into
 * band_out just before the block is counted, while its rows are in cache */
static uint64_t fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *state, int dilations,
                      const uint8_t *band, uint8_t *band_out, const int *thickness, int nregions, unsigned exact,
                      int threads, struct sl_figures *out)
{
    nregions = regions_init(thickness, nregions, out);
    if (threads <= 0)
        threads = omp_get_max_threads();
    const int W = v->w, H = v->h, check = exact != 0;
    /* blocks of rows of ~64 K pixels, handed out as threads come free */
    const int rows = W > 0 ? (65536 + W - 1) / W : 1;
    const int nblk = W > 0 ? (H + rows - 1) / rows : 0;
    const size_t need = state ? sl_contour_scratch(W, rows, dilations) : 0;
    struct fused_tabs *T = malloc(sizeof *T);
    uint64_t *hist = calloc((size_t)K_N + K_BANDS + 1, sizeof *hist);
    uint32_t *th = calloc((size_t)threads * K_N, sizeof *th);
    uint8_t *scratch = state ? malloc(need * (size_t)threads) : NULL;
    if (!T || !hist || !th || (state && !scratch)) {
        /* no memory for the tables: one thing after the other, pixel by
         * pixel; the caller counts the violations itself */
        free(T);
        free(hist);
        free(th);
        free(scratch);
        if (state) {
            sl_contour_bands_plain(W, H, state, dilations, band_out);
            band = band_out;
        }
        sl_figures_compute_pixelwise(v, vd, band, thickness, nregions, out);
        return UINT64_MAX;
    }
    if (state)
        band = band_out;
    fused_tabs_init(T, thickness, nregions, vd->has_base, exact);
    uint64_t viol = 0;
#pragma omp parallel num_threads(threads) reduction(+ : viol)
    {
        uint32_t *h = th + (size_t)omp_get_thread_num() * K_N;
        uint8_t *sc = scratch ? scratch + need * (size_t)omp_get_thread_num() : NULL;
        uint64_t tests[K_BANDS + 1] = {0};
        size_t since = 0;   /* pixels counted into h since it was last added up */
#pragma omp for schedule(dynamic, 1)
        for (int b = 0; b < nblk; b++) {
            const size_t i0 = (size_t)b * (size_t)rows * (size_t)W;
            const size_t i1 = (size_t)(b + 1 == nblk ? H : (b + 1) * rows) * (size_t)W;
            if (since + (i1 - i0) > UINT32_MAX) {
                /* a uint32 count could overflow: add up and start again */
#pragma omp critical(sl_fig_fused)
                for (unsigned k = 0; k < K_N; k++)
                    hist[k] += h[k];
                memset(h, 0, K_N * sizeof *h);
                since = 0;
            }
            if (sc)
                sl_contour_bands_rows(W, H, state, dilations, (int)(i0 / (size_t)W), (int)(i1 / (size_t)W),
                                      band_out, sc);
            viol += fused_span(T, v, vd, band, check, i0, i1, h, tests);
            since += i1 - i0;
        }
#pragma omp critical(sl_fig_fused)
        {
            for (unsigned k = 0; k < K_N; k++)
                hist[k] += h[k];
            for (int k = 0; k <= K_BANDS; k++)
                hist[K_N + (unsigned)k] += tests[k];
        }
    }
    free(th);
    free(scratch);
    int hints = 0;   /* Moderno's count: PnFL pixels are hinted when the method hints at all */
    for (unsigned k = 0; k < K_N && vd->has_base; k++)
        hints |= hist[k] && ((k >> K_HOW) & 7u) == 1u;
    for (unsigned k = 0; k < K_N; k++) {
        const uint64_t w = hist[k];
        if (!w)
            continue;
        const unsigned t = k & 3u;
        if (t == SL_T_BACKGROUND) {
            out->background += w;
            continue;
        }
        const uint8_t vv = v_rep[(k >> K_V) & 3u], how = how_rep[(k >> K_HOW) & 7u];
        const uint8_t base = v_rep[(k >> K_BASE) & 3u];
        const int truth_lit = t == SL_T_LIT;
        out->wrong_image += (vv == SL_V_LIT && !truth_lit) || (vv == SL_V_SHADOW && truth_lit) ? w : 0;
        const unsigned m = T->bandmask[k >> K_BAND];
        for (int r = 0; r < nregions; r++)
            if (m >> r & 1u)
                count_px(out->r[r].n, (uint8_t)t, vv, how, base, vd->has_base, hints, w);
    }
    for (unsigned c = 0; c < K_BANDS; c++)
        for (int r = 0; r < nregions; r++)
            if (T->bandmask[c] >> r & 1u)
                out->r[r].n[SL_FIG_ray_tri_tests] += hist[K_N + c];
    free(hist);
    free(T);
    percentages(out);
    return check ? viol : 0;
}

uint64_t sl_figures_fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                          const int *thickness, int nregions, unsigned exact, int threads, struct sl_figures *out)
{
    return fused(v, vd, NULL, 0, band, NULL, thickness, nregions, exact, threads, out);
}

uint64_t sl_score_fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *state, int dilations,
                        uint8_t *band, const int *thickness, int nregions, unsigned exact, int threads,
                        struct sl_figures *out)
{
    return fused(v, vd, state, dilations, band, band, thickness, nregions, exact, threads, out);
}

void sl_figures_compute(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                        const int *thickness, int nregions, struct sl_figures *out)
{
    sl_figures_fused(v, vd, band, thickness, nregions, 0, 0, out);
}

static void percentages(struct sl_figures *out)
{
    const int nregions = out->nregions;
    for (int r = 0; r < nregions; r++) {
        struct sl_region_figures *g = &out->r[r];
        g->n[SL_FIG_wrong_caught] = g->n[SL_FIG_wrong];
        for (int f = 0; f < SL_FIG_COUNT; f++) {
            const char *of = fig_of[f];
            double base = NAN;
            if (strcmp(of, "wrong_image") == 0)
                base = (double)out->wrong_image;
            else
                for (int b = 0; b < SL_FIG_COUNT; b++)
                    if (of[0] && strcmp(of, fig_name[b]) == 0)
                        base = (double)g->n[b];
            g->pct[f] = (base > 0.0) ? 100.0 * (double)g->n[f] / base : NAN;
        }
    }
}
