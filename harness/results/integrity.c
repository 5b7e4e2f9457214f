/*
 * integrity.c — see integrity.h.
 *
 * Invariants:
 * - The serialisation is a function of the stored values alone (their
 *   SQLite types and bytes, in the order SQLite lists the columns), never of
 *   how C formats them, so the writer and `verify` agree on every platform
 *   of one byte order of REAL bits (written little-endian explicitly).
 * - The `digest` column is found by name and left out; every other column
 *   of the cell row and of its figure rows is in.
 * Nothing here prints.
 */
#include "integrity.h"
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>
#include "store_int.h"
#include "util.h"

struct sl_integ {
    sqlite3_stmt *cell, *figs;
};

enum sl_err sl_integ_open(struct sqlite3 *db, const char *schema, const char *path, struct sl_integ **out,
                          struct sl_diag *d)
{
    *out = NULL;
    struct sl_integ *g = sl_calloc(1, sizeof *g);
    if (!g)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "digest statements");
    char *qc = sqlite3_mprintf("SELECT * FROM \"%w\".cells WHERE cell_id = ?1", schema);
    /* (region, figure) is unique within a cell: the order is total */
    char *qf = sqlite3_mprintf("SELECT * FROM \"%w\".figures WHERE cell_id = ?1 ORDER BY region, figure", schema);
    int rc = qc && qf ? SQLITE_OK : SQLITE_NOMEM;
    if (rc == SQLITE_OK)
        rc = sqlite3_prepare_v3(db, qc, -1, SQLITE_PREPARE_PERSISTENT, &g->cell, NULL);
    if (rc == SQLITE_OK)
        rc = sqlite3_prepare_v3(db, qf, -1, SQLITE_PREPARE_PERSISTENT, &g->figs, NULL);
    sqlite3_free(qc);
    sqlite3_free(qf);
    if (rc != SQLITE_OK) {
        enum sl_err e = sl_fail(d, SL_E_IO, path, 0, NULL, "cannot prepare the cell digest: %s", sqlite3_errmsg(db));
        sl_integ_close(g);
        return e;
    }
    *out = g;
    return SL_OK;
}

void sl_integ_close(struct sl_integ *g)
{
    if (!g)
        return;
    sqlite3_finalize(g->cell);
    sqlite3_finalize(g->figs);
    free(g);
}

static uLong put_u64(uLong crc, uint64_t v)
{
    unsigned char b[8];
    for (int i = 0; i < 8; i++)
        b[i] = (unsigned char)(v >> (8 * i));
    return crc32(crc, b, 8);
}

/* One row of st: its tag, its column count, then each column but `skip`. */
static uLong put_row(uLong crc, sqlite3_stmt *st, unsigned char tag, const char *skip)
{
    int n = sqlite3_column_count(st);
    crc = crc32(crc, &tag, 1);
    crc = put_u64(crc, (uint64_t)n);
    for (int i = 0; i < n; i++) {
        if (skip && strcmp(sqlite3_column_name(st, i), skip) == 0)
            continue;
        int type = sqlite3_column_type(st, i);
        unsigned char t = (unsigned char)type;
        crc = crc32(crc, &t, 1);
        if (type == SQLITE_INTEGER) {
            crc = put_u64(crc, (uint64_t)sqlite3_column_int64(st, i));
        } else if (type == SQLITE_FLOAT) {
            double v = sqlite3_column_double(st, i);
            uint64_t bits;
            memcpy(&bits, &v, sizeof bits);
            crc = put_u64(crc, bits);
        } else if (type == SQLITE_TEXT || type == SQLITE_BLOB) {
            const void *p = type == SQLITE_TEXT ? (const void *)sqlite3_column_text(st, i) : sqlite3_column_blob(st, i);
            int len = sqlite3_column_bytes(st, i);
            crc = put_u64(crc, (uint64_t)len);
            if (len > 0)
                crc = crc32(crc, p, (uInt)len);
        }
    }
    return crc;
}

int sl_integ_digest(struct sl_integ *g, int64_t cell_id, uint32_t *out)
{
    uLong crc = crc32(0L, Z_NULL, 0);
    int rc = sqlite3_bind_int64(g->cell, 1, cell_id);
    if (rc == SQLITE_OK) {
        rc = sqlite3_step(g->cell);
        if (rc == SQLITE_ROW) {
            crc = put_row(crc, g->cell, 'C', "digest");
            rc = SQLITE_OK;
        } else if (rc == SQLITE_DONE) {
            rc = SQLITE_NOTFOUND;
        }
    }
    sqlite3_reset(g->cell);
    if (rc == SQLITE_OK)
        rc = sqlite3_bind_int64(g->figs, 1, cell_id);
    if (rc == SQLITE_OK) {
        while ((rc = sqlite3_step(g->figs)) == SQLITE_ROW)
            crc = put_row(crc, g->figs, 'F', NULL);
        rc = rc == SQLITE_DONE ? SQLITE_OK : rc;
    }
    sqlite3_reset(g->figs);
    *out = (uint32_t)crc;
    return rc;
}

