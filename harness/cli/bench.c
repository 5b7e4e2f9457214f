/*
 * bench.c — `shadowlab bench`: each stage against its plain counterpart and
 * the studies against their targets (the measurements are the bench
 * module's; this file parses the options).
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <string.h>
#include "bench.h"
#include "cli.h"

int cli_bench(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"reps", required_argument, NULL, OPT_REPS},         {"only", required_argument, NULL, OPT_ONLY},
        {"scene", required_argument, NULL, OPT_SCENE},       {"viewport", required_argument, NULL, OPT_VIEWPORT},
        {"map", required_argument, NULL, OPT_MAP},           {"csv", required_argument, NULL, OPT_CSV},
        {"gl", required_argument, NULL, OPT_GL}, {"markdown", required_argument, NULL, OPT_MARKDOWN}, {0, 0, 0, 0},
    };
    const struct cli_parser p = {"bench", "", cli_usage_bench, lo};
    struct sl_bench_opts o = {.config = NULL, .reps = 0, .out = stdout};
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case OPT_REPS: {
            long long v;
            if (!cli_opt_int_or_usage("bench", "--reps", optarg, 1, 1000, &v, cli_usage_bench))
                return 2;
            o.reps = (int)v;
            break;
        }
        case OPT_ONLY:
            if (sl_bench_parse_stages(optarg, &o.stages, &d))
                return cli_usage_error(d.msg, cli_usage_bench);
            break;
        case OPT_SCENE: o.scene = optarg; break;
        case OPT_VIEWPORT: {
            if (!cli_parse_wxh(optarg, 1, 16384, &o.width, &o.height))
                return cli_usage_error("bench: --viewport wants WxH, 1..16384 each", cli_usage_bench);
            break;
        }
        case OPT_MAP: {
            long long v;
            if (!cli_opt_int_or_usage("bench", "--map", optarg, 16, 16384, &v, cli_usage_bench))
                return 2;
            o.map = (int)v;
            break;
        }
        case OPT_CSV: o.csv = optarg; break;
        case OPT_MARKDOWN: o.markdown = optarg; break;
        case OPT_GL:
            if (!(o.gl = sl_gl_backend_parse(optarg)))
                return cli_usage_error("bench: --gl wants osmesa or egl", cli_usage_bench);
            break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind + 1 < argc)
        return cli_usage_error("bench: one CONFIG at most", cli_usage_bench);
    o.config = optind < argc ? argv[optind] : NULL;
    enum sl_err e = sl_bench(&o, NULL, &d);
    return e ? cli_fail(e, &d) : 0;
}
