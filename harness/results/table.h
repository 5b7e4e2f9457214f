/*
 * table.h — thesis-style tables from cells of figures, in Markdown, CSV or
 * LaTeX (booktabs). One renderer serves `shadowlab run` (table.md, from the
 * cells in memory) and `shadowlab table` (from the results store), so the
 * two can never disagree.
 *
 * Layout: one table per (scene, viewpoint, viewport, label); rows are the
 * figures of figures.h (count, and percentage of its base where it has one);
 * columns are map size x region, map sizes ascending, regions in the order of
 * the cells (contours ascending, whole image last). This puts Morais 2015
 * Table 7 (light/shadow correct/incorrect) and Moderno 2011 Tables 17/18
 * (wrong pixels and the share caught per contour) in one place.
 * CSV is the long form: one line per (cell, region, figure).
 * A cell is a struct sl_cell_record (cellcols.h), as the store returns it.
 * Markdown, CSV and LaTeX are built as the table model (tabmodel.h) and
 * written by its emitters (emit.h); LaTeX here is the thesis' per-cell floats
 * (the model's fixed layout: `shadowlab table --format latex`, the report); a
 * paper takes pivot.h's tables, and a run writes those
 * (SL_TABLE_LATEX_SUMMARY, SL_TABLE_LATEX_DETAIL).
 * Does not: read files or the database.
 */
#ifndef SL_TABLE_H
#define SL_TABLE_H
#include "tex.h"   /* sl_tex_text: the tables' and the report's LaTeX text */
#include <stdint.h>
#include <stdio.h>
#include "cellcols.h"
#include "sl_error.h"

/* JSON: pivots only (pivot.h). LATEX_SUMMARY and LATEX_DETAIL: the run's
 * table.tex and table-detail.tex (pivot.h: sl_pivot_tex_summary, _detail),
 * no names of their own. */
enum sl_table_format {
    SL_TABLE_MD = 0, SL_TABLE_CSV, SL_TABLE_LATEX, SL_TABLE_JSON, SL_TABLE_LATEX_SUMMARY, SL_TABLE_LATEX_DETAIL
};
int sl_table_format_parse(const char *name);     /* -1 if unknown: md, csv, latex, json */

/* Render cells (any order; grouped and sorted by the renderer). `title` heads
 * the output (Markdown/LaTeX), NULL for none. Two cells of one table with the
 * same map size are refused (SL_E_USAGE, key names the table); a failed write
 * to `out` is SL_E_IO. */
enum sl_err sl_table_write(FILE *out, enum sl_table_format fmt, const char *title,
                           const struct sl_cell_record *cells, int ncells, struct sl_diag *d);

/* Which figure rows a table shows. Zero means every row (the Markdown files
 * and CSV keep everything). `produced` leaves out the rows a method does not
 * produce: a figure past the core ones (pixels ... wrong_caught, always
 * shown: a zero there is a result) that is 0 in every column of the table.
 * `pick` (figure names, see sl_table_figures_parse) shows those rows only,
 * in figures.h's order; a soft table none of whose figures is picked is left
 * out. LaTeX always splits a table by map size (one float each) and never
 * writes a heading or scales: a float still wider than the line has its
 * cells stacked (count above percentage) when its rows then fit a page, else
 * it is split by regions into floats that each repeat the figure names. */
struct sl_table_rows {
    int           produced;
    int           picked;                /* pick_hard/pick_soft are set */
    unsigned char pick_hard[SL_FIG_COUNT];
    unsigned char pick_soft[SL_SFIG_COUNT];
};
enum sl_err sl_table_write_rows(FILE *out, enum sl_table_format fmt, const char *title,
                                const struct sl_cell_record *cells, int ncells, const struct sl_table_rows *rows,
                                struct sl_diag *d);
/* "wrong,light_incorrect" -> rows->pick_*; "all" picks nothing and clears
 * produced. An unknown name is SL_E_USAGE (key "--figures") listing them. */
enum sl_err sl_table_figures_parse(const char *list, struct sl_table_rows *rows, struct sl_diag *d);


#endif
