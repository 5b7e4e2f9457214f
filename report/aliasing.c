/*
 * aliasing.c — the report's aliasing section (seed 004, issue 21): per view
 * the wrong pixels of every label and map size beside the memory its maps
 * take (texels) and its time, with the aliasing error m of its pixels
 * (aliasing.h: median m of the PFL pixels and of the wrong ones; wrong
 * pixels and the image's PFL pixels by m band), and one plot of the error
 * rate against m per label: in each band, the wrong pixels over the PFL
 * pixels, pooled over the study's views and map sizes (whole image).
 * "Is this error aliasing (m > 1) or something else?": a method whose
 * errors fall in the bands m <= 1 errs for another reason (self-shadowing,
 * a leak); one whose error rate climbs with m is limited by its resolution.
 * Reads the cells' records only; nothing here prints.
 */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "report_int.h"

static const char *const band_name[SL_ALIAS_BANDS] = {"m ≤ 1", "1–2", "2–4", "4–8", "> 8"};

int sl_report_aliasing_applies(const struct sl_report_study *s)
{
    for (int i = 0; i < s->n; i++)
        if (s->cells[i].has_alias && (!s->cells[i].has_soft || s->cells[i].frac))
            return 1;
    return 0;
}

/* The index of the whole image's region in the cell's aliasing figures, -1 if none. */
static int image_region(const struct sl_cell_record *c)
{
    for (int r = 0; r < c->alias.nregions; r++)
        if (c->alias.thickness[r] == 0)
            return r;
    return -1;
}

static double milli(uint64_t v) { return (double)v / 1000.0; }

/* Time of a cell's method: its stages summed (zpart's and lispsm's slices'
 * maps in its map pass, as the driver's layers are NSM's). */
static double cell_ms(const struct sl_cell_record *c)
{
    return sl_report_cell_ms(c, 0);
}

static enum sl_err view_tables(struct sl_report_doc *doc, const struct sl_report_study *s,
                               const struct sl_report_view *v, struct sl_diag *d)
{
    char id[160], slug[128], vs[128];
    snprintf(vs, sizeof vs, "%s-%s-%dx%d", v->scene, v->viewpoint, v->vw, v->vh);
    sl_tab_slug(vs, slug, sizeof slug);
    snprintf(id, sizeof id, "%s-aliasing-%s", s->slug, slug);
    struct sl_tab t;
    sl_tab_init(&t, id, 8 + SL_ALIAS_BANDS, 2,
                       "%s / %s / %s %dx%d: wrong pixels, memory, time and aliasing error m", s->name, v->scene,
                       v->viewpoint, v->vw, v->vh);
    static const char *const heads[] = {"method", "map", "texels", "wrong", "wrong %", "m median",
                                        "m median, wrong", "layers + step ms"};
    for (int k = 0; k < 8; k++)
        sl_tab_head(&t, k, "%s", heads[k]);
    for (int b = 0; b < SL_ALIAS_BANDS; b++)
        sl_tab_head(&t, 8 + b, "%s%s", strncmp(band_name[b], "m ", 2) ? "m " : "", band_name[b]);
    sl_tab_notef(&t,
             "Whole image, PFL pixels. texels: the shadow-map texels the method looks up (k maps for k slices); "
             "wrong %%: of the PFL pixels; m median: over the PFL pixels, and over the wrong ones; "
             "layers + step ms: the cell's stages summed (ms_cost: map pass, zpart's and lispsm's slices' maps included, "
             "post, lookup, readback, rays), medians. The band columns (m <= 1, 1-2, 2-4, 4-8, > 8): the wrong pixels whose m falls in "
             "the band, and in brackets the band's share of all PFL pixels of the view.");
    int rows = 0, once = 0;
    for (int l = 0; l < s->nlabels; l++)
        for (int m = 0; m < s->nmaps; m++) {
            const struct sl_cell_record *c = sl_report_study_cell(s, v, s->labels[l], s->maps[m]);
            int r = c && c->has_alias && (!c->has_soft || c->frac) ? image_region(c) : -1;
            if (r < 0)
                continue;
            const uint64_t *n = c->alias.n[r];
            const double *pct = c->alias.pct[r];
            uint64_t wrong = 0, pfl = 0;
            for (int b = 0; b < SL_ALIAS_BANDS; b++) {
                wrong += n[SL_AFIG_wrong_m_le1 + b];
                pfl += n[SL_AFIG_px_m_le1 + b];
            }
            pfl += n[SL_AFIG_m_none];
            sl_tab_row(&t, m == 0);
            sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
            sl_tab_cell(&t, 1, "%d²", s->maps[m]);
            sl_tab_cell(&t, 2, "%.2fM", (double)c->texels / 1048576.0);
            sl_tab_cell(&t, 3, "%llu", (unsigned long long)wrong);
            sl_tab_cell(&t, 4, "%.3f", pfl ? 100.0 * (double)wrong / (double)pfl : 0.0);
            sl_tab_cell(&t, 5, "%.3f", milli(n[SL_AFIG_m_median_milli]));
            if (wrong)
                sl_tab_cell(&t, 6, "%.3f", milli(n[SL_AFIG_wrong_m_median_milli]));
            sl_tab_cell(&t, 7, "%.1f%s", cell_ms(c), c->runs == 1 ? SL_REPORT_ONCE : "");
            once |= c->runs == 1;
            for (int b = 0; b < SL_ALIAS_BANDS; b++)
                sl_tab_cell(&t, 8 + b, "%llu (%.1f%%)", (unsigned long long)n[SL_AFIG_wrong_m_le1 + b],
                                   isnan(pct[SL_AFIG_px_m_le1 + b]) ? 0.0 : pct[SL_AFIG_px_m_le1 + b]);
            rows++;
        }
    if (once)
        sl_report_tab_once(&t);
    enum sl_err e = rows ? sl_report_doc_table(doc, &t, d) : SL_OK;
    sl_tab_free(&t);
    return e;
}

