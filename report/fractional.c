/*
 * fractional.c — the fractional errors of a study's frac cells (issue 36):
 * a method that writes a visibility in 0..1 (a technique package: pcf,
 * vsm, msm ...) under a hard light, scored against the 0/1 truth over the
 * PFL pixels (the cell's soft figures, softfig.h, with frac = 1).
 *
 * With a 0/1 truth t and the method's v, the error v - t is >= 0 where the
 * truth is shadowed (light leaking) and <= 0 where it is lit
 * (over-darkening), so over the PFL pixels
 *   mae  = mean |v - t| = leak + dark,   bias = mean (v - t) = leak - dark,
 *   leak = (mae + bias) / 2,             dark = (mae - bias) / 2,
 * both in percent of full visibility per PFL pixel. Said per pixel where it
 * can happen: leak * pixels / (truth-shadowed pixels) is the visibility a
 * truth-shadowed pixel gets on average, dark * pixels / (truth-lit pixels)
 * what a truth-lit pixel loses.
 *
 * One row per label and map size, pooled over the study's views with each
 * view weighted by its PFL pixels (the means) or summed (the counts). Cells
 * without frac (area lights: layouts.c's soft table) are never read here.
 * Reads the cells' records only; nothing here prints.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "report_int.h"

struct frac_row {
    int      ncells, nwrong;
    double   wrong;       /* the sum of the views' own wrong % (their mean: the report's one "wrong %") */
    uint64_t px, umbra, lit, within;
    uint64_t rays, pfl;   /* a hybrid's traced pixels (technique.yaml's trace:) and the cells' PFL pixels */
    double   mae, bias;   /* sums of pct * px */
};

static int frac_row(const struct sl_report_study *s, const char *label, int map, struct frac_row *r)
{
    memset(r, 0, sizeof *r);
    for (int i = 0; i < s->n; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        if (!c->has_soft || !c->frac || c->map_size != map || strcmp(c->label, label) != 0)
            continue;
        const struct sl_soft_figures *f = &c->soft;
        uint64_t px = f->n[SL_SFIG_soft_pixels];
        r->ncells++;
        r->rays += c->rays;
        r->pfl += c->n_pfl;
        if (px > 0 && !isnan(f->pct[SL_SFIG_soft_mae]) && !isnan(f->pct[SL_SFIG_soft_bias])) {
            r->px += px;
            r->mae += f->pct[SL_SFIG_soft_mae] * (double)px;
            r->bias += f->pct[SL_SFIG_soft_bias] * (double)px;
            r->umbra += f->n[SL_SFIG_soft_truth_umbra];
            r->lit += f->n[SL_SFIG_soft_truth_lit];
            r->within += f->n[SL_SFIG_soft_within_005];
        }
        int g = sl_report_region(c, 0);
        if (g >= 0 && c->fig.r[g].n[SL_FIG_pixels]) {
            r->wrong += 100.0 * (double)c->fig.r[g].n[SL_FIG_wrong] / (double)c->fig.r[g].n[SL_FIG_pixels];
            r->nwrong++;
        }
    }
    return r->ncells;
}

/* Leaking against over-darkening, a marker per label (its display name in
 * the legend, beside the data), its map sizes joined smallest to largest:
 * which way each technique errs. */
