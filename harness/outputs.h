/*
 * outputs.h — what `shadowlab run` writes beside its results: the tables
 * (table.md, table.tex, figures.csv), the cost per cell (costs.csv and the
 * Markdown cost table), texel coherence's patterns (patterns.csv and its
 * Markdown table) and run.yaml; and the record of a computed cell
 * (cellcols.h) that the tables and the store are given.
 *
 * costs.csv's columns are the cell columns of cellcols.h that have a csv
 * position, in that order, then git_sha, config_hash and machine.
 *
 * Owns nothing: each function writes to the FILE it is given, which the run
 * opens, stages and renames. Does not: compute cells, open files or folders,
 * touch the store (run.c puts the record), or print anywhere else.
 */
#ifndef SL_OUTPUTS_H
#define SL_OUTPUTS_H
#include <stdio.h>
#include "run.h"

/* The overlay's file name inside the run's overlays/ folder. */
void sl_out_overlay_name(const struct sl_config *c, const struct sl_cell *cl, char *out, size_t n);

/* cl as a record: key, counts, costs and figures; study and config_hash from
 * c. No overlay, run_id, git SHA or machine (the caller's). */
void sl_out_record(const struct sl_config *c, const struct sl_cell *cl, struct sl_cell_record *r);

/* The computed cells as tables (table.h); SL_E_NOMEM, or sl_table_write's error. */
enum sl_err sl_out_write_tables(FILE *f, enum sl_table_format fmt, const struct sl_config *c,
                                const struct sl_run_result *res, struct sl_diag *d);
void sl_out_write_costs_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
void sl_out_write_costs_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
/* Texel coherence's undecided pixels by pattern (Moderno 2011 Tables 20/22). */
void sl_out_write_patterns_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
void sl_out_write_patterns_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
void sl_out_write_run_yaml(FILE *f, const struct sl_config *c, const struct sl_run_result *res);

#endif
