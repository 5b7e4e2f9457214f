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
 * Does not: read files or the database.
 */
#ifndef SL_TABLE_H
#define SL_TABLE_H
#include <stdint.h>
#include <stdio.h>
#include "figures.h"
#include "softfig.h"
#include "sl_error.h"

enum sl_table_format { SL_TABLE_MD = 0, SL_TABLE_CSV, SL_TABLE_LATEX };
int sl_table_format_parse(const char *name);     /* -1 if unknown: md, csv, latex */

/* What a cell cost: machine-independent counters, and wall times in ms.
 * Stages timed over the config's repetitions keep {median, min, max}; the
 * others were measured once. Zero when unknown. */
enum { SL_MED = 0, SL_MIN = 1, SL_MAX = 2 };
struct sl_table_costs {
    int      runs;                      /* timed repetitions behind each median */
    uint64_t truth_rays;                /* shadow rays of the truth pass (0 when cached) */
    uint64_t lookups, rays, tri_tests;  /* the method's: map lookups, shadow rays, ray-triangle tests */
    uint64_t gs_prims, fragments;       /* of the layers the method reads (GL queries) */
    uint64_t violations;                /* of its declared exactness (must be 0) */
    double   gbuffer_render[3], truth[3], map_render[3], method[3];
    double   gbuffer_readback, fit, map_readback, ray_step, step[4], contours, figures, overlay;
};

struct sl_table_cell {
    char     scene[64], viewpoint[32], method[32], label[48];
    int      vw, vh, map_size;
    uint64_t n_pfl, n_pnfl, n_background, n_truth_lit, n_truth_shadow;
    struct sl_figures fig;             /* hard shadows (fig.nregions = 0 for a soft method's cell) */
    int      has_soft;                 /* an area light: the soft figures below; a hard method's cell
                                        * has both, its hard figures against the light's centre */
    struct sl_soft_figures soft;
    struct sl_table_costs cost;
    char     study[64];                 /* the config's name */
    char     overlay[512];              /* error overlay PNG: relative to the database's folder
                                         * (store) or to the run's folder (run); "" = none */
    int64_t  run_id;                    /* 0 when not from the store */
    /* provenance of the numbers, printed under each table and in CSV rows */
    char     git_sha[48], config_hash[24], machine[256];
};

/* Render cells (any order; grouped and sorted by the renderer). `title` heads
 * the output (Markdown/LaTeX), NULL for none. Two cells of one table with the
 * same map size are refused (SL_E_USAGE, key names the table); a failed write
 * to `out` is SL_E_IO. */
enum sl_err sl_table_write(FILE *out, enum sl_table_format fmt, const char *title,
                           const struct sl_table_cell *cells, int ncells, struct sl_diag *d);

/* s as LaTeX text: the ten specials escaped, and the few non-ASCII signs
 * shadowlab writes (², ×, –, →) as LaTeX. Shared by the tables and the report. */
void sl_tex_text(FILE *f, const char *s);

#endif
