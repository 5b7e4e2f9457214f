/*
 * merge.c — see merge.h.
 *
 * Column lists come from PRAGMA table_info of the merged store rather than
 * from SL_CELL_COLUMNS, so a column added to cellcols.h is carried without a
 * change here (both sides are the same schema version: sl_store_open_existing
 * refuses another one before anything is attached).
 */
#define _GNU_SOURCE
#include "merge.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "integrity.h"
#include "storefile.h"
#include "util.h"

struct sl_merge {
    struct sl_store *store;   /* holds the lock and made the schema */
    sqlite3 *db;              /* our connection, for ATTACH */
    char path[1100], dir[1100];
    char hash[24], first[1100];
    int append;
    char *config_text;
    char config_path[512];
    char *run_cols, *cell_cols, *fig_cols;   /* comma lists without the ids we remap */
    struct sl_integ *integ;                  /* digests of the merged cells */
    int64_t *replace;                        /* stored cells a shard's copy replaces (sorted) */
    int nreplace;
    int shard_files;                         /* the shard attached has tables plan and files (schema 23) */
};

static enum sl_err db_fail(struct sl_merge *m, struct sl_diag *d, const char *what)
{
    return sl_fail(d, SL_E_IO, m->path, 0, NULL, "%s: %s", what, sqlite3_errmsg(m->db));
}

/* "a, b, c": the table's columns but `skip1` and `skip2`. */
static char *columns(sqlite3 *db, const char *table, const char *skip1, const char *skip2)
{
    char *q = sqlite3_mprintf("PRAGMA main.table_info(%s)", table);
    sqlite3_stmt *st = NULL;
    char *out = NULL;
    if (q && sqlite3_prepare_v2(db, q, -1, &st, NULL) == SQLITE_OK) {
        out = sqlite3_mprintf("%s", "");
        while (out && sqlite3_step(st) == SQLITE_ROW) {
            const char *n = (const char *)sqlite3_column_text(st, 1);
            if (!n || !strcmp(n, skip1) || (skip2 && !strcmp(n, skip2)))
                continue;
            char *next = sqlite3_mprintf("%s%s%s", out, out[0] ? ", " : "", n);
            sqlite3_free(out);
            out = next;
        }
    }
    sqlite3_finalize(st);
    sqlite3_free(q);
    return out;
}

enum sl_err sl_merge_open(const char *out_path, int append, struct sl_merge **out, struct sl_diag *d)
{
    return sl_merge_open_held(NULL, out_path, append, out, d);
}

enum sl_err sl_merge_open_held(struct sl_store *held, const char *out_path, int append, struct sl_merge **out,
                               struct sl_diag *d)
{
    struct sl_merge *m = sl_calloc(1, sizeof *m);
    if (!m)
        return sl_fail(d, SL_E_NOMEM, out_path, 0, NULL, "merge");
    m->append = append;
    snprintf(m->path, sizeof m->path, "%s", out_path);
    sl_path_dir(out_path, m->dir, sizeof m->dir);
    enum sl_err e = held ? SL_OK : sl_store_open(out_path, &m->store, d);   /* held: the caller's lock */
    /* URIs: shards are attached read-only (sl_storefile_ro_uri) */
    if (!e && sqlite3_open_v2(out_path, &m->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_URI, NULL) != SQLITE_OK)
        e = db_fail(m, d, "cannot open");
    if (!e) {
        sqlite3_busy_timeout(m->db, 10000);
        m->run_cols = columns(m->db, "runs", "run_id", NULL);
        m->cell_cols = columns(m->db, "cells", "cell_id", "run_id");
        m->fig_cols = columns(m->db, "figures", "cell_id", NULL);
        if (!m->run_cols || !m->cell_cols || !m->fig_cols)
            e = db_fail(m, d, "cannot read the schema");
    }
    if (!e)
        e = sl_integ_open(m->db, "main", m->path, &m->integ, d);
    if (e) {
        sl_merge_close(m);
        return e;
    }
    *out = m;
    return SL_OK;
}

enum sl_err sl_merge_seal(struct sl_merge *m, struct sl_diag *d)
{
    /* the merge's own connection first: the journal switch of the seal
     * wants the store's connection alone on the file */
    sl_integ_close(m->integ);
    m->integ = NULL;
    if (sqlite3_close(m->db) != SQLITE_OK)
        return db_fail(m, d, "cannot close");
    m->db = NULL;
    return m->store ? sl_store_seal(m->store, d) : SL_OK;
}

