/*
 * test.c — `shadowlab test technique NAME`: a technique package's test
 * (run/techtest.h), one line per check; exit 0 when all pass, 1 on a
 * finding, 2 when the package cannot be tested.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "techtest.h"

static const char *verdict(int bad) { return bad ? "FAIL" : "ok  "; }

static void print_result(const struct sl_techtest_result *r)
{
    const double px = r->pixels ? (double)r->pixels : 1.0;
    char frames[48] = "";
    if (r->frames > 1)
        snprintf(frames, sizeof frames, " x %d cube faces", r->frames);
    printf("technique %s: %s/%s, %dx%d view, %d² map%s (guard band %d, reach %d), %" PRIu64 " pixels looked up "
           "(%s)\n", r->file, r->scene, r->viewpoint, r->w, r->h, r->map_size, frames, r->guard, r->reach, r->pixels,
           r->renderer);
    printf("  %s compile      glslang and the GL\n", verdict(0));
    printf("  %s determinism  %" PRIu64 " pixel(s) differ between two runs\n", verdict(r->unstable > 0), r->unstable);
    printf("  %s reach        %" PRIu64 " pixel(s) change (%" PRIu64 " verdicts) with what lies beyond the "
           "declared reach", verdict(r->reach_changed > 0), r->reach_changed, r->reach_verdicts);
    if (r->reach_changed)
        printf(", the first at pixel (%d, %d) (rows from the bottom): the lookup reads beyond its declared "
               "reach (technique.yaml, reach)",
               r->reach_x, r->reach_y);
    putchar('\n');
    printf("  %s non-finite   %" PRIu64 " lookup(s) NaN or +-inf, %" PRIu64 " map texel(s) not finite\n",
           verdict(r->nonfinite + r->map_nonfinite > 0), r->nonfinite, r->map_nonfinite);
    printf("  %s taps         %g declared%s; counted %u .. %u, mean %.2f a pixel\n", verdict(r->taps_off),
           r->taps_declared, r->taps_given ? "" : " (the default: technique.yaml gives none)", r->taps_min,
           r->taps_max, r->taps_mean);
    printf("  info time         map %.2f ms, post %.2f ms, lookup %.2f ms (%.1f ns a pixel)\n", r->ms_map,
           r->ms_post, r->ms_lookup, 1e6 * r->ms_lookup / px);
    if (r->findings)
        printf("%d finding(s)\n", r->findings);
    else
        printf("passes\n");
}

int cli_test(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"scene", required_argument, NULL, OPT_SCENE},
                                       {"viewpoint", required_argument, NULL, OPT_VIEWPOINT},
                                       {"viewport", required_argument, NULL, OPT_VIEWPORT},
                                       {"map", required_argument, NULL, OPT_MAP},
                                       {"gl", required_argument, NULL, OPT_GL}, {0, 0, 0, 0}};
    const struct cli_parser p = {"test", "", cli_usage_test, lo};
    struct sl_techtest_opts o = {0};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        long long n;
        if (c == OPT_SCENE)
            o.scene = optarg;
        else if (c == OPT_VIEWPOINT)
            o.viewpoint = optarg;
        else if (c == OPT_VIEWPORT) {
            if (!cli_parse_wxh(optarg, 16, 8192, &o.w, &o.h))
                return cli_usage_error("test: --viewport wants WxH, 16..8192 each", cli_usage_test);
        } else if (c == OPT_MAP) {
            if (!cli_opt_int_or_usage("test", "--map", optarg, 16, 16384, &n, cli_usage_test))
                return 2;
            o.map_size = (int)n;
        } else if (c == OPT_GL) {
            if (!(o.gl = sl_gl_backend_parse(optarg)))
                return cli_usage_error("test: --gl wants osmesa or egl", cli_usage_test);
        } else
            return cli_opt_exit(c);
    }
    if (optind + 2 != argc || strcmp(argv[optind], "technique") != 0)
        return cli_usage_error("test: technique NAME", cli_usage_test);
    o.name = argv[optind + 1];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_techtest_result r;
    enum sl_err e = sl_techtest(&o, &r, &d);
    if (e)
        return cli_fail(e, &d);
    print_result(&r);
    return r.findings ? 1 : 0;
}
