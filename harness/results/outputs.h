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
 * And the run's folder: staged in a hidden folder and swapped into place at
 * the end (sl_out_stage_*), and each computed cell put into the store with
 * the path of its overlay.
 *
 * Owns: nothing between calls. Does not: compute cells, or print anywhere
 * but the FILEs it is given.
 */
#ifndef SL_OUTPUTS_H
#define SL_OUTPUTS_H
#include <stdio.h>
#include "cellcols.h"
#include "config.h"
#include "plan.h"
#include "provenance.h"
#include "runresult.h"
#include "store.h"
#include "table.h"

/* The overlay's file name inside the run's overlays/ folder, and the EXR
 * file's inside exr/. */
void sl_out_overlay_name(const struct sl_config *c, const struct sl_cell *cl, char *out, size_t n);
void sl_out_exr_name(const struct sl_config *c, const struct sl_cell *cl, char *out, size_t n);
/* The cell's visibility file (outputs.visibility: exr), named as its EXR
 * layers' file, inside visibility/. */
#define sl_out_visibility_name sl_out_exr_name

/* cl as a record: key, counts, costs and figures; study and config_hash from
 * c. No overlay, run_id, git SHA or machine (the caller's). */
void sl_out_record(const struct sl_config *c, const struct sl_cell *cl, struct sl_cell_record *r);

/* The computed cells as tables (table.h); SL_E_NOMEM, or sl_table_write's error. */
enum sl_err sl_out_write_tables(FILE *f, enum sl_table_format fmt, const struct sl_config *c,
                                const struct sl_run_result *res, struct sl_diag *d);
/* Markdown for the terminal: the rows a method does not produce left out. */
enum sl_err sl_out_print_tables(FILE *f, const struct sl_config *c, const struct sl_run_result *res,
                                struct sl_diag *d);
void sl_out_write_costs_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
void sl_out_write_costs_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
/* Texel coherence's undecided pixels by pattern (Moderno 2011 Tables 20/22). */
void sl_out_write_patterns_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
void sl_out_write_patterns_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res);
void sl_out_write_run_yaml(FILE *f, const struct sl_config *c, const struct sl_run_result *res);

/* The run's folders: results land in a hidden staging folder
 * <root>/.<name>.partial-<pid>, which replaces <root>/<name> once every file
 * is written, so a reader never sees a half-written results folder. */
#define SL_OUT_CLAIM ".claim"   /* the staging folder's lock file (outputs.c) */
struct sl_out_dirs {
    int  claim;            /* fd + 1 of the staging folder's claim, flock()ed; 0 none */
    char root[1024];
    char final[1100];      /* <root>/<name> */
    char stage[1100];      /* the staging folder, "" none */
    char overlays[1200];   /* <stage>/overlays */
    char exr[1200];        /* <stage>/exr */
    char visibility[1200]; /* <stage>/visibility (outputs.visibility: exr) */
};
/* SL_E_USAGE naming path when it is a symbolic link: a run never writes
 * through one (a pre-existing link under --out could point anywhere). */
enum sl_err sl_out_no_link(const char *path, struct sl_diag *d);
/* The same for a store at path and the files SQLite and its lock keep
 * beside it (-wal, -shm, -journal, .lock). */
enum sl_err sl_out_no_store_link(const char *path, struct sl_diag *d);

/* Make the staging folder (and its overlays/ and exr/ when the config asks),
 * claimed by this run until it is finished or dropped; <root>/<name> must
 * not be a symbolic link. */
enum sl_err sl_out_stage_begin(const struct sl_config *c, const char *root, struct sl_out_dirs *o,
                               struct sl_diag *d);
/* Write the run's files into the staging folder; after a resumed run, carry
 * the overlays and EXR files of the cells it skipped from the previous
 * folder (or a killed run's staging folder), so what the store points at
 * is in place; then swap the staging folder into place. */
enum sl_err sl_out_stage_finish(const struct sl_config *c, const struct sl_run_result *res,
                                struct sl_out_dirs *o, int resume, struct sl_diag *d);
/* Remove the staging folder (a run that failed). NULL-safe on an empty o. */
void sl_out_stage_drop(struct sl_out_dirs *o);

