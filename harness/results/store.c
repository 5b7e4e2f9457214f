/*
 * store.c — see store.h.
 *
 * Invariants:
 * - A cell row and all its figure rows are written in one BEGIN IMMEDIATE ...
 *   COMMIT; any failure in between rolls back, so a reader (or a process
 *   killed half-way) never sees a cell without its figures.
 * - Counts are uint64 in C and signed 64-bit in SQLite: a count that does not
 *   fit is bound as -1, which the CHECK (... >= 0) constraints refuse, so it
 *   fails the transaction instead of wrapping.
 * - NaN percentages are stored as NULL and read back as NAN.
 * - A database is ours only if its user_version is SL_STORE_VERSION and its
 *   tables are exactly the ones below (compared ignoring white space); an
 *   empty file is initialised. Anything else is refused before it is touched
 *   (no WAL switch, no schema), so a wrong path never damages another file.
 * - The figure CHECK lists the names of figures.h (softfig.h, aliasing.h), and the cells table the
 *   columns of cellcols.h: adding a figure or a stored column there changes
 *   the schema text, and old databases are refused at open instead of
 *   failing at the first put. Bump SL_STORE_VERSION with such a change.
 * Nothing here prints; errors name the database file and carry sqlite's text.
 */
#define _XOPEN_SOURCE 700
#include "store.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <sqlite3.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>
#include "integrity.h"
#include "store_int.h"
#include "storefile.h"
#include "util.h"

