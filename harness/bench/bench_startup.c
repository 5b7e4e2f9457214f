/*
 * bench_startup.c — the `startup` stage of `shadowlab bench` (bench.h):
 * how long a verb that renders nothing takes to start and finish, against
 * the same binary with the libraries it used to link at start preloaded.
 *
 * OpenImageIO, libOSMesa, libEGL and Embree are loaded on first use
 * (image.c, render/glload.h, truth/rtload.h); before that change they were
 * linked, so every process loaded them. The plain counterpart is this very
 * binary with those libraries in LD_PRELOAD (SL_EAGER_LIBS, their files as
 * CMake found them), so both sides run the same code and differ only in
 * what the dynamic loader maps at start. Each repetition runs the two sides
 * one after the other, the order alternating. Per child: wall time, CPU
 * time (user+sys) and peak RSS from wait4's rusage.
 *
 * Peak RSS: Linux carries the spawning process's high-water mark into the
 * child's at exec (posix_spawn shares the parent's memory until then), so a
 * child's ru_maxrss is never below the bench's own RSS at that moment.
 * bench.c therefore runs this stage first, before it opens a GL context or
 * loads anything, and the table states that floor.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include "bench_stages.h"
#include "util.h"

#ifndef SL_EAGER_LIBS
#define SL_EAGER_LIBS ""
#endif

#define TARGET_STARTUP_MS 50.0   /* `validate` of the default config, median wall */

extern char **environ;

struct sample { double wall_ms, cpu_ms, rss_mib; };

/* argv run as a child of this binary, output discarded; preload = NULL for
 * the binary as it is. -1 when it did not run or exit 0. */
