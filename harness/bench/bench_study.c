/*
 * bench_study.c — the bench's study stages (bench.h): Moderno 2011's study
 * without and with its files, Morais 2015's, each run as `shadowlab run
 * CONFIG --no-cache -D 'repetitions={warmup: 0, runs: 1}'` runs it (timed
 * once: the targets were set so), each in a process of its own.
 *
 * Why a process each: a study run after the bench's other stages in the
 * same process measured what those stages left behind. The Morais study
 * read 96.1 s of CPU after the layers stage against 77.2 s without it, the
 * same binary (glibc's malloc thresholds, raised by the stages' big
 * arrays, and the heap they leave). A child forked before this process
 * has made a thread, a GL context or a heap of its own starts where
 * `shadowlab run` starts: the libraries loaded, nothing else. Its rusage
 * is its own.
 */
#define _GNU_SOURCE   /* open_memstream, mkdtemp, nftw */
#include "bench_stages.h"
#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include "run.h"
#include "util.h"

#define TARGET_MODERNO_S     60.0
#define TARGET_MORAIS_S      300.0
/* issue 20: CPU time (user+sys), minor page faults, peak RSS; 0 = none */
#define TARGET_MODERNO_CPU_S 12.0
#define TARGET_MORAIS_CPU_S  90.0
#define TARGET_MORAIS_FAULTS 500000.0
#define TARGET_MORAIS_RSS_MIB 1024.0

static int rm_cb(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(p);
}

/* files: 1 runs the study as `shadowlab run CONFIG --no-cache -o TMP` (with
 * the -D above) does
 * (overlays and tables written, a store), into a temporary folder removed
 * after; 0 computes only. */