#define SL_STORE_VERSION 23   /* 23: cells' cost stages ms_map .. ms_gpu_lookup, runs_map, runs per cell
                               * (cellcols.h; ms_method the per-pixel step for every method), and the tables
                               * plan (the sweep's cell keys per config hash) and files (each file a run
                               * writes: path, size, CRC-32); 22: a hard light's class figures within SL_SOFT_HARD_TOL (softfig.h;
                               * the same tables, other values); 21: figures leaking, over_dark (softfig.h); 20: cells.nonfinite (cellcols.h);
                               * 19: cells.family, beside (the method's origin, method.h), display;
                               * 18: cells.frac (a hard light's fractional errors, cellcols.h);
                               * 17: cells.digest, one cell per config hash and key (UNIQUE);
                               * 16: figure names by instr(); 15: cells.n_outside_cone, light (view.h);
                               * 14: cells.faces, ms_face_max (lightframe.h); 13: aliasing figures, cells.texels;
                               * 12: cells.flicker, flicker_compared, ms_flicker; 11: ms_gpu_gbuffer, ms_gpu_map;
                               * 10: runs.gl_backend; 9: contour_from, PnFL-inclusive figures; 8: soft figures;
                               * 7: study, config text, costs, overlay path; 2-6: traced, hints, confirmed, ... */
#define SL_STORE_OLDEST 16   /* the oldest schema readers read (through an upgraded copy) */
#define SL_STR_(x) #x
#define SL_STR(x) SL_STR_(x)
#define SL_STORE_BUSY_MS 10000

/* ---- schema ---- */

#define SL_HEX16_CHECK(col) \
    "CHECK (length(" col ") = 16 AND " col " NOT GLOB '*[^0-9a-f]*')"
#define SL_FIG_SQL_NAME(name, text, of) #name ","

/* The cell columns of cellcols.h, by kind: their SQL declaration, their
 * name in the INSERT, SELECT and VALUES lists (flag columns are not stored),
 * how a record's value is bound and how a row's value is read back. */
#define SL_SQL_DECL_text(name)     "TEXT NOT NULL"
#define SL_SQL_DECL_path(name)     "TEXT"
#define SL_SQL_DECL_dim(name)      "INTEGER NOT NULL CHECK (" #name " > 0)"
#define SL_SQL_DECL_index(name)    "INTEGER NOT NULL"
#define SL_SQL_DECL_runs(name)     "INTEGER NOT NULL CHECK (" #name " >= 0)"
#define SL_SQL_DECL_count(name)    "INTEGER NOT NULL CHECK (" #name " >= 0)"
#define SL_SQL_DECL_wrong(name)    "INTEGER NOT NULL CHECK (" #name " >= 0)"
#define SL_SQL_DECL_ms(name)       "REAL"
#define SL_SQL_DECL_viewport(name) "TEXT NOT NULL"
#define SL_SQL_STORED_flag(...)
#define SL_SQL_STORED(kind, ...) SL_SQL_STORED_##kind(__VA_ARGS__)
#define SL_SQL_STORED_text(...) __VA_ARGS__
#define SL_SQL_STORED_path(...) __VA_ARGS__
#define SL_SQL_STORED_dim(...) __VA_ARGS__
#define SL_SQL_STORED_index(...) __VA_ARGS__
#define SL_SQL_STORED_runs(...) __VA_ARGS__
#define SL_SQL_STORED_count(...) __VA_ARGS__
#define SL_SQL_STORED_wrong(...) __VA_ARGS__
#define SL_SQL_STORED_ms(...) __VA_ARGS__
#define SL_SQL_STORED_viewport(...) __VA_ARGS__
#define SL_SQL_COL(name, kind, size, csv, head, check, key, from) \
    SL_SQL_STORED(kind, "  " #name " " SL_SQL_DECL_##kind(name) ",\n")
#define SL_SQL_NAME(name, kind, size, csv, head, check, key, from) SL_SQL_STORED(kind, ", " #name)
#define SL_SQL_L_NAME(name, kind, size, csv, head, check, key, from) SL_SQL_STORED(kind, ", l." #name)
#define SL_SQL_PARAM(name, kind, size, csv, head, check, key, from) SL_SQL_STORED(kind, ",?")

static const char sql_runs[] =
    "CREATE TABLE runs (\n"
    "  run_id         INTEGER PRIMARY KEY,\n"
    "  time_utc       TEXT NOT NULL,\n"
    "  git_sha        TEXT NOT NULL,\n"
    "  study          TEXT NOT NULL,\n"
    "  config_path    TEXT NOT NULL,\n"
    "  config_hash    TEXT NOT NULL " SL_HEX16_CHECK("config_hash") ",\n"
    "  config_text    TEXT NOT NULL,\n"
    "  host           TEXT NOT NULL,\n"
    "  cpu            TEXT NOT NULL,\n"
    "  isa            TEXT NOT NULL,\n"
    "  gl_renderer    TEXT NOT NULL,\n"
    "  gl_version     TEXT NOT NULL,\n"
    "  gl_backend     TEXT NOT NULL,\n"
    "  embree         TEXT NOT NULL,\n"
    "  threads        INTEGER NOT NULL,\n"
    "  lp_num_threads TEXT NOT NULL\n"
    ")";

static const char sql_cells[] =
    "CREATE TABLE cells (\n"
    "  cell_id        INTEGER PRIMARY KEY,\n"
    "  run_id         INTEGER NOT NULL REFERENCES runs (run_id),\n"
    "  config_hash    TEXT NOT NULL " SL_HEX16_CHECK("config_hash") ",\n"
    SL_CELL_COLUMNS(SL_SQL_COL)
    "  digest         INTEGER NOT NULL CHECK (digest BETWEEN 0 AND 4294967295),\n"
    "  CHECK (viewport = vw || 'x' || vh),\n"
    "  UNIQUE (config_hash, scene, viewpoint, vw, vh, map_size, label)\n"
    ")";

/* Figure names: instr() over a comma-delimited list, not IN (...): under a
 * CHECK, SQLite builds an ephemeral index of an IN list for each row
 * inserted (8 us a row, 233 rows a cell); a name with a comma would match
 * across two names. The list stays in the schema text (the invariant above). */
static const char sql_figures[] =
    "CREATE TABLE figures (\n"
    "  cell_id    INTEGER NOT NULL REFERENCES cells (cell_id),\n"
    "  scene      TEXT NOT NULL,\n"
    "  viewpoint  TEXT NOT NULL,\n"
    "  viewport   TEXT NOT NULL,\n"
    "  map_size   INTEGER NOT NULL,\n"
    "  label      TEXT NOT NULL,\n"
    "  region     TEXT NOT NULL CHECK (region = 'image' OR region GLOB '[1-9]px'\n"
    "               OR region GLOB '[1-9][0-9]px' OR region GLOB '[1-9][0-9][0-9]px'),\n"
    "  figure     TEXT NOT NULL CONSTRAINT figure_known CHECK (instr(\n"
    "               '," SL_FIGURES(SL_FIG_SQL_NAME) SL_SOFT_FIGURES(SL_FIG_SQL_NAME)
    SL_ALIAS_FIGURES(SL_FIG_SQL_NAME) "background,', ',' || figure || ',') > 0\n"
    "               AND instr(figure, ',') = 0),\n"
    "  count      INTEGER NOT NULL CHECK (count >= 0),\n"
    "  percent    REAL,\n"
    "  percent_of TEXT,\n"
    "  UNIQUE (cell_id, region, figure)\n"
    ")";

/* The sweep a config hash names: every cell key of its plan, whichever
 * run (or slice, --cells) stored it first. A config hash fixes the sweep, so
 * every run of one hash records the same rows (INSERT OR IGNORE). */
static const char sql_plan[] =
    "CREATE TABLE plan (\n"
    "  config_hash    TEXT NOT NULL " SL_HEX16_CHECK("config_hash") ",\n"
    "  cell_index     INTEGER NOT NULL CHECK (cell_index >= 0),\n"
    "  scene          TEXT NOT NULL,\n"
    "  viewpoint      TEXT NOT NULL,\n"
    "  vw             INTEGER NOT NULL CHECK (vw > 0),\n"
    "  vh             INTEGER NOT NULL CHECK (vh > 0),\n"
    "  map_size       INTEGER NOT NULL CHECK (map_size > 0),\n"
    "  label          TEXT NOT NULL,\n"
    "  UNIQUE (config_hash, scene, viewpoint, vw, vh, map_size, label),\n"
    "  UNIQUE (config_hash, cell_index)\n"
    ")";

/* Each file a run writes beside the store (a cell's overlay and EXR files),
 * its path as the cell's overlay column keeps it (relative to the store's
 * folder, or absolute), its size and CRC-32 (zlib), written in the cell's
 * transaction. One row per path: a later cell that writes the same file
 * (the same key under another config hash) takes the row over. */
static const char sql_files[] =
    "CREATE TABLE files (\n"
    "  path           TEXT NOT NULL PRIMARY KEY,\n"
    "  run_id         INTEGER NOT NULL REFERENCES runs (run_id),\n"
    "  cell_id        INTEGER REFERENCES cells (cell_id),\n"
    "  size           INTEGER NOT NULL CHECK (size >= 0),\n"
    "  crc32          INTEGER NOT NULL CHECK (crc32 BETWEEN 0 AND 4294967295)\n"
    ")";

static const struct { const char *name, *sql; } sl_tables[] = {
    {"runs", sql_runs},
    {"cells", sql_cells},
    {"figures", sql_figures},
    {"plan", sql_plan},
    {"files", sql_files},
};

/* latest-per-key query; per-run filter; ad-hoc figure queries (the resume
 * lookup uses the UNIQUE key's own index) */
static const char *const sl_indexes[] = {
    "CREATE INDEX cells_key ON cells (scene, viewpoint, vw, vh, map_size, label, run_id)",
    "CREATE INDEX cells_run ON cells (run_id)",
    "CREATE INDEX figures_key ON figures (scene, viewpoint, viewport, map_size, label, figure, region)",
    "CREATE INDEX files_cell ON files (cell_id)",
};

/* ---- statements kept for the life of the store ---- */

static const char sql_ins_run[] =
    "INSERT INTO runs (time_utc, git_sha, study, config_path, config_hash, config_text, host, cpu, isa, "
    "gl_renderer, gl_version, gl_backend, embree, threads, lp_num_threads) "
    "VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)";

/* digest 0 until the cell's figures are in, in the same transaction */
static const char sql_ins_cell[] =
    "INSERT INTO cells (run_id, config_hash" SL_CELL_COLUMNS(SL_SQL_NAME) ", digest) VALUES (?,?"
    SL_CELL_COLUMNS(SL_SQL_PARAM) ", 0)";

static const char sql_set_digest[] = "UPDATE cells SET digest = ?2 WHERE cell_id = ?1";

/* A cell computed again (a run without --resume) replaces the stored one of
 * its config hash and key: its figures first (they reference it). */
static const char sql_del_files[] =
    "DELETE FROM files WHERE cell_id IN (SELECT cell_id FROM cells WHERE config_hash = ?1 AND scene = ?2 "
    "AND viewpoint = ?3 AND vw = ?4 AND vh = ?5 AND map_size = ?6 AND label = ?7)";
static const char sql_ins_file[] =
    "INSERT OR REPLACE INTO files (path, run_id, cell_id, size, crc32) VALUES (?,?,?,?,?)";
static const char sql_del_figs[] =
    "DELETE FROM figures WHERE cell_id IN (SELECT cell_id FROM cells WHERE config_hash = ?1 AND scene = ?2 "
    "AND viewpoint = ?3 AND vw = ?4 AND vh = ?5 AND map_size = ?6 AND label = ?7)";
static const char sql_del_cell[] =
    "DELETE FROM cells WHERE config_hash = ?1 AND scene = ?2 AND viewpoint = ?3 AND vw = ?4 AND vh = ?5 "
    "AND map_size = ?6 AND label = ?7";

static const char sql_ins_fig[] =
    "INSERT INTO figures (cell_id, scene, viewpoint, viewport, map_size, label, region, figure, "
    "count, percent, percent_of) VALUES (?,?,?,?,?,?,?,?,?,?,?)";

static const char sql_has_cell[] =
    "SELECT COALESCE((SELECT cell_id FROM cells WHERE config_hash = ?1 AND scene = ?2 AND viewpoint = ?3 "
    "AND vw = ?4 AND vh = ?5 AND map_size = ?6 AND label = ?7), 0)";

/* Latest cell per key: highest run, then highest cell id within the run.
 * Filters are on key columns, so filtering before ranking does not change
 * which cell of a key is the latest. Ordered by scene, then sweep order. */
static const char sql_query_cells[] =
    "WITH latest AS (\n"
    "  SELECT c.*, row_number() OVER (PARTITION BY scene, viewpoint, vw, vh, map_size, label\n"
    "                                 ORDER BY run_id DESC, cell_id DESC) AS rn\n"
    "  FROM cells c\n"
    "  WHERE (?1 IS NULL OR scene = ?1) AND (?2 IS NULL OR viewpoint = ?2)\n"
    "    AND (?3 IS NULL OR instr(',' || ?3 || ',', ',' || label || ',') > 0)\n"
    "    AND (?4 = 0 OR map_size = ?4) AND (?5 = 0 OR run_id = ?5)\n"
    "    AND (?6 IS NULL OR run_id IN (SELECT run_id FROM runs WHERE study = ?6)))\n"
    "SELECT l.cell_id, l.config_hash, r.git_sha, r.host, r.cpu, r.isa, r.gl_renderer, r.study, l.run_id, l.digest\n"
    "       " SL_CELL_COLUMNS(SL_SQL_L_NAME) "\n"
    "FROM latest l JOIN runs r ON r.run_id = l.run_id\n"
    "WHERE l.rn = 1\n"
    "ORDER BY l.scene, l.cell_index, l.run_id, l.cell_id";

/* regions as figures.c orders them: contours ascending, whole image last */
static const char sql_query_figs[] =
    "SELECT region, figure, count, percent FROM figures WHERE cell_id = ?1 "
    "ORDER BY region = 'image', CAST(region AS INTEGER), figure";

enum {
    ST_BEGIN, ST_COMMIT, ST_ROLLBACK, ST_INS_RUN, ST_INS_CELL, ST_INS_FIG, ST_HAS_CELL,
    ST_QUERY_CELLS, ST_QUERY_FIGS, ST_SET_DIGEST, ST_DEL_FILES, ST_DEL_FIGS, ST_DEL_CELL, ST_INS_FILE, ST_COUNT
};
static const char *const sl_stmt_sql[ST_COUNT] = {
    [ST_BEGIN] = "BEGIN IMMEDIATE",
    [ST_COMMIT] = "COMMIT",
    [ST_ROLLBACK] = "ROLLBACK",
    [ST_INS_RUN] = sql_ins_run,
    [ST_INS_CELL] = sql_ins_cell,
    [ST_INS_FIG] = sql_ins_fig,
    [ST_HAS_CELL] = sql_has_cell,
    [ST_QUERY_CELLS] = sql_query_cells,
    [ST_QUERY_FIGS] = sql_query_figs,
    [ST_SET_DIGEST] = sql_set_digest,
    [ST_DEL_FILES] = sql_del_files,
    [ST_INS_FILE] = sql_ins_file,
    [ST_DEL_FIGS] = sql_del_figs,
    [ST_DEL_CELL] = sql_del_cell,
};

struct sl_store {
    sqlite3      *db;
    sqlite3_stmt *st[ST_COUNT];
    char         *path;
    int           lockfd;   /* <real path>.lock, flock()ed while open for writing; -1 if none */
    char          lockpath[4200];   /* its name, removed on close (storefile.h) */
    struct sl_integ *integ; /* cell digests: written by put, checked by query */
    struct sl_storefile_ro ro;   /* a reader's URI, and its private copy when one was needed */
    int           read_version;  /* the schema of the file read, when an older one (upgraded copy); else 0 */
};

/* ---- helpers ---- */

/* SL_E_IO naming the database, with the context and sqlite's message. */
__attribute__((format(printf, 4, 5))) static enum sl_err db_fail(const struct sl_store *s, struct sl_diag *d,
                                                                   const char *key, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return sl_fail(d, SL_E_IO, s->path, 0, key, "%s: %s", what,
                   s->db ? sqlite3_errmsg(s->db) : "no database handle");
}

static sqlite3_int64 to_i64(uint64_t v)
{
    /* out of range -> -1, which the >= 0 CHECKs refuse */
    return v > (uint64_t)INT64_MAX ? -1 : (sqlite3_int64)v;
}

/* Binds parameters in order and remembers the first failure. */
struct binder {
    sqlite3_stmt *st;
    int           i, rc;
};

static void b_text(struct binder *b, const char *v)
{
    if (b->rc == SQLITE_OK)
        b->rc = sqlite3_bind_text(b->st, b->i, v ? v : "", -1, SQLITE_STATIC);
    b->i++;
}

static void b_text_or_null(struct binder *b, const char *v)
{
    if (b->rc == SQLITE_OK)
        b->rc = (v && v[0]) ? sqlite3_bind_text(b->st, b->i, v, -1, SQLITE_STATIC)
                            : sqlite3_bind_null(b->st, b->i);
    b->i++;
}

static void b_int(struct binder *b, sqlite3_int64 v)
{
    if (b->rc == SQLITE_OK)
        b->rc = sqlite3_bind_int64(b->st, b->i, v);
    b->i++;
}

static void b_u64(struct binder *b, uint64_t v) { b_int(b, to_i64(v)); }

static void b_real(struct binder *b, double v)
{
    if (b->rc == SQLITE_OK)
        b->rc = isnan(v) ? sqlite3_bind_null(b->st, b->i) : sqlite3_bind_double(b->st, b->i, v);
    b->i++;
}

/* SQLITE_OK when every parameter was bound without error. */
static int b_done(const struct binder *b)
{
    if (b->rc != SQLITE_OK)
        return b->rc;
    return b->i - 1 == sqlite3_bind_parameter_count(b->st) ? SQLITE_OK : SQLITE_RANGE;
}

/* A cell's config hash and key, as ?1..?7 of the key statements. */
static void key_bind(struct binder *b, const char *hash, const char *scene, const char *viewpoint, int vw, int vh,
                     int map_size, const char *label)
{
    b_text(b, hash);
    b_text(b, scene);
    b_text(b, viewpoint);
    b_int(b, vw);
    b_int(b, vh);
    b_int(b, map_size);
    b_text(b, label);
}

static void st_clear(sqlite3_stmt *st)
{
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
}

/* Step a statement that returns no row; SQLITE_DONE on success. The error
 * message stays readable through sqlite3_errmsg until the next call. */
static int st_exec(sqlite3_stmt *st)
{
    int rc = sqlite3_step(st);
    return rc == SQLITE_ROW ? SQLITE_DONE : rc;
}

/* a == b ignoring white space (sqlite_master keeps the CREATE text, but may
 * normalise spacing around its first keywords) */
static int same_sql(const char *a, const char *b)
{
    for (;;) {
        while (*a == ' ' || *a == '\n' || *a == '\t' || *a == '\r')
            a++;
        while (*b == ' ' || *b == '\n' || *b == '\t' || *b == '\r')
            b++;
        if (*a != *b)
            return 0;
        if (!*a)
            return 1;
        a++;
        b++;
    }
}

/* One-shot integer query; SQLITE_OK and *out on success. */
static int query_int(sqlite3 *db, const char *sql, sqlite3_int64 *out)
{
    sqlite3_stmt *st = NULL;
    int rc = sqlite3_prepare_v2(db, sql, -1, &st, NULL);
    if (rc == SQLITE_OK) {
        rc = sqlite3_step(st);
        if (rc == SQLITE_ROW) {
            *out = sqlite3_column_int64(st, 0);
            rc = SQLITE_OK;
        } else if (rc == SQLITE_DONE) {
            rc = SQLITE_ERROR;
        }
    }
    sqlite3_finalize(st);
    return rc;
}

/* ---- open / close ---- */

static enum sl_err create_schema(struct sl_store *s, struct sl_diag *d)
{
    for (size_t i = 0; i < sizeof sl_tables / sizeof sl_tables[0]; i++)
        if (sqlite3_exec(s->db, sl_tables[i].sql, NULL, NULL, NULL) != SQLITE_OK)
            return db_fail(s, d, NULL, "cannot create table %s", sl_tables[i].name);
    for (size_t i = 0; i < sizeof sl_indexes / sizeof sl_indexes[0]; i++)
        if (sqlite3_exec(s->db, sl_indexes[i], NULL, NULL, NULL) != SQLITE_OK)
            return db_fail(s, d, NULL, "cannot create index");
    char v[64];
    snprintf(v, sizeof v, "PRAGMA user_version = %d", SL_STORE_VERSION);
    if (sqlite3_exec(s->db, v, NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot set the schema version");
    return SL_OK;
}

/* An empty database becomes a version-1 store; a concurrent creator is
 * serialised by BEGIN IMMEDIATE and the re-check inside it. */
static enum sl_err init_if_empty(struct sl_store *s, struct sl_diag *d)
{
    if (sqlite3_exec(s->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot start creating the schema");
    sqlite3_int64 ver = -1, nobj = -1;
    enum sl_err e = SL_OK;
    if (query_int(s->db, "PRAGMA user_version", &ver) != SQLITE_OK ||
        query_int(s->db, "SELECT count(*) FROM sqlite_master", &nobj) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot read the schema");
    else if (ver == 0 && nobj == 0)
        e = create_schema(s, d);
    if (e == SL_OK && sqlite3_exec(s->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot commit the schema");
    if (e != SL_OK)
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    return e;
}

static enum sl_err check_schema(struct sl_store *s, struct sl_diag *d)
{
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(s->db, "SELECT sql FROM sqlite_master WHERE type = 'table' AND name = ?1",
                           -1, &st, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot read the schema");
    enum sl_err e = SL_OK;
    for (size_t i = 0; i < sizeof sl_tables / sizeof sl_tables[0] && !e; i++) {
        sqlite3_bind_text(st, 1, sl_tables[i].name, -1, SQLITE_STATIC);
        int rc = sqlite3_step(st);
        if (rc == SQLITE_ROW) {
            const char *sql = (const char *)sqlite3_column_text(st, 0);
            if (!sql || !same_sql(sql, sl_tables[i].sql))
                e = sl_fail(d, SL_E_IO, s->path, 0, sl_tables[i].name,
                            "table differs from schema version %d of this build (a store written by "
                            "another build of the same version?)", SL_STORE_VERSION);
        } else if (rc == SQLITE_DONE) {
            e = sl_fail(d, SL_E_IO, s->path, 0, sl_tables[i].name,
                        "table missing from a schema version %d store", SL_STORE_VERSION);
        } else {
            e = db_fail(s, d, NULL, "cannot read the schema");
        }
        sqlite3_reset(st);
    }
    sqlite3_finalize(st);
    return e;
}

/* The SQL expression a column of this schema takes in an upgraded copy when
 * the older store lacks it: what a build of that time did not store. NOT
 * NULL columns: 0 for a number (frac: no fractional errors, nonfinite: none
 * counted, digest: recomputed below), '' for a text (family, beside,
 * display: unknown; readers then fall back to the label); else NULL. */
static const char *absent_value(const char *type, int notnull)
{
    if (!notnull)
        return "NULL";
    return strstr(type, "TEXT") ? "''" : "0";
}

/* "a, b, c" and the matching SELECT list for table t of main from old: each
 * of main's columns, taken from old when it has it, else absent_value. */
static int copy_lists(sqlite3 *db, const char *t, char **cols, char **sel)
{
    *cols = *sel = NULL;
    char *q = sqlite3_mprintf("SELECT m.name, m.type, m.\"notnull\", o.name IS NOT NULL FROM pragma_table_info(%Q, "
                              "'main') m LEFT JOIN pragma_table_info(%Q, 'old') o ON o.name = m.name ORDER BY m.cid",
                              t, t);
    sqlite3_stmt *st = NULL;
    int rc = q ? sqlite3_prepare_v2(db, q, -1, &st, NULL) : SQLITE_NOMEM;
    sqlite3_free(q);
    sqlite3_str *c = sqlite3_str_new(db), *v = sqlite3_str_new(db);
    int n = 0;
    while (rc == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 0), *type = (const char *)sqlite3_column_text(st, 1);
        sqlite3_str_appendf(c, "%s\"%w\"", n ? ", " : "", name);
        if (sqlite3_column_int(st, 3))
            sqlite3_str_appendf(v, "%s\"%w\"", n ? ", " : "", name);
        else
            sqlite3_str_appendf(v, "%s%s", n ? ", " : "", absent_value(type ? type : "", sqlite3_column_int(st, 2)));
        n++;
    }
    sqlite3_finalize(st);
    *cols = sqlite3_str_finish(c);
    *sel = sqlite3_str_finish(v);
    return rc == SQLITE_OK && n > 0 && *cols && *sel ? SQLITE_OK : SQLITE_ERROR;
}

/* A reader never writes the store it reads: one of an older schema (16 to
 * 22, every version a release has written since the store took its present
 * tables) is read through a private upgraded copy. A fresh store of this
 * schema is made in a private folder (storefile.h), the old one attached
 * read-only (after its quick_check), and its runs, cells and figures copied
 * column by column: a column the old schema lacks takes absent_value; where
 * an old store (before 17's UNIQUE) holds one key of one config hash twice,
 * the later cell wins, as every reader of that time took it; each cell's
 * digest is computed in the copy (a store before 17 carries none of its
 * own, so it vouches for the copy only: sl_store_read_version says so). */
static enum sl_err reader_upgrade(struct sl_store *s, struct sl_diag *d)
{
    enum sl_err e = sl_storefile_private(&s->ro, s->path, d);
    if (e)
        return e;
    char up[sizeof s->ro.tmpdir + 16];
    snprintf(up, sizeof up, "%s/upgraded.db", s->ro.tmpdir);
    snprintf(s->ro.upgraded, sizeof s->ro.upgraded, "%s", up);
    sqlite3 *old = s->db;
    s->db = NULL;
    sqlite3_close(old);   /* attached below by its URI instead */
    if (sqlite3_open_v2(up, &s->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot make its upgraded private copy %s", up);
    sqlite3_busy_timeout(s->db, SL_STORE_BUSY_MS);
    /* the copy is private and rebuilt at each open: no journal needed */
    (void)sqlite3_exec(s->db, "PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF", NULL, NULL, NULL);
    char *att = sqlite3_mprintf("ATTACH DATABASE %Q AS old", s->ro.uri);
    int rc = att ? sqlite3_exec(s->db, att, NULL, NULL, NULL) : SQLITE_NOMEM;
    sqlite3_free(att);
    if (rc != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot attach it to its upgraded copy");
    if ((e = sl_integ_quick_check(s->db, "old", s->path, "refusing to read it", d)))
        return e;
    if (sqlite3_exec(s->db, "BEGIN", NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot upgrade it");
    e = create_schema(s, d);
    static const char *const order[] = {"runs", "cells", "figures"};
    for (int t = 0; t < 3 && !e; t++) {
        char *cols = NULL, *sel = NULL;
        rc = copy_lists(s->db, order[t], &cols, &sel);
        /* cells: later rows replace earlier ones of their key; figures:
         * those of the cells kept */
        char *q = rc != SQLITE_OK ? NULL
                  : t == 0 ? sqlite3_mprintf("INSERT INTO main.runs (%s) SELECT %s FROM old.runs", cols, sel)
                  : t == 1 ? sqlite3_mprintf("INSERT OR REPLACE INTO main.cells (%s) SELECT %s FROM old.cells "
                                             "ORDER BY run_id, cell_id", cols, sel)
                           : sqlite3_mprintf("INSERT OR IGNORE INTO main.figures (%s) SELECT %s FROM old.figures "
                                             "WHERE cell_id IN (SELECT cell_id FROM main.cells)", cols, sel);
        if (!q || sqlite3_exec(s->db, q, NULL, NULL, NULL) != SQLITE_OK)
            e = db_fail(s, d, order[t], "cannot copy its %s into the upgraded copy", order[t]);
        sqlite3_free(q);
        sqlite3_free(cols);
        sqlite3_free(sel);
    }
    /* From 17 on, each old cell carries its digest over its old row: it is
     * checked there, and a cell that fails it is carried into the copy with
     * a digest that fails too, so every reader refuses it as it would
     * have refused the original (and verify names it); before 17 there is
     * nothing to check. */
    sqlite3_int64 has_digest = 0;
    if (!e && query_int(s->db, "SELECT count(*) FROM pragma_table_info('cells', 'old') WHERE name = 'digest'",
                        &has_digest) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot read its schema");
    struct sl_integ *g = NULL, *go = NULL;
    if (!e)
        e = sl_integ_open(s->db, "main", s->path, &g, d);
    if (!e && has_digest)
        e = sl_integ_open(s->db, "old", s->path, &go, d);
    sqlite3_stmt *ids = NULL, *set = NULL;
    if (!e && (sqlite3_prepare_v2(s->db, has_digest ? "SELECT c.cell_id, o.digest FROM main.cells c JOIN old.cells o "
                                  "ON o.cell_id = c.cell_id" : "SELECT cell_id, 0 FROM main.cells", -1, &ids,
                                  NULL) != SQLITE_OK ||
               sqlite3_prepare_v2(s->db, sql_set_digest, -1, &set, NULL) != SQLITE_OK))
        e = db_fail(s, d, NULL, "cannot digest the upgraded copy");
    while (!e && sqlite3_step(ids) == SQLITE_ROW) {
        uint32_t dg = 0, was = 0;
        sqlite3_int64 id = sqlite3_column_int64(ids, 0);
        if (sl_integ_digest(g, id, &dg) != SQLITE_OK || (go && sl_integ_digest(go, id, &was) != SQLITE_OK)) {
            e = db_fail(s, d, NULL, "cannot digest cell %lld of the upgraded copy", (long long)id);
            break;
        }
        if (go && was != (uint32_t)sqlite3_column_int64(ids, 1))
            dg = ~dg;   /* damaged in the original: damaged in the copy */
        sqlite3_bind_int64(set, 1, id);
        sqlite3_bind_int64(set, 2, dg);
        if (sqlite3_step(set) != SQLITE_DONE)
            e = db_fail(s, d, NULL, "cannot digest the upgraded copy");
        sqlite3_reset(set);
    }
    sqlite3_finalize(ids);
    sqlite3_finalize(set);
    sl_integ_close(g);
    sl_integ_close(go);
    if (!e && sqlite3_exec(s->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot commit the upgraded copy");
    if (e && !sqlite3_get_autocommit(s->db))
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    if (!e && sqlite3_exec(s->db, "DETACH DATABASE old", NULL, NULL, NULL) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot let go of it");
    return e;
}

static enum sl_err store_setup(struct sl_store *s, struct sl_diag *d)
{
    sqlite3_busy_timeout(s->db, SL_STORE_BUSY_MS);
    sqlite3_int64 ver = -1, nobj = -1;
    int rc = query_int(s->db, "PRAGMA user_version", &ver);
    if (rc == SQLITE_NOTADB)
        return sl_fail(d, SL_E_IO, s->path, 0, NULL,
                       "not a shadowlab results store: %s", sqlite3_errmsg(s->db));
    if (rc != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot read the schema version");
    if (ver == 0) {
        if (query_int(s->db, "SELECT count(*) FROM sqlite_master", &nobj) != SQLITE_OK)
            return db_fail(s, d, NULL, "cannot read the schema");
        if (nobj != 0)
            return sl_fail(d, SL_E_IO, s->path, 0, NULL,
                           "an SQLite database but not a shadowlab results store (user_version 0, "
                           "%lld schema objects); refusing to touch it", (long long)nobj);
        if (s->lockfd < 0)   /* a reader makes no schema */
            return sl_fail(d, SL_E_IO, s->path, 0, NULL, "an empty file, not a results store");
    } else if (ver >= SL_STORE_OLDEST && ver < SL_STORE_VERSION && s->lockfd < 0) {
        enum sl_err e = reader_upgrade(s, d);
        if (e)
            return e;
        s->read_version = (int)ver;
        ver = SL_STORE_VERSION;
    } else if (ver != SL_STORE_VERSION) {
        return sl_fail(d, SL_E_IO, s->path, 0, NULL,
                       "results store of schema version %lld; this build %s version %d%s",
                       (long long)ver, s->lockfd < 0 ? "reads versions " SL_STR(SL_STORE_OLDEST) " to" : "writes",
                       SL_STORE_VERSION, ver > SL_STORE_VERSION ? " (a newer build wrote it)"
                       : ver >= SL_STORE_OLDEST ? " (an older store: verify, table, report and check read it; "
                         "write into a new store, or read it with the build that wrote it)"
                       : " (read it with the build that wrote it, or run its config again into a new store)");
    }
    enum sl_err e;
    /* Damage inside SQLite's pages goes unnoticed until a query trips on it;
     * a writer checks first, so a run never adds to a damaged store. */
    if (s->lockfd >= 0 && (e = sl_integ_quick_check(s->db, "main", s->path, "refusing to write into it", d)))
        return e;
    /* ours (or empty) from here on: WAL lets readers run beside a writing run */
    sqlite3_int64 ignore = 0;
    if (s->lockfd >= 0)
        (void)query_int(s->db, "PRAGMA journal_mode = WAL", &ignore);
    if (sqlite3_exec(s->db, "PRAGMA foreign_keys = ON", NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot enable foreign keys");
    if (ver == 0 && (e = init_if_empty(s, d)))
        return e;
    if ((e = check_schema(s, d)))
        return e;
    for (int i = 0; i < ST_COUNT; i++)
        if (sqlite3_prepare_v3(s->db, sl_stmt_sql[i], -1, SQLITE_PREPARE_PERSISTENT, &s->st[i], NULL) !=
            SQLITE_OK)
            return db_fail(s, d, NULL, "cannot prepare statement %d", i);
    return sl_integ_open(s->db, "main", s->path, &s->integ, d);
}

static enum sl_err store_open(const char *path, int readonly, struct sl_store **out, struct sl_diag *d)
{
    if (!out)
        return sl_fail(d, SL_E_USAGE, path, 0, NULL, "sl_store_open: no output pointer");
    *out = NULL;
    if (!path || !path[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "results store: empty path");
    struct sl_store *s = sl_calloc(1, sizeof *s);
    size_t n = strlen(path) + 1;
    char *p = s ? sl_calloc(n, 1) : NULL;
    if (!p) {
        free(s);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "results store handle");
    }
    memcpy(p, path, n);
    s->path = p;
    s->lockfd = -1;
    /* One writer per file (storefile.h); readers through a read-only URI,
     * so a store on read-only media can be read. */
    enum sl_err e = readonly ? SL_OK : sl_storefile_lock(path, &s->lockfd, s->lockpath, sizeof s->lockpath, d);
    if (!e && readonly)
        e = sl_storefile_ro_open(path, &s->ro, d);
    if (!e) {
        int rc = readonly ? sqlite3_open_v2(s->ro.uri, &s->db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, NULL)
                          : sqlite3_open_v2(path, &s->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL);
        e = rc == SQLITE_OK ? SL_OK : db_fail(s, d, NULL, "cannot open");
    }
    if (!e)
        e = store_setup(s, d);
    if (e) {
        sl_store_close(s);
        return e;
    }
    *out = s;
    return SL_OK;
}

enum sl_err sl_store_open(const char *path, struct sl_store **out, struct sl_diag *d)
{
    return store_open(path, 0, out, d);
}

enum sl_err sl_store_open_existing(const char *path, struct sl_store **out, struct sl_diag *d)
{
    struct stat sb;
    if (!path || stat(path, &sb) != 0 || !S_ISREG(sb.st_mode))
        return sl_fail(d, SL_E_IO, path, 0, NULL, "no results store here (run `shadowlab run CONFIG` first)");
    return store_open(path, 1, out, d);
}

void sl_store_close(struct sl_store *s)
{
    if (!s)
        return;
    for (int i = 0; i < ST_COUNT; i++)
        sqlite3_finalize(s->st[i]);
    sl_integ_close(s->integ);
    sqlite3_close(s->db);
    sl_storefile_unlock(s->lockfd, s->lockpath);   /* after SQLite let go of the file; -1: none */
    sl_storefile_ro_release(&s->ro);   /* after SQLite let go of the copy */
    free(s->path);
    free(s);
}

enum sl_err sl_store_copy(const char *from, const char *to, struct sl_diag *d)
{
    struct sl_store *src = NULL;
    enum sl_err e = sl_store_open_existing(from, &src, d);
    if (e)
        return e;
    sqlite3 *dst = NULL;
    int rc = sqlite3_open_v2(to, &dst, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL);
    sqlite3_backup *b = rc == SQLITE_OK ? sqlite3_backup_init(dst, "main", src->db, "main") : NULL;
    if (b) {
        rc = sqlite3_backup_step(b, -1);   /* every page, in one step */
        rc = rc == SQLITE_DONE ? sqlite3_backup_finish(b) : (sqlite3_backup_finish(b), rc);
    } else if (rc == SQLITE_OK) {
        rc = sqlite3_errcode(dst);
    }
    if (rc != SQLITE_OK)
        e = sl_fail(d, SL_E_OUTPUT, to, 0, NULL, "cannot copy the store %s here: %s", from,
                    dst ? sqlite3_errmsg(dst) : sqlite3_errstr(rc));
    if (sqlite3_close(dst) != SQLITE_OK && !e)
        e = sl_fail(d, SL_E_OUTPUT, to, 0, NULL, "cannot close the copy of %s", from);
    sl_store_close(src);
    return e;
}

/* ---- writing ---- */

/* The checkpoint's own words (PRAGMA wal_checkpoint: busy, frames in the
 * -wal, frames copied) decide, not the pragma's return code alone: a
 * checkpoint that could not copy every frame (a reader holding an old
 * snapshot, a disk that filled as the .db grew) still "succeeds". */
enum sl_err sl_store_seal(struct sl_store *s, struct sl_diag *d)
{
    if (!s || s->lockfd < 0)
        return sl_fail(d, SL_E_USAGE, s ? s->path : NULL, 0, NULL, "sl_store_seal: not a writer's store");
    char wal[4200];
    snprintf(wal, sizeof wal, "%s-wal", s->path);
    struct stat ws;
    long long wal_bytes = stat(wal, &ws) == 0 ? (long long)ws.st_size : 0;
    sqlite3_stmt *st = NULL;
    /* the tests' disk that fills at the last step: no checkpoint, none on
     * close either, the -wal left as a full disk leaves it */
    int fault = sl_storefile_fault("checkpoint");
    if (fault)
        sqlite3_db_config(s->db, SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, NULL);
    int rc = fault ? SQLITE_FULL : sqlite3_prepare_v2(s->db, "PRAGMA main.wal_checkpoint(TRUNCATE)", -1, &st, NULL);
    int busy = -1, frames = -1, copied = -1;
    if (rc == SQLITE_OK && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        busy = sqlite3_column_int(st, 0);
        frames = sqlite3_column_int(st, 1);
        copied = sqlite3_column_int(st, 2);
        rc = SQLITE_OK;
    }
    char why[300];
    snprintf(why, sizeof why, "%s", fault ? sqlite3_errstr(rc) : rc != SQLITE_OK ? sqlite3_errmsg(s->db) : "");
    sqlite3_finalize(st);
    if (rc == SQLITE_OK && busy != 0)
        snprintf(why, sizeof why, "%d of %d frames copied, a reader held the rest", copied, frames);
    if (rc != SQLITE_OK || busy != 0) {
        char dir[4200];
        sl_path_dir(s->path, dir, sizeof dir);
        return sl_fail(d, SL_E_OUTPUT, s->path, 0, NULL,
                       "the final checkpoint failed (%s): %lld bytes of results are still only in %s, so the .db "
                       "alone is not the whole store; free at least %lld bytes on the filesystem of %s (or end "
                       "the readers of the store), then `shadowlab run CONFIG --resume` completes it",
                       why, wal_bytes, wal, wal_bytes, dir);
    }
    /* Rollback journal from here: closing leaves no -wal at all (the next
     * writer switches back to WAL). Refused only while a reader holds the
     * store; everything is in the .db already, so that is not a failure. */
    sqlite3_int64 ignore = 0;
    (void)query_int(s->db, "PRAGMA main.journal_mode = DELETE", &ignore);
    return sl_storefile_sync(s->path, d);
}

enum sl_err sl_store_begin_run(struct sl_store *s, const struct sl_provenance *p, const char *study,
                               const char *config_path, unsigned long long config_hash,
                               const char *config_text, int64_t *run_id, struct sl_diag *d)
{
    if (!s || !p || !run_id)
        return sl_fail(d, SL_E_USAGE, s ? s->path : NULL, 0, NULL, "sl_store_begin_run: missing argument");
    char hash[24];
    snprintf(hash, sizeof hash, "%016llx", config_hash);
    sqlite3_stmt *st = s->st[ST_INS_RUN];
    struct binder b = {st, 1, SQLITE_OK};
    b_text(&b, p->time_utc);
    b_text(&b, p->git_sha);
    b_text(&b, study);
    b_text(&b, config_path);
    b_text(&b, hash);
    b_text(&b, config_text);
    b_text(&b, p->host);
    b_text(&b, p->cpu);
    b_text(&b, p->isa);
    b_text(&b, p->gl_renderer);
    b_text(&b, p->gl_version);
    b_text(&b, p->gl_backend);
    b_text(&b, p->embree);
    b_int(&b, p->threads);
    b_text(&b, p->lp_threads);
    enum sl_err e = SL_OK;
    if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
        e = db_fail(s, d, NULL, "cannot record the run");
    else
        *run_id = sqlite3_last_insert_rowid(s->db);
    st_clear(st);
    return e;
}

static enum sl_err put_figure(struct sl_store *s, sqlite3_int64 cell_id, const struct sl_cell_record *c,
                              const char *viewport, const char *region, const char *figure,
                              uint64_t count, double pct, const char *of, const char *key,
                              struct sl_diag *d)
{
    sqlite3_stmt *st = s->st[ST_INS_FIG];
    struct binder b = {st, 1, SQLITE_OK};
    b_int(&b, cell_id);
    b_text(&b, c->scene);
    b_text(&b, c->viewpoint);
    b_text(&b, viewport);
    b_int(&b, c->map_size);
    b_text(&b, c->label);
    b_text(&b, region);
    b_text(&b, figure);
    b_u64(&b, count);
    b_real(&b, pct);
    b_text_or_null(&b, of);
    enum sl_err e = SL_OK;
    if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
        e = db_fail(s, d, key, "cannot store figure %s of region %s", figure, region);
    st_clear(st);
    return e;
}

static enum sl_err put_cell_row(struct sl_store *s, int64_t run_id, const char *hash,
                                const struct sl_cell_record *c, const char *viewport, const char *key,
                                sqlite3_int64 *cell_id, struct sl_diag *d)
{
    sqlite3_stmt *st = s->st[ST_INS_CELL];
    struct binder b = {st, 1, SQLITE_OK};
    b_int(&b, run_id);
    b_text(&b, hash);
#define SL_BIND_text(name)     b_text(&b, c->name);
#define SL_BIND_path(name)     b_text_or_null(&b, c->name);
#define SL_BIND_dim(name)      b_int(&b, c->name);
#define SL_BIND_index(name)    b_int(&b, c->name);
#define SL_BIND_runs(name)     b_int(&b, c->name);
#define SL_BIND_count(name)    b_u64(&b, SL_CELL_U64_count(c, name));
#define SL_BIND_wrong(name)    b_u64(&b, SL_CELL_U64_wrong(c, name));
#define SL_BIND_ms(name)       b_real(&b, c->name);
#define SL_BIND_viewport(name) b_text(&b, viewport);
#define SL_BIND_flag(name)
#define SL_BIND(name, kind, size, csv, head, check, key, from) SL_BIND_##kind(name)
    SL_CELL_COLUMNS(SL_BIND)
#undef SL_BIND
    enum sl_err e = SL_OK;
    if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
        e = db_fail(s, d, key, "cannot store the cell");
    else
        *cell_id = sqlite3_last_insert_rowid(s->db);
    st_clear(st);
    return e;
}

enum sl_err sl_store_put_cell(struct sl_store *s, int64_t run_id, unsigned long long config_hash,
                              const struct sl_cell_record *c, struct sl_diag *d)
{
    return sl_store_put_cell_files(s, run_id, config_hash, c, NULL, 0, d);
}

enum sl_err sl_store_put_cell_files(struct sl_store *s, int64_t run_id, unsigned long long config_hash,
                                    const struct sl_cell_record *c, const struct sl_store_file *files, int nfiles,
                                    struct sl_diag *d)
{
    if (!s || !c)
        return sl_fail(d, SL_E_USAGE, s ? s->path : NULL, 0, NULL, "sl_store_put_cell: missing argument");
    const struct sl_figures *fig = &c->fig;
    char key[96], viewport[32], hash[24];
    snprintf(key, sizeof key, "%s/%s/%dx%d/%d/%s", c->scene, c->viewpoint, c->vw, c->vh, c->map_size,
             c->label);
    if (fig->nregions < 0 || fig->nregions > SL_MAX_REGIONS)
        return sl_fail(d, SL_E_USAGE, s->path, 0, key, "cell has %d regions (at most %d)", fig->nregions,
                       SL_MAX_REGIONS);
    snprintf(viewport, sizeof viewport, "%dx%d", c->vw, c->vh);
    snprintf(hash, sizeof hash, "%016llx", config_hash);

    sqlite3_stmt *begin = s->st[ST_BEGIN];
    int rc = st_exec(begin);
    sqlite3_reset(begin);
    if (rc != SQLITE_DONE)
        return db_fail(s, d, key, "cannot start the cell's transaction");

    sqlite3_int64 cell_id = 0;
    enum sl_err e = SL_OK;
    for (int k = ST_DEL_FILES; k <= ST_DEL_CELL && !e; k++) {   /* the key once: a new computation replaces it */
        sqlite3_stmt *del = s->st[k];
        struct binder b = {del, 1, SQLITE_OK};
        key_bind(&b, hash, c->scene, c->viewpoint, c->vw, c->vh, c->map_size, c->label);
        if (b_done(&b) != SQLITE_OK || st_exec(del) != SQLITE_DONE)
            e = db_fail(s, d, key, "cannot replace the stored cell");
        st_clear(del);
    }
    if (!e)
        e = put_cell_row(s, run_id, hash, c, viewport, key, &cell_id, d);
    for (int r = 0; r < fig->nregions && !e; r++) {
        const struct sl_region_figures *g = &fig->r[r];
        char region[16];
        sl_region_name(g->thickness, region, sizeof region);
        for (int k = 0; k < SL_FIG_COUNT && !e; k++)
            e = put_figure(s, cell_id, c, viewport, region, sl_figure_name((enum sl_figure)k), g->n[k],
                           g->pct[k], sl_figure_of((enum sl_figure)k), key, d);
        for (int k = 0; c->has_alias && r < c->alias.nregions && k < SL_AFIG_COUNT && !e; k++)   /* same regions */
            e = put_figure(s, cell_id, c, viewport, region, sl_alias_figure_name((enum sl_alias_figure)k),
                           c->alias.n[r][k], c->alias.pct[r][k], sl_alias_figure_of((enum sl_alias_figure)k), key, d);
    }
    for (int k = 0; c->has_soft && k < SL_SFIG_COUNT && !e; k++)
        e = put_figure(s, cell_id, c, viewport, "image", sl_soft_figure_name((enum sl_soft_figure)k), c->soft.n[k],
                       c->soft.pct[k], sl_soft_figure_of((enum sl_soft_figure)k), key, d);
    if (!e)
        e = put_figure(s, cell_id, c, viewport, "image", "background", fig->background, NAN, NULL, key, d);
    for (int i = 0; i < nfiles && !e; i++) {
        sqlite3_stmt *st = s->st[ST_INS_FILE];
        struct binder b = {st, 1, SQLITE_OK};
        b_text(&b, files[i].path);
        b_int(&b, run_id);
        b_int(&b, cell_id);
        b_int(&b, files[i].size);
        b_int(&b, files[i].crc32);
        if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
            e = db_fail(s, d, key, "cannot record the file %s", files[i].path);
        st_clear(st);
    }
    uint32_t digest = 0;   /* of the rows as stored, in their transaction */
    if (!e && sl_integ_digest(s->integ, cell_id, &digest) != SQLITE_OK)
        e = db_fail(s, d, key, "cannot digest the cell");
    if (!e) {
        sqlite3_stmt *st = s->st[ST_SET_DIGEST];
        struct binder b = {st, 1, SQLITE_OK};
        b_int(&b, cell_id);
        b_int(&b, digest);
        if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
            e = db_fail(s, d, key, "cannot store the cell's digest");
        st_clear(st);
    }
    if (!e) {
        sqlite3_stmt *commit = s->st[ST_COMMIT];
        rc = st_exec(commit);
        sqlite3_reset(commit);
        if (rc != SQLITE_DONE)
            e = db_fail(s, d, key, "cannot commit the cell");
    }
    if (e && !sqlite3_get_autocommit(s->db)) {
        /* the diag already holds the first error; rolling back keeps no part of the cell */
        sqlite3_stmt *rb = s->st[ST_ROLLBACK];
        sqlite3_step(rb);
        sqlite3_reset(rb);
    }
    return e;
}

/* ---- reading ---- */

int64_t sl_store_cell_id(struct sl_store *s, unsigned long long config_hash, const char *scene,
                         const char *viewpoint, int vw, int vh, int map_size, const char *label)
{
    if (!s || !scene || !viewpoint || !label)
        return 0;
    char hash[24];
    snprintf(hash, sizeof hash, "%016llx", config_hash);
    sqlite3_stmt *st = s->st[ST_HAS_CELL];
    struct binder b = {st, 1, SQLITE_OK};
    key_bind(&b, hash, scene, viewpoint, vw, vh, map_size, label);
    /* an error reads as "not stored": the cell is recomputed and the put
     * reports the error */
    int64_t id = b_done(&b) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int64(st, 0) : 0;
    st_clear(st);
    return id;
}

int sl_store_has_cell(struct sl_store *s, unsigned long long config_hash, const char *scene,
                      const char *viewpoint, int vw, int vh, int map_size, const char *label)
{
    return sl_store_cell_id(s, config_hash, scene, viewpoint, vw, vh, map_size, label) != 0;
}

static void col_text(sqlite3_stmt *st, int i, char *buf, size_t n)
{
    const unsigned char *t = sqlite3_column_text(st, i);
    snprintf(buf, n, "%s", t ? (const char *)t : "");
}

static uint64_t col_u64(sqlite3_stmt *st, int i)
{
    sqlite3_int64 v = sqlite3_column_int64(st, i);
    return v < 0 ? 0 : (uint64_t)v;
}

/* Figures of one cell into c->fig (c->fig.wrong_image is already set). */
static enum sl_err load_figures(struct sl_store *s, sqlite3_int64 cell_id, struct sl_cell_record *c,
                                struct sl_diag *d)
{
    sqlite3_stmt *st = s->st[ST_QUERY_FIGS];
    struct sl_figures *f = &c->fig;
    enum sl_err e = SL_OK;
    int rc = SQLITE_DONE;
    if (sqlite3_bind_int64(st, 1, cell_id) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot read the figures of cell %lld", (long long)cell_id);
    while (!e && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        const char *region = (const char *)sqlite3_column_text(st, 0);
        const char *figure = (const char *)sqlite3_column_text(st, 1);
        uint64_t count = col_u64(st, 2);
        double pct = sqlite3_column_type(st, 3) == SQLITE_NULL ? NAN : sqlite3_column_double(st, 3);
        if (figure && strcmp(figure, "background") == 0) {
            f->background = count;
            continue;
        }
        int sk = 0;
        while (sk < SL_SFIG_COUNT && (!figure || strcmp(figure, sl_soft_figure_name((enum sl_soft_figure)sk)) != 0))
            sk++;
        if (sk < SL_SFIG_COUNT) {
            if (!c->has_soft)
                for (int j = 0; j < SL_SFIG_COUNT; j++)
                    c->soft.pct[j] = NAN;
            c->has_soft = 1;
            c->soft.n[sk] = count;
            c->soft.pct[sk] = pct;
            continue;
        }
        int t = sl_region_thickness(region), k = 0;
        if (figure && t >= 0 && sl_alias_figures_put(&c->alias, t, figure, count, pct))
            continue;   /* has_alias: set below */
        while (k < SL_FIG_COUNT && (!figure || strcmp(figure, sl_figure_name((enum sl_figure)k)) != 0))
            k++;
        if (t < 0 || k == SL_FIG_COUNT) {
            e = sl_fail(d, SL_E_IO, s->path, 0, NULL, "cell %lld: unknown region '%s' or figure '%s'",
                        (long long)cell_id, region ? region : "", figure ? figure : "");
            break;
        }
        /* rows come grouped by region in output order */
        if (f->nregions == 0 || f->r[f->nregions - 1].thickness != t) {
            if (f->nregions == SL_MAX_REGIONS) {
                e = sl_fail(d, SL_E_IO, s->path, 0, NULL, "cell %lld has more than %d regions",
                            (long long)cell_id, SL_MAX_REGIONS);
                break;
            }
            struct sl_region_figures *g = &f->r[f->nregions++];
            g->thickness = t;
            for (int j = 0; j < SL_FIG_COUNT; j++)
                g->pct[j] = NAN;
        }
        f->r[f->nregions - 1].n[k] = count;
        f->r[f->nregions - 1].pct[k] = pct;
    }
    c->has_alias = c->alias.nregions > 0;
    if (!e && rc != SQLITE_DONE)
        e = db_fail(s, d, NULL, "cannot read the figures of cell %lld", (long long)cell_id);
    st_clear(st);
    return e;
}

enum sl_err sl_store_query(struct sl_store *s, const struct sl_store_filter *f,
                           struct sl_cell_record **out, int *n, struct sl_diag *d)
{
    if (!out || !n)
        return sl_fail(d, SL_E_USAGE, s ? s->path : NULL, 0, NULL, "sl_store_query: no output pointer");
    *out = NULL;
    *n = 0;
    if (!s)
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_store_query: no store");
    static const struct sl_store_filter any = {0};
    if (!f)
        f = &any;
    sqlite3_stmt *st = s->st[ST_QUERY_CELLS];
    struct binder b = {st, 1, SQLITE_OK};
    b_text_or_null(&b, f->scene);
    b_text_or_null(&b, f->viewpoint);
    b_text_or_null(&b, f->label);
    b_int(&b, f->map_size);
    b_int(&b, f->run_id);
    b_text_or_null(&b, f->study);
    if (b_done(&b) != SQLITE_OK) {
        st_clear(st);
        return db_fail(s, d, NULL, "cannot query cells");
    }
    struct sl_cell_record *cells = NULL;
    int count = 0, cap = 0, rc = SQLITE_DONE;
    enum sl_err e = SL_OK;
    while (!e && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (count == cap) {
            int ncap = cap ? 2 * cap : 16;
            struct sl_cell_record *nc = realloc(cells, (size_t)ncap * sizeof *nc);
            if (!nc) {
                e = sl_fail(d, SL_E_NOMEM, s->path, 0, NULL, "%d cells", ncap);
                break;
            }
            cells = nc;
            cap = ncap;
        }
        struct sl_cell_record *c = &cells[count++];
        memset(c, 0, sizeof *c);
        int i = 0;
        sqlite3_int64 cell_id = sqlite3_column_int64(st, i++);
        col_text(st, i++, c->config_hash, sizeof c->config_hash);
        col_text(st, i++, c->git_sha, sizeof c->git_sha);
        const char *host = (const char *)sqlite3_column_text(st, i++);
        const char *cpu = (const char *)sqlite3_column_text(st, i++);
        const char *isa = (const char *)sqlite3_column_text(st, i++);
        snprintf(c->machine, sizeof c->machine, "%s/%s/%s", host ? host : "", cpu ? cpu : "",
                 isa ? isa : "");
        col_text(st, i++, c->gl_renderer, sizeof c->gl_renderer);
        col_text(st, i++, c->study, sizeof c->study);
        c->run_id = sqlite3_column_int64(st, i++);
        uint32_t want = (uint32_t)sqlite3_column_int64(st, i++), got = 0;
#define SL_READ_text(name)     col_text(st, i++, c->name, sizeof c->name);
#define SL_READ_path(name)     col_text(st, i++, c->name, sizeof c->name);
#define SL_READ_dim(name)      c->name = sqlite3_column_int(st, i++);
#define SL_READ_index(name)    c->name = sqlite3_column_int(st, i++);
#define SL_READ_runs(name)     c->name = sqlite3_column_int(st, i++);
#define SL_READ_count(name)    SL_CELL_U64_count(c, name) = col_u64(st, i++);
#define SL_READ_wrong(name)    SL_CELL_U64_wrong(c, name) = col_u64(st, i++);
#define SL_READ_ms(name)                                                                     \
        c->name = sqlite3_column_type(st, i) == SQLITE_NULL ? NAN : sqlite3_column_double(st, i); \
        i++;
#define SL_READ_viewport(name) i++;
#define SL_READ_flag(name)
#define SL_READ(name, kind, size, csv, head, check, key, from) SL_READ_##kind(name)
        SL_CELL_COLUMNS(SL_READ)
#undef SL_READ
        /* a reader trusts no cell its digest does not vouch for */
        if (sl_integ_digest(s->integ, cell_id, &got) != SQLITE_OK)
            e = db_fail(s, d, NULL, "cannot digest cell %lld", (long long)cell_id);
        else if (got != want)
            e = sl_fail(d, SL_E_IO, s->path, 0, NULL, "cell %s/%s/%dx%d/%d/%s (cell %lld) is damaged: its "
                        "rows no longer match their digest; `shadowlab verify` names every damaged cell",
                        c->scene, c->viewpoint, c->vw, c->vh, c->map_size, c->label, (long long)cell_id);
        if (!e)
            e = load_figures(s, cell_id, c, d);
    }
    if (!e && rc != SQLITE_DONE)
        e = db_fail(s, d, NULL, "cannot query cells");
    st_clear(st);
    if (e) {
        free(cells);
        return e;
    }
    *out = cells;
    *n = count;
    return SL_OK;
}

long sl_store_count(struct sl_store *s, const char *table)
{
    static const char *const sql[][2] = {
        {"runs", "SELECT count(*) FROM runs"},
        {"cells", "SELECT count(*) FROM cells"},
        {"figures", "SELECT count(*) FROM figures"},
    };
    if (!s || !table)
        return -1;
    for (size_t i = 0; i < sizeof sql / sizeof sql[0]; i++)
        if (strcmp(table, sql[i][0]) == 0) {
            sqlite3_int64 v = -1;
            return query_int(s->db, sql[i][1], &v) == SQLITE_OK ? (long)v : -1;
        }
    return -1;
}

/* The store's own check of every cell's digest (integrity.h does the work
 * on a database handle; it never calls back into the store). */
enum sl_err sl_store_verify(struct sl_store *s, struct sl_store_verify *r, struct sl_diag *d)
{
    const char *path = NULL;
    struct sqlite3 *db = sl_store_handle(s, &path);
    if (!db || !r)
        return sl_fail(d, SL_E_USAGE, path, 0, NULL, "sl_store_verify: missing argument");
    return sl_integ_verify(db, "main", path, r, d);
}

struct sqlite3 *sl_store_handle(struct sl_store *s, const char **path)
{
    *path = s ? s->path : NULL;
    return s ? s->db : NULL;
}

int sl_store_version(void)
{
    return SL_STORE_VERSION;
}

/* ---- the plan: completeness ---- */

enum sl_err sl_store_put_plan(struct sl_store *s, unsigned long long config_hash, const struct sl_store_key *k,
                              int n, struct sl_diag *d)
{
    char hash[24];
    snprintf(hash, sizeof hash, "%016llx", config_hash);
    sqlite3_stmt *st = NULL;
    if (sqlite3_exec(s->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot start recording the plan");
    enum sl_err e = SL_OK;
    if (sqlite3_prepare_v2(s->db, "INSERT OR IGNORE INTO plan (config_hash, cell_index, scene, viewpoint, vw, vh, "
                           "map_size, label) VALUES (?,?,?,?,?,?,?,?)", -1, &st, NULL) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot record the plan");
    for (int i = 0; i < n && !e; i++) {
        struct binder b = {st, 1, SQLITE_OK};
        b_text(&b, hash);
        b_int(&b, k[i].index);
        b_text(&b, k[i].scene);
        b_text(&b, k[i].viewpoint);
        b_int(&b, k[i].vw);
        b_int(&b, k[i].vh);
        b_int(&b, k[i].map_size);
        b_text(&b, k[i].label);
        if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
            e = db_fail(s, d, NULL, "cannot record cell %d of the plan", k[i].index);
        st_clear(st);
    }
    sqlite3_finalize(st);
    if (!e && sqlite3_exec(s->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot commit the plan");
    if (e && !sqlite3_get_autocommit(s->db))
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    return e;
}

/* A planned key with a stored cell of its config hash. */
#define SL_PLAN_STORED                                                                                  \
    "EXISTS (SELECT 1 FROM cells c WHERE c.config_hash = p.config_hash AND c.scene = p.scene AND "        \
    "c.viewpoint = p.viewpoint AND c.vw = p.vw AND c.vh = p.vh AND c.map_size = p.map_size AND "           \
    "c.label = p.label)"

enum sl_err sl_store_sweeps(struct sl_store *s, struct sl_store_sweep **out, int *n, struct sl_diag *d)
{
    *out = NULL;
    *n = 0;
    /* every hash with a plan, then those with cells but no plan (older stores) */
    static const char sql[] =
        "WITH h AS (SELECT config_hash FROM plan UNION SELECT config_hash FROM cells)\n"
        "SELECT h.config_hash,\n"
        "  (SELECT study FROM runs r WHERE r.config_hash = h.config_hash ORDER BY run_id LIMIT 1),\n"
        "  (SELECT group_concat(run_id, ', ') FROM (SELECT run_id FROM runs r WHERE r.config_hash = h.config_hash\n"
        "     ORDER BY run_id)),\n"
        "  (SELECT count(*) FROM plan p WHERE p.config_hash = h.config_hash),\n"
        "  (SELECT count(*) FROM plan p WHERE p.config_hash = h.config_hash AND " SL_PLAN_STORED "),\n"
        "  (SELECT count(*) FROM cells c WHERE c.config_hash = h.config_hash)\n"
        "FROM h ORDER BY h.config_hash";
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(s->db, sql, -1, &st, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot read the plan");
    struct sl_store_sweep *v = NULL;
    int cnt = 0, rc;
    enum sl_err e = SL_OK;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        struct sl_store_sweep *nv = realloc(v, (size_t)(cnt + 1) * sizeof *v);
        if (!nv) {
            e = sl_fail(d, SL_E_NOMEM, s->path, 0, NULL, "sweeps");
            break;
        }
        v = nv;
        struct sl_store_sweep *w = &v[cnt++];
        memset(w, 0, sizeof *w);
        col_text(st, 0, w->config_hash, sizeof w->config_hash);
        col_text(st, 1, w->study, sizeof w->study);
        const char *runs = (const char *)sqlite3_column_text(st, 2);
        size_t rl = runs ? strlen(runs) : 0;
        if (rl >= sizeof w->runs)
            snprintf(w->runs, sizeof w->runs, "%.*s...", (int)sizeof w->runs - 4, runs);
        else
            snprintf(w->runs, sizeof w->runs, "%s", runs ? runs : "");
        int planned = sqlite3_column_int(st, 3);
        w->planned = planned ? planned : -1;
        w->stored = planned ? sqlite3_column_int(st, 4) : sqlite3_column_int(st, 5);
    }
    if (!e && rc != SQLITE_DONE)
        e = db_fail(s, d, NULL, "cannot read the plan");
    sqlite3_finalize(st);
    if (e) {
        free(v);
        return e;
    }
    *out = v;
    *n = cnt;
    return SL_OK;
}

enum sl_err sl_store_missing(struct sl_store *s, const char *config_hash, struct sl_store_key **out, int *n,
                             struct sl_diag *d)
{
    *out = NULL;
    *n = 0;
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(s->db, "SELECT cell_index, scene, viewpoint, vw, vh, map_size, label FROM plan p "
                           "WHERE p.config_hash = ?1 AND NOT " SL_PLAN_STORED " ORDER BY cell_index", -1, &st,
                           NULL) != SQLITE_OK ||
        sqlite3_bind_text(st, 1, config_hash, -1, SQLITE_TRANSIENT) != SQLITE_OK) {
        sqlite3_finalize(st);
        return db_fail(s, d, NULL, "cannot read the plan");
    }
    /* keys, then their strings, in one block: 3 strings of at most 200 bytes each */
    enum { KEYTEXT = 600 };
    int cap = 0, cnt = 0, rc;
    char *block = NULL;
    enum sl_err e = SL_OK;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (cnt == cap) {
            int ncap = cap ? 2 * cap : 16;
            char *nb = realloc(block, (size_t)ncap * (sizeof(struct sl_store_key) + KEYTEXT));
            if (!nb) {
                e = sl_fail(d, SL_E_NOMEM, s->path, 0, NULL, "missing cells");
                break;
            }
            /* the strings move behind the larger key array */
            memmove(nb + (size_t)ncap * sizeof(struct sl_store_key), nb + (size_t)cap * sizeof(struct sl_store_key),
                    (size_t)cap * KEYTEXT);
            block = nb;
            cap = ncap;
        }
        char *text = block + (size_t)cap * sizeof(struct sl_store_key) + (size_t)cnt * KEYTEXT;
        const char *sc = (const char *)sqlite3_column_text(st, 1), *vp = (const char *)sqlite3_column_text(st, 2),
                   *lb = (const char *)sqlite3_column_text(st, 6);
        snprintf(text, 200, "%s", sc ? sc : "");
        snprintf(text + 200, 200, "%s", vp ? vp : "");
        snprintf(text + 400, 200, "%s", lb ? lb : "");
        struct sl_store_key *k = (struct sl_store_key *)block + cnt++;
        k->index = sqlite3_column_int(st, 0);
        k->vw = sqlite3_column_int(st, 3);
        k->vh = sqlite3_column_int(st, 4);
        k->map_size = sqlite3_column_int(st, 5);
    }
    if (!e && rc != SQLITE_DONE)
        e = db_fail(s, d, NULL, "cannot read the plan");
    sqlite3_finalize(st);
    if (e) {
        free(block);
        return e;
    }
    /* pointers last: the block no longer moves */
    for (int i = 0; i < cnt; i++) {
        struct sl_store_key *k = (struct sl_store_key *)block + i;
        char *text = block + (size_t)cap * sizeof(struct sl_store_key) + (size_t)i * KEYTEXT;
        k->scene = text;
        k->viewpoint = text + 200;
        k->label = text + 400;
    }
    *out = (struct sl_store_key *)block;
    *n = cnt;
    return SL_OK;
}

/* ---- files ---- */

enum sl_err sl_store_file_digest(const char *path, long long *size, uint32_t *crc, struct sl_diag *d)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(errno));
    uLong c = crc32(0L, Z_NULL, 0);
    long long total = 0;
    unsigned char buf[65536];
    int en = 0;
    for (;;) {
        ssize_t r = read(fd, buf, sizeof buf);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            en = errno;
        if (r <= 0)
            break;
        c = crc32(c, buf, (uInt)r);
        total += r;
    }
    close(fd);
    if (en)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(en));
    *size = total;
    *crc = (uint32_t)c;
    return SL_OK;
}

const char *sl_store_path(const struct sl_store *s)
{
    return s ? s->path : NULL;
}

/* A recorded path as a path from here: relative ones from the store's folder. */
static void file_at(const struct sl_store *s, const char *rec, char *out, size_t n)
{
    if (rec[0] == '/') {
        snprintf(out, n, "%s", rec);
        return;
    }
    char dir[4200];
    sl_path_dir(s->path, dir, sizeof dir);
    snprintf(out, n, "%s/%s", dir, rec);
}

int sl_store_file_recorded(struct sl_store *s, const char *path, long long *size, uint32_t *crc)
{
    sqlite3_stmt *st = NULL;
    int r = -1;
    if (sqlite3_prepare_v2(s->db, "SELECT size, crc32 FROM files WHERE path = ?1", -1, &st, NULL) == SQLITE_OK &&
        sqlite3_bind_text(st, 1, path, -1, SQLITE_TRANSIENT) == SQLITE_OK) {
        int rc = sqlite3_step(st);
        if (rc == SQLITE_ROW) {
            *size = sqlite3_column_int64(st, 0);
            *crc = (uint32_t)sqlite3_column_int64(st, 1);
            r = 1;
        } else if (rc == SQLITE_DONE) {
            r = 0;
        }
    }
    sqlite3_finalize(st);
    return r;
}

enum sl_err sl_store_check_files(struct sl_store *s, int only_present, struct sl_store_files_check *r,
                                 struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(s->db, "SELECT path, size, crc32 FROM files ORDER BY path", -1, &st, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot read the recorded files");
    enum sl_err e = SL_OK;
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        const char *rec = (const char *)sqlite3_column_text(st, 0);
        long long want_size = sqlite3_column_int64(st, 1), size = 0;
        uint32_t want_crc = (uint32_t)sqlite3_column_int64(st, 2), crc = 0;
        char at[4400], why[160] = "";
        file_at(s, rec ? rec : "", at, sizeof at);
        r->recorded++;
        struct stat sb;
        if (stat(at, &sb) != 0)
            snprintf(why, sizeof why, "missing");
        else if (r->present++, !S_ISREG(sb.st_mode))
            snprintf(why, sizeof why, "not a regular file");
        else if (sl_store_file_digest(at, &size, &crc, NULL) != SL_OK)
            snprintf(why, sizeof why, "cannot be read");
        else if (size != want_size)
            snprintf(why, sizeof why, "%lld bytes, %lld recorded", size, want_size);
        else if (crc != want_crc)
            snprintf(why, sizeof why, "its CRC-32 %08x differs from the recorded %08x", crc, want_crc);
        if (!why[0])
            continue;
        struct sl_store_file_bad *nb = realloc(r->bad, (size_t)(r->nbad + 1) * sizeof *nb);
        if (!nb) {
            e = sl_fail(d, SL_E_NOMEM, s->path, 0, NULL, "damaged files");
            break;
        }
        r->bad = nb;
        snprintf(nb[r->nbad].path, sizeof nb[r->nbad].path, "%s", rec ? rec : "");
        snprintf(nb[r->nbad].why, sizeof nb[r->nbad].why, "%s", why);
        r->nbad++;
    }
    if (!e && rc != SQLITE_DONE)
        e = db_fail(s, d, NULL, "cannot read the recorded files");
    sqlite3_finalize(st);
    if (!e && only_present && r->present == 0) {   /* the .db alone: nothing beside it to check */
        free(r->bad);
        r->bad = NULL;
        r->nbad = 0;
    }
    if (e) {
        free(r->bad);
        memset(r, 0, sizeof *r);
    }
    return e;
}

enum sl_err sl_store_put_run_files(struct sl_store *s, int64_t run_id, const struct sl_store_file *files, int n,
                                   struct sl_diag *d)
{
    sqlite3_stmt *st = s->st[ST_INS_FILE];
    if (sqlite3_exec(s->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
        return db_fail(s, d, NULL, "cannot start recording the run's files");
    enum sl_err e = SL_OK;
    for (int i = 0; i < n && !e; i++) {
        struct binder b = {st, 1, SQLITE_OK};
        b_text(&b, files[i].path);
        b_int(&b, run_id);
        if (b.rc == SQLITE_OK)
            b.rc = sqlite3_bind_null(st, b.i);
        b.i++;
        b_int(&b, files[i].size);
        b_int(&b, files[i].crc32);
        if (b_done(&b) != SQLITE_OK || st_exec(st) != SQLITE_DONE)
            e = db_fail(s, d, NULL, "cannot record the file %s", files[i].path);
        st_clear(st);
    }
    if (!e && sqlite3_exec(s->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
        e = db_fail(s, d, NULL, "cannot commit the run's files");
    if (e && !sqlite3_get_autocommit(s->db))
        sqlite3_exec(s->db, "ROLLBACK", NULL, NULL, NULL);
    return e;
}

int sl_store_read_version(const struct sl_store *s)
{
    return s && s->read_version ? s->read_version : SL_STORE_VERSION;
}
