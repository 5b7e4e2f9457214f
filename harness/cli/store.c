/*
 * store.c — the verbs on results stores as files: `shadowlab merge` (the
 * shards of a split sweep into one store) and `shadowlab verify` (every
 * cell against its digest). cli_print_merge is shared with run --jobs,
 * whose workers' stores are merged the same way.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "config.h"
#include "plan.h"
#include "store.h"
#include "submit.h"

/* What a merge did, shard by shard, and the cells of the sweep it lacks. */
int cli_print_merge(const char *const *shards, const struct sl_shards_result *r, const char *out)
{
    for (int i = 0; i < r->nshards; i++) {
        const struct sl_merge_shard *s = &r->shard[i];
        if (r->absent[i])
            fprintf(stderr, "shadowlab: merge: %s: not there (its cells are missing below)\n", shards[i]);
        else
            printf("%s: %d cell(s) copied, %d duplicate(s) skipped, %d run(s), %d overlay(s)%s\n", shards[i],
                   s->cells, s->duplicates, s->runs, s->overlays, s->overlays_missing ? " (some not found)" : "");
    }
    const struct sl_config *c = &r->config;
    for (int i = 0; i < r->nmissing && i < 50; i++) {
        struct sl_cell_key k;
        sl_plan_cell(c, r->missing[i], &k);
        fprintf(stderr, "shadowlab: merge: missing cell %d: %s/%s %dx%d map %d '%s'\n", r->missing[i],
                c->scenes[k.scene].name, c->scenes[k.scene].viewpoints[k.vp], c->viewport_w[k.viewport],
                c->viewport_h[k.viewport], c->maps[k.map], c->methods[k.method].label);
    }
    if (r->nmissing > 50)
        fprintf(stderr, "shadowlab: merge: ... and %d more missing\n", r->nmissing - 50);
    printf("merged into %s: %d of %d cell(s) of the sweep stored, %d missing; %d copied, %d duplicate(s), "
           "%.2f s (%.1f ms per 1,000 cells)\n", out, r->total - r->nmissing, r->total, r->nmissing, r->copied,
           r->duplicates, r->seconds, r->copied ? 1e6 * r->seconds / r->copied : 0.0);
    return r->nmissing ? 1 : 0;
}

int cli_merge(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"out", required_argument, NULL, 'o'},
                                       {"allow-mixed", no_argument, NULL, OPT_ALLOW_MIXED}, {0, 0, 0, 0}};
    const struct cli_parser p = {"merge", "o:", cli_usage_merge, lo};
    const char *out = NULL;
    unsigned flags = 0;
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == OPT_ALLOW_MIXED)
            flags |= SL_MERGE_ALLOW_MIXED;
        else if (c != 'o')
            return cli_opt_exit(c);
        else
            out = optarg;
    }
    int n = argc - optind;
    if (!out || n < 1)
        return cli_usage_error("merge: wants SHARD.db... and -o STORE.db", cli_usage_merge);
    const char **shards = (const char **)(argv + optind);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_shards_result r;
    enum sl_err e = sl_shards_merge(shards, n, out, flags, &r, &d);
    int rc = e ? cli_fail(e, &d) : cli_print_merge(shards, &r, out);
    sl_shards_result_free(&r);
    return rc;
}

int cli_say_sweeps(const char *verb, const char *db, int missing, int quiet_whole)
{
    struct sl_diag d = {0};
    struct sl_store *st = NULL;
    struct sl_store_sweep *w = NULL;
    int n = 0, incomplete = 0;
    enum sl_err e = sl_store_open_existing(db, &st, &d);
    if (!e)
        e = sl_store_sweeps(st, &w, &n, &d);
    for (int i = 0; !e && i < n; i++) {
        const struct sl_store_sweep *s = &w[i];
        if (quiet_whole && (s->planned < 0 || s->stored >= s->planned))
            continue;
        if (s->planned < 0) {   /* a store written before plans were recorded */
            fprintf(stderr, "shadowlab: %s: %s: sweep '%s' (config %s, run %s): %d cells; its plan is not recorded "
                    "(a store of schema 22 or older), so whether it is complete is unknown\n", verb, db, s->study,
                    s->config_hash, s->runs, s->stored);
            continue;
        }
        fprintf(stderr, "shadowlab: %s: %s: sweep '%s' (config %s, run %s): %d of %d cells%s\n", verb, db, s->study,
                s->config_hash, s->runs, s->stored, s->planned, s->stored < s->planned ? ", incomplete" : "");
        if (s->stored >= s->planned)
            continue;
        incomplete++;
        struct sl_store_key *k = NULL;
        int nk = 0;
        if (missing > 0 && !(e = sl_store_missing(st, s->config_hash, &k, &nk, &d))) {
            for (int j = 0; j < nk && j < missing; j++)
                fprintf(stderr, "shadowlab: %s: %s: missing cell %d: %s/%s/%dx%d/%d/%s\n", verb, db, k[j].index,
                        k[j].scene, k[j].viewpoint, k[j].vw, k[j].vh, k[j].map_size, k[j].label);
            if (nk > missing)
                fprintf(stderr, "shadowlab: %s: %s: ... and %d more missing\n", verb, db, nk - missing);
        }
        free(k);
    }
    free(w);
    sl_store_close(st);
    if (e) {
        cli_fail(e, &d);
        return -1;
    }
    return incomplete;
}

