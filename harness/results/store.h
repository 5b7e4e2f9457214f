/*
 * store.h — the results store: SQLite (results/shadowlab.db by default).
 *
 * Every run appends a run row (time, git SHA, config path and hash, host, CPU,
 * ISA, GL renderer and version, Embree version, thread counts). Every cell
 * appends a cell row (its key, counts and costs) and one row per figure keyed
 * by (scene, viewpoint, viewport, map size, method label, region, figure), in
 * ONE transaction, so a killed run leaves no partial cell. A cell is
 * identified across runs by the config hash and its key; `--resume` asks
 * sl_store_has_cell and skips what is there.
 *
 * A cell is a struct sl_cell_record (cellcols.h): the `cells` table's
 * columns, its INSERT and its SELECT are generated from SL_CELL_COLUMNS.
 *
 * Owns: the sqlite3 handle (sl_store_close). Does not: compute or format
 * (table.c formats what sl_store_query returns); know the tables.
 * Schema versioned with PRAGMA user_version; a database of another version is
 * refused with SL_E_IO naming the file.
 */
#ifndef SL_STORE_H
#define SL_STORE_H
#include <stdint.h>
#include "cellcols.h"
#include "provenance.h"
#include "sl_error.h"

struct sl_store;

/* Open or create the database at path. Its folder must exist: the caller
 * makes it (sl_mkdirs); the store creates no folders. */
enum sl_err sl_store_open(const char *path, struct sl_store **out, struct sl_diag *d);
/* The same for readers (table, check, report): a missing file is SL_E_IO
 * naming it, never a new empty store. */
enum sl_err sl_store_open_existing(const char *path, struct sl_store **out, struct sl_diag *d);
void        sl_store_close(struct sl_store *s);   /* NULL-safe */
/* A writer's last step (a run, a merge): every frame of the -wal into the
 * .db (wal_checkpoint(TRUNCATE), checked), the journal switched to DELETE so
 * closing leaves no -wal, the .db and its folder fsync()ed: afterwards the
 * .db alone holds the whole store. SL_E_OUTPUT naming the store, the bytes
 * still only in its -wal and what to free, when any step fails (the -wal is
 * kept: the next writer, `run --resume`, checkpoints it). */
enum sl_err sl_store_seal(struct sl_store *s, struct sl_diag *d);
/* A copy of the store at from (read as a reader does, its -wal included)
 * into the new file to, page by page (SQLite's backup API): the start of a
 * merge that must leave the store at from untouched until it renames the
 * finished copy over it. SL_E_OUTPUT naming to when it cannot be written. */
enum sl_err sl_store_copy(const char *from, const char *to, struct sl_diag *d);

/* study: the config's name; config_text: the filled-in config (may be NULL). */
enum sl_err sl_store_begin_run(struct sl_store *s, const struct sl_provenance *p, const char *study,
                               const char *config_path, unsigned long long config_hash,
                               const char *config_text, int64_t *run_id, struct sl_diag *d);

/* 1 if a cell with this config hash and key is stored (by any run), else 0
 * (also on a database error: the cell is then recomputed and its put reports
 * the error). */
int sl_store_has_cell(struct sl_store *s, unsigned long long config_hash, const char *scene,
                      const char *viewpoint, int vw, int vh, int map_size, const char *label);
/* The same cell's id (its row in cells), 0 when it is not stored. */
int64_t sl_store_cell_id(struct sl_store *s, unsigned long long config_hash, const char *scene,
                         const char *viewpoint, int vw, int vh, int map_size, const char *label);

/* Append one cell (its columns of cellcols.h, its figures, its soft figures
 * when has_soft) in one transaction. NAN stage times are stored as NULL (not
 * measured); study, run_id and the provenance fields are the run's, not read. */
enum sl_err sl_store_put_cell(struct sl_store *s, int64_t run_id, unsigned long long config_hash,
                              const struct sl_cell_record *c, struct sl_diag *d);

/* Cells for tables: filters may be NULL / 0 for "any"; when a key was stored
 * several times, the latest run's cell wins (with run_id set: the latest of
 * that run). Ordered by scene, then the config's sweep order (cell_index).
 * Each cell's regions come back as figures.c orders them (contours ascending,
 * whole image last), NULL percentages and times as NAN, machine as
 * "host/cpu/isa" of its run. *out is malloc'ed (free), NULL when *n is 0 or on error. */
struct sl_store_filter {
    const char *study;                      /* the config's name */
    const char *scene, *viewpoint, *label;  /* label: one, or several "a,b" (labels have no ',') */
    int         map_size;
    int64_t     run_id;                     /* 0 = all runs */
};
enum sl_err sl_store_query(struct sl_store *s, const struct sl_store_filter *f,
                           struct sl_cell_record **out, int *n, struct sl_diag *d);

/* One run (one invocation of `shadowlab run`): where its numbers came from. */
struct sl_store_run {
    int64_t run_id;
    struct sl_provenance prov;              /* git SHA, time, host, CPU, ISA, GL, Embree, threads */
    char    study[64];                      /* the config's name */
    char    config_path[512];
    char    config_hash[24];
    char   *config_text;                    /* the filled-in config, as written beside the results */
    int     ncells;                         /* cells this run stored */
};
/* Every run, oldest first. Free with sl_store_runs_free. */
enum sl_err sl_store_runs(struct sl_store *s, struct sl_store_run **out, int *n, struct sl_diag *d);
void        sl_store_runs_free(struct sl_store_run *r, int n);   /* NULL-safe */

/* `shadowlab verify`: SQLite's quick_check, then every cell's digest
 * (integrity.h) recomputed from what is stored. */
struct sl_store_damage {
    int64_t cell_id, run_id;
    char    key[200];                       /* scene/viewpoint/WxH/map/label */
};
struct sl_store_verify {
    long    cells, figures;                 /* rows checked */
    int     ndamaged;                       /* cells whose digest differs */
    struct sl_store_damage *damaged;        /* all of them, by cell id (malloc'ed) */
    double  seconds;
};
/* SL_OK when the store could be read through, damaged cells or not (r says);
 * SL_E_IO naming the store when quick_check fails or a query does. */
enum sl_err sl_store_verify(struct sl_store *s, struct sl_store_verify *r, struct sl_diag *d);
void        sl_store_verify_free(struct sl_store_verify *r);   /* NULL-safe */

/* The schema version this build reads and writes (PRAGMA user_version). */
int sl_store_version(void);

/* Number of rows in a table ("runs", "cells", "figures"); -1 on error (tests). */
long sl_store_count(struct sl_store *s, const char *table);

#endif
