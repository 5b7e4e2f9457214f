/*
 * figures.h — the numbers of one (view, map size, method): per region (the
 * 2, 4 and 6 px contours and the whole image) the pixel counts of Morais 2015
 * Table 7 and Moderno 2011 Tables 5, 17 and 18.
 *
 * Counting rules: background pixels are counted once, apart, and enter no
 * region. PnFL pixels are in every count of pixels and of shadow (the method
 * shadows them by definition and is always right there), so that
 * light + shadow + uncertain = pixels in the region, as in the seeds' tables.
 * "correct"/"incorrect" compare the verdict with the truth.
 *
 * PnFL in the hints, confirmations and NSM's light/shadow split: the two
 * theses count them differently, and both counts exist. Morais 2015 keeps
 * PnFL apart (his PFL/PnFL tables): nsm_light, nsm_shadow, hinted*,
 * confirmed, corrected and the vs-NSM classes count PFL pixels only.
 * Moderno 2011 counts PnFL as shadow, hinted and confirmed ("all approaches
 * use normals", §4.4; Table 18's shadow pixels include them): the *_moderno
 * figures, defined for a method that reports NSM's verdicts (has_base).
 * PnFL are never wrong, so the wrong counts are the same under both; only
 * their bases differ.
 * Does not: format or write (run.c does).
 */
#ifndef SL_FIGURES_H
#define SL_FIGURES_H
#include <stdint.h>
#include "method.h"
#include "view.h"

#define SL_MAX_REGIONS 8

/* name, what it counts, the figure its percentage is taken of ("" = none) */
#define SL_FIGURES(X)                                                              \
    X(pixels,           "pixels in the region (not background)",      "")         \
    X(pfl,              "pixels facing the light",                    "pixels")   \
    X(pnfl,             "pixels not facing the light",                "pixels")   \
    X(light,            "pixels the method puts in light",            "pixels")   \
    X(shadow,           "pixels the method puts in shadow (with PnFL)", "pixels") \
    X(uncertain,        "pixels the method leaves undecided",         "pixels")   \
    X(light_correct,    "in light, lit in truth",                     "light")    \
    X(light_incorrect,  "in light, shadowed in truth (wrongly lit)",  "light")    \
    X(shadow_correct,   "in shadow, shadowed in truth",               "shadow")   \
    X(shadow_incorrect, "in shadow, lit in truth (wrongly shadowed)", "shadow")   \
    X(wrong,            "wrong pixels (both kinds)",                  "pixels")   \
    X(wrong_caught,     "wrong pixels of the whole image inside this region", "wrong_image") \
    X(traced,           "pixels decided by a shadow ray (uncertain to the maps)", "pixels") \
    X(traced_shadow,    "of those, shadowed in truth",                "traced")   \
    X(hinted,           "PFL pixels given a coherence hint (PnFL apart)",              "pixels")   \
    X(hinted_wrong,     "of those, hinted wrongly",                   "hinted")   \
    X(nsm_light,        "pixels NSM puts in light (PFL; PnFL are never lit)",             "pixels")   \
    X(nsm_shadow,       "pixels NSM puts in shadow (PFL only: Morais's count)",            "pixels")   \
    X(hinted_light,     "NSM-lit pixels hinted (Moderno Tables 7-8 light)", "nsm_light") \
    X(hinted_light_wrong, "NSM-lit pixels hinted wrongly",            "nsm_light") \
    X(hinted_shadow,    "NSM-shadowed PFL pixels hinted (PnFL apart)",                 "nsm_shadow") \
    X(hinted_shadow_wrong, "NSM-shadowed pixels hinted wrongly",      "nsm_shadow") \
    X(confirmed,        "shadow confirmed by a ray-triangle hit",     "pixels")   \
    X(confirmed_adj,    "of those, in the chain's adjacency step",    "confirmed") \
    X(corrected,        "lit turned shadowed by a ray-triangle hit",  "pixels")   \
    X(fixed_ls,         "vs NSM: L->S, now right (corrected)",        "pixels")   \
    X(broken_ls,        "vs NSM: L->S, now wrong (turned bad)",       "pixels")   \
    X(fixed_sl,         "vs NSM: S->L, now right (corrected)",        "pixels")   \
    X(broken_sl,        "vs NSM: S->L, now wrong (turned bad)",       "pixels")   \
    X(kept_right,       "vs NSM: unchanged and right (maintained correct)", "pixels") \
    X(kept_wrong,       "vs NSM: unchanged and wrong (maintained incorrect)", "pixels") \
    X(ray_tri_tests,    "ray-triangle tests outside Embree spent on these pixels", "")         \
    X(nsm_shadow_moderno, "pixels NSM puts in shadow, PnFL with them (Moderno's count)", "pixels") \
    X(hinted_moderno,   "pixels hinted, PnFL with them when the method hints (Moderno's count)", "pixels") \
    X(hinted_shadow_moderno, "NSM-shadowed pixels hinted, PnFL with them (Moderno Tables 7-8 shadow)", "nsm_shadow_moderno") \
    X(hinted_shadow_wrong_moderno, "NSM-shadowed pixels hinted wrongly (Moderno Tables 7-8)", "nsm_shadow_moderno") \
    X(conf_moderno,     "hints + confirmations + corrections, PnFL with them (Moderno Table 13)", "pixels") \
    X(conf_step2_moderno, "the same without the adjacency step's (Moderno Table 12)", "pixels") \
    X(conf_light_moderno, "NSM-lit pixels hinted or corrected (Moderno Table 12 light)", "nsm_light") \
    X(conf_shadow_moderno, "NSM-shadowed hinted or confirmed, PnFL with them (Moderno Table 13 shadow)", "nsm_shadow_moderno") \
    X(conf_shadow_step2_moderno, "the same without the adjacency step's (Moderno Table 12 shadow)", "nsm_shadow_moderno")    \
    X(kept_ll_right,    "vs NSM: L->L and right (Moderno Table 23 maintained correct L->L)", "pixels") \
    X(kept_ss_right_moderno, "vs NSM: S->S and right, PnFL with them (Table 23 maintained correct S->S)", "pixels") \
    X(kept_ll_wrong,    "vs NSM: L->L and wrong (Table 23 maintained incorrect L->L)", "pixels") \
    X(kept_ss_wrong,    "vs NSM: S->S and wrong (Table 23 maintained incorrect S->S)", "pixels")

