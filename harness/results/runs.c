/*
 * runs.c — the runs table read back: where each run's numbers came from
 * (sl_store_runs, store.h). A listing read once per table, report or
 * check, so its statement is prepared per call rather than kept with the
 * store's own; it reads through the store's connection (store_int.h).
 * Nothing here prints.
 */
#define _XOPEN_SOURCE 700   /* strdup */
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "store_int.h"

static void col_text(sqlite3_stmt *st, int i, char *buf, size_t n)
{
    const unsigned char *t = sqlite3_column_text(st, i);
    snprintf(buf, n, "%s", t ? (const char *)t : "");
}

static const char sql_query_runs[] =
    "SELECT r.run_id, r.time_utc, r.git_sha, r.study, r.config_path, r.config_hash, r.config_text,\n"
    "       r.host, r.cpu, r.isa, r.gl_renderer, r.gl_version, r.gl_backend, r.embree, r.threads, r.lp_num_threads,\n"
    "       (SELECT count(*) FROM cells c WHERE c.run_id = r.run_id)\n"
    "FROM runs r ORDER BY r.run_id";

enum sl_err sl_store_runs(struct sl_store *s, struct sl_store_run **out, int *n, struct sl_diag *d)
{
    if (!s || !out || !n)
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_store_runs: missing argument");
    *out = NULL;
    *n = 0;
    const char *path = NULL;
    sqlite3 *db = sl_store_handle(s, &path);
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(db, sql_query_runs, -1, &st, NULL) != SQLITE_OK)
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot list the runs: %s", sqlite3_errmsg(db));
    struct sl_store_run *runs = NULL;
    int count = 0, cap = 0, rc;
    enum sl_err e = SL_OK;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (count == cap) {
            int ncap = cap ? 2 * cap : 8;
            struct sl_store_run *nr = realloc(runs, (size_t)ncap * sizeof *nr);
            if (!nr) {
                e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "%d runs", ncap);
                break;
            }
            runs = nr;
            cap = ncap;
        }
        struct sl_store_run *r = &runs[count++];
        memset(r, 0, sizeof *r);
        int i = 0;
        r->run_id = sqlite3_column_int64(st, i++);
        col_text(st, i++, r->prov.time_utc, sizeof r->prov.time_utc);
        col_text(st, i++, r->prov.git_sha, sizeof r->prov.git_sha);
        col_text(st, i++, r->study, sizeof r->study);
        col_text(st, i++, r->config_path, sizeof r->config_path);
        col_text(st, i++, r->config_hash, sizeof r->config_hash);
        const unsigned char *text = sqlite3_column_text(st, i++);
        col_text(st, i++, r->prov.host, sizeof r->prov.host);
        col_text(st, i++, r->prov.cpu, sizeof r->prov.cpu);
        col_text(st, i++, r->prov.isa, sizeof r->prov.isa);
        col_text(st, i++, r->prov.gl_renderer, sizeof r->prov.gl_renderer);
        col_text(st, i++, r->prov.gl_version, sizeof r->prov.gl_version);
        col_text(st, i++, r->prov.gl_backend, sizeof r->prov.gl_backend);
        col_text(st, i++, r->prov.embree, sizeof r->prov.embree);
        r->prov.threads = sqlite3_column_int(st, i++);
        col_text(st, i++, r->prov.lp_threads, sizeof r->prov.lp_threads);
        r->ncells = sqlite3_column_int(st, i++);
        r->config_text = strdup(text ? (const char *)text : "");
        if (!r->config_text) {
            e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "config text of run %lld", (long long)r->run_id);
            break;
        }
    }
    if (!e && rc != SQLITE_DONE)
        e = sl_fail(d, SL_E_IO, path, 0, NULL, "cannot list the runs: %s", sqlite3_errmsg(db));
    sqlite3_finalize(st);
    if (e) {
        sl_store_runs_free(runs, count);
        return e;
    }
    *out = runs;
    *n = count;
    return SL_OK;
}

void sl_store_runs_free(struct sl_store_run *r, int n)
{
    if (!r)
        return;
    for (int i = 0; i < n; i++)
        free(r[i].config_text);
    free(r);
}
