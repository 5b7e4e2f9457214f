/*
 * softfig.h — the numbers of one soft-shadow cell (an area light; Curtis
 * 2009): a method's visible fraction of the light per pixel against the
 * area truth's.
 *
 * Every non-background pixel counts but one whose method visibility is
 * not finite (NaN, +-inf: no error can be taken of it; the cell counts it
 * apart, nonfinite); a pixel is lit when its visible fraction
 * is 1, in umbra when it is 0, in penumbra otherwise (the truth's estimate,
 * from its samples: a pixel with every sample visible is lit). The errors are
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
 * truth `t` visible fractions, truth standard errors `se` (may be NULL). */
void sl_soft_figures_compute(int w, int h, const uint32_t *tri, const float *v, const float *t, const float *se,
                             struct sl_soft_figures *out);

#endif