static enum sl_err leak_plot(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                             struct sl_diag *d)
{
    char *body = NULL, *data = NULL;
    size_t blen = 0, dlen = 0;
    FILE *m, *dm;
    enum sl_err oe = sl_report_open_script(&m, &body, &blen, &dm, &data, &dlen, s->name, d);
    if (oe)
        return oe;
    int nb = 0, npts = 0;
    double xs[SL_REPORT_MAXKEYS * 16], ys[SL_REPORT_MAXKEYS * 16];
    char title[200];
    snprintf(title, sizeof title, "%s: light leaking against over-darkening", s->name);
    fputs("set title ", m);
    sl_report_gp_quote(m, title);
    fputs("\nset lmargin at screen 0.13\nset rmargin at screen 0.56\nset tmargin at screen 0.90\n"
          "set bmargin at screen 0.14\nset grid\nset border 3\nset tics nomirror\n"
          "set key at screen 0.58, screen 0.90 left top Left reverse samplen 2 spacing 1.1 box\n"
          "set xlabel 'light leaking, % of visibility per PFL pixel'\n"
          "set ylabel 'over-darkening, % of visibility per PFL pixel'\n", m);
    char *plot = NULL;
    size_t plen = 0;
    FILE *pm = open_memstream(&plot, &plen);
    for (int l = 0; pm && l < s->nlabels; l++) {
        int any = 0;
        for (int mi = 0; mi < s->nmaps && npts < SL_REPORT_MAXKEYS * 16; mi++) {
            struct frac_row r;
            if (!frac_row(s, s->labels[l], s->maps[mi], &r) || !r.px)
                continue;
            double mae = r.mae / (double)r.px, bias = r.bias / (double)r.px;
            if (!any)
                fprintf(dm, "%s# %s: leaking over-darkening map\n", nb ? "\n\n" : "", s->labels[l]);
            any = 1;
            xs[npts] = (mae + bias) / 2.0;
            ys[npts] = (mae - bias) / 2.0;
            fprintf(dm, "%.6g %.6g %d\n", xs[npts], ys[npts], s->maps[mi]);
            npts++;
        }
        if (!any)
            continue;
        const char *col;
        int pt;
        sl_report_style(nb, &col, &pt);
        fprintf(pm, "%sDATA index %d using (XZERO_OF(1)):(YZERO_OF(2)) with linespoints pt %d ps 1.2 lw 1.2 "
                    "lc rgb '%s' title ", nb ? ", \\\n  " : "", nb, pt, col);
        sl_report_gp_quote(pm, sl_report_display(s, s->labels[l]));
        nb++;
    }
    if (pm)
        fclose(pm);
    int lx = sl_report_axis(m, "x", xs, npts, 1), ly = sl_report_axis(m, "y", ys, npts, 1);
    fprintf(m, "plot %s\n", plot ? plot : "");
    free(plot);
    enum sl_err e = sl_report_close_script(m, dm, &body, &data, !pm, s->name, d);
    if (!e && nb > 0 && (lx >= 0 || ly >= 0)) {
        char name[160], cap[600];
        snprintf(name, sizeof name, "%s-leaking", s->slug);
        snprintf(cap, sizeof cap, "%s. Per method (its map sizes joined smallest to largest), the two kinds of "
                 "error of the table above: right, more light where the truth is shadowed; up, less where it is "
                 "lit.%s", title, lx == 1 || ly == 1 ? " Log scale where the values span more than two decades; "
                                                      "a zero at the tick labelled 0." : "");
        e = sl_report_plot_draw(doc, gnuplot, name, 900, 600, data, body, cap, d);
    }
    free(body), free(data);
    return e;
}