static enum sl_err bench_study(const char *path, const char *label, double target_s, const double tgt[3],
                               enum sl_gl_backend gl, int files, FILE *out, struct sl_bench_result *res,
                               struct sl_diag *d)
{
    struct sl_config c;
    /* the targets (issue 20) were set on the studies timed once, before the
     * default repetitions became {warmup: 1, runs: 3}: a study's wall and
     * CPU time grow with every timed repetition, so the bench keeps one */
    static const char *const once[] = {"repetitions={warmup: 0, runs: 1}"};
    enum sl_err e = sl_config_load_with(path, once, 1, &c, d);
    if (e)
        return e;
    if (gl)
        c.gl = gl;
    char tmp[] = "/tmp/shadowlab-bench-XXXXXX";
    if (files && !mkdtemp(tmp))
        return sl_fail(d, SL_E_OUTPUT, tmp, 0, NULL, "cannot make a temporary folder: %s", strerror(errno));
    struct sl_run_opts ro = {.out_root = files ? tmp : NULL, .table_out = NULL, .write_files = files,
                             .store = files ? NULL : "", .cache_dir = ""};
    struct sl_run_result rr;
    struct rusage ru0, ru1;
    char load0[64], load1[64];
    sl_bench_loadavg(load0, sizeof load0);
    getrusage(RUSAGE_SELF, &ru0);
    double t0 = sl_now(), c0 = sl_bench_cpu_s();
    e = sl_run(&c, &ro, &rr, d);
    sl_config_free(&c);   /* its packages: the run is done with them (names and counts are the config's own) */
    double wall = sl_now() - t0, cpu = sl_bench_cpu_s() - c0;
    getrusage(RUSAGE_SELF, &ru1);
    sl_bench_loadavg(load1, sizeof load1);
    if (files)
        nftw(tmp, rm_cb, 16, FTW_DEPTH | FTW_PHYS);
    if (e)
        return e;
    /* {CPU s, minor faults, peak RSS MiB} against tgt (0: no target, not a row) */
    const double got[3] = {cpu, (double)(ru1.ru_minflt - ru0.ru_minflt), ru1.ru_maxrss / 1024.0};
    static const char *const what[3][2] = {{"CPU (user+sys)", "s"}, {"minor page faults", "faults"},
                                           {"peak RSS of the process so far", "MiB"}};
    uint64_t viol = 0, rays = 0;
    double ms_method = 0, ms_cost = 0;
    for (int i = 0; i < rr.ncells; i++) {
        const struct sl_cell_key *k = &rr.cells[i].key, *p = i ? &rr.cells[i - 1].key : NULL;
        viol += rr.cells[i].violations;
        /* a view's truth is reported with each of its (contiguous) cells */
        if (!p || p->scene != k->scene || p->viewport != k->viewport || p->vp != k->vp)
            rays += rr.cells[i].truth_rays;
        ms_method += rr.cells[i].ms.method[SL_MED];
        ms_cost += rr.cells[i].ms.total[SL_MED];
    }
    int layers = 0;
    for (int l = 0; l < SL_LAYER_COUNT; l++)
        layers += rr.passes.layers[l];
    fprintf(out, "## Study %s (%s): %d cells, %.1f s wall, %.1f s CPU (user+sys), %.0f minor page faults, "
                 "peak RSS %.0f MiB\n\n", c.name, path, rr.ncells, wall, got[0], got[1], got[2]);
    if (files)
        fprintf(out, "Overlays and tables written (%d sheets by the writer's thread: %.1f s wall, %.1f s CPU, "
                     "counted in the run's), a store, no truth cache; load average %s before, %s after. ",
                rr.overlays_written, rr.ms_overlay_writer / 1e3, rr.ms_overlay_writer_cpu / 1e3, load0, load1);
    else
        fprintf(out, "No files, no store, no truth cache; load average %s before, %s after. ", load0, load1);
    fprintf(out, "%d threads. Scenes loaded %d (load %.0f ms, BVH %.0f ms), "
                 "G-buffers %d, truths traced %d (%llu rays), layer renders %d",
            c.threads, rr.passes.scenes, rr.ms_scene, rr.ms_bvh, rr.passes.gbuffers, rr.passes.truths_traced,
            (unsigned long long)rays, layers);
    for (int l = 0, first = 1; l < SL_LAYER_COUNT; l++)
        if (rr.passes.layers[l]) {
            fprintf(out, "%s%s %d", first ? " (" : ", ", sl_layer_names[l], rr.passes.layers[l]);
            first = 0;
        }
    fprintf(out, "%s, method runs %d (their per-pixel steps' medians summed: %.0f ms; the cells' stages, "
                 "map pass to rays: %.0f ms); exactness violations: %llu.\n\n",
            layers ? ")" : "", rr.passes.method_runs, ms_method, ms_cost, (unsigned long long)viol);
    struct sl_bench_row *row = sl_bench_add_row(res, "study", "s", wall, 0, target_s, SL_BENCH_AT_MOST);
    if (row)
        snprintf(row->name, sizeof row->name, "%s, %d cells, wall", label, rr.ncells);
    for (int k = 0; k < 3; k++)
        if (tgt[k] > 0 && (row = sl_bench_add_row(res, "study", what[k][1], got[k], 0, tgt[k], SL_BENCH_AT_MOST)))
            snprintf(row->name, sizeof row->name, "%s, %s", label, what[k][0]);
    /* not a speed, but a fast layer that loses exactness is no gain */
    row = sl_bench_add_row(res, "study", "pixels", (double)viol, 0, 0, SL_BENCH_AT_MOST);
    if (row)
        snprintf(row->name, sizeof row->name, "%s, exactness violations", label);
    sl_run_result_free(&rr);
    return SL_OK;
}


/* One study's arguments. */
struct study {
    const char *path, *label;
    double target_s, tgt[3];
    int files;
};

/* The threads of this process (/proc/self/task), 0 when unknown. */
static int threads_now(void)
{
    DIR *dir = opendir("/proc/self/task");
    if (!dir)
        return 0;
    int n = 0;
    for (struct dirent *e; (e = readdir(dir));)
        n += e->d_name[0] != '.';
    closedir(dir);
    return n;
}

/* What a child sends back through its file: its error, its message, its
 * rows, then its Markdown. */
struct child_out {
    enum sl_err e;
    struct sl_diag d;
    struct sl_bench_result rows;
    size_t len;
};

/* s in a child forked now, its section to out and its rows to res. In
 * this process when it has threads already (a fork would copy their locks
 * and not them), saying so. */