enum sl_err sl_integ_quick_check(struct sqlite3 *db, const char *schema, const char *path, const char *doing,
                                 struct sl_diag *d)
{
    sqlite3_stmt *q = NULL;
    char *sql = sqlite3_mprintf("PRAGMA \"%w\".quick_check(1)", schema);
    int rc = sql ? sqlite3_prepare_v2(db, sql, -1, &q, NULL) : SQLITE_NOMEM;
    sqlite3_free(sql);
    if (rc != SQLITE_OK)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "the store is damaged (quick_check could not run: %s); %s",
                       sqlite3_errmsg(db), doing);
    rc = sqlite3_step(q);
    const unsigned char *t = rc == SQLITE_ROW ? sqlite3_column_text(q, 0) : NULL;
    enum sl_err e = SL_OK;
    if (rc != SQLITE_ROW)
        e = sl_fail(d, SL_E_IO, path, 0, NULL, "the store is damaged (quick_check failed: %s); %s",
                    sqlite3_errmsg(db), doing);
    else if (!t || strcmp((const char *)t, "ok") != 0) {
        char why[200];   /* its first line: the message stays one line */
        snprintf(why, sizeof why, "%s", t ? (const char *)t : "no answer");
        for (char *c = why; *c; c++)
            if (*c == '\n')
                *c = ' ';
        e = sl_fail(d, SL_E_IO, path, 0, NULL, "the store is damaged (SQLite quick_check: %s); %s", why, doing);
    }
    sqlite3_finalize(q);
    return e;
}

enum sl_err sl_integ_verify(struct sqlite3 *db, const char *schema, const char *path, struct sl_store_verify *r,
                            struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    double t0 = sl_now();
    enum sl_err e = sl_integ_quick_check(db, schema, path, "no cell can be trusted", d);
    if (e)
        return e;
    struct sl_integ *g = NULL;
    if ((e = sl_integ_open(db, schema, path, &g, d)))
        return e;
    sqlite3_stmt *st = NULL;
    char *q = sqlite3_mprintf("SELECT cell_id, digest, run_id, scene, viewpoint, vw, vh, map_size, label, "
                              "(SELECT count(*) FROM \"%w\".figures f WHERE f.cell_id = c.cell_id) "
                              "FROM \"%w\".cells c ORDER BY cell_id", schema, schema);
    int rc = q ? sqlite3_prepare_v2(db, q, -1, &st, NULL) : SQLITE_NOMEM;
    sqlite3_free(q);
    int cap = 0;
    while (rc == SQLITE_OK && !e && (rc = sqlite3_step(st)) == SQLITE_ROW) {
        rc = SQLITE_OK;
        int64_t id = sqlite3_column_int64(st, 0);
        uint32_t want = (uint32_t)sqlite3_column_int64(st, 1), got = 0;
        r->cells++;
        r->figures += sqlite3_column_int64(st, 9);
        if ((rc = sl_integ_digest(g, id, &got)) != SQLITE_OK)
            break;
        if (got == want && sqlite3_column_type(st, 1) == SQLITE_INTEGER)
            continue;
        if (r->ndamaged == cap) {
            int ncap = cap ? 2 * cap : 16;
            struct sl_store_damage *nd = realloc(r->damaged, (size_t)ncap * sizeof *nd);
            if (!nd) {
                e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "%d damaged cells", ncap);
                break;
            }
            r->damaged = nd;
            cap = ncap;
        }
        struct sl_store_damage *b = &r->damaged[r->ndamaged++];
        b->cell_id = id;
        b->run_id = sqlite3_column_int64(st, 2);
        const char *sc = (const char *)sqlite3_column_text(st, 3), *vp = (const char *)sqlite3_column_text(st, 4),
                   *lb = (const char *)sqlite3_column_text(st, 8);
        snprintf(b->key, sizeof b->key, "%s/%s/%dx%d/%d/%s", sc ? sc : "", vp ? vp : "", sqlite3_column_int(st, 5),
                 sqlite3_column_int(st, 6), sqlite3_column_int(st, 7), lb ? lb : "");
    }
    if (!e && rc != SQLITE_OK && rc != SQLITE_DONE)
        e = sl_fail(d, SL_E_IO, path, 0, NULL, "the store is damaged (cannot read its cells: %s)", sqlite3_errmsg(db));
    sqlite3_finalize(st);
    sl_integ_close(g);
    r->seconds = sl_now() - t0;
    if (e)
        sl_store_verify_free(r);
    return e;
}

void sl_store_verify_free(struct sl_store_verify *r)
{
    if (!r)
        return;
    free(r->damaged);
    memset(r, 0, sizeof *r);
}
