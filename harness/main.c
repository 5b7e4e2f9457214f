/*
 * main.c — the command line. The only place that prints errors and exits:
 * 0 success, 1 a check failed, 2 bad input or usage (and any other failure
 * that leaves no result).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "bench.h"
#include "config.h"
#include "method.h"
#include "provenance.h"
#include "run.h"
#include "scene.h"
#include "util.h"

static const char usage[] =
    "usage: shadowlab <command> ...\n"
    "  run CONFIG [--out DIR]     run an experiment; results under DIR/<name>/ (default results/)\n"
    "  validate FILE              check a config without touching GL or Embree\n"
    "  bench [CONFIG] [--reps N]  truth pass vs a plain Embree loop, and stage times\n"
    "  list methods|scenes        what can be named in a config\n"
    "  version                    print the git SHA this binary was built from\n";

static int fail(enum sl_err e, const struct sl_diag *d)
{
    char line[1200];
    sl_diag_format(d, e, line, sizeof line);
    fprintf(stderr, "shadowlab: %s\n", line);
    return 2;
}

static int usage_error(const char *msg)
{
    fprintf(stderr, "shadowlab: %s\n%s", msg, usage);
    return 2;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return usage_error("missing command");
    const char *cmd = argv[1];
    struct sl_diag d;
    memset(&d, 0, sizeof d);

    if (strcmp(cmd, "run") == 0) {
        const char *cfg = NULL, *out = NULL;
        for (int i = 2; i < argc; i++) {
            if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
                out = argv[++i];
            else if (argv[i][0] == '-')
                return usage_error("run: unknown option");
            else if (!cfg)
                cfg = argv[i];
            else
                return usage_error("run: one config at a time");
        }
        if (!cfg)
            return usage_error("run: missing CONFIG");
        struct sl_config c;
        enum sl_err e = sl_config_load(cfg, &c, &d);
        if (e)
            return fail(e, &d);
        struct sl_run_opts o = {.out_root = out, .table_out = stdout, .write_files = 1};
        struct sl_run_result r;
        e = sl_run(&c, &o, &r, &d);
        sl_run_result_free(&r);
        return e ? fail(e, &d) : 0;
    }
    if (strcmp(cmd, "validate") == 0) {
        if (argc != 3)
            return usage_error("validate: one FILE");
        struct sl_config c;
        enum sl_err e = sl_config_load(argv[2], &c, &d);
        if (e)
            return fail(e, &d);
        printf("%s: ok (%d viewpoint(s), %d viewport(s), %d map size(s), %d method(s))\n", argv[2],
               c.nviewpoints, c.nviewports, c.nmaps, c.nmethods);
        sl_config_write(&c, stdout);
        return 0;
    }
    if (strcmp(cmd, "bench") == 0) {
        struct sl_bench_opts o = {.config = NULL, .reps = 0, .out = stdout};
        for (int i = 2; i < argc; i++) {
            if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) {
                o.reps = atoi(argv[++i]);
                if (o.reps < 1 || o.reps > 1000)
                    return usage_error("bench: --reps must be 1..1000");
            } else if (argv[i][0] == '-') {
                return usage_error("bench: unknown option");
            } else {
                o.config = argv[i];
            }
        }
        enum sl_err e = sl_bench(&o, &d);
        return e ? fail(e, &d) : 0;
    }
    if (strcmp(cmd, "list") == 0) {
        if (argc == 3 && strcmp(argv[2], "methods") == 0) {
            for (int i = 0; i < sl_method_count(); i++)
                printf("%-12s %s\n", sl_method_at(i)->name, sl_method_at(i)->summary);
            return 0;
        }
        if (argc == 3 && strcmp(argv[2], "scenes") == 0) {
            for (int i = 0; i < sl_scene_count(); i++)
                printf("%-12s %s\n", sl_scene_name(i), sl_scene_summary(i));
            return 0;
        }
        return usage_error("list: methods or scenes");
    }
    if (strcmp(cmd, "version") == 0) {
        printf("shadowlab %s\n", sl_git_sha());
        return 0;
    }
    if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
        fputs(usage, stdout);
        return 0;
    }
    return usage_error("unknown command");
}