enum sl_err sl_report_fractional(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                                 struct sl_diag *d)
{
    sl_report_doc_para(doc,
                       "Methods that write a visibility between 0 and 1 (technique packages) under a hard light, "
                       "against the ray-traced 0/1 truth over the PFL pixels. With a 0/1 truth every error is one of "
                       "two kinds: light leaking (the method gives light where the truth is shadowed) and over-darkening (it takes light where the "
                       "truth is lit); the mean |v − truth| is their sum and the signed bias (method − truth) "
                       "their difference, so leaking = (|v − truth| + bias) / 2 and over-darkening = "
                       "(|v − truth| − bias) / 2. Wrong %%: the same cells' hard figures (their "
                       "lit/shadowed verdicts), whole image, the mean of the views' own percentages: the one "
                       "definition of wrong %% in the report, its plots and table.tex.");
    /* the lights the truths were computed for, each once ("directional
     * light", "spot light, 70°": the cells' own words) */
    char lights[256] = "";
    size_t lo = 0;
    for (int i = 0; i < s->n; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        if (!c->has_soft || !c->frac)
            continue;
        const char *w = c->light[0] ? c->light : "hard light";
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = s->cells[j].has_soft && s->cells[j].frac &&
                   !strcmp(s->cells[j].light[0] ? s->cells[j].light : "hard light", w);
        if (!seen && lo < sizeof lights)
            lo += (size_t)snprintf(lights + lo, sizeof lights - lo, "%s%s", lo ? "; " : "", w);
    }
    char id[160];
    snprintf(id, sizeof id, "%s-fractional", s->slug);
    struct sl_tab t;
    sl_tab_init(&t, id, 13, 2, "%s: fractional errors against the 0/1 truth of the %s, per label and map size",
                s->name, lights[0] ? lights : "hard light");
    static const char *const head[] = {"label",   "map",     "cells",          "PFL pixels",
                                       "wrong % (hard)", "|v − t|", "bias",           "leaking",
                                       "over-darkening", "within 0.05", "leaking", "over-darkening",
                                       "% of PFL pixels"};
    for (int k = 0; k < 13; k++)
        sl_tab_head(&t, k, "%s", head[k]);
    sl_tab_group(&t, 5, "%s", "");
    sl_tab_group(&t, 5, "%% of visibility per PFL pixel");
    sl_tab_group(&t, 2, "per truth-shadowed / truth-lit pixel");
    sl_tab_group(&t, 1, "rays traced");
    int any = 0;
    for (int l = 0; l < s->nlabels; l++) {
        int first = 1;
        for (int m = 0; m < s->nmaps; m++) {
            struct frac_row r;
            if (!frac_row(s, s->labels[l], s->maps[m], &r))
                continue;
            sl_tab_row(&t, first);
            if (first)
                sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
            first = 0;
            any = 1;
            sl_tab_cell(&t, 1, "%d²", s->maps[m]);
            sl_tab_cell(&t, 2, "%d", r.ncells);
            sl_tab_cell(&t, 3, "%llu", (unsigned long long)r.px);
            if (r.pfl)
                sl_tab_cell(&t, 12, "%.2f", 100.0 * (double)r.rays / (double)r.pfl);
            else
                sl_tab_cell(&t, 12, "–");
            if (r.nwrong)
                sl_tab_cell(&t, 4, "%.3f", r.wrong / r.nwrong);
            else
                sl_tab_cell(&t, 4, "–");
            if (!r.px) {
                for (int k = 5; k < 12; k++)
                    sl_tab_cell(&t, k, "–");
                continue;
            }
            double px = (double)r.px, mae = r.mae / px, bias = r.bias / px;
            double leak = (mae + bias) / 2.0, dark = (mae - bias) / 2.0;
            sl_tab_cell(&t, 5, "%.3f", mae);
            sl_tab_cell(&t, 6, "%+.3f", bias);
            sl_tab_cell(&t, 7, "%.3f", leak);
            sl_tab_cell(&t, 8, "%.3f", dark);
            sl_tab_cell(&t, 9, "%.2f%%", 100.0 * (double)r.within / px);
            if (r.umbra)
                sl_tab_cell(&t, 10, "%.2f (of %llu)", leak * px / (double)r.umbra, (unsigned long long)r.umbra);
            else
                sl_tab_cell(&t, 10, "–");
            if (r.lit)
                sl_tab_cell(&t, 11, "%.2f (of %llu)", dark * px / (double)r.lit, (unsigned long long)r.lit);
            else
                sl_tab_cell(&t, 11, "–");
        }
    }
    sl_tab_notef(&t,
             "|v − t|: the mean |v − truth|; it, the bias (method − truth), leaking and over-darkening in %% of "
             "full visibility per PFL pixel (leaking + over-darkening = |v − t|); within 0.05: share of the PFL "
             "pixels. The last two columns say the same per pixel where it can happen: the visibility a "
             "truth-shadowed pixel gets on average, and what a truth-lit pixel loses (%% of full visibility; the "
             "pixel counts after \"of\"). Rays traced: a hybrid's (technique.yaml's trace: band), in %% of the PFL "
             "pixels, which is their share of raytrace's rays (one a PFL pixel); 0 for a package that traces "
             "nothing. Pooled over the study's views, weighted by their PFL pixels; wrong %% (hard) the mean of "
             "the views' own percentages.");
    enum sl_err e = SL_OK;
    if (any)
        e = sl_report_doc_table(doc, &t, d);
    else
        sl_report_doc_para(doc, "No frac cell of this study has PFL pixels.");
    sl_tab_free(&t);
    if (!e && any) {
        /* a hard light's truth has no penumbra: a technique that draws one
         * on purpose is charged for all of it (issue 47) */
        sl_report_doc_para(doc, "Caveat: under a hard light the truth has no penumbra, so a technique that draws "
                                "one on purpose (PCSS widens its filter by the blockers' distance to a light of "
                                "light_size texels, 8 by default under a directional or point light; PCF and the "
                                "prefiltered maps blur the edge by their kernel) is charged for all of it: outside "
                                "the hard shadow as leaking, inside the lit side as over-darkening, and in the hard "
                                "wrong %% wherever its visibility crosses the threshold. A high rank here measures "
                                "how far such a technique is from a hard shadow, not how good a soft shadow it "
                                "draws; configs/techniques-area.yaml scores the same techniques against an area "
                                "light's truth.");
        e = leak_plot(doc, s, gnuplot, d);
    }
    return e;
}
