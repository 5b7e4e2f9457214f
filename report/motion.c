/*
 * motion.c — the report's section on errors over motion: per path, viewport
 * and map size of a study, the temporal table (results/motion.h) and a plot
 * of wrong pixels and flicker per frame per label.
 * Invariant: nothing is written for a study without path frames.
 */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "motion.h"
#include "report_int.h"

static int same_group(const struct sl_motion_row *a, const struct sl_motion_row *b)
{
    return !strcmp(a->scene, b->scene) && !strcmp(a->path, b->path) && a->vw == b->vw && a->vh == b->vh &&
           a->map_size == b->map_size;
}

static enum sl_err group(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                         const struct sl_motion_row *rows, int n, struct sl_diag *d)
{
    const struct sl_motion_row *r0 = &rows[0];
    char id[200], slug[160], raw[160];
    snprintf(raw, sizeof raw, "%s-%s-%dx%d-%d", r0->scene, r0->path, r0->vw, r0->vh, r0->map_size);
    sl_tab_slug(raw, slug, sizeof slug);
    snprintf(id, sizeof id, "%s-motion-%s", s->slug, slug);
    struct sl_tab t;
    sl_tab_init(&t, id, 8, 1, "%s / %s, path %s, %dx%d, map %d²: errors over motion", s->name, r0->scene,
                       r0->path, r0->vw, r0->vh, r0->map_size);
    static const char *const head[8] = {"label", "frames", "mean wrong", "worst wrong (frame)", "flicker",
                                        "mean per pair", "worst flicker (frame)", "per 1,000 contour px"};
    for (int c = 0; c < 8; c++)
        sl_tab_head(&t, c, "%s", head[c]);
    sl_tab_notef(&t, "Wrong: the whole image's wrong pixels per frame. Flicker: pixels whose "
             "verdict changes from one frame to the next while their truth does not, compared by surface point "
             "(reprojected through the G-buffer onto the same triangle; pixel for pixel when the camera holds "
             "still); %d pairs of frames compared of %d frames. Per 1,000 contour px: of the thinnest contour of "
             "the later frame of each pair.", r0->pairs, r0->frames);
    char labels[32][48];
    int nl = 0;
    for (int i = 0; i < n; i++) {
        const struct sl_motion_row *r = &rows[i];
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "%s", r->label);
        sl_tab_cell(&t, 1, "%d", r->frames);
        sl_tab_cell(&t, 2, "%.1f", r->mean_wrong);
        sl_tab_cell(&t, 3, "%llu (%d)", (unsigned long long)r->worst_wrong, r->worst_frame);
        sl_tab_cell(&t, 4, "%llu", (unsigned long long)r->flicker);
        if (r->pairs) {
            sl_tab_cell(&t, 5, "%.1f", r->mean_flicker);
            sl_tab_cell(&t, 6, "%llu (%d)", (unsigned long long)r->worst_flicker, r->worst_flicker_frame);
        } else {
            sl_tab_cell(&t, 5, "n/a");
            sl_tab_cell(&t, 6, "n/a");
        }
        if (isnan(r->per_1000))
            sl_tab_cell(&t, 7, "n/a");
        else
            sl_tab_cell(&t, 7, "%.2f", r->per_1000);
        if (nl < 32)
            snprintf(labels[nl++], sizeof labels[0], "%s", r->label);
    }
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    if (e)
        return e;
    /* the plot: wrong pixels per frame and flicker, one panel each */
    char *data = NULL, *body = NULL;
    size_t dlen = 0, blen = 0;
    FILE *dm = open_memstream(&data, &dlen), *m = open_memstream(&body, &blen);
    if (!dm || !m) {
        if (dm) fclose(dm);
        if (m) fclose(m);
        free(data);
        free(body);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, id, "plot");
    }
    fprintf(dm, "# frame, then per label: wrong pixels, flicker against the frame before (NaN: not compared)\n");
    sl_motion_series(dm, s->cells, s->n, r0, labels, nl);
    /* two panels, one scale each (wrong pixels above, flicker below), one style per label */
    fprintf(m, "set datafile missing '-'\nset grid\nset border 3\nset tics nomirror\nset yrange [0:*]\n"
               "set lmargin at screen 0.08\nset rmargin at screen 0.80\nset multiplot\n");
    for (int panel = 0; panel < 2; panel++) {
        fprintf(m, "%sset tmargin at screen %s\nset bmargin at screen %s\nset xlabel '%s'\nset ylabel '%s'\nplot ",
                panel ? "unset key\n" : "set key at screen 0.81, screen 0.95 left top Left reverse samplen 1.5\n",
                panel ? "0.47" : "0.95", panel ? "0.12" : "0.53", panel ? "frame" : "",
                panel ? "flicker against the frame before, pixels" : "wrong pixels");
        for (int l = 0; l < nl; l++) {
            const char *col;
            int pt;
            sl_report_style(l, &col, &pt);
            fprintf(m, "%sDATA using 1:%d with linespoints lw 1.5 pt %d ps 0.6 lc rgb '%s' title ", l ? ", \\\n     " : "",
                    2 + 2 * l + panel, pt, col);
            sl_report_gp_quote(m, labels[l]);
        }
        fputc('\n', m);
    }
    fputs("unset multiplot", m);
    fputc('\n', m);
    int bad = ferror(dm) || ferror(m);
    fclose(dm);
    fclose(m);
    if (bad || !data || !body) {
        free(data);
        free(body);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, id, "plot");
    }
    char cap[300];
    snprintf(cap, sizeof cap, "%s, path %s, %dx%d, map %d²: wrong pixels and flicker per frame", r0->scene,
             r0->path, r0->vw, r0->vh, r0->map_size);
    e = sl_report_plot_draw(doc, gnuplot, id, 1100, 480, data, body, cap, d);
    free(data);
    free(body);
    return e;
}

enum sl_err sl_report_motion(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                             struct sl_diag *d)
{
    struct sl_motion_row *rows = NULL;
    int n = 0;
    enum sl_err e = sl_motion_rows(s->cells, s->n, &rows, &n, d);
    if (e || n == 0) {
        free(rows);
        return e;
    }
    sl_report_doc_heading(doc, 3, NULL, "%s: errors over motion", s->name);
    sl_report_doc_para(doc, "Each frame of a path is a view like any other (its cells are in every table "
                            "above); here the frames are read in order. Exact methods flicker nowhere by "
                            "construction: their verdicts equal the truth, and a pixel counts only where the truth "
                            "holds still.");
    for (int i = 0; i < n && !e;) {
        int k = i + 1;
        while (k < n && same_group(&rows[i], &rows[k]))
            k++;
        e = group(doc, s, gnuplot, rows + i, k - i, d);
        i = k;
    }
    free(rows);
    return e;
}
