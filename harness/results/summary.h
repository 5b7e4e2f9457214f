/*
 * summary.h — the summary rows the theses report over a study (Moderno 2011
 * Tables 5-15): for one figure, its average over every cell and region, and
 * per map size the best and worst cell with its scene, viewpoint and
 * contour, plus a named "average case" (the thesis's: Bench, "with"
 * viewpoint, 2-pixel contour). Values are the figure's percentage. One
 * summary per label of the cells given (in their order), as Markdown, CSV
 * (one header) or LaTeX (a booktabs float each, escaped, fitted to the line,
 * never scaled). All three are the table model (tabmodel.h) written by its
 * emitters (emit.h); the LaTeX float is the model's fixed layout.
 * Does not: query the store or choose cells (the caller filters).
 */
#ifndef SL_SUMMARY_H
#define SL_SUMMARY_H
#include <stdio.h>
#include "table.h"

struct sl_summary_opts {
    int         figure;            /* enum sl_figure */
    int         lower_is_better;   /* 0: best = highest percentage */
    int         region;            /* contour thickness, 0 = whole image, -1 = every contour */
    const char *avg_scene;         /* the average case, NULL for none */
    const char *avg_viewpoint;
    int         avg_region;
    int         avg_map;           /* 0 = the first map size that has the cell */
    int         continued;         /* a later figure of the same output: no CSV header, no LaTeX comment */
};

enum sl_err sl_summary_write(FILE *out, enum sl_table_format fmt, const struct sl_cell_record *cells, int n,
                             const struct sl_summary_opts *o, struct sl_diag *d);

#endif