void sl_merge_close(struct sl_merge *m)
{
    if (!m)
        return;
    sl_integ_close(m->integ);
    sqlite3_close(m->db);
    sl_store_close(m->store);
    sqlite3_free(m->run_cols);
    sqlite3_free(m->cell_cols);
    sqlite3_free(m->fig_cols);
    free(m->config_text);
    free(m->replace);
    free(m);
}

static int id_cmp(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

enum sl_err sl_merge_replace(struct sl_merge *m, const int64_t *ids, int n, struct sl_diag *d)
{
    free(m->replace);
    m->replace = NULL;
    m->nreplace = 0;
    if (n <= 0)
        return SL_OK;
    if (!(m->replace = sl_calloc((size_t)n, sizeof *m->replace)))
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cells to replace");
    memcpy(m->replace, ids, (size_t)n * sizeof *ids);
    qsort(m->replace, (size_t)n, sizeof *m->replace, id_cmp);
    m->nreplace = n;
    return SL_OK;
}

static int replaced(const struct sl_merge *m, int64_t id)
{
    return m->nreplace && bsearch(&id, m->replace, (size_t)m->nreplace, sizeof id, id_cmp) != NULL;
}

const char *sl_merge_config_hash(const struct sl_merge *m)
{
    return m && m->hash[0] ? m->hash : NULL;
}

const char *sl_merge_config_text(const struct sl_merge *m)
{
    return m ? m->config_text : NULL;
}

const char *sl_merge_config_path(const struct sl_merge *m)
{
    return m && m->config_path[0] ? m->config_path : NULL;
}

/* Put src at dst (a hard link where both lie on one filesystem, else a
 * copy), whole or not at all: through dst.tmp and a rename, so a reader sees
 * the old file or the new one. replace: over a file already at dst (a copied
 * cell's own overlay supersedes one of an older computation of that key),
 * else keep it. 1 put, 0 dst was kept, -1 src missing or dst unwritable. */
static int gather(const char *src, const char *dst, int replace)
{
    if (!replace && access(dst, F_OK) == 0)
        return 0;
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%s.tmp", dst);
    unlink(tmp);
    int ok = link(src, tmp) == 0;
    if (!ok) {
        int in = open(src, O_RDONLY), outfd = in >= 0 ? open(tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644) : -1;
        ok = in >= 0 && outfd >= 0;
        char buf[65536];
        ssize_t r;
        while (ok && (r = read(in, buf, sizeof buf)) > 0)
            ok = write(outfd, buf, (size_t)r) == r;
        if (in >= 0)
            close(in);
        if (outfd >= 0 && close(outfd) != 0)
            ok = 0;
    }
    if (!ok || rename(tmp, dst) != 0) {
        unlink(tmp);
        return -1;
    }
    return 1;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* One overlay: the shard's (relative to its folder, or absolute) into
 * <dir>/<study>/overlays/, and the merged cell pointed at it. */
static enum sl_err gather_overlay(struct sl_merge *m, const char *shard_dir, const char *study, const char *ov,
                                  sqlite3_int64 cell, struct sl_merge_shard *info, struct sl_diag *d)
{
    char src[2400], dst[2400], rel[1400];
    if (ov[0] == '/')
        snprintf(src, sizeof src, "%s", ov);
    else
        snprintf(src, sizeof src, "%s/%s", shard_dir, ov);
    snprintf(rel, sizeof rel, "%s/overlays/%s", study, base_name(ov));
    snprintf(dst, sizeof dst, "%s/%s", m->dir, rel);
    int g = gather(src, dst, 1);
    if (g < 0) {
        info->overlays_missing++;   /* the cell keeps the path it had */
        return SL_OK;
    }
    info->overlays += g;
    char *q = sqlite3_mprintf("UPDATE main.cells SET overlay = %Q WHERE cell_id = %lld", rel, cell);
    int rc = q ? sqlite3_exec(m->db, q, NULL, NULL, NULL) : SQLITE_NOMEM;
    sqlite3_free(q);
    return rc == SQLITE_OK ? SL_OK : db_fail(m, d, "cannot point a merged cell at its overlay");
}

static void gather_exr(struct sl_merge *m, const char *shard_dir, const char *study, struct sl_merge_shard *info)
{
    char from[2400], to[2400];
    snprintf(from, sizeof from, "%s/%s/exr", shard_dir, study);
    DIR *dir = opendir(from);
    if (!dir)
        return;
    snprintf(to, sizeof to, "%s/%s/exr", m->dir, study);
    if (sl_mkdirs(to, NULL) == SL_OK) {
        struct dirent *e;
        while ((e = readdir(dir))) {
            if (e->d_name[0] == '.' || strstr(e->d_name, ".tmp."))
                continue;
            char a[2800], b[2800];
            snprintf(a, sizeof a, "%s/%s", from, e->d_name);
            snprintf(b, sizeof b, "%s/%s", to, e->d_name);
            if (gather(a, b, m->append) > 0)
                info->exr++;
        }
    }
    closedir(dir);
}

static int exec(sqlite3 *db, const char *sql)
{
    return sqlite3_exec(db, sql, NULL, NULL, NULL);
}

/* The one config hash (and study) of the shard, read through db under
 * schema name `schema` ("" when it holds no run). */
static enum sl_err shard_hash(sqlite3 *db, const char *schema, const char *shard, struct sl_merge_shard *info,
                              struct sl_diag *d)
{
    sqlite3_stmt *st = NULL;
    char *q = sqlite3_mprintf("SELECT config_hash, study FROM %s.runs UNION SELECT c.config_hash, r.study "
                              "FROM %s.cells c JOIN %s.runs r USING (run_id)", schema, schema, schema);
    int rc = q ? sqlite3_prepare_v2(db, q, -1, &st, NULL) : SQLITE_NOMEM;
    sqlite3_free(q);
    if (rc != SQLITE_OK)
        return sl_fail(d, SL_E_IO, shard, 0, NULL, "cannot read its runs: %s", sqlite3_errmsg(db));
    int n = 0;
    enum sl_err e = SL_OK;
    while (!e && sqlite3_step(st) == SQLITE_ROW) {
        const char *h = (const char *)sqlite3_column_text(st, 0), *s = (const char *)sqlite3_column_text(st, 1);
        if (n++ == 0) {
            snprintf(info->config_hash, sizeof info->config_hash, "%s", h ? h : "");
            snprintf(info->study, sizeof info->study, "%s", s ? s : "");
        } else if (strcmp(h ? h : "", info->config_hash) != 0)
            e = sl_fail(d, SL_E_USAGE, shard, 0, NULL,
                        "holds runs of two configs (hash %s and %s): merge shards of one sweep", info->config_hash,
                        h ? h : "");
    }
    sqlite3_finalize(st);
    return e;
}

/* Where the shard's cells were computed: the git SHA, GL renderer and ISA
 * of the runs that hold cells; a second one in info->other. */
static enum sl_err shard_provenance(sqlite3 *db, const char *shard, struct sl_merge_shard *info, struct sl_diag *d)
{
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(db, "SELECT DISTINCT git_sha, gl_renderer, isa FROM runs WHERE run_id IN "
                           "(SELECT run_id FROM cells) ORDER BY run_id", -1, &st, NULL) != SQLITE_OK)
        return sl_fail(d, SL_E_IO, shard, 0, NULL, "cannot read its runs: %s", sqlite3_errmsg(db));
    int n = 0;
    while (sqlite3_step(st) == SQLITE_ROW && n < 2) {
        const char *g = (const char *)sqlite3_column_text(st, 0), *r = (const char *)sqlite3_column_text(st, 1),
                   *i = (const char *)sqlite3_column_text(st, 2);
        snprintf(n++ ? info->other : info->provenance, sizeof info->provenance, "git %s, GL '%s', ISA %s",
                 g ? g : "", r ? r : "", i ? i : "");
    }
    sqlite3_finalize(st);
    return SL_OK;
}

enum sl_err sl_merge_probe(const char *shard, struct sl_merge_shard *info, struct sl_diag *d)
{
    memset(info, 0, sizeof *info);
    struct stat sb;
    if (stat(shard, &sb) != 0)
        return sl_fail(d, SL_E_IO, shard, 0, NULL, "cannot read the shard: %s", strerror(errno));
    if (!S_ISREG(sb.st_mode))
        return sl_fail(d, SL_E_USAGE, shard, 0, NULL, "%s, not a results store: a shard is a file",
                       S_ISDIR(sb.st_mode) ? "a folder" : "a device or special file");
    struct sl_store *probe = NULL;
    enum sl_err e = sl_store_open_existing(shard, &probe, d);   /* a results store of this version */
    /* a shard is attached as it is: its cells must have today's columns
     * (23 added the cost stages to 22's cells, and a cell's digest covers
     * every column); older ones are read through an upgraded copy by the
     * readers, not merged */
    int ver = e ? 0 : sl_store_read_version(probe);
    if (!e && ver < sl_store_version())
        e = sl_fail(d, SL_E_IO, shard, 0, NULL, "a results store of schema %d: merge takes shards of schema "
                    "%d (verify, table, report and check read it; run its config again to merge it)", ver,
                    sl_store_version());
    /* SQLite's page check and every cell's digest, before anything is written */
    struct sl_store_verify v = {0};
    if (!e && !(e = sl_store_verify(probe, &v, d)) && v.ndamaged)
        e = sl_fail(d, SL_E_IO, shard, 0, NULL, "%d damaged cell(s), the first %s (cell %lld): its rows no "
                    "longer match their digest (`shadowlab verify` names all); nothing merged", v.ndamaged,
                    v.damaged[0].key, (long long)v.damaged[0].cell_id);
    sl_store_verify_free(&v);
    sl_store_close(probe);
    if (e)
        return e;
    sqlite3 *db = NULL;
    char uri[4200];
    if (sl_storefile_ro_uri(shard, uri, sizeof uri) != 0 ||
        sqlite3_open_v2(uri, &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, NULL) != SQLITE_OK)
        e = sl_fail(d, SL_E_IO, shard, 0, NULL, "cannot open: %s", db ? sqlite3_errmsg(db) : "path too long");
    else if (!(e = shard_hash(db, "main", shard, info, d)))
        e = shard_provenance(db, shard, info, d);
    sqlite3_close(db);
    return e;
}

/* The merged run of shard run `id`: copied the first time one of its cells
 * is, so a run whose cells all were there already (a second merge of the
 * same shard) adds no row. Two runs alike in every column (two workers
 * started in the same second) stay two runs. */
static enum sl_err merged_run(struct sl_merge *m, sqlite3_stmt *cp, sqlite3_int64 id, sqlite3_int64 **map,
                              int *nmap, sqlite3_int64 *out, struct sl_merge_shard *info, struct sl_diag *d)
{
    if (id < 0 || id > 100000000)
        return sl_fail(d, SL_E_IO, m->path, 0, NULL, "shard run id %lld out of range", (long long)id);
    if (id >= *nmap) {
        int n = (int)id + 64;
        sqlite3_int64 *p = realloc(*map, (size_t)n * sizeof *p);
        if (!p)
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "merge run map");
        memset(p + *nmap, 0, (size_t)(n - *nmap) * sizeof *p);
        *map = p;
        *nmap = n;
    }
    if (!(*map)[id]) {
        sqlite3_bind_int64(cp, 1, id);
        int rc = sqlite3_step(cp);
        sqlite3_reset(cp);
        if (rc != SQLITE_DONE || sqlite3_changes(m->db) != 1)
            return sl_fail(d, SL_E_IO, m->path, 0, NULL, "shard cell names run %lld, which it does not hold",
                           (long long)id);
        (*map)[id] = sqlite3_last_insert_rowid(m->db);
        info->runs++;
    }
    *out = (*map)[id];
    return SL_OK;
}

