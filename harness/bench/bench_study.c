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
    double ms_method = 0;
    for (int i = 0; i < rr.ncells; i++) {
        const struct sl_cell_key *k = &rr.cells[i].key, *p = i ? &rr.cells[i - 1].key : NULL;
        viol += rr.cells[i].violations;
        /* a view's truth is reported with each of its (contiguous) cells */
        if (!p || p->scene != k->scene || p->viewport != k->viewport || p->vp != k->vp)
            rays += rr.cells[i].truth_rays;
        ms_method += rr.cells[i].ms.method[SL_MED];
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
    fprintf(out, "%s, method runs %d (their median times summed: %.0f ms); exactness violations: %llu.\n\n",
            layers ? ")" : "", rr.passes.method_runs, ms_method, (unsigned long long)viol);
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
