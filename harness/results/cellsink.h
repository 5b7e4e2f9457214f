/*
 * cellsink.h — where a run hands each finished cell: its row in the store
 * (one transaction per cell, after the cell's overlay sheet is on disk, so
 * a stored cell is a whole one and `--resume` skips it), the overlay writer
 * its sheets go to (ovwriter.h), the staging folder its files land in and,
 * once the loop is done, the run's own files: tables, costs, the rebuilt
 * figures from the store, the motion outputs (outputs.h, motion_run.h).
 *
 * The run opens its parts in the order it needs (the staging folder before
 * any GL or Embree work; the store once the provenance is known) and hands
 * the sink each cell; sl_sink_close gives everything back, dropping the
 * staging folder of a failed run.
 *
 * Owns: the store handle, the overlay writer, the staging folder. Does not:
 * compute or score a cell, print, or decide which cells run.
 */
#ifndef SL_CELLSINK_H
#define SL_CELLSINK_H
#include <stdint.h>
#include <stdio.h>
#include "outputs.h"
#include "ovwriter.h"

struct sl_cell_sink {
    const struct sl_config *config;
    int                     write_files;   /* 0: compute only (no staging folder, no run files) */
    struct sl_out_dirs      dirs;          /* the staging folder (sl_out_stage_begin), when write_files */
    char                    store_path[1100];   /* the database, "" none */
    struct sl_store        *st;            /* open (sl_sink_open_store), or NULL */
    int64_t                 run_id;        /* the run's row in st */
    struct sl_ovw          *ovw;           /* the overlay writer (sl_sink_open_overlays), or NULL */
    struct sl_sheet_sink    sheets;        /* ovw as the sink scoring hands its sheets to */
};

/* The overlay writer thread: sheets are written off the cells' path. */
enum sl_err sl_sink_open_overlays(struct sl_cell_sink *s, struct sl_diag *d);
/* Where a cell's scoring hands its sheets: the writer, or NULL (written by
 * the cell itself). */
const struct sl_sheet_sink *sl_sink_sheets(const struct sl_cell_sink *s);
/* The store at store_path (none when ""), with the run's row carrying the
 * filled-in config and p. */
enum sl_err sl_sink_open_store(struct sl_cell_sink *s, const struct sl_provenance *p, struct sl_diag *d);

/* One finished cell: its sheet on disk first, then its row (no-op without
 * a store). */
enum sl_err sl_sink_put(struct sl_cell_sink *s, const struct sl_cell *cell, struct sl_diag *d);
/* Every sheet written (a write error fails the run). */
enum sl_err sl_sink_drain(struct sl_cell_sink *s, struct sl_diag *d);
/* The run's files into the staging folder, renamed to the final one (after
 * a resumed run, carrying the files of the cells it skipped), the store's
 * figures and tables rebuilt, the motion outputs, and the tables echoed to
 * table_out (NULL: none), only when write_files; then, files or not, the
 * store sealed (sl_store_seal: its .db alone holds it, synced to disk). */
enum sl_err sl_sink_finish(struct sl_cell_sink *s, struct sl_run_result *res, int resume, FILE *table_out,
                           struct sl_diag *d);
/* The writer's counts into res, everything closed; failed: the staging
 * folder dropped. */
void sl_sink_close(struct sl_cell_sink *s, struct sl_run_result *res, int failed);

#endif
