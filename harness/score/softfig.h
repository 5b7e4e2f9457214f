/*
 * softfig.h — the numbers of one soft-shadow cell (an area light; Curtis
 * 2009): a method's visible fraction of the light per pixel against the
 * area truth's.
 *
 * Every non-background pixel counts but one whose method visibility is
 * not finite (NaN, +-inf: no error can be taken of it; the cell counts it
 * apart, nonfinite); a pixel is lit when its visible fraction
 * is 1, in umbra when it is 0, in penumbra otherwise (the truth's estimate,
 * from its samples: a pixel with every sample visible is lit), each within
 * the caller's tolerance: 0 under an area light, SL_SOFT_HARD_TOL under a
 * hard light (below). The errors are
 * in units of visibility (0..1) and reported as percentages of full
 * visibility (an MAE of 2.5 means the method is off by 0.025 on average).
 * Does not: compute visibility, format or store.
 */
#ifndef SL_SOFTFIG_H
#define SL_SOFTFIG_H
#include <stdint.h>

/* name, what it is, what its value is ("count" figures: the value is a share
 * of `of`, in percent; "mean" figures: a mean in percent of full visibility) */
#define SL_SOFT_FIGURES(X) SL_SOFT_BASE_FIGURES(X) SL_SOFT_SPLIT_FIGURES(X)
#define SL_SOFT_BASE_FIGURES(X)                                                                 \
    X(soft_pixels,        "pixels (not background)",                                  "")           \
    X(soft_mae,           "mean absolute error of the visible fraction",               "visibility") \
    X(soft_rmse,          "root mean square error of the visible fraction",            "visibility") \
    X(soft_bias,          "mean signed error (method - truth): > 0 too light",         "visibility") \
    X(soft_within_005,    "pixels within 0.05 of the truth",                            "soft_pixels") \
    X(soft_within_010,    "pixels within 0.1 of the truth",                             "soft_pixels") \
    X(soft_truth_lit,     "pixels lit in truth (every sample visible)",                 "soft_pixels") \
    X(soft_truth_umbra,   "pixels in umbra in truth (no sample visible)",               "soft_pixels") \
    X(soft_truth_penumbra,"pixels in penumbra in truth",                                "soft_pixels") \
    X(soft_lit_right,     "lit in truth and lit by the method",                         "soft_truth_lit") \
    X(soft_umbra_right,   "umbra in truth and umbra by the method",                     "soft_truth_umbra") \
    X(soft_penumbra_right,"penumbra in truth and penumbra by the method",               "soft_truth_penumbra") \
    X(soft_class_right,   "pixels the method classes as the truth does (lit/umbra/penumbra)", "soft_pixels") \
    X(soft_truth_stderr,  "mean standard error of the truth's estimate",               "visibility")

/* The mean error split by its sign (leaking + over_dark = soft_mae; with a
 * 0/1 truth, (mae + bias) / 2 and (mae - bias) / 2): figures of the store,
 * figures.csv and the pivot; a baseline may lack them (check.c) */
#define SL_SOFT_SPLIT_FIGURES(X)                                                                \
    X(leaking,            "light leaking: mean of max(v - truth, 0) (too light)",         "visibility") \
    X(over_dark,          "over-darkening: mean of max(truth - v, 0) (too dark)",         "visibility")

/* The class tolerance under a hard light (directional, spot, point), whose
 * truth is exactly 0 or 1: a method's visibility v is lit when v >= 1 - tol,
 * umbra when v <= tol. A filtered method (pcf, vsm, evsm, msm) almost never
 * writes exactly 0 or 1, so exact classes call nearly every pixel penumbra
 * whatever its error (EVSM 2.66% classed right at a mean error of 0.37%);
 * with the tolerance a class is right exactly when |v - t| <= tol, so
 * soft_class_right = soft_within_005, soft_lit_right is the share of the
 * truth-lit pixels not over-darkened by more than tol and soft_umbra_right
 * of the truth-shadowed ones not leaking more than tol. 0.05 as the
 * within_005 figure and the fractional overlay's key (score/cell.c). An area
 * truth's classes stay exact (lit: every sample visible), so its figures
 * and baselines are unchanged. */
#define SL_SOFT_HARD_TOL 0.05

enum sl_soft_figure {
#define SL_SOFT_ENUM(name, text, of) SL_SFIG_##name,
    SL_SOFT_FIGURES(SL_SOFT_ENUM)
#undef SL_SOFT_ENUM
    SL_SFIG_COUNT
};

const char *sl_soft_figure_name(enum sl_soft_figure f);
const char *sl_soft_figure_text(enum sl_soft_figure f);
const char *sl_soft_figure_of(enum sl_soft_figure f);

struct sl_soft_figures {
    uint64_t n[SL_SFIG_COUNT];     /* counts (for the means: the pixels they average over) */
    double   pct[SL_SFIG_COUNT];   /* share of `of` in percent, or the mean in percent of visibility;
                                    * NAN when `of` is 0 */
};

/* Over every non-background pixel (tri != 0) of a w*h view: method `v` and
 * truth `t` visible fractions, truth standard errors `se` (may be NULL);
 * the classes lit/umbra/penumbra within `tol` of 1 and 0 (0: exact, an area
 * light; SL_SOFT_HARD_TOL: a hard light's 0/1 truth). */
void sl_soft_figures_compute(int w, int h, const uint32_t *tri, const float *v, const float *t, const float *se,
                             double tol, struct sl_soft_figures *out);

#endif
