/*
 * report_store.c — sl_report_write: the report of a results store. Refuses
 * bad input before anything is written (see report.c), reads the runs and,
 * per study, the latest cell of each key, then hands them to
 * sl_report_build. Kept apart from report.c so the page writer builds and
 * is tested without a store.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "report_int.h"
#include "util.h"

enum sl_err sl_report_write(const struct sl_report_opts *o, char *dir_out, size_t n, struct sl_diag *d)
{
    if (dir_out && n)
        dir_out[0] = '\0';
    if (!o || !o->db || !o->db[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "missing RESULTS_DB");
    struct stat st;
    if (stat(o->db, &st) != 0)
        return sl_fail(d, SL_E_IO, o->db, 0, NULL, "no such results store: %s", strerror(errno));
    if (!S_ISREG(st.st_mode))
        return sl_fail(d, SL_E_IO, o->db, 0, NULL, "not a file: a results store is an SQLite file");
    if (st.st_size == 0)
        return sl_fail(d, SL_E_IO, o->db, 0, NULL, "empty file, not a results store");
    char gp[1024];
    enum sl_err e = sl_report_gnuplot_find(o->gnuplot, gp, sizeof gp, d);
    if (e)
        return e;

    /* the database's folder: overlays are relative to it; the default output is in it */
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", o->db);
    char *slash = strrchr(dir, '/');
    if (slash == dir)
        dir[1] = '\0';
    else if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    char outdir[1100];
    if (o->out_dir && o->out_dir[0])
        snprintf(outdir, sizeof outdir, "%s", o->out_dir);
    else
        snprintf(outdir, sizeof outdir, "%s/report", dir);

    struct sl_store *s = NULL;
    struct sl_store_run *runs = NULL;
    struct sl_cell_record *all = NULL;
    int nruns = 0, nall = 0;
    e = sl_store_open_existing(o->db, &s, d);
    if (!e)
        e = sl_store_runs(s, &runs, &nruns, d);
    /* one query per study: the latest cell of a key wins within its study only */
    for (int i = 0; i < nruns && !e; i++) {
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = strcmp(runs[j].study, runs[i].study) == 0;
        if (seen)
            continue;
        struct sl_store_filter f = {.study = runs[i].study};
        struct sl_cell_record *cells = NULL;
        int n = 0;
        e = sl_store_query(s, &f, &cells, &n, d);
        if (!e && n > 0) {
            struct sl_cell_record *grown = realloc(all, (size_t)(nall + n) * sizeof *grown);
            if (!grown) {
                e = sl_fail(d, SL_E_NOMEM, o->db, 0, NULL, "%d cells", nall + n);
            } else {
                all = grown;
                memcpy(all + nall, cells, (size_t)n * sizeof *cells);
                nall += n;
            }
        }
        free(cells);
    }
    if (!e && nall == 0)
        e = sl_fail(d, SL_E_USAGE, o->db, 0, NULL, "the results store holds no cells (%d run(s)): nothing to report",
                    nruns);
    if (!e) {
        struct sl_report_input in = {all, nall, runs, nruns, o->db, dir, s};
        e = sl_report_build_with(&in, outdir, gp, o->self_contained, o->latex, d);
    }
    if (!e && dir_out)
        snprintf(dir_out, n, "%s", outdir);
    free(all);
    sl_store_runs_free(runs, nruns);
    sl_store_close(s);
    return e;
}