/* The error rate in each band per label, pooled over the study's cells. */
static enum sl_err rate_plot(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                             struct sl_diag *d)
{
    char *body = NULL, *data = NULL;
    size_t blen = 0, dlen = 0;
    FILE *m, *dm;
    enum sl_err oe = sl_report_open_script(&m, &body, &blen, &dm, &data, &dlen, s->name, d);
    if (oe)
        return oe;
    char id[160];
    snprintf(id, sizeof id, "%s-aliasing-rate", s->slug);
    struct sl_tab t;
    sl_tab_init(&t, id, 1 + SL_ALIAS_BANDS, 1, "%s: error rate by aliasing error m, %% of the band's PFL "
                       "pixels (all views and map sizes)", s->name);
    sl_tab_head(&t, 0, "method");
    for (int b = 0; b < SL_ALIAS_BANDS; b++)
        sl_tab_head(&t, 1 + b, "%s", band_name[b]);
    int nblocks = 0, nrates = 0;
    double rates[SL_REPORT_MAXKEYS * SL_ALIAS_BANDS];
    for (int l = 0; l < s->nlabels; l++) {
        uint64_t w[SL_ALIAS_BANDS] = {0}, p[SL_ALIAS_BANDS] = {0};
        int any = 0;
        for (int i = 0; i < s->n; i++) {
            const struct sl_cell_record *c = &s->cells[i];
            int r = c->has_alias && (!c->has_soft || c->frac) && strcmp(c->label, s->labels[l]) == 0 ? image_region(c) : -1;
            if (r < 0)
                continue;
            any = 1;
            for (int b = 0; b < SL_ALIAS_BANDS; b++) {
                w[b] += c->alias.n[r][SL_AFIG_wrong_m_le1 + b];
                p[b] += c->alias.n[r][SL_AFIG_px_m_le1 + b];
            }
        }
        if (!any)
            continue;
        fprintf(dm, "%s# %s: band wrong/PFL %%\n", nblocks ? "\n\n" : "", s->labels[l]);
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
        for (int b = 0; b < SL_ALIAS_BANDS; b++) {
            if (p[b] == 0) {
                fprintf(dm, "%d NaN\n", b);
                continue;
            }
            double rate = 100.0 * (double)w[b] / (double)p[b];
            fprintf(dm, "%d %.6g\n", b, rate);
            rates[nrates++] = rate;
            sl_tab_cell(&t, 1 + b, "%.3f (%llu / %llu)", rate, (unsigned long long)w[b],
                               (unsigned long long)p[b]);
        }
        nblocks++;
    }
    char title[200];
    snprintf(title, sizeof title, "%s: error rate against the aliasing error m", s->name);
    fputs("set title ", m);
    sl_report_gp_quote(m, title);
    fputs("\nset grid\nset border 3\nset tics nomirror\n", m);
    int logy = sl_report_axis(m, "y", rates, nrates, 1);
    fputs("set xrange [-0.3:4.3]\nset xtics ('m ≤ 1' 0, '1–2' 1, '2–4' 2, '4–8' 3, '> 8' 4)\n"
          "set xlabel 'aliasing error m of the pixel (texel footprint / pixel footprint, seed 004 eq. 61)'\n"
          "set ylabel 'wrong pixels, % of the band''s PFL pixels'\n"
          "set key outside right top Left reverse samplen 1.5\nplot ", m);
    int b = 0;
    for (int l = 0; l < s->nlabels && b < nblocks; l++) {
        int has = 0;
        for (int i = 0; i < s->n && !has; i++)
            has = s->cells[i].has_alias && (!s->cells[i].has_soft || s->cells[i].frac) && strcmp(s->cells[i].label, s->labels[l]) == 0;
        if (!has)
            continue;
        const char *col;
        int pt;
        sl_report_style(b, &col, &pt);
        fprintf(m, "%sDATA index %d using 1:(YZERO_OF(2)) with linespoints lw 1.5 pt %d lc rgb '%s' title ", b ? ", \\\n  " : "",
                b, pt, col);
        sl_report_gp_quote(m, sl_report_display(s, s->labels[l]));
        b++;
    }
    fputc('\n', m);
    enum sl_err e = sl_report_close_script(m, dm, &body, &data, 0, s->name, d);
    if (!e && nblocks > 0 && logy < 0)
        sl_report_doc_para(doc, "No method of this study gets a pixel wrong in any band of m: the error-rate plot "
                                "is not drawn.");
    else if (!e && nblocks > 0) {
        char name[160], cap[400];
        snprintf(name, sizeof name, "%s-aliasing-rate", s->slug);
        snprintf(cap, sizeof cap, "%s: per method, its wrong pixels over its PFL pixels in each band of m, pooled "
                 "over the study's views and map sizes (whole image; %s; a band without pixels is left out).",
                 title, logy == 1 ? "log scale, a zero rate at the tick labelled 0" : "linear scale");
        e = sl_report_plot_draw(doc, gnuplot, name, 900, 560, data, body, cap, d);
        if (!e)
            e = sl_report_doc_table(doc, &t, d);
    }
    sl_tab_free(&t);
    free(body);
    free(data);
    return e;
}

enum sl_err sl_report_aliasing(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                               struct sl_diag *d)
{
    sl_report_doc_para(doc, "The aliasing error m of a pixel (seed 004, appendix A, eq. 61: m = w_l / w_c) is the "
                            "width on the surface of the shadow-map texel that serves the pixel over the width of "
                            "the pixel itself, both found exactly by cutting their beams with the pixel's tangent "
                            "plane (eq. 58, so grazing pixels get their true, large footprints); in 3-D, the most "
                            "pixels one texel spans along any direction. m > 1: one texel decides several pixels, "
                            "and a shadow edge is blocky there (aliasing); wrong pixels with m <= 1 are wrong for "
                            "another reason (self-shadowing, a leak, depth precision).");
    enum sl_err e = rate_plot(doc, s, gnuplot, d);
    for (int v = 0; v < s->nviews && !e; v++)
        e = view_tables(doc, s, &s->views[v], d);
    return e;
}
