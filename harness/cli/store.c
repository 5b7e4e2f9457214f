/*
 * store.c — the verbs on results stores as files: `shadowlab merge` (the
 * shards of a split sweep into one store) and `shadowlab verify` (every
 * cell against its digest). cli_print_merge is shared with run --jobs,
 * whose workers' stores are merged the same way.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
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

/* Every cell against its digest: exit 0 intact, 2 naming each damaged cell. */
int cli_verify(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {0, 0, 0, 0}};
    const struct cli_parser p = {"verify", "", cli_usage_verify, lo};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;)
        return cli_opt_exit(c);
    if (argc - optind != 1)
        return cli_usage_error("verify: wants one STORE.db", cli_usage_verify);
    const char *db = argv[optind];
    struct sl_diag d = {0};
    struct sl_store *st = NULL;
    struct sl_store_verify v = {0};
    enum sl_err e = sl_store_open_existing(db, &st, &d);
    e = e ? e : sl_store_verify(st, &v, &d);
    sl_store_close(st);
    for (int i = 0; !e && i < v.ndamaged; i++)
        fprintf(stderr, "shadowlab: verify: %s: damaged cell %s (cell %lld, run %lld): its rows no longer match "
                "their digest\n", db, v.damaged[i].key, (long long)v.damaged[i].cell_id, (long long)v.damaged[i].run_id);
    if (!e)
        printf("%s: %ld cell(s), %ld figure row(s) checked in %.3f s (%.1f us per cell): %d damaged\n", db, v.cells,
               v.figures, v.seconds, v.cells ? 1e6 * v.seconds / (double)v.cells : 0.0, v.ndamaged);
    int rc = e ? cli_fail(e, &d) : v.ndamaged ? 2 : 0;
    sl_store_verify_free(&v);
    return rc;
}
