/*
 * figures.c — see figures.h. Invariant (tested): in every region
 * pfl + pnfl = pixels and light + shadow + uncertain = pixels.
 */
#include "figures.h"
#include <math.h>
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

void sl_figures_compute(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                        const int *thickness, int nregions, struct sl_figures *out)
{
    memset(out, 0, sizeof *out);
    if (nregions > SL_MAX_REGIONS)
        nregions = SL_MAX_REGIONS;
    out->nregions = nregions;
    for (int r = 0; r < nregions; r++)
        out->r[r].thickness = thickness[r];
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
            uint64_t *c = out->r[r].n;
            c[SL_FIG_pixels]++;
            c[t == SL_T_PNFL ? SL_FIG_pnfl : SL_FIG_pfl]++;
            if (verdict == SL_V_LIT) {
                c[SL_FIG_light]++;
                c[truth_lit ? SL_FIG_light_correct : SL_FIG_light_incorrect]++;
            } else if (verdict == SL_V_SHADOW) {
                c[SL_FIG_shadow]++;
                c[truth_lit ? SL_FIG_shadow_incorrect : SL_FIG_shadow_correct]++;
            } else {
                c[SL_FIG_uncertain]++;
            }
            c[SL_FIG_wrong] += (uint64_t)wrong;
            if (vd->how[i] == SL_HOW_TRACED) {
                c[SL_FIG_traced]++;
                c[SL_FIG_traced_shadow] += (uint64_t)(t == SL_T_SHADOW);
            }
            if (vd->how[i] == SL_HOW_HINT) {
                c[SL_FIG_hinted]++;
                c[SL_FIG_hinted_wrong] += (uint64_t)wrong;
            }
            c[SL_FIG_confirmed] += (uint64_t)(vd->how[i] == SL_HOW_CONFIRM || vd->how[i] == SL_HOW_CONFIRM_ADJ);
            c[SL_FIG_confirmed_adj] += (uint64_t)(vd->how[i] == SL_HOW_CONFIRM_ADJ);
            c[SL_FIG_ray_tri_tests] += vd->tests[i];
            c[SL_FIG_corrected] += (uint64_t)(vd->how[i] == SL_HOW_CORRECT);
            if (vd->has_base && t != SL_T_PNFL) {
                int bl = vd->base[i] == SL_V_LIT;
                c[bl ? SL_FIG_nsm_light : SL_FIG_nsm_shadow]++;
                if (vd->how[i] == SL_HOW_HINT) {
                    c[bl ? SL_FIG_hinted_light : SL_FIG_hinted_shadow]++;
                    c[bl ? SL_FIG_hinted_light_wrong : SL_FIG_hinted_shadow_wrong] += (uint64_t)wrong;
                }
            }
            if (vd->has_base) {
                uint8_t how = vd->how[i];
                int pnfl = t == SL_T_PNFL, bl = !pnfl && vd->base[i] == SL_V_LIT;
                int hinted = how == SL_HOW_HINT || (pnfl && hints);
                int conf = how == SL_HOW_HINT || how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ ||
                           how == SL_HOW_CORRECT || pnfl;
                c[SL_FIG_nsm_shadow_moderno] += (uint64_t)!bl;
                c[SL_FIG_kept_ss_right_moderno] += (uint64_t)pnfl;   /* shadowed by both, always right */
                c[SL_FIG_hinted_moderno] += (uint64_t)hinted;
                if (!bl) {
                    c[SL_FIG_hinted_shadow_moderno] += (uint64_t)hinted;
                    c[SL_FIG_hinted_shadow_wrong_moderno] += (uint64_t)(how == SL_HOW_HINT && wrong);
                }
                c[SL_FIG_conf_moderno] += (uint64_t)conf;
                c[SL_FIG_conf_step2_moderno] += (uint64_t)(conf && how != SL_HOW_CONFIRM_ADJ);
                if (bl)
                    c[SL_FIG_conf_light_moderno] += (uint64_t)(how == SL_HOW_HINT || how == SL_HOW_CORRECT);
                else {
                    int cs = how == SL_HOW_HINT || how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ || pnfl;
                    c[SL_FIG_conf_shadow_moderno] += (uint64_t)cs;
                    c[SL_FIG_conf_shadow_step2_moderno] += (uint64_t)(cs && how != SL_HOW_CONFIRM_ADJ);
                }
            }
            if (vd->has_base && t != SL_T_PNFL && (verdict == SL_V_LIT || verdict == SL_V_SHADOW)) {
                uint8_t b = vd->base[i];
                if (b == verdict) {
                    c[wrong ? SL_FIG_kept_wrong : SL_FIG_kept_right]++;
                    if (b == SL_V_LIT)
                        c[wrong ? SL_FIG_kept_ll_wrong : SL_FIG_kept_ll_right]++;
                    else
                        c[wrong ? SL_FIG_kept_ss_wrong : SL_FIG_kept_ss_right_moderno]++;
                }
                else if (b == SL_V_LIT)
                    c[wrong ? SL_FIG_broken_ls : SL_FIG_fixed_ls]++;
                else if (b == SL_V_SHADOW)
                    c[wrong ? SL_FIG_broken_sl : SL_FIG_fixed_sl]++;
            }
        }
    }
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
