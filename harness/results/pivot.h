/*
 * pivot.h — one table a paper takes: one figure of many cells, its rows and
 * columns two of the cells' keys (label, method, scene, viewpoint, viewport,
 * map_size, region), each entry the mean (median, sum, min, max) of the
 * figure over what is left, in Markdown, CSV, JSON or LaTeX.
 *
 * The figure is a name of figures.h (per region), of softfig.h (the whole
 * image) or a counter or time of cellcols.h (ms_method, rays, ...: the whole
 * image). Its value is its percentage of its own base (figures.h's
 * percent_of), a count (of "count", and the figures without a base), or its
 * percentage of another figure of the same region (of "pfl").
 * --where KEY=VALUE keeps the points whose KEY is VALUE; a KEY given twice
 * keeps either value (label=a and label=b compare two labels).
 * Region is "image" unless it is a row or column key or a --where names it:
 * contours are nested in the image, a mean over them means nothing.
 *
 * LaTeX: booktabs, every name escaped, numbers right-aligned with thin-space
 * thousands separators, never scaled. A table estimated wider than a plain
 * article's \columnwidth (or of more than 8 numeric columns) is transposed
 * when that fits, else split into several tables by columns; the info says
 * so and the caller tells the user. A table of more rows than a page holds is a
 * float per page (34 rows), the heads on each.
 * Markdown, CSV and JSON are never split. Markdown, CSV and each LaTeX
 * table are the table model (tabmodel.h) written by its emitters (emit.h);
 * JSON is not a table but the aggregation's record (per row the values at
 * full precision, their counts and timed_once), which scripts read.
 *
 * Also the run's LaTeX (sl_pivot_tex_summary, sl_pivot_tex_detail): a few
 * summary tables per study and a per-view appendix.
 *
 * A paper takes the LaTeX as it is (issue 47): table* floats (a one- and a
 * two-column class both take them; a longtable fails in a two-column one);
 * captions in words (the figure and its base, per which keys, what an entry
 * aggregates over and how many values, what every entry shares, the light,
 * the study), never a figure's or a counter's name; rows and captions name
 * a label by its display name; numbers by sl_tab_sig (an exact 0 as 0, a
 * small value with two significant digits, never 0.00); a \label that holds
 * the study, --of, --agg and every --where; a pivot whose entries are all
 * 0 a sentence, not a table (info->zero).
 * Owns: nothing it returns. Does not: read the store, print to a terminal.
 */
#ifndef SL_PIVOT_H
#define SL_PIVOT_H
#include <stdio.h>
#include "cellcols.h"
#include "sl_error.h"
#include "table.h"

/* 0 is "the default" (rows: label, columns: map_size). */
#define SL_PIVOT_KEYS(X) X(label) X(method) X(scene) X(viewpoint) X(viewport) X(map_size) X(region)
enum sl_pivot_key {
    SL_PK_DEFAULT = 0,
#define SL_PK_ENUM(name) SL_PK_##name,
    SL_PIVOT_KEYS(SL_PK_ENUM)
#undef SL_PK_ENUM
    SL_PK_COUNT
};
const char *sl_pivot_key_name(enum sl_pivot_key k);
int         sl_pivot_key_parse(const char *name);   /* -1 if unknown */

enum sl_pivot_agg { SL_AGG_MEAN = 0, SL_AGG_MEDIAN, SL_AGG_SUM, SL_AGG_MIN, SL_AGG_MAX };
int sl_pivot_agg_parse(const char *name);            /* -1 if unknown */
/* The i-th counter or time of cellcols.h a pivot's --figure takes (besides
 * the figures of figures.h and softfig.h); NULL past the last. */
const char *sl_pivot_counter_name(int i);

#define SL_PIVOT_MAX_WHERE 16

struct sl_pivot_desc {
    enum sl_pivot_key rows, cols;       /* default label x map_size */
    const char       *figure;           /* NULL: "wrong" */
    const char       *of;               /* NULL: the figure's base; "count"; or a figure name */
    enum sl_pivot_agg agg;
    int               nwhere;
    struct { enum sl_pivot_key key; const char *value; } where[SL_PIVOT_MAX_WHERE];
    const char       *tex_label;        /* \label{tab:...} key, NULL: from the figure and keys */
};

/* How the LaTeX came out (zero for the other formats). */
struct sl_pivot_info {
    int nrows, ncols;                   /* the table's, before any split */
    int parts;                          /* tables written (0: no cell had the figure) */
    int transposed;
    int zero;                           /* LaTeX: every entry 0, a sentence written instead of the table */
};

/* "label=nsm" -> p->where[p->nwhere++]; SL_E_USAGE (key "--where") if the
 * key is unknown, no '=' or too many. value points into kv. */
enum sl_err sl_pivot_where_parse(struct sl_pivot_desc *p, const char *kv, struct sl_diag *d);

/* fmt: SL_TABLE_MD, CSV, LATEX or JSON. SL_E_USAGE for an unknown figure,
 * a base that does not apply, rows = cols; no matching value is not an
 * error (an empty table, parts 0). info may be NULL. */
enum sl_err sl_pivot_write(FILE *out, enum sl_table_format fmt, const struct sl_cell_record *cells, int ncells,
                           const struct sl_pivot_desc *p, struct sl_pivot_info *info, struct sl_diag *d);

/* The run's table.tex: per study, label x map size of the wrong and the
 * undecided pixels (% of the image's), the method's time (ms), an area
 * light's error, and label x scene when there are several scenes. */
enum sl_err sl_pivot_tex_summary(FILE *out, const char *title, const struct sl_cell_record *cells, int ncells,
                                 struct sl_diag *d);
/* The run's table-detail.tex: per view floats of every label and map
 * size (light, shadow, undecided, wrong, the share caught by each contour,
 * the time), for an appendix. */
enum sl_err sl_pivot_tex_detail(FILE *out, const char *title, const struct sl_cell_record *cells, int ncells,
                                struct sl_diag *d);


#endif
