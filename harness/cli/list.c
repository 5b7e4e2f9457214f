/*
 * list.c — `shadowlab list methods|scenes`: what a config can name, and
 * where each scene file was found.
 */
#define _GNU_SOURCE   /* getopt_long */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "method.h"
#include "scenefile.h"

int cli_list(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {0, 0, 0, 0}};
    const struct cli_parser p = {"list", "", cli_usage_list, lo};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;)
        return cli_opt_exit(c);
    argc -= optind - 1;
    argv += optind - 1;
    if (argc == 2 && strcmp(argv[1], "methods") == 0) {
        for (int i = 0; i < sl_method_count(); i++)
            printf("%-12s %s\n", sl_method_at(i)->name, sl_method_at(i)->summary);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "scenes") == 0) {
        static char names[256][64], descr[256][160], paths[256][1024];
        static const char *origin[256];
        int n = sl_scene_list_where(names, descr, paths, origin, 256);
        for (int i = 0; i < n; i++)
            printf("%-14s %-50s [%s: %s]\n", names[i], descr[i], origin[i], paths[i]);
        if (n == 0) {
            char dirs[16][1024];
            const char *o[16];
            int nd = sl_scene_dirs(NULL, dirs, o, 16);
            fprintf(stderr, "shadowlab: no scene files in");
            for (int i = 0; i < nd; i++)
                fprintf(stderr, "%s %s (%s)", i ? "," : "", dirs[i], o[i]);
            fputc('\n', stderr);
        }
        return 0;
    }
    return cli_usage_error("list: methods or scenes", cli_usage_list);
}
