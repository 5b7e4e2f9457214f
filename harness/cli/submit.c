/*
 * submit.c — `shadowlab submit`: the sweep as a Slurm job array plus a
 * merge job. Its options are parsed by submit.c of the driver (they are
 * written into the job scripts); this file prints what was written and
 * submitted.
 */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "config.h"
#include "submit.h"

int cli_submit(int argc, char **argv)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_submit_opts o;
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(cli_usage_submit, stdout);
            return 0;
        }
    enum sl_err e = sl_submit_parse(argc, argv, &o, &d);
    if (e) {
        char line[1200];
        sl_diag_format(&d, e, line, sizeof line);
        return cli_usage_error(line, cli_usage_submit);
    }
    struct sl_config c;
    if ((e = sl_config_load(o.config, &c, &d)))
        return cli_fail(e, &d);
    static struct sl_submit_result r;
    e = sl_submit(&c, &o, &r, &d);
    sl_config_free(&c);
    if (e)
        return cli_fail(e, &d);
    printf("%d task(s) over %d cell(s):", r.ntasks, r.total);
    for (int i = 0; i < r.ntasks; i++)
        printf(" %d:%d", r.bounds[i], r.bounds[i + 1]);
    printf("\n%d of %d view(s) start in two tasks (their G-buffer and truth are computed twice)\n",
           r.split_views, r.nviews);
    printf("array script: %s\nmerge script: %s\nmerged store: %s\n", r.array_script, r.merge_script, r.merged);
    if (!o.dry_run)
        printf("array job %s, merge job %s (afterok:%s)\n", r.array_job, r.merge_job, r.array_job);
    return 0;
}