/* The file rows of a copied cell, at the paths its files are gathered to:
 * <study>/<folder>/<name> (overlays/, exr/: gather_overlay, gather_exr),
 * their size and CRC-32 as the shard recorded them (a file gathered is the
 * same bytes). */
static enum sl_err copy_files(struct sl_merge *m, sqlite3_stmt *sel, sqlite3_stmt *ins, sqlite3_int64 cell,
                              sqlite3_int64 to, sqlite3_int64 run, const char *study, const char *shard_dir,
                              struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    sqlite3_bind_int64(sel, 1, cell);
    int rc;
    while (!e && (rc = sqlite3_step(sel)) == SQLITE_ROW) {
        const char *p = (const char *)sqlite3_column_text(sel, 0);
        char dir[1300], rel[1500];
        snprintf(dir, sizeof dir, "%s", p ? p : "");
        char *slash = strrchr(dir, '/');
        const char *name = slash ? slash + 1 : dir;
        if (slash)
            *slash = '\0';
        const char *folder = slash ? base_name(dir) : "";
        if (slash)
            snprintf(rel, sizeof rel, "%s/%s/%s", study, folder, name);
        else
            snprintf(rel, sizeof rel, "%s/%s", study, name);
        /* the copied cell's EXR file goes with it, over one of an earlier
         * computation of its key (its record is this file's: an EXR's header
         * holds the time it was written, so two computations differ);
         * gather_exr then brings the shard's files no record names */
        if (slash && strcmp(folder, "exr") == 0 && p && p[0] != '/') {
            char src[2600], dst[2600], dir[1400];
            snprintf(src, sizeof src, "%s/%s", shard_dir, p);
            snprintf(dir, sizeof dir, "%s/%s/exr", m->dir, study);
            snprintf(dst, sizeof dst, "%s/%s", m->dir, rel);
            if (sl_mkdirs(dir, NULL) == SL_OK)
                (void)gather(src, dst, 1);   /* a file not there: verify names it missing */
        }
        sqlite3_bind_text(ins, 1, rel, -1, SQLITE_TRANSIENT);
        sqlite3_bind_int64(ins, 2, run);
        sqlite3_bind_int64(ins, 3, to);
        sqlite3_bind_int64(ins, 4, sqlite3_column_int64(sel, 1));
        sqlite3_bind_int64(ins, 5, sqlite3_column_int64(sel, 2));
        if (sqlite3_step(ins) != SQLITE_DONE)
            e = db_fail(m, d, "cannot record a merged cell's file");
        sqlite3_reset(ins);
    }
    if (!e && rc != SQLITE_DONE)
        e = db_fail(m, d, "cannot read a shard's files");
    sqlite3_reset(sel);
    return e;
}

