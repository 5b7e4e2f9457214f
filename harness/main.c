/*
 * main.c — the program's entry: the environment a verb runs in, then the
 * verb from the table (cli/usage.c). The verbs, their options, their help
 * texts and the printing of errors are in cli/ (cli/cli.h says what they
 * share); the exit codes: 0 success, 1 a check failed, 2 bad input or
 * usage, 3 a system failure.
 */
#define _GNU_SOURCE   /* setenv */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli/cli.h"

/* OpenMP's idle threads spin between parallel regions by default (libgomp:
 * for up to GOMP_SPINCOUNT turns), burning a core while the main thread
 * renders or scores alone. On a shared machine that costs: the Morais
 * study's last 64 cells, alternating, at load 5-7 on this 2-core VM, took
 * 24.1-27.7 s CPU spinning and 16.5-19.0 s waiting passively, and less wall
 * time too (README, Performance). libgomp reads its policy once, as it loads,
 * before main: so a rendering verb whose environment sets neither
 * OMP_WAIT_POLICY nor GOMP_SPINCOUNT runs itself again with
 * OMP_WAIT_POLICY=passive. Either variable set keeps the user's choice. */
static void wait_passively(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return;
    if (setenv("OMP_WAIT_POLICY", "passive", 1))
        return;
    execv("/proc/self/exe", argv);
    unsetenv("OMP_WAIT_POLICY");   /* no /proc: go on as the runtime already is */
}

int main(int argc, char **argv)
{
    const struct cli_verb *v = argc >= 2 ? cli_verb_find(argv[1]) : NULL;
    if (v && v->passive_omp)
        wait_passively(argv);
    if (argc < 2)
        return cli_usage_error("missing command", cli_usage());
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-V") || !strcmp(cmd, "--version"))
        return cli_version(argc - 1, argv + 1);   /* the verb `version` (cli/version.c) */
    int help = !strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help");
    if (help && argc == 2) {
        fputs(cli_usage(), stdout);
        return 0;
    }
    if (help && !strcmp(argv[2], "--man")) {
        cli_man(stdout);
        return 0;
    }
    if (help && !strcmp(argv[2], "--config"))
        return cli_config_reference(stdout);
    if (help && !strcmp(argv[2], "--bash-completion")) {
        cli_completion(stdout);
        return 0;
    }
    if (help)
        v = cli_verb_find(argv[2]);   /* help VERB = VERB --help */
    if (!v) {
        fprintf(stderr, "shadowlab: unknown command '%s'\n%s", help ? argv[2] : cmd, cli_usage());
        return 2;
    }
    if (help) {
        fputs(v->usage, stdout);
        return 0;
    }
    /* the verb sees itself as argv[0], as getopt_long expects */
    return v->fn(argc - 1, argv + 1);
}