static enum sl_err study_in_child(const struct study *s, enum sl_gl_backend gl, FILE *out,
                                  struct sl_bench_result *res, struct sl_diag *d)
{
    int nthreads = threads_now();
    FILE *tmp = nthreads == 1 ? tmpfile() : NULL;
    pid_t pid = tmp ? fork() : -1;
    if (pid < 0) {
        if (tmp)
            fclose(tmp);
        fprintf(out, "(This study ran in the bench's own process: %s.)\n\n",
                nthreads != 1 ? "it had threads already" : "no child process could be made");
        return bench_study(s->path, s->label, s->target_s, s->tgt, gl, s->files, out, res, d);
    }
    if (pid == 0) {
        /* the child: the study, then everything back through tmp */
        struct child_out *c = calloc(1, sizeof *c);
        char *md = NULL;
        size_t len = 0;
        FILE *mem = c ? open_memstream(&md, &len) : NULL;
        if (!mem)
            _exit(3);
        c->e = bench_study(s->path, s->label, s->target_s, s->tgt, gl, s->files, mem, &c->rows, &c->d);
        fclose(mem);
        c->len = len;
        int ok = fwrite(c, sizeof *c, 1, tmp) == 1 && fwrite(md, 1, len, tmp) == len && fflush(tmp) == 0;
        _exit(ok ? 0 : 3);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    enum sl_err e = SL_OK;
    struct child_out *c = calloc(1, sizeof *c);
    char *md = NULL;
    rewind(tmp);
    if (!c)
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "bench study");
    else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || fread(c, sizeof *c, 1, tmp) != 1 ||
             !(md = malloc(c->len + 1)) || fread(md, 1, c->len, tmp) != c->len)
        e = sl_fail(d, SL_E_IO, s->path, 0, NULL, "the study's process %s %d and gave back no result",
                    WIFSIGNALED(status) ? "was killed by signal" : "ended with status",
                    WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status));
    else if (c->e) {
        *d = c->d;
        e = c->e;
    } else {
        fwrite(md, 1, c->len, out);
        for (int i = 0; i < c->rows.nrows; i++) {
            struct sl_bench_row *row = sl_bench_add_row(res, "study", "", 0, 0, 0, SL_BENCH_AT_MOST);
            if (row)
                *row = c->rows.rows[i];
        }
    }
    fclose(tmp);
    free(md);
    free(c);
    return e;
}

enum sl_err sl_bench_studies(const struct sl_bench_opts *o, unsigned stages, FILE *out,
                             struct sl_bench_result *res, struct sl_diag *d)
{
    const char *moderno = o->moderno ? o->moderno : "configs/moderno-2011.yaml";
    const char *morais = o->morais ? o->morais : "configs/morais-2015.yaml";
    /* issue 20's Moderno target is the study as run, overlays on: the same
     * again writing its files (the sheets by the run's writer thread) */
    const struct study all[3] = {
        {moderno, "moderno-2011", TARGET_MODERNO_S, {TARGET_MODERNO_CPU_S, 0, 0}, 0},
        {moderno, "moderno-2011 overlays on", TARGET_MODERNO_S, {TARGET_MODERNO_CPU_S, 0, 0}, 1},
        {morais, "morais-2015", TARGET_MORAIS_S, {TARGET_MORAIS_CPU_S, TARGET_MORAIS_FAULTS, TARGET_MORAIS_RSS_MIB},
         0},
    };
    enum sl_err e = SL_OK;
    for (int i = 0; i < 3 && !e; i++)
        if (stages & (i < 2 ? SL_BENCH_STAGE(MODERNO) : SL_BENCH_STAGE(MORAIS)))
            e = study_in_child(&all[i], o->gl, out, res, d);
    return e;
}

/* ---- timing: what the default repetitions cost -------------------------- */

/* One run of the study in a child process: wall and CPU (user+sys) seconds,
 * the cells, and the run's timing line (reps.h, sl_reps_describe). */
struct timing_out {
    enum sl_err e;
    struct sl_diag d;
    double wall, cpu;
    int ncells;
    char line[1024];
};

static void timing_run(const char *path, const char *override, enum sl_gl_backend gl, struct timing_out *t)
{
    struct sl_config c;
    const char *const ov[1] = {override};
    memset(t, 0, sizeof *t);
    if ((t->e = sl_config_load_with(path, ov, override ? 1 : 0, &c, &t->d)))
        return;
    if (gl)
        c.gl = gl;
    struct sl_run_opts ro = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result rr;
    double t0 = sl_now(), c0 = sl_bench_cpu_s();
    t->e = sl_run(&c, &ro, &rr, &t->d);
    t->wall = sl_now() - t0;
    t->cpu = sl_bench_cpu_s() - c0;
    if (!t->e) {
        t->ncells = rr.ncells;
        sl_reps_describe(&rr.reps, rr.ms_total, t->line, sizeof t->line);
    }
    sl_config_free(&c);
    sl_run_result_free(&rr);
}

/* timing_run in a child forked now (a study after another in one process
 * measures what the first left behind: see the top of this file). */
