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

/* One cell key of a sweep's plan. */
struct sl_store_key {
    const char *scene, *viewpoint, *label;
    int         vw, vh, map_size;
    int         index;                      /* its place in the sweep (cell_index) */
};
/* The plan of the sweep config_hash names: every one of its cell keys, all
 * of them whatever slice (--cells) the run computes, so a store says which
 * cells it lacks. Idempotent (a key recorded once per config hash), in one
 * transaction. */
enum sl_err sl_store_put_plan(struct sl_store *s, unsigned long long config_hash, const struct sl_store_key *k,
                              int n, struct sl_diag *d);

/* A file a cell's computation wrote beside the store (its overlay, its EXR):
 * path as the store keeps it (relative to the store's folder, or absolute),
 * size and CRC-32 of its bytes. */
struct sl_store_file {
    char               path[1200];
    long long          size;
    uint32_t           crc32;
};
/* The CRC-32 (zlib) and size of the file at path; SL_E_IO naming it when it
 * cannot be read. */
enum sl_err sl_store_file_digest(const char *path, long long *size, uint32_t *crc, struct sl_diag *d);

/* The files of the run itself (its tables), cell_id NULL, in one
 * transaction; a path recorded before (an earlier run's table of the same
 * name) is taken over. */
enum sl_err sl_store_put_run_files(struct sl_store *s, int64_t run_id, const struct sl_store_file *files, int n,
                                   struct sl_diag *d);

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
/* The same with the files the cell wrote, recorded in the cell's transaction
 * (a file row of the key's earlier cell goes with it). */
enum sl_err sl_store_put_cell_files(struct sl_store *s, int64_t run_id, unsigned long long config_hash,
                                    const struct sl_cell_record *c, const struct sl_store_file *files, int nfiles,
                                    struct sl_diag *d);

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

/* Completeness: each sweep (config hash) the store holds cells or a plan
 * of, with how many of its planned cells are stored. */
struct sl_store_sweep {
    char config_hash[24];
    char study[64];
    char runs[128];                         /* its runs' ids, "1, 2, 5" (cut, with "...", when long) */
    int  planned;                           /* cells of its plan; -1 when no plan is recorded (a store
                                             * written before schema 23) */
    int  stored;                            /* planned keys with a stored cell (all its cells when no plan) */
};
enum sl_err sl_store_sweeps(struct sl_store *s, struct sl_store_sweep **out, int *n, struct sl_diag *d);
/* The planned keys of config_hash that have no stored cell, by cell index;
 * strings owned by *out's block (free(*out) alone). */
enum sl_err sl_store_missing(struct sl_store *s, const char *config_hash, struct sl_store_key **out, int *n,
                             struct sl_diag *d);

/* Files the store records: every one, checked against what lies at its
 * path (relative paths from the store's folder). */
struct sl_store_file_bad {
    char      path[1200];                   /* as recorded */
    char      why[160];                     /* "missing", "12345 bytes, recorded 12346", "CRC-32 differs" */
};
struct sl_store_files_check {
    int  recorded, present;                 /* rows, files found at their path */
    int  nbad;
    struct sl_store_file_bad *bad;          /* malloc'ed */
};
/* only_present: skip the check (r->nbad 0) when no recorded file is at its
 * path, the .db having been copied alone (verify's default); else every
 * missing file is bad. */
enum sl_err sl_store_check_files(struct sl_store *s, int only_present, struct sl_store_files_check *r,
                                 struct sl_diag *d);
/* The recorded size and CRC-32 of the file with this path as the store
 * keeps it: 1 when recorded, 0 when not, -1 on error. */
int sl_store_file_recorded(struct sl_store *s, const char *path, long long *size, uint32_t *crc);
/* The store's folder (from its path), for resolving relative file paths. */
const char *sl_store_path(const struct sl_store *s);

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

/* The schema version of the file s was opened on: an older one (16 and on)
 * is read through a private upgraded copy (store.c); before 17 its cells
 * carried no digest, so the copy's digests vouch for the copy only. */
int sl_store_read_version(const struct sl_store *s);

/* The schema version this build reads and writes (PRAGMA user_version). */
int sl_store_version(void);

/* Number of rows in a table ("runs", "cells", "figures"); -1 on error (tests). */
long sl_store_count(struct sl_store *s, const char *table);

#endif