static enum sl_err copy_cells(struct sl_merge *m, const char *shard_dir, struct sl_merge_shard *info,
                              struct sl_diag *d)
{
    sqlite3_int64 *map = NULL;
    int nmap = 0;
    sqlite3_stmt *st = NULL, *dup = NULL, *cc = NULL, *cf = NULL, *cr = NULL, *df = NULL, *dc = NULL, *dg = NULL;
    sqlite3_stmt *dfl = NULL, *sfl = NULL, *ifl = NULL;
    const int files = m->shard_files;
    char *ins_r = sqlite3_mprintf("INSERT INTO main.runs (%s) SELECT %s FROM shard.runs WHERE run_id = ?",
                                  m->run_cols, m->run_cols);
    char *ins_c = sqlite3_mprintf("INSERT INTO main.cells (run_id, %s) SELECT ?1, %s FROM shard.cells WHERE cell_id = ?2",
                                  m->cell_cols, m->cell_cols);
    char *ins_f = sqlite3_mprintf("INSERT INTO main.figures (cell_id, %s) SELECT ?1, %s FROM shard.figures "
                                  "WHERE cell_id = ?2", m->fig_cols, m->fig_cols);
    enum sl_err e = SL_OK;
    if (!ins_c || !ins_f || !ins_r || sqlite3_prepare_v2(m->db, ins_c, -1, &cc, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db, ins_r, -1, &cr, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db, ins_f, -1, &cf, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db,
                           "SELECT cell_id, run_id, config_hash, scene, viewpoint, vw, vh, map_size, label, overlay "
                           "FROM shard.cells ORDER BY cell_id", -1, &st, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db,
                           "SELECT cell_id FROM main.cells WHERE config_hash = ?1 AND scene = ?2 AND viewpoint = ?3 "
                           "AND vw = ?4 AND vh = ?5 AND map_size = ?6 AND label = ?7",
                           -1, &dup, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db, "DELETE FROM main.figures WHERE cell_id = ?1", -1, &df, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db, "DELETE FROM main.cells WHERE cell_id = ?1", -1, &dc, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db, "UPDATE main.cells SET digest = ?2 WHERE cell_id = ?1", -1, &dg, NULL) != SQLITE_OK ||
        sqlite3_prepare_v2(m->db, "DELETE FROM main.files WHERE cell_id = ?1", -1, &dfl, NULL) != SQLITE_OK ||
        (files && sqlite3_prepare_v2(m->db, "SELECT path, size, crc32 FROM shard.files WHERE cell_id = ?1", -1, &sfl,
                                     NULL) != SQLITE_OK) ||
        sqlite3_prepare_v2(m->db, "INSERT OR REPLACE INTO main.files (path, run_id, cell_id, size, crc32) "
                           "VALUES (?1, ?2, ?3, ?4, ?5)", -1, &ifl, NULL) != SQLITE_OK)
        e = db_fail(m, d, "cannot read the shard's cells");
    while (!e && sqlite3_step(st) == SQLITE_ROW) {
        sqlite3_int64 cell = sqlite3_column_int64(st, 0), run = sqlite3_column_int64(st, 1);
        /* a key already in the store (the schema holds it once): another
         * shard or an earlier merge brought it; kept, so merging is
         * idempotent; append (run --jobs): the fresh cell replaces it, as a
         * second `run` would; so does one of the cells a resume recomputes
         * because its files were lost (sl_merge_replace) */
        for (int k = 2; k <= 8; k++)
            sqlite3_bind_value(dup, k - 1, sqlite3_column_value(st, k));
        sqlite3_int64 old = sqlite3_step(dup) == SQLITE_ROW ? sqlite3_column_int64(dup, 0) : 0;
        sqlite3_reset(dup);
        if (old && !m->append && !replaced(m, old)) {
            info->duplicates++;
            continue;
        }
        if (old) {
            sqlite3_bind_int64(dfl, 1, old);
            sqlite3_bind_int64(df, 1, old);
            sqlite3_bind_int64(dc, 1, old);
            int ok = sqlite3_step(dfl) == SQLITE_DONE && sqlite3_step(df) == SQLITE_DONE &&
                     sqlite3_step(dc) == SQLITE_DONE;
            sqlite3_reset(dfl);
            sqlite3_reset(df);
            sqlite3_reset(dc);
            if (!ok) {
                e = db_fail(m, d, "cannot replace a stored cell");
                break;
            }
        }
        sqlite3_int64 to_run = 0;
        if ((e = merged_run(m, cr, run, &map, &nmap, &to_run, info, d)))
            break;
        sqlite3_bind_int64(cc, 1, to_run);
        sqlite3_bind_int64(cc, 2, cell);
        if (sqlite3_step(cc) != SQLITE_DONE) {
            e = db_fail(m, d, "cannot copy a cell");
            break;
        }
        sqlite3_reset(cc);
        sqlite3_int64 to = sqlite3_last_insert_rowid(m->db);
        sqlite3_bind_int64(cf, 1, to);
        sqlite3_bind_int64(cf, 2, cell);
        if (sqlite3_step(cf) != SQLITE_DONE) {
            e = db_fail(m, d, "cannot copy a cell's figures");
            break;
        }
        sqlite3_reset(cf);
        info->cells++;
        const char *ov = (const char *)sqlite3_column_text(st, 9);
        if (ov && ov[0])
            e = gather_overlay(m, shard_dir, info->study, ov, to, info, d);
        if (!e && files)
            e = copy_files(m, sfl, ifl, cell, to, to_run, info->study, shard_dir, d);
        /* the copy's own digest: its cell id, run id and overlay path are the merged store's */
        uint32_t digest = 0;
        if (!e && sl_integ_digest(m->integ, to, &digest) != SQLITE_OK)
            e = db_fail(m, d, "cannot digest a merged cell");
        if (!e) {
            sqlite3_bind_int64(dg, 1, to);
            sqlite3_bind_int64(dg, 2, digest);
            if (sqlite3_step(dg) != SQLITE_DONE)
                e = db_fail(m, d, "cannot store a merged cell's digest");
            sqlite3_reset(dg);
        }
    }
    sqlite3_finalize(st);
    sqlite3_finalize(dup);
    sqlite3_finalize(cc);
    sqlite3_finalize(cf);
    sqlite3_finalize(cr);
    sqlite3_finalize(df);
    sqlite3_finalize(dc);
    sqlite3_finalize(dg);
    sqlite3_finalize(dfl);
    sqlite3_finalize(sfl);
    sqlite3_finalize(ifl);
    sqlite3_free(ins_r);
    free(map);
    sqlite3_free(ins_c);
    sqlite3_free(ins_f);
    return e;
}

