/*
 * bench_jobs.c — the `jobs` stage of `shadowlab bench` (bench.h): one study
 * as one process against `run --jobs 2`, the same cells either way.
 *
 * Both sides are whole runs with their files and stores (the workers of
 * --jobs cannot run without a store to merge), each in a fresh temporary
 * folder with no truth cache, so neither is helped by the other. The one
 * process is this binary run as a child (`run CONFIG -o DIR --no-cache -q`);
 * the --jobs side is sl_jobs_run itself, which forks its workers from this
 * binary too, so its merge is timed apart. CPU time is user+sys of the
 * children (RUSAGE_CHILDREN, every descendant once reaped) plus, for --jobs,
 * this process's own during the merge. Wall time on a loaded machine says
 * little: read it with the load average the bench prints at start and end.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>
#include "bench_stages.h"
#include "submit.h"
#include "util.h"

extern char **environ;

static double cpu_of(int who)
{
    struct rusage ru;
    getrusage(who, &ru);
    return (double)ru.ru_utime.tv_sec + (double)ru.ru_stime.tv_sec +
           1e-6 * ((double)ru.ru_utime.tv_usec + (double)ru.ru_stime.tv_usec);
}

static int rm_entry(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(p);
}

/* This binary as `run CONFIG -o DIR --no-cache -q [--gl B]`, its output to
 * /dev/null; its exit status, or -1 when it could not be started. */
static int run_child(const char *config, const char *dir, const char *gl)
{
    char *argv[12];
    int n = 0;
    argv[n++] = "shadowlab";
    argv[n++] = "run";
    argv[n++] = (char *)config;
    argv[n++] = "-o";
    argv[n++] = (char *)dir;
    argv[n++] = "--no-cache";
    argv[n++] = "-q";
    if (gl) {
        argv[n++] = "--gl";
        argv[n++] = (char *)gl;
    }
    argv[n] = NULL;
    return sl_bench_spawn_self(argv, environ, NULL);
}

enum sl_err sl_bench_jobs(const char *path, enum sl_gl_backend gl, FILE *out, struct sl_bench_result *res,
                          struct sl_diag *d)
{
    struct sl_config c;
    enum sl_err e = sl_config_load(path, &c, d);
    if (e)
        return e;
    sl_config_free(&c);   /* its values only from here on: the runs are child processes */
    /* under $TMPDIR as the store's private copies are (storefile.c), else /tmp */
    const char *tdir = getenv("TMPDIR");
    char tmp[512];
    snprintf(tmp, sizeof tmp, "%s/shadowlab-bench-jobs.XXXXXX", tdir && tdir[0] ? tdir : "/tmp");
    if (!mkdtemp(tmp))
        return sl_fail(d, SL_E_OUTPUT, tmp, 0, NULL, "cannot make a temporary folder: %s", strerror(errno));
    char one[600], par[600];
    snprintf(one, sizeof one, "%s/one", tmp);
    snprintf(par, sizeof par, "%s/jobs", tmp);
    const char *glname = gl ? sl_gl_backend_name(gl) : NULL;

    double t0 = sl_now(), c0 = cpu_of(RUSAGE_CHILDREN);
    int rc = run_child(path, one, glname);
    double one_wall = sl_now() - t0, one_cpu = cpu_of(RUSAGE_CHILDREN) - c0;
    if (rc) {
        e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "the one-process run failed (exit %d)", rc);
        goto out;
    }

    struct sl_jobs_opts jo = {.jobs = 2, .out_root = par, .cache = "", .gl = glname};
    struct sl_jobs_result r;
    t0 = sl_now();
    c0 = cpu_of(RUSAGE_CHILDREN);
    double s0 = cpu_of(RUSAGE_SELF);
    e = sl_jobs_run(&c, &jo, &r, d);
    double par_wall = sl_now() - t0;
    double par_cpu = cpu_of(RUSAGE_CHILDREN) - c0 + cpu_of(RUSAGE_SELF) - s0;
    if (e)
        goto out;
    if (r.merge.nmissing)
        e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "--jobs 2 left %d cell(s) missing", r.merge.nmissing);
    else {
        fprintf(out, "## One process against `run --jobs 2` (%s): %d cells\n\n", path, r.merge.total);
        fprintf(out, "| run | wall s | CPU s (user+sys) |\n|---|---:|---:|\n");
        fprintf(out, "| one process | %.1f | %.1f |\n| --jobs 2 | %.1f | %.1f |\n\n", one_wall, one_cpu, par_wall,
                par_cpu);
        fprintf(out, "--jobs 2: %d of %d view(s) started in both workers (their G-buffer and truth computed "
                     "twice); merge of %d cells %.2f s, %.2f s per 1,000 cells.\n\n",
                r.split_views, r.nviews, r.merge.copied, r.merge.seconds,
                r.merge.copied ? 1e3 * r.merge.seconds / r.merge.copied : 0.0);
        /* the target: two workers on two cores beat one process, with the
         * merge included; a ratio over 1 is a MISS, not an error */
        struct sl_bench_row *row = sl_bench_add_row(res, "jobs", "s", par_wall, one_wall, 1.0, SL_BENCH_AT_MOST);
        if (row) {
            snprintf(row->name, sizeof row->name, "%s, --jobs 2 over one process, wall", c.name);
            snprintf(row->note, sizeof row->note, "CPU %.1f s vs %.1f s", par_cpu, one_cpu);
        }
    }
    sl_jobs_result_free(&r);
out:
    nftw(tmp, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    return e;
}