static void timing_in_child(const char *path, const char *override, enum sl_gl_backend gl, struct timing_out *t)
{
    FILE *tmp = threads_now() == 1 ? tmpfile() : NULL;
    pid_t pid = tmp ? fork() : -1;
    if (pid < 0) {
        if (tmp)
            fclose(tmp);
        timing_run(path, override, gl, t);
        return;
    }
    if (pid == 0) {
        struct timing_out *c = calloc(1, sizeof *c);
        if (!c)
            _exit(3);
        timing_run(path, override, gl, c);
        _exit(fwrite(c, sizeof *c, 1, tmp) == 1 && fflush(tmp) == 0 ? 0 : 3);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    rewind(tmp);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || fread(t, sizeof *t, 1, tmp) != 1) {
        memset(t, 0, sizeof *t);
        t->e = sl_fail(&t->d, SL_E_IO, path, 0, NULL, "the study's process gave back no result");
    }
    fclose(tmp);
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* {min, median, max} of v[0..n) (sorted in place). */
static void min_med_max(double *v, int n, double out[3])
{
    qsort(v, (size_t)n, sizeof v[0], cmp_d);
    out[0] = v[0];
    out[1] = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    out[2] = v[n - 1];
}

enum sl_err sl_bench_timing(const char *path, enum sl_gl_backend gl, int pairs, FILE *out,
                            struct sl_bench_result *res, struct sl_diag *d)
{
    /* the study computed once (every stage timed by its one real run)
     * against the study as its config runs it (the default repetitions:
     * reps.h), alternating, the once-run first in odd pairs, so drift of a
     * shared machine hits both sides alike */
    static const char *const off = "repetitions={mode: off}";
    if (pairs < 1)
        pairs = 3;
    if (pairs > 16)
        pairs = 16;
    double cpu[2][16], wall[2][16];
    char line[1024] = "", load0[64], load1[64];
    int ncells = 0;
    sl_bench_loadavg(load0, sizeof load0);
    for (int p = 0; p < pairs; p++)
        for (int k = 0; k < 2; k++) {
            const int side = (p % 2) ? 1 - k : k;   /* 0: once, 1: default */
            struct timing_out t;
            timing_in_child(path, side == 0 ? off : NULL, gl, &t);
            if (t.e) {
                *d = t.d;
                return t.e;
            }
            cpu[side][p] = t.cpu;
            wall[side][p] = t.wall;
            ncells = t.ncells;
            if (side == 1)
                snprintf(line, sizeof line, "%s", t.line);
        }
    sl_bench_loadavg(load1, sizeof load1);
    double c0[3], c1[3], w0[3], w1[3];
    min_med_max(cpu[0], pairs, c0);
    min_med_max(cpu[1], pairs, c1);
    min_med_max(wall[0], pairs, w0);
    min_med_max(wall[1], pairs, w1);
    fprintf(out, "## Timing: what the default repetitions cost (%s, %d cells)\n\n", path, ncells);
    fprintf(out, "The study computed once (`-D 'repetitions={mode: off}'`) against the study as its config "
                 "runs it (the default repetitions, reps.h), %d pairs alternating, each run a process of its "
                 "own, no files, no store, no truth cache; load average %s before, %s after.\n\n",
            pairs, load0, load1);
    fprintf(out, "| run | CPU (user+sys) min | median | max | wall min | median | max |\n");
    fprintf(out, "|---|---:|---:|---:|---:|---:|---:|\n");
    fprintf(out, "| once (mode: off) | %.1f s | %.1f s | %.1f s | %.1f s | %.1f s | %.1f s |\n", c0[0], c0[1], c0[2],
            w0[0], w0[1], w0[2]);
    fprintf(out, "| default | %.1f s | %.1f s | %.1f s | %.1f s | %.1f s | %.1f s |\n\n", c1[0], c1[1], c1[2], w1[0],
            w1[1], w1[2]);
    fprintf(out, "Default over once, CPU: %.2fx of the medians, %.2fx of the minima. The default run's %s.\n\n",
            c1[1] / c0[1], c1[0] / c0[0], line);
    struct sl_bench_row *row =
        sl_bench_add_row(res, "timing", "s", c1[1], c0[1], SL_BENCH_TARGET_TIMING_RATIO, SL_BENCH_AT_MOST);
    if (row)
        snprintf(row->name, sizeof row->name, "study with default timing / once, CPU median (n %d)", pairs);
    return SL_OK;
}