/* Every cell against its digest, every recorded file against its size and
 * CRC-32, every sweep against its plan: exit 0 whole, 1 an incomplete sweep,
 * 2 damage (named). */
int cli_verify(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"files", no_argument, NULL, OPT_FILES},
                                       {"no-files", no_argument, NULL, OPT_NO_FILES}, {0, 0, 0, 0}};
    const struct cli_parser p = {"verify", "", cli_usage_verify, lo};
    int files = -1;   /* -1: when the files sit beside the store */
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == OPT_FILES)
            files = 1;
        else if (c == OPT_NO_FILES)
            files = 0;
        else
            return cli_opt_exit(c);
    }
    if (argc - optind != 1)
        return cli_usage_error("verify: wants one STORE.db", cli_usage_verify);
    const char *db = argv[optind];
    struct sl_diag d = {0};
    struct sl_store *st = NULL;
    struct sl_store_verify v = {0};
    struct sl_store_files_check fc = {0};
    enum sl_err e = sl_store_open_existing(db, &st, &d);
    e = e ? e : sl_store_verify(st, &v, &d);
    if (!e && files)
        e = sl_store_check_files(st, files < 0, &fc, &d);
    int read_version = e ? 0 : sl_store_read_version(st);
    sl_store_close(st);
    for (int i = 0; !e && i < v.ndamaged; i++)
        fprintf(stderr, "shadowlab: verify: %s: damaged cell %s (cell %lld, run %lld): its rows no longer match "
                "their digest\n", db, v.damaged[i].key, (long long)v.damaged[i].cell_id, (long long)v.damaged[i].run_id);
    for (int i = 0; !e && i < fc.nbad; i++)
        if (strcmp(fc.bad[i].why, "missing") == 0)
            fprintf(stderr, "shadowlab: verify: %s: missing file %s\n", db, fc.bad[i].path);
        else
            fprintf(stderr, "shadowlab: verify: %s: damaged file %s: %s\n", db, fc.bad[i].path, fc.bad[i].why);
    if (!e) {
        printf("%s: %ld cell(s), %ld figure row(s) checked in %.3f s (%.1f us per cell): %d damaged\n", db, v.cells,
               v.figures, v.seconds, v.cells ? 1e6 * v.seconds / (double)v.cells : 0.0, v.ndamaged);
        if (read_version < sl_store_version())
            printf("%s: a store of schema %d, read through a private copy upgraded to schema %d%s\n", db, read_version,
                   sl_store_version(), read_version < 17 ? "; its cells carry no digest of their own (digests came "
                   "with schema 17), so only SQLite's quick_check vouched for their values" : "");
        if (files && fc.recorded && (files > 0 || fc.present))
            printf("%s: %d recorded file(s) checked: %d missing or damaged\n", db, fc.recorded, fc.nbad);
        else if (files && fc.recorded)
            printf("%s: %d recorded file(s) not checked: none is beside the store (--files checks them anyway)\n", db,
                   fc.recorded);
    }
    int incomplete = e ? 0 : cli_say_sweeps("verify", db, 50, 0);
    int rc = e ? cli_fail(e, &d) : v.ndamaged || fc.nbad || incomplete < 0 ? 2 : incomplete ? 1 : 0;
    sl_store_verify_free(&v);
    free(fc.bad);
    return rc;
}
