/*
 * report.c — `shadowlab report`: the HTML and Markdown report of a results
 * store (and its LaTeX with --latex).
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "report.h"

int cli_report(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"out", required_argument, NULL, 'o'},
                                       {"self-contained", no_argument, NULL, OPT_SELF_CONTAINED},
                                       {"latex", no_argument, NULL, OPT_LATEX}, {0, 0, 0, 0}};
    const struct cli_parser p = {"report", "o:", cli_usage_report, lo};
    struct sl_report_opts o = {0};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == 'o')
            o.out_dir = optarg;
        else if (c == OPT_SELF_CONTAINED)
            o.self_contained = 1;
        else if (c == OPT_LATEX)
            o.latex = 1;
        else
            return cli_opt_exit(c);
    }
    if (optind >= argc)
        return cli_usage_error("report: missing RESULTS_DB", cli_usage_report);
    if (optind + 1 < argc)
        return cli_usage_error("report: one RESULTS_DB", cli_usage_report);
    o.db = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    char dir[1100];
    enum sl_err e = sl_report_write(&o, dir, sizeof dir, &d);
    if (e)
        return cli_fail(e, &d);
    printf("report: %s/report.html, %s/report.md%s%s%s%s\n", dir, dir, o.self_contained ? ", " : "",
           o.self_contained ? "(self-contained)" : "", o.latex ? ", " : "", o.latex ? "report.tex" : "");
    return 0;
}
