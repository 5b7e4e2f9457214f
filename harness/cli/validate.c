/*
 * validate.c — `shadowlab validate`: a config or a scene file parsed and
 * checked, the scenes and models it names loaded; no GL and no Embree, so
 * it is quick and runs anywhere.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "config.h"
#include "plan.h"
#include "preview.h"
#include "scene.h"
#include "scenefile.h"

int cli_validate(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"define", required_argument, NULL, 'D'}, {0, 0, 0, 0}};
    const struct cli_parser p = {"validate", "D:", cli_usage_validate, lo};
    struct cli_overrides ov = {.n = 0};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c != 'D')
            return cli_opt_exit(c);
        if (!cli_add_override(&ov, "validate", optarg, cli_usage_validate))
            return 2;
    }
    if (optind + 1 != argc)
        return cli_usage_error("validate: one FILE", cli_usage_validate);
    const char *file = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (sl_file_is_scene(file)) {
        if (ov.n)
            return cli_usage_error("validate: -D applies to a config, not to a scene file", cli_usage_validate);
        struct sl_scene s;
        enum sl_err e = sl_scene_load(file, &s, &d);
        if (e)
            return cli_fail(e, &d);
        printf("%s: ok: scene '%s', %u triangles, %u vertices, %d mesh(es), %d viewpoint(s), "
               "bounds (%g, %g, %g) .. (%g, %g, %g)\n", file, s.name, s.nt, s.nv, s.nranges, s.nvp,
               s.origin[0] + s.lo[0], s.origin[1] + s.lo[1], s.origin[2] + s.lo[2], s.origin[0] + s.hi[0],
               s.origin[1] + s.hi[1], s.origin[2] + s.hi[2]);
        /* per mesh, in world units, to frame viewpoints without a run */
        for (int m = 0; m < s.nranges; m++) {
            const struct sl_mesh_range *r = &s.ranges[m];
            double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
            for (uint32_t t = r->first; t < r->first + r->count; t++)
                for (int k = 0; k < 3; k++) {
                    const float *v = &s.pos[3 * s.idx[3 * t + k]];
                    for (int a = 0; a < 3; a++) {
                        lo[a] = v[a] < lo[a] ? v[a] : lo[a];
                        hi[a] = v[a] > hi[a] ? v[a] : hi[a];
                    }
                }
            printf("  mesh %-16s %8u triangles, bounds (%g, %g, %g) .. (%g, %g, %g)\n", r->name, r->count,
                   s.origin[0] + lo[0], s.origin[1] + lo[1], s.origin[2] + lo[2], s.origin[0] + hi[0],
                   s.origin[1] + hi[1], s.origin[2] + hi[2]);
        }
        sl_scene_free(&s);
        return 0;
    }
    struct sl_config c;
    enum sl_err e = sl_config_load_with(file, ov.v, ov.n, &c, &d);
    if (e)
        return cli_fail(e, &d);
    cli_note_left_out(&c);
    printf("%s: ok: %d scene(s), %d cell(s)\n", file, c.nscenes, sl_plan_count(&c));
    sl_config_write(&c, stdout);
    sl_config_free(&c);
    return 0;
}