static char *first_config_text(sqlite3 *db, char *path, size_t n)
{
    sqlite3_stmt *st = NULL;
    char *t = NULL;
    if (sqlite3_prepare_v2(db, "SELECT config_text, config_path FROM shard.runs ORDER BY run_id LIMIT 1", -1, &st,
                           NULL) == SQLITE_OK &&
        sqlite3_step(st) == SQLITE_ROW) {
        const char *s = (const char *)sqlite3_column_text(st, 0), *p = (const char *)sqlite3_column_text(st, 1);
        t = s ? strdup(s) : NULL;
        snprintf(path, n, "%s", p ? p : "");
    }
    sqlite3_finalize(st);
    return t;
}

enum sl_err sl_merge_add(struct sl_merge *m, const char *shard, struct sl_merge_shard *info, struct sl_diag *d)
{
    memset(info, 0, sizeof *info);
    struct sl_store *probe = NULL;
    enum sl_err e = sl_store_open_existing(shard, &probe, d);   /* a results store of this version */
    sl_store_close(probe);
    if (e)
        return e;
    char shard_dir[1100];
    sl_path_dir(shard, shard_dir, sizeof shard_dir);

    /* read as a reader reads it: a -wal beside a shard on read-only media
     * through a private copy (storefile.h) */
    struct sl_storefile_ro ro;
    if ((e = sl_storefile_ro_open(shard, &ro, d)))
        return e;
    char *att = sqlite3_mprintf("ATTACH DATABASE %Q AS shard", ro.uri);
    if (!att || exec(m->db, att) != SQLITE_OK) {
        sqlite3_free(att);
        e = db_fail(m, d, "cannot attach the shard");
        sl_storefile_ro_release(&ro);
        return e;
    }
    sqlite3_free(att);
    e = shard_hash(m->db, "shard", shard, info, d);
    if (!e && info->config_hash[0] && m->hash[0] && strcmp(m->hash, info->config_hash) != 0)
        e = sl_fail(d, SL_E_USAGE, shard, 0, NULL,
                    "holds config hash %s (study '%s'), but %s holds %s: not a shard of the same sweep",
                    info->config_hash, info->study, m->first, m->hash);
    if (!e && info->config_hash[0]) {
        char ov[1300];
        snprintf(ov, sizeof ov, "%s/%s/overlays", m->dir, info->study);
        e = sl_mkdirs(ov, d);
    }
    if (!e && info->config_hash[0]) {
        if (exec(m->db, "BEGIN IMMEDIATE") != SQLITE_OK)
            e = db_fail(m, d, "cannot begin");
        /* a shard has its plan and files (only shards of this schema are taken,
         * above); checked again rather than assumed */
        sqlite3_int64 v23 = 0;
        sqlite3_stmt *q = NULL;
        if (sqlite3_prepare_v2(m->db, "SELECT count(*) FROM shard.sqlite_master WHERE type = 'table' AND name IN "
                               "('plan', 'files')", -1, &q, NULL) == SQLITE_OK && sqlite3_step(q) == SQLITE_ROW)
            v23 = sqlite3_column_int64(q, 0);
        sqlite3_finalize(q);
        m->shard_files = v23 == 2;
        if (!e)
            e = copy_cells(m, shard_dir, info, d);
        if (!e && m->shard_files &&
            exec(m->db, "INSERT OR IGNORE INTO main.plan (config_hash, cell_index, scene, viewpoint, vw, vh, map_size, "
                 "label) SELECT config_hash, cell_index, scene, viewpoint, vw, vh, map_size, label FROM shard.plan") !=
                SQLITE_OK)
            e = db_fail(m, d, "cannot copy the shard's plan");
        sl_storefile_fault_point("merge");   /* the tests: killed inside the shard's transaction */
        if (!e && exec(m->db, "COMMIT") != SQLITE_OK)
            e = db_fail(m, d, "cannot commit");
        if (e)
            exec(m->db, "ROLLBACK");
    }
    if (!e && info->config_hash[0] && !m->hash[0]) {
        snprintf(m->hash, sizeof m->hash, "%s", info->config_hash);
        snprintf(m->first, sizeof m->first, "%s", shard);
        m->config_text = first_config_text(m->db, m->config_path, sizeof m->config_path);
    }
    if (exec(m->db, "DETACH DATABASE shard") != SQLITE_OK && !e)
        e = db_fail(m, d, "cannot detach the shard");
    sl_storefile_ro_release(&ro);
    if (!e && info->study[0])
        gather_exr(m, shard_dir, info->study, info);
    return e;
}