enum sl_figure {
#define SL_FIG_ENUM(name, text, of) SL_FIG_##name,
    SL_FIGURES(SL_FIG_ENUM)
#undef SL_FIG_ENUM
    SL_FIG_COUNT
};

const char *sl_figure_name(enum sl_figure f);
const char *sl_figure_text(enum sl_figure f);
const char *sl_figure_of(enum sl_figure f);

struct sl_region_figures {
    int      thickness;                 /* 0 = whole image */
    uint64_t n[SL_FIG_COUNT];
    double   pct[SL_FIG_COUNT];         /* of the base figure; NAN when none */
};

struct sl_figures {
    uint64_t background;
    uint64_t wrong_image;               /* wrong pixels in the whole image */
    int      nregions;
    struct sl_region_figures r[SL_MAX_REGIONS];
};

/* thickness[] lists the regions (0 = whole image), at most SL_MAX_REGIONS.
 * Counts through sl_figures_fused on every core (exact 0, threads 0). */
void sl_figures_compute(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                        const int *thickness, int nregions, struct sl_figures *out);

/* The same figures, and the exactness check's count, in one multithreaded
 * pass over the pixels (a histogram of each pixel's classes; figures.c).
 * Returns how many PFL pixels (v->cls) break a guarantee in `exact`
 * (SL_EXACT_*: a lit pixel not lit in truth, a shadowed one not shadowed, a
 * confirmed/corrected/traced one wrong; 0 when exact is 0), or UINT64_MAX
 * when it had no memory for its tables and counted the figures pixel by
 * pixel without checking. threads <= 0: omp_get_max_threads(). */
uint64_t sl_figures_fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                          const int *thickness, int nregions, unsigned exact, int threads,
                          struct sl_figures *out);

/* The contour bands and the same in one pass: block by block, each block's
 * bands drawn from the states (sl_contour_bands_rows: `dilations` as
 * sl_contour_bands takes it) into band (w * h, every row written, as
 * sl_contour_bands writes it) and counted while in cache. Returns as
 * sl_figures_fused. */
uint64_t sl_score_fused(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *state, int dilations,
                        uint8_t *band, const int *thickness, int nregions, unsigned exact, int threads,
                        struct sl_figures *out);

/* The reference: the same counting rules, pixel by pixel on one thread, as
 * the figures were counted before the fused pass (tests and the bench
 * compare the two). */
void sl_figures_compute_pixelwise(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                                  const int *thickness, int nregions, struct sl_figures *out);

#endif