static int spawn_one(char *const *argv, const char *preload, struct sample *s)
{
    size_t n = 0;
    while (environ[n])
        n++;
    char **env = calloc(n + 3, sizeof *env);
    if (!env)
        return -1;
    size_t k = 0;
    const char *asan = "";
    for (size_t i = 0; i < n; i++)
        if (strncmp(environ[i], "ASAN_OPTIONS=", 13) == 0)
            asan = environ[i] + 13;
        else if (strncmp(environ[i], "LD_PRELOAD=", 11) != 0)
            env[k++] = environ[i];
    char pre[1200], asan_opts[600];
    if (preload) {
        snprintf(pre, sizeof pre, "LD_PRELOAD=%s", preload);
        env[k++] = pre;
    }
    /* a sanitized build refuses libraries loaded before its runtime unless
     * told the order does not matter (only the eager side preloads) */
    snprintf(asan_opts, sizeof asan_opts, "ASAN_OPTIONS=%s%s%s", asan, asan[0] && preload ? ":" : "",
             preload ? "verify_asan_link_order=0" : "");
    if (asan[0] || preload)
        env[k++] = asan_opts;
    env[k] = NULL;
    struct rusage ru;
    double t0 = sl_now();
    int rc = sl_bench_spawn_self(argv, env, &ru);
    s->wall_ms = 1e3 * (sl_now() - t0);
    free(env);
    s->cpu_ms = 1e3 * ((double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                       1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec));
    s->rss_mib = ru.ru_maxrss / 1024.0;
    return rc == 0 ? 0 : -1;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* min and median of field f over n samples */
static void stats(const struct sample *s, int n, size_t f, double *mn, double *med)
{
    double v[64];
    for (int i = 0; i < n; i++)
        memcpy(&v[i], (const char *)&s[i] + f, sizeof v[i]);
    qsort(v, (size_t)n, sizeof v[0], cmp_d);
    *mn = v[0];
    *med = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

enum sl_err sl_bench_startup(const char *config, int reps, FILE *out, struct sl_bench_result *res,
                             struct sl_diag *d)
{
    if (reps > 64)
        reps = 64;
    char *version[] = {"shadowlab", "version", NULL};
    char *validate[] = {"shadowlab", "validate", (char *)config, NULL};
    char *help[] = {"shadowlab", "help", "run", NULL};
    struct { const char *name; char *const *argv; } verbs[] = {
        {"version", version}, {"validate", validate}, {"help run", help},
    };
    if (access(config, R_OK) != 0)
        return sl_fail(d, SL_E_IO, config, 0, NULL, "cannot read the config `validate` is timed on");
    const char *eager = SL_EAGER_LIBS;
    struct rusage self;
    getrusage(RUSAGE_SELF, &self);
    fprintf(out, "## Start-up of the verbs that render nothing\n\n");
    fprintf(out, "Lazy: this binary (OpenImageIO, OSMesa, EGL and Embree loaded on first use). Eager: the same "
                 "binary with those libraries preloaded (`LD_PRELOAD=%s`), as when they were linked. %d "
                 "repetitions each, the two sides alternating. `validate` reads %s. Wall and CPU time "
                 "(user+sys) and peak RSS per process (wait4; never below the bench's own %.0f MiB when it "
                 "spawns them, which Linux carries into a child at exec).\n\n",
            eager, reps, config, self.ru_maxrss / 1024.0);
    fprintf(out, "| verb | lazy wall min | lazy wall median | lazy CPU median | lazy RSS | eager wall min | "
                 "eager wall median | eager CPU median | eager RSS |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (size_t v = 0; v < sizeof verbs / sizeof verbs[0]; v++) {
        struct sample lazy[64], full[64];
        /* one untimed run of each side warms the page cache */
        struct sample warm;
        if (spawn_one(verbs[v].argv, NULL, &warm) || (eager[0] && spawn_one(verbs[v].argv, eager, &warm)))
            return sl_fail(d, SL_E_INTERNAL, config, 0, NULL, "`shadowlab %s` failed in the bench", verbs[v].name);
        for (int r = 0; r < reps; r++) {
            int first_lazy = (r & 1) == 0;
            for (int side = 0; side < 2; side++) {
                int is_lazy = (side == 0) == first_lazy;
                if (!is_lazy && !eager[0])
                    continue;   /* nothing to preload: the eager side is the lazy one (below) */
                if (spawn_one(verbs[v].argv, is_lazy ? NULL : eager, is_lazy ? &lazy[r] : &full[r]))
                    return sl_fail(d, SL_E_INTERNAL, config, 0, NULL, "`shadowlab %s` failed in the bench",
                                   verbs[v].name);
            }
        }
        if (!eager[0])
            memcpy(full, lazy, sizeof lazy[0] * (size_t)reps);
        double lw, lwm, lc, lcm, lr, lrm, fw, fwm, fc, fcm, fr, frm;
        stats(lazy, reps, offsetof(struct sample, wall_ms), &lw, &lwm);
        stats(lazy, reps, offsetof(struct sample, cpu_ms), &lc, &lcm);
        stats(lazy, reps, offsetof(struct sample, rss_mib), &lr, &lrm);
        stats(full, reps, offsetof(struct sample, wall_ms), &fw, &fwm);
        stats(full, reps, offsetof(struct sample, cpu_ms), &fc, &fcm);
        stats(full, reps, offsetof(struct sample, rss_mib), &fr, &frm);
        fprintf(out, "| %s | %.1f ms | %.1f ms | %.1f ms | %.0f MiB | %.1f ms | %.1f ms | %.1f ms | %.0f MiB |\n",
                verbs[v].name, lw, lwm, lcm, lrm, fw, fwm, fcm, frm);
        if (v == 1) {   /* the row with a target: validate, the verb the issue names */
            struct sl_bench_row *row =
                sl_bench_add_row(res, "startup", "ms", lwm, 0, TARGET_STARTUP_MS, SL_BENCH_AT_MOST);
            if (row) {
                snprintf(row->name, sizeof row->name, "validate, median wall (lazy loading)");
                snprintf(row->note, sizeof row->note, "eager %.1f ms; CPU %.1f vs %.1f ms; RSS %.0f vs %.0f MiB",
                         fwm, lcm, fcm, lrm, frm);
            }
        }
    }
    fprintf(out, "\n");
    return SL_OK;
}
