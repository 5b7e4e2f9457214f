/*
 * preview.c — `shadowlab preview`: a quick shaded PNG per viewpoint of a
 * scene, for framing cameras; prints each file written.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "preview.h"

int cli_preview(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"out", required_argument, NULL, 'o'},
                                       {"viewpoint", required_argument, NULL, OPT_VIEWPOINT},
                                       {"size", required_argument, NULL, OPT_SIZE},
                                       {"gl", required_argument, NULL, OPT_GL}, {0, 0, 0, 0}};
    const struct cli_parser p = {"preview", "o:", cli_usage_preview, lo};
    struct sl_preview_opts o = {0};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == 'o')
            o.out_dir = optarg;
        else if (c == OPT_VIEWPOINT)
            o.viewpoint = optarg;
        else if (c == OPT_SIZE) {
            if (!cli_parse_wxh(optarg, 16, 8192, &o.w, &o.h))
                return cli_usage_error("preview: --size wants WxH, 16..8192 each", cli_usage_preview);
        } else if (c == OPT_GL) {
            if (!(o.gl = sl_gl_backend_parse(optarg)))
                return cli_usage_error("preview: --gl wants osmesa or egl", cli_usage_preview);
        } else
            return cli_opt_exit(c);
    }
    if (optind + 1 != argc)
        return cli_usage_error("preview: one SCENE", cli_usage_preview);
    o.scene = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_preview_result r;
    enum sl_err e = sl_preview(&o, &r, &d);
    for (int i = 0; i < r.n; i++)
        printf("%s\n", r.path[i]);
    if (e)
        return cli_fail(e, &d);
    fprintf(stderr, "shadowlab: %d preview(s) in %.0f ms (%s)\n", r.n, r.ms_total, r.renderer);
    return 0;
}