/* The run row of the store, carrying the filled-in config. */
enum sl_err sl_out_begin_run(struct sl_store *st, const struct sl_config *c, const struct sl_provenance *p,
                             int64_t *run_id, struct sl_diag *d);
/* Put one computed cell into the store, with its overlay's path as the store
 * keeps it (relative to the database's folder when the results folder lies
 * under it, else absolute) and, in the same transaction, the path, size and
 * CRC-32 of each file it wrote (overlay, EXR; read from the staging folder,
 * recorded at the path they will have in the results folder); dirs: the
 * run's folders, NULL when no files are written. */
enum sl_err sl_out_store_cell(struct sl_store *st, int64_t run_id, const struct sl_config *c,
                              const struct sl_cell *cl, const char *store_path, const struct sl_out_dirs *dirs,
                              struct sl_diag *d);

/* The run's own files (the regular files at the top of the results folder:
 * tables, CSV, run.yaml, config.yaml) recorded in the store with their size
 * and CRC-32, once they are in place. */
enum sl_err sl_out_record_run_files(struct sl_store *st, int64_t run_id, const char *store_path,
                                    const struct sl_out_dirs *dirs, struct sl_diag *d);

/* The store's cells of this config (its study name and hash), in store
 * order; *cells malloc'ed (free it), *n their number. */
enum sl_err sl_out_stored_cells(struct sl_store *st, const struct sl_config *c, struct sl_cell_record **cells,
                                int *n, struct sl_diag *d);

/* 1 when the store holds the cell of key k for this config (a resumed run
 * skips it). */
int     sl_out_stored(const struct sl_config *c, const struct sl_cell_key *k, struct sl_store *st);
/* Its row's id in the store, 0 when not stored. */
int64_t sl_out_stored_id(const struct sl_config *c, const struct sl_cell_key *k, struct sl_store *st);

/* The files a stored cell's key names in a results folder: its overlay
 * (overlays/NAME.png, when the config asks for overlays) and its EXR file
 * (exr/NAME.exr, when it asks for EXR files). A resumed run treats a
 * stored cell whose files are in none of the folders it carries from as not
 * stored: it recomputes the cell, which replaces its row, and writes the
 * files again (a lost overlay is repaired, not only reported). */
struct sl_out_kept {
    int   n;
    char (*dir)[1200];   /* folders holding overlays/ and exr/ */
};
/* The folders the files of a skipped cell can come from: final, and every
 * dead run's claimable staging folder <root>/.<name>.partial-* but `own`
 * (those carry_previous carries from; NULL root: final only). */
enum sl_err sl_out_kept_find(const struct sl_config *c, const char *root, const char *final, const char *own,
                             struct sl_out_kept *k, struct sl_diag *d);
/* 1 when every file the config asks for of the cell of key `key` is in one
 * of k's folders (always 1 when it asks for none), and, when st (the store
 * whose results folder is k's first) records the file, of its recorded size
 * and CRC-32: a damaged file is computed again like a lost one. */
int  sl_out_kept_whole(const struct sl_config *c, const struct sl_cell_key *key, const struct sl_out_kept *k,
                       struct sl_store *st);
void sl_out_kept_free(struct sl_out_kept *k);   /* NULL-safe on a zeroed k */

/* One table written in several formats, a file each: dir/files[i].name by
 * write(f, files[i].fmt, arg, d), in the order given. The first failure
 * stops the loop; the file it was writing is not left behind (the files
 * before it are). Serves the run's figures.csv/table.md/table.tex from the
 * store and motion.md/csv/tex. */
struct sl_out_format_file {
    const char          *name;
    enum sl_table_format fmt;
};
typedef enum sl_err (*sl_out_format_writer)(FILE *f, enum sl_table_format fmt, const void *arg,
                                            struct sl_diag *d);
enum sl_err sl_out_write_formats(const char *dir, const struct sl_out_format_file *files, int nfiles,
                                 sl_out_format_writer write, const void *arg, struct sl_diag *d);

/* Rebuild dir's figures.csv, table.md and table.tex from the store's cells of
 * this config when it holds more than `computed`; *stored = how many it holds. */
enum sl_err sl_out_rebuild_from_store(struct sl_store *st, const struct sl_config *c, int computed,
                                      const char *dir, int *stored, struct sl_diag *d);

#endif
