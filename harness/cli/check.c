/*
 * check.c — `shadowlab check`: a results store against a committed baseline
 * (exit 1 when anything moved outside its tolerance), or --update to write
 * the baseline from the store.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "check.h"
#include "cli.h"

int cli_check(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"baseline", required_argument, NULL, OPT_BASELINE}, {"study", required_argument, NULL, OPT_STUDY},
        {"rows", required_argument, NULL, OPT_ROWS},         {"update", no_argument, NULL, OPT_UPDATE},
        {"format", required_argument, NULL, OPT_FORMAT},     {"json", required_argument, NULL, OPT_JSON},
        {"junit", required_argument, NULL, OPT_JUNIT},       {"exact", no_argument, NULL, OPT_EXACT},
        {0, 0, 0, 0},
    };
    const struct cli_parser p = {"check", "", cli_usage_check, lo};
    const char *baseline = NULL, *json = NULL, *junit = NULL;
    struct sl_check_opts o = {0};
    int update = 0;
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case OPT_BASELINE: baseline = optarg; break;
        case OPT_STUDY: o.study = optarg; break;
        case OPT_ROWS: {
            long long v;
            if (!cli_opt_int_or_usage("check", "--rows", optarg, 1, 1000000, &v, cli_usage_check))
                return 2;
            o.max_rows = (int)v;
            break;
        }
        case OPT_UPDATE: update = 1; break;
        case OPT_EXACT: o.exact = 1; break;
        case OPT_FORMAT:
            if (strcmp(optarg, "text") && strcmp(optarg, "md"))
                return cli_usage_error("check: --format text or md", cli_usage_check);
            o.format = strcmp(optarg, "md") ? SL_CHECK_TEXT : SL_CHECK_MD;
            break;
        case OPT_JSON: json = optarg; break;
        case OPT_JUNIT: junit = optarg; break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind + 1 < argc)
        return cli_usage_error("check: one results store at a time", cli_usage_check);
    const char *db = optind < argc ? argv[optind] : NULL;
    if (!db || !baseline)
        return cli_usage_error("check: wants DB and --baseline FILE", cli_usage_check);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (update) {
        enum sl_err e = sl_check_write_baseline(db, baseline, o.study, &d);
        if (e)
            return cli_fail(e, &d);
        fprintf(stderr, "shadowlab: wrote %s from %s\n", baseline, db);
        return 0;
    }
    /* colour only for a person at a terminal (https://no-color.org) */
    const char *nc = getenv("NO_COLOR");
    o.color = o.format == SL_CHECK_TEXT && isatty(1) && !(nc && nc[0]);
    struct { const char *path; FILE **f; } outs[] = {{json, &o.json}, {junit, &o.junit}};
    for (int i = 0; i < 2; i++)
        if (outs[i].path && !(*outs[i].f = fopen(outs[i].path, "w"))) {
            sl_fail(&d, SL_E_OUTPUT, outs[i].path, 0, NULL, "cannot write");
            if (o.json)
                fclose(o.json);
            return cli_fail(SL_E_OUTPUT, &d);
        }
    struct sl_check_result r;
    enum sl_err e = sl_check(db, baseline, &o, stdout, &r, &d);
    for (int i = 0; i < 2; i++)
        if (*outs[i].f && fclose(*outs[i].f) != 0 && !e)
            e = sl_fail(&d, SL_E_OUTPUT, outs[i].path, 0, NULL, "cannot write");
    if (e)
        return cli_fail(e, &d);
    /* how whole each sweep is, beside the verdict (an incomplete sweep's
     * missing cells are the baseline's missing rows when it names them) */
    if (cli_say_sweeps("check", db, 0, 1) < 0)
        return 2;
    return r.failed || r.missing ? 1 : 0;
}
