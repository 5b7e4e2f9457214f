/*
 * softfig.c — see softfig.h. Invariants (tested): lit + umbra + penumbra =
 * pixels; the right ones never exceed their class; within 0.05 <= within 0.1.
 */
#include "softfig.h"
#include <math.h>
#include <string.h>

static const char *const sfig_name[] = {
#define F(name, text, of) #name,
    SL_SOFT_FIGURES(F)
#undef F
};
static const char *const sfig_text[] = {
#define F(name, text, of) text,
    SL_SOFT_FIGURES(F)
#undef F
};
static const char *const sfig_of[] = {
#define F(name, text, of) of,
    SL_SOFT_FIGURES(F)
#undef F
};

const char *sl_soft_figure_name(enum sl_soft_figure f) { return sfig_name[f]; }
const char *sl_soft_figure_text(enum sl_soft_figure f) { return sfig_text[f]; }
const char *sl_soft_figure_of(enum sl_soft_figure f) { return sfig_of[f]; }

/* The counts below index the truth's class (0 lit, 1 umbra, 2 penumbra)
 * from the first of each triple: the X-macro must keep them in that order. */
_Static_assert(SL_SFIG_soft_truth_umbra == SL_SFIG_soft_truth_lit + 1 &&
                   SL_SFIG_soft_truth_penumbra == SL_SFIG_soft_truth_lit + 2 &&
                   SL_SFIG_soft_umbra_right == SL_SFIG_soft_lit_right + 1 &&
                   SL_SFIG_soft_penumbra_right == SL_SFIG_soft_lit_right + 2,
               "soft figures: lit, umbra, penumbra in order");

/* 0 lit, 1 umbra, 2 penumbra, within tol of 1 and 0; in double and as
 * |v - t| below, so that with a 0/1 truth a class is right exactly when
 * the pixel is within tol (no float rounding apart at the boundary) */
static int soft_class(float v, double tol)
{
    double x = v;
    return x >= 1.0 || 1.0 - x <= tol ? 0 : x <= tol ? 1 : 2;
}

void sl_soft_figures_compute(int w, int h, const uint32_t *tri, const float *v, const float *t, const float *se,
                             double tol, struct sl_soft_figures *out)
{
    memset(out, 0, sizeof *out);
    double sum_abs = 0, sum_sq = 0, sum_signed = 0, sum_se = 0, sum_leak = 0, sum_dark = 0;
    uint64_t *n = out->n;
    size_t np = (size_t)w * (size_t)h;
    for (size_t i = 0; i < np; i++) {
        if (!tri[i] || !isfinite(v[i]))
            continue;   /* not finite: no error to take (the cell counts it, nonfinite) */
        n[SL_SFIG_soft_pixels]++;
        double e = (double)v[i] - (double)t[i];
        sum_abs += fabs(e);
        sum_sq += e * e;
        sum_signed += e;
        sum_leak += e > 0 ? e : 0;
        sum_dark += e < 0 ? -e : 0;
        if (se)
            sum_se += se[i];
        n[SL_SFIG_soft_within_005] += fabs(e) <= 0.05;
        n[SL_SFIG_soft_within_010] += fabs(e) <= 0.1;
        int ct = soft_class(t[i], tol), cm = soft_class(v[i], tol);
        n[SL_SFIG_soft_truth_lit + ct]++;
        n[SL_SFIG_soft_lit_right + ct] += ct == cm;
        n[SL_SFIG_soft_class_right] += ct == cm;
    }
    uint64_t px = n[SL_SFIG_soft_pixels];
    n[SL_SFIG_soft_mae] = n[SL_SFIG_soft_rmse] = n[SL_SFIG_soft_bias] = px;
    n[SL_SFIG_leaking] = n[SL_SFIG_over_dark] = px;
    n[SL_SFIG_soft_truth_stderr] = se ? px : 0;
    for (int k = 0; k < SL_SFIG_COUNT; k++) {
        out->pct[k] = NAN;
        const char *of = sfig_of[k];
        if (!of[0])
            continue;
        if (!strcmp(of, "visibility"))
            continue;   /* the means, below */
        for (int b = 0; b < SL_SFIG_COUNT; b++)
            if (!strcmp(of, sfig_name[b]) && n[b])
                out->pct[k] = 100.0 * (double)n[k] / (double)n[b];
    }
    if (px) {
        out->pct[SL_SFIG_soft_mae] = 100.0 * sum_abs / (double)px;
        out->pct[SL_SFIG_soft_rmse] = 100.0 * sqrt(sum_sq / (double)px);
        out->pct[SL_SFIG_soft_bias] = 100.0 * sum_signed / (double)px;
        out->pct[SL_SFIG_leaking] = 100.0 * sum_leak / (double)px;
        out->pct[SL_SFIG_over_dark] = 100.0 * sum_dark / (double)px;
        if (se)
            out->pct[SL_SFIG_soft_truth_stderr] = 100.0 * sum_se / (double)px;
    }
}
