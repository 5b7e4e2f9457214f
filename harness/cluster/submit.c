/*
 * submit.c — see submit.h.
 */
#define _GNU_SOURCE
#include "submit.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "outputs.h"
#include "plan.h"
#include "storefile.h"
#include "util.h"

/* ---- merge with the sweep ---- */

static int file_exists(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0 && S_ISREG(sb.st_mode);
}

/* The sweep the shards computed: the config file the runs were given when it
 * is still there unchanged (its hash matches, and scene paths relative to it
 * resolve), else the filled-in config text the runs carry, loaded from a
 * temporary file beside the merged store. */
static enum sl_err sweep_config(const struct sl_merge *m, const char *out_dir, struct sl_config *c,
                                struct sl_diag *d)
{
    unsigned long long want = strtoull(sl_merge_config_hash(m), NULL, 16);
    const char *path = sl_merge_config_path(m);
    struct sl_diag ignore;
    if (path && file_exists(path) && sl_config_load(path, c, &ignore) == SL_OK) {
        if (c->hash == want)
            return SL_OK;
        sl_config_free(c);   /* another file now: the runs' own text below */
    }
    const char *text = sl_merge_config_text(m);
    if (!text)
        return sl_fail(d, SL_E_IO, NULL, 0, NULL, "the shards' runs carry no config: cannot name missing cells");
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%s/.merge-config-%ld.yaml", out_dir, (long)getpid());
    unlink(tmp);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f) {
        if (fd >= 0)
            close(fd);
        return sl_fail(d, SL_E_OUTPUT, tmp, 0, NULL, "cannot write: %s", strerror(errno));
    }
    fputs(text, f);
    fclose(f);
    enum sl_err e = sl_config_load(tmp, c, d);
    unlink(tmp);
    c->hash = want;   /* the cells are keyed by the hash of the file the runs read */
    return e;
}

/* A store file no one else writes (its writer's lock held) and its
 * SQLite companions, removed. */
static void drop_store_file(const char *p)
{
    static const char *const tails[] = {"", "-wal", "-shm", "-journal", ".lock"};
    for (size_t i = 0; i < sizeof tails / sizeof tails[0]; i++) {
        char f[1400];
        snprintf(f, sizeof f, "%s%s", p, tails[i]);
        unlink(f);
    }
}

/* Not there at all (its cells are then reported missing); anything else
 * that is there is probed, and refused unless it is a sound store. */
static int absent(const char *p)
{
    struct stat sb;
    return lstat(p, &sb) != 0 && errno == ENOENT;
}

static enum sl_err shards_merge(const char *const *shards, int n, const char *out, unsigned flags,
                                struct sl_store *held, const int64_t *replace, int nreplace,
                                struct sl_shards_result *r, struct sl_diag *d);

enum sl_err sl_shards_merge(const char *const *shards, int n, const char *out, unsigned flags,
                            struct sl_shards_result *r, struct sl_diag *d)
{
    return shards_merge(shards, n, out, flags, NULL, NULL, 0, r, d);
}

/* held: the merged store, open and locked by the caller (run --jobs), else
 * NULL; replace: its cells a shard's copy replaces (sl_merge_replace). */
static enum sl_err shards_merge(const char *const *shards, int n, const char *out, unsigned flags,
                                struct sl_store *held, const int64_t *replace, int nreplace,
                                struct sl_shards_result *r, struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    r->nshards = n;
    r->shard = sl_calloc((size_t)n + 1, sizeof *r->shard);
    r->absent = sl_calloc((size_t)n + 1, sizeof *r->absent);
    if (!r->shard || !r->absent)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "merge result");
    /* every shard there is checked before the merged store is touched: a
     * shard of another config leaves nothing half merged */
    const char *first = NULL, *first_prov = NULL;
    char hash[24] = "", prov[256] = "";
    for (int i = 0; i < n; i++) {
        if (absent(shards[i]))
            continue;
        struct sl_merge_shard p;
        enum sl_err e = sl_merge_probe(shards[i], &p, d);
        if (e)
            return e;
        if (!p.config_hash[0])
            continue;
        if (!first) {
            first = shards[i];
            snprintf(hash, sizeof hash, "%s", p.config_hash);
        } else if (strcmp(hash, p.config_hash) != 0) {
            return sl_fail(d, SL_E_USAGE, shards[i], 0, NULL,
                           "holds config hash %s (study '%s'), but %s holds %s: not a shard of the same sweep",
                           p.config_hash, p.study, first, hash);
        }
        /* numbers of two builds, GL renderers or ISAs are not one sweep
         * unless asked: the merged runs keep each provenance either way */
        if (!(flags & SL_MERGE_ALLOW_MIXED) && p.other[0])
            return sl_fail(d, SL_E_USAGE, shards[i], 0, NULL, "holds cells of %s and of %s: merge with "
                           "--allow-mixed to keep both", p.provenance, p.other);
        if (!(flags & SL_MERGE_ALLOW_MIXED) && p.provenance[0] && first_prov && strcmp(prov, p.provenance) != 0)
            return sl_fail(d, SL_E_USAGE, shards[i], 0, NULL, "its cells are of %s, but %s's of %s: merge with "
                           "--allow-mixed to keep both", p.provenance, first_prov, prov);
        if (p.provenance[0] && !first_prov) {
            first_prov = shards[i];
            snprintf(prov, sizeof prov, "%s", p.provenance);
        }
    }
    char dir[1200];
    sl_path_dir(out, dir, sizeof dir);
    enum sl_err e = sl_mkdirs(dir, d);
    if (e)
        return e;
    /* Atomic: `merge` (no held store) builds the merged store as a new file
     * beside the target, "<target>.merging" (the target copied in first,
     * when there is one), and renames it over the target only once it is
     * whole and sealed; a merge killed at any moment leaves the old target
     * (or none) and a stale .merging file the next merge replaces. The
     * target's writer lock is held throughout, so no run writes the target
     * meanwhile (and no second merge uses the same .merging file). A run's
     * --jobs merge (held) writes into its own locked store, each shard in
     * one transaction: the run itself is what --resume completes. */
    int tfd = -1;
    char tlock[4200] = "", work[1300] = "";
    const char *into = out;
    if (!held) {
        struct stat sb;
        if ((e = sl_storefile_lock(out, &tfd, tlock, sizeof tlock, d)))
            return e;
        snprintf(work, sizeof work, "%s.merging", out);
        drop_store_file(work);   /* a killed merge's, never renamed */
        sl_storefile_fault_point("merge");
        if (stat(out, &sb) == 0 && sb.st_size > 0)
            e = sl_store_copy(out, work, d);
        into = work;
        sl_storefile_fault_point("merge");
    }
    struct sl_merge *m = NULL;
    if (!e && (e = sl_merge_open_held(held, into, (flags & SL_MERGE_APPEND) != 0, &m, d)))
        goto done;
    if (!e && (e = sl_merge_replace(m, replace, nreplace, d)))
        goto done;
    double t0 = sl_now();
    for (int i = 0; i < n && !e; i++) {
        if (absent(shards[i])) {
            r->absent[i] = 1;
            continue;
        }
        sl_storefile_fault_point("merge");
        e = sl_merge_add(m, shards[i], &r->shard[i], d);
        sl_storefile_fault_point("merge");
        r->copied += r->shard[i].cells;
        r->duplicates += r->shard[i].duplicates;
    }
    r->seconds = sl_now() - t0;
    if (!e && !sl_merge_config_hash(m))
        e = sl_fail(d, SL_E_USAGE, n ? shards[0] : out, 0, NULL, "no shard holds a run: nothing to merge");
    if (!e)
        e = sl_merge_seal(m, d);   /* the merged .db alone holds it, synced */
    sl_storefile_fault_point("merge");
    if (!e && !held) {
        if (rename(work, out) != 0)
            e = sl_fail(d, SL_E_OUTPUT, out, 0, NULL, "cannot rename the merged store %s into place: %s", work,
                        strerror(errno));
        else
            e = sl_storefile_sync(out, d);   /* the new name, durable */
        sl_storefile_fault_point("merge");
    }
    if (!e) {
        e = sweep_config(m, dir, &r->config, d);
        struct sl_store *st = NULL;
        if (!e)
            e = sl_store_open_existing(out, &st, d);
        if (!e) {
            r->total = sl_plan_count(&r->config);
            r->missing = sl_calloc((size_t)r->total + 1, sizeof *r->missing);
            if (!r->missing)
                e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "missing cells");
            for (int i = 0; !e && i < r->total; i++) {
                struct sl_cell_key k;
                sl_plan_cell(&r->config, i, &k);
                if (!sl_out_stored(&r->config, &k, st))
                    r->missing[r->nmissing++] = i;
            }
        }
        sl_store_close(st);
    }
done:
    sl_merge_close(m);
    if (!held) {
        drop_store_file(work);   /* gone after the rename; a failed merge's copy otherwise */
        sl_storefile_unlock(tfd, tlock);
    }
    return e;
}

void sl_shards_result_free(struct sl_shards_result *r)
{
    sl_config_free(&r->config);
    free(r->shard);
    free(r->absent);
    free(r->missing);
    memset(r, 0, sizeof *r);
}

/* ---- Slurm ---- */

static enum sl_err want_int(const char *opt, const char *v, int lo, int hi, int *out, struct sl_diag *d)
{
    char *end;
    long x = v ? strtol(v, &end, 10) : 0;
    if (!v || end == v || *end || x < lo || x > hi)
        return sl_fail(d, SL_E_USAGE, NULL, 0, opt, "wants a whole number %d..%d", lo, hi);
    *out = (int)x;
    return SL_OK;
}

/* Slurm's own checks come later; these only keep the script's #SBATCH lines
 * to one token each (a value with a blank or a quote would break the line). */
static enum sl_err want_word(const char *opt, const char *v, const char **out, struct sl_diag *d)
{
    if (!v || !v[0] || strpbrk(v, " \t\n'\"\\$`"))
        return sl_fail(d, SL_E_USAGE, NULL, 0, opt, "wants one word");
    *out = v;
    return SL_OK;
}

enum sl_err sl_submit_parse(int argc, char **argv, struct sl_submit_opts *o, struct sl_diag *d)
{
    memset(o, 0, sizeof *o);
    enum sl_err e = SL_OK;
    for (int i = 1; i < argc && !e; i++) {   /* argv[0] is the verb */
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (!strcmp(a, "--tasks"))
            e = want_int(a, v, 1, SL_SUBMIT_MAX_TASKS, &o->tasks, d);
        else if (!strcmp(a, "--cells-per-task"))
            e = want_int(a, v, 1, 1 << 30, &o->cells_per_task, d);
        else if (!strcmp(a, "--max-running"))
            e = want_int(a, v, 1, SL_SUBMIT_MAX_TASKS, &o->max_running, d);
        else if ((!strcmp(a, "--out") || !strcmp(a, "-o")) && v)
            o->out = v;
        else if (!strcmp(a, "--partition"))
            e = want_word(a, v, &o->partition, d);
        else if (!strcmp(a, "--time"))
            e = want_word(a, v, &o->time, d);
        else if (!strcmp(a, "--mem"))
            e = want_word(a, v, &o->mem, d);
        else {
            takes = 0;
            if (!strcmp(a, "--dry-run"))
                o->dry_run = 1;
            else if (!strcmp(a, "--slurm"))
                o->slurm = 1;
            else if (a[0] == '-')
                e = sl_fail(d, SL_E_USAGE, NULL, 0, a, "unknown option or missing value");
            else if (!o->config)
                o->config = a;
            else
                e = sl_fail(d, SL_E_USAGE, NULL, 0, a, "one CONFIG at a time");
        }
        i += takes;
    }
    if (!e && !o->config)
        e = sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "missing CONFIG");
    if (!e && !o->slurm)
        e = sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "--slurm: the only scheduler there is, name it");
    if (!e && o->tasks && o->cells_per_task)
        e = sl_fail(d, SL_E_USAGE, NULL, 0, "--tasks", "give --tasks or --cells-per-task, not both");
    return e;
}

/* s in single quotes for bash ('\'' for a quote inside). */
static void quote(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++)
        if (*s == '\'')
            fputs("'\\''", f);
        else
            fputc(*s, f);
    fputc('\'', f);
}

static void sbatch_lines(FILE *f, const struct sl_submit_opts *o)
{
    if (o->partition)
        fprintf(f, "#SBATCH --partition=%s\n", o->partition);
    if (o->time)
        fprintf(f, "#SBATCH --time=%s\n", o->time);
    if (o->mem)
        fprintf(f, "#SBATCH --mem=%s\n", o->mem);
}

/* Run argv (a program on PATH), its first stdout line into out. */
static enum sl_err run_capture(char *const argv[], const char *what, char *out, size_t n, struct sl_diag *d)
{
    int fd[2];
    if (pipe(fd) != 0)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, argv[0], "pipe: %s", strerror(errno));
    pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, argv[0], "fork: %s", strerror(errno));
    }
    if (pid == 0) {
        dup2(fd[1], 1);
        close(fd[0]);
        close(fd[1]);
        execvp(argv[0], argv);
        _exit(127);
    }
    close(fd[1]);
    FILE *f = fdopen(fd[0], "r");
    out[0] = '\0';
    if (f) {
        if (fgets(out, (int)n, f))
            out[strcspn(out, "\r\n;")] = '\0';   /* --parsable: "id" or "id;cluster" */
        while (fgetc(f) != EOF)
            ;
        fclose(f);
    } else {
        close(fd[0]);
    }
    int st = 0;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
        ;
    if (!WIFEXITED(st) || WEXITSTATUS(st) == 127)
        return sl_fail(d, SL_E_USAGE, NULL, 0, argv[0], "cannot run it: is Slurm installed here and on PATH?");
    if (WEXITSTATUS(st) != 0 || !out[0])
        return sl_fail(d, SL_E_USAGE, what, 0, argv[0], "refused it (exit %d; its message is above)",
                       WEXITSTATUS(st));
    return SL_OK;
}

static enum sl_err write_script(const char *path, void (*body)(FILE *, const void *), const void *arg,
                                struct sl_diag *d)
{
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    unlink(tmp);   /* never written through a link planted there */
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f) {
        if (fd >= 0)
            close(fd);
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    }
    body(f, arg);
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    if (bad || chmod(tmp, 0755) != 0 || rename(tmp, path) != 0) {
        unlink(tmp);
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    }
    return SL_OK;
}

struct script_ctx {
    const struct sl_config *c;
    const struct sl_submit_opts *o;
    const struct sl_submit_result *r;
    char exe[PATH_MAX], config[PATH_MAX], out[PATH_MAX];
};

static void array_body(FILE *f, const void *arg)
{
    const struct script_ctx *x = arg;
    const struct sl_submit_result *r = x->r;
    fprintf(f, "#!/bin/bash\n# written by `shadowlab submit`: study '%s' (config hash %016llx), %d cells in %d tasks\n",
            x->c->name, x->c->hash, r->total, r->ntasks);
    fprintf(f, "#SBATCH --job-name=shadowlab-%s\n#SBATCH --array=0-%d", x->c->name, r->ntasks - 1);
    if (x->o->max_running)
        fprintf(f, "%%%d", x->o->max_running);
    fprintf(f, "\n#SBATCH --output=%s/slurm/task-%%a.log\n", x->out);
    sbatch_lines(f, x->o);
    fprintf(f, "# task i computes cells[i] of the sweep into its own store (never a file two hosts write);\n"
               "# --resume: a requeued or re-submitted task computes only the cells its store lacks;\n"
               "# the truth cache is shared (its files are written under a temporary name and renamed)\n"
               "set -euo pipefail\ncells=(");
    for (int i = 0; i < r->ntasks; i++)
        fprintf(f, "%s%d:%d", i ? " " : "", r->bounds[i], r->bounds[i + 1]);
    fprintf(f, ")\ni=${SLURM_ARRAY_TASK_ID:?submit this script with sbatch}\ndir=");
    quote(f, x->out);
    fprintf(f, "/shards/task-$i\nmkdir -p \"$dir\"\nexec ");
    quote(f, x->exe);
    fprintf(f, " run ");
    quote(f, x->config);
    fprintf(f, " --cells \"${cells[$i]}\" --out \"$dir\" --db \"$dir/shadowlab.db\" --cache ");
    quote(f, x->out);
    fprintf(f, "/cache --resume\n");
}

static void merge_body(FILE *f, const void *arg)
{
    const struct script_ctx *x = arg;
    fprintf(f, "#!/bin/bash\n# written by `shadowlab submit`: the %d shards of study '%s' into one store\n",
            x->r->ntasks, x->c->name);
    fprintf(f, "#SBATCH --job-name=shadowlab-%s-merge\n#SBATCH --output=%s/slurm/merge.log\n", x->c->name, x->out);
    sbatch_lines(f, x->o);
    fprintf(f, "set -euo pipefail\nexec ");
    quote(f, x->exe);
    fprintf(f, " merge");
    for (int i = 0; i < x->r->ntasks; i++) {
        fputs(" \\\n  ", f);
        quote(f, x->out);
        fprintf(f, "/shards/task-%d/shadowlab.db", i);
    }
    fputs(" \\\n  -o ", f);
    quote(f, x->r->merged);
    fputc('\n', f);
}

/* Absolute forms: the script runs on another host, in another folder. */
static enum sl_err absolute(const char *what, const char *p, char *out, struct sl_diag *d)
{
    if (!realpath(p, out))
        return sl_fail(d, SL_E_IO, p, 0, what, "cannot resolve: %s", strerror(errno));
    if (strpbrk(out, "\n"))
        return sl_fail(d, SL_E_USAGE, p, 0, what, "a path with a line break cannot go into a batch script");
    return SL_OK;
}

enum sl_err sl_submit(const struct sl_config *c, const struct sl_submit_opts *o, struct sl_submit_result *r,
                      struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    static struct script_ctx x;
    memset(&x, 0, sizeof x);
    x.c = c;
    x.o = o;
    x.r = r;
    r->total = sl_plan_count(c);
    int want = o->tasks;
    if (!want) {
        int k = o->cells_per_task ? o->cells_per_task : SL_SUBMIT_CELLS_PER_TASK;
        want = (r->total + k - 1) / k;
    }
    if (want > SL_SUBMIT_MAX_TASKS)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--cells-per-task", "%d tasks: at most %d", want,
                       SL_SUBMIT_MAX_TASKS);
    r->ntasks = sl_plan_slices(c, want, r->bounds);
    r->split_views = sl_plan_split_views(c, r->bounds, r->ntasks, &r->nviews);
    const char *out = o->out ? o->out : "results";
    char slurm_dir[1200];
    snprintf(slurm_dir, sizeof slurm_dir, "%s/slurm", out);
    enum sl_err e;
    if ((e = sl_out_no_link(slurm_dir, d)) || (e = sl_mkdirs(slurm_dir, d)) || (e = absolute("--out", out, x.out, d)) ||
        (e = absolute("CONFIG", o->config, x.config, d)) || (e = absolute("shadowlab", "/proc/self/exe", x.exe, d)))
        return e;
    snprintf(r->merged, sizeof r->merged, "%s/shadowlab.db", x.out);
    snprintf(r->array_script, sizeof r->array_script, "%s/slurm/array.sh", x.out);
    snprintf(r->merge_script, sizeof r->merge_script, "%s/slurm/merge.sh", x.out);
    if ((e = write_script(r->array_script, array_body, &x, d)) || (e = write_script(r->merge_script, merge_body, &x, d)))
        return e;
    if (o->dry_run)
        return SL_OK;
    char *arr[] = {"sbatch", "--parsable", r->array_script, NULL};
    if ((e = run_capture(arr, r->array_script, r->array_job, sizeof r->array_job, d)))
        return e;
    char dep[128];
    snprintf(dep, sizeof dep, "--dependency=afterok:%s", r->array_job);
    char *mrg[] = {arr[0], "--parsable", dep, r->merge_script, NULL};
    return run_capture(mrg, r->merge_script, r->merge_job, sizeof r->merge_job, d);
}

/* ---- worker processes on this machine ---- */

static int rm_cb(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb;
    (void)flag;
    (void)ftw;
    return remove(p);
}

static double tv_s(struct timeval t)
{
    return (double)t.tv_sec + 1e-6 * (double)t.tv_usec;
}

/* One worker: this binary, `run CONFIG --cells A:B` into its own folder and
 * store, its stdout and stderr into its log. It dies with this process (a
 * parent-death signal: SIGKILL, checked against the race of a parent that
 * died before the signal was set), and it inherits the workers' folder's
 * lock (lock_fd), so that folder stays taken until the last of them is
 * gone. With resume it skips what its shard or the main store holds. */
static enum sl_err spawn_worker(const struct sl_config *c, const struct sl_jobs_opts *o, const char *dir,
                                const char *cache, const char *main_store, struct sl_jobs_worker *w, pid_t *out,
                                struct sl_diag *d)
{
    char cells[64], db[1300];
    snprintf(cells, sizeof cells, "%d:%d", w->first, w->last);
    snprintf(db, sizeof db, "%s/shadowlab.db", dir);
    snprintf(w->log, sizeof w->log, "%s/run.log", dir);
    enum sl_err e;
    if ((e = sl_out_no_store_link(db, d)))
        return e;
    char *argv[20];
    int n = 0;
    argv[n++] = "shadowlab";
    argv[n++] = "run";
    argv[n++] = (char *)c->path;
    argv[n++] = "--cells";
    argv[n++] = cells;
    argv[n++] = "--out";
    argv[n++] = (char *)dir;
    argv[n++] = "--db";
    argv[n++] = db;
    if (cache[0]) {
        argv[n++] = "--cache";
        argv[n++] = (char *)cache;
    } else {
        argv[n++] = "--no-cache";
    }
    if (o->gl) {
        argv[n++] = "--gl";
        argv[n++] = (char *)o->gl;
    }
    if (o->resume) {
        argv[n++] = "--resume";
        argv[n++] = "--stored-in";
        argv[n++] = (char *)main_store;
    }
    argv[n] = NULL;
    int fd = open(w->log, O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        return sl_fail(d, SL_E_OUTPUT, w->log, 0, NULL, "cannot write: %s", strerror(errno));
    const pid_t parent = getpid();
    pid_t pid = fork();
    if (pid == 0) {
        if (prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || getppid() != parent)
            _exit(127);
        dup2(fd, 1);
        dup2(fd, 2);
        execv("/proc/self/exe", argv);
        _exit(127);
    }
    close(fd);
    if (pid < 0)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "fork: %s", strerror(errno));
    *out = pid;
    return SL_OK;
}

/* The workers' folder, taken: an flock on its .lock, waited for (up to 30 s)
 * while the workers of a run just killed die (their parent-death signal);
 * the fd is inherited by the workers (no close-on-exec). -1 on failure. */
static int take_workdir(const char *workdir, struct sl_diag *d)
{
    char lk[1300];
    snprintf(lk, sizeof lk, "%s/.lock", workdir);
    int fd = open(lk, O_RDWR | O_CREAT | O_NOFOLLOW, 0644);
    if (fd < 0) {
        sl_fail(d, SL_E_OUTPUT, lk, 0, NULL, "cannot open: %s", strerror(errno));
        return -1;
    }
    for (int i = 0; i < 600; i++) {
        if (flock(fd, LOCK_EX | LOCK_NB) == 0)
            return fd;
        if (errno != EWOULDBLOCK && errno != EINTR)
            break;
        struct timespec ts = {0, 50 * 1000 * 1000};
        nanosleep(&ts, NULL);
    }
    close(fd);
    sl_fail(d, SL_E_IO, workdir, 0, "--jobs", "in use by the workers of another run (its lock %s is held)", lk);
    return -1;
}

/* Every entry of dir but its .lock removed: the shards of an earlier run that
 * a run without --resume does not go on from. */
static void clear_workdir(const char *dir)
{
    DIR *dp = opendir(dir);
    if (!dp)
        return;
    struct dirent *e;
    while ((e = readdir(dp))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") || !strcmp(e->d_name, ".lock"))
            continue;
        char p[1500];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        nftw(p, rm_cb, 16, FTW_DEPTH | FTW_PHYS);
    }
    closedir(dp);
}

/* The overlays the store's cells of this config name that are not on disk
 * (paths relative to the store's folder, or absolute); the first few names
 * into r. */
static enum sl_err count_missing_overlays(struct sl_store *st, const struct sl_config *c, const char *store_path,
                                          struct sl_jobs_result *r, struct sl_diag *d)
{
    struct sl_cell_record *cells = NULL;
    int n = 0;
    enum sl_err e = sl_out_stored_cells(st, c, &cells, &n, d);
    if (e)
        return e;
    char dir[1200];
    sl_path_dir(store_path, dir, sizeof dir);
    for (int i = 0; i < n; i++) {
        if (!cells[i].overlay[0])
            continue;
        char p[2800];
        if (cells[i].overlay[0] == '/')
            snprintf(p, sizeof p, "%s", cells[i].overlay);
        else
            snprintf(p, sizeof p, "%s/%s", dir, cells[i].overlay);
        if (access(p, F_OK) == 0)
            continue;
        if (r->overlays_missing < (int)(sizeof r->missing_overlay / sizeof r->missing_overlay[0]))
            snprintf(r->missing_overlay[r->overlays_missing], sizeof r->missing_overlay[0], "%s", p);
        r->overlays_missing++;
    }
    free(cells);
    return SL_OK;
}

/* The main store's cells of this config whose overlay or EXR file is not in
 * gathered (<the store's folder>/<name>, where the merge puts them): their
 * ids into *ids (malloc'ed), their number into *n. The workers of a resumed
 * run compute those cells again (they test the same, run.c), and the merge
 * replaces them with the fresh copies. */
static enum sl_err files_lost(struct sl_store *st, const struct sl_config *c, const char *gathered, int64_t **ids,
                              int *n, struct sl_diag *d)
{
    *ids = NULL;
    *n = 0;
    if (!c->overlays && !c->exr)
        return SL_OK;
    const int total = sl_plan_count(c);
    struct sl_out_kept kept = {0};
    enum sl_err e = sl_out_kept_find(c, NULL, gathered, NULL, &kept, d);
    if (!e && !(*ids = sl_calloc((size_t)total + 1, sizeof **ids)))
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "cells to recompute");
    for (int i = 0; !e && i < total; i++) {
        struct sl_cell_key k;
        sl_plan_cell(c, i, &k);
        int64_t id = sl_out_stored_id(c, &k, st);
        if (id && !sl_out_kept_whole(c, &k, &kept, st))
            (*ids)[(*n)++] = id;
    }
    sl_out_kept_free(&kept);
    return e;
}

/* Wait for the started workers; a stop (SIGINT or SIGTERM to this process)
 * is passed on to each live one, which stops after its cell under way. */
static void wait_workers(const struct sl_jobs_opts *o, pid_t *pids, int started, double t0, struct sl_jobs_result *r)
{
    int left = started;
    while (left > 0) {
        int st = 0;
        struct rusage ru;
        pid_t p = wait4(-1, &st, WNOHANG, &ru);
        if (p < 0 && errno == EINTR)
            continue;
        if (p < 0)
            break;
        if (p == 0) {
            if (o->stop && *o->stop && !r->interrupted) {
                r->interrupted = *o->stop;
                for (int i = 0; i < started; i++)
                    if (pids[i] > 0)
                        kill(pids[i], *o->stop);
            }
            struct timespec ts = {0, 20 * 1000 * 1000};
            nanosleep(&ts, NULL);
            continue;
        }
        for (int i = 0; i < started; i++)
            if (pids[i] == p) {
                r->w[i].status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
                r->w[i].wall_s = sl_now() - t0;
                r->w[i].cpu_s = tv_s(ru.ru_utime) + tv_s(ru.ru_stime);
                r->cpu_s += r->w[i].cpu_s;
                pids[i] = -1;
                left--;
            }
    }
}

enum sl_err sl_jobs_run(const struct sl_config *c, const struct sl_jobs_opts *o, struct sl_jobs_result *r,
                        struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    const char *root = o->out_root ? o->out_root : "results";
    int jobs = o->jobs < 1 ? 1 : o->jobs > 64 ? 64 : o->jobs;
    int bounds[65];
    r->nworkers = sl_plan_slices(c, jobs, bounds);
    r->split_views = sl_plan_split_views(c, bounds, r->nworkers, &r->nviews);
    if (o->store)
        snprintf(r->store, sizeof r->store, "%s", o->store);
    else if (c->store[0])
        snprintf(r->store, sizeof r->store, "%s/%s", root, c->store);   /* under --out (config.c) */
    else
        snprintf(r->store, sizeof r->store, "%s/shadowlab.db", root);
    char cache[1200];
    if (o->cache)
        snprintf(cache, sizeof cache, "%s", o->cache);
    else
        snprintf(cache, sizeof cache, "%s/cache", root);
    snprintf(r->workdir, sizeof r->workdir, "%s/.jobs-%s", root, c->name);
    /* where the merge gathers the overlays: <the store's folder>/<name> */
    char store_dir[1200], gathered[1300], final[1300];
    sl_path_dir(r->store, store_dir, sizeof store_dir);
    snprintf(gathered, sizeof gathered, "%s/%s", store_dir, c->name);
    snprintf(final, sizeof final, "%s/%s", root, c->name);
    enum sl_err e;
    /* nothing the run names itself is a symbolic link it would write through */
    if ((!o->store && (e = sl_out_no_store_link(r->store, d))) || (!o->cache && (e = sl_out_no_link(cache, d))) ||
        (e = sl_out_no_link(r->workdir, d)) || (e = sl_out_no_link(gathered, d)) || (e = sl_out_no_link(final, d)))
        return e;
    if ((e = sl_mkdirs(root, d)) || (e = sl_mkdirs(store_dir, d)))
        return e;
    /* the main store's writer lock for the whole run: no other run writes it
     * while the workers read it (--resume) and the merge fills it */
    struct sl_store *main_st = NULL;
    if ((e = sl_store_open(r->store, &main_st, d)))
        return e;
    int lock = -1;
    if ((e = sl_mkdirs(r->workdir, d)) || (lock = take_workdir(r->workdir, d)) < 0) {
        sl_store_close(main_st);
        return e ? e : SL_E_IO;
    }
    if (!o->resume)
        clear_workdir(r->workdir);
    int64_t *lost = NULL;
    int nlost = 0;
    if (o->resume && (e = files_lost(main_st, c, gathered, &lost, &nlost, d))) {
        close(lock);
        sl_store_close(main_st);
        return e;
    }
    pid_t pids[64];
    double t0 = sl_now();
    int started = 0;
    for (int i = 0; i < r->nworkers && !e; i++) {
        struct sl_jobs_worker *w = &r->w[i];
        w->first = bounds[i];
        w->last = bounds[i + 1];
        char dir[1300];
        snprintf(dir, sizeof dir, "%s/task-%d", r->workdir, i);
        if ((e = sl_out_no_link(dir, d)) || (e = sl_mkdirs(dir, d)))
            break;
        if (!(e = spawn_worker(c, o, dir, cache, r->store, w, &pids[i], d)))
            started++;
    }
    /* wait for every worker started, even after a failure: none is left behind */
    if (e)
        for (int i = 0; i < started; i++)
            kill(pids[i], SIGTERM);
    wait_workers(o, pids, started, t0, r);
    r->wall_s = sl_now() - t0;
    int failed = 0;
    for (int i = 0; i < started; i++) {
        int st = r->w[i].status;
        /* a worker stopped by the signal passed on exits 128 + it: not a failure */
        failed |= st != 0 && !(r->interrupted && st == 128 + r->interrupted);
    }
    if (!e && failed)
        e = sl_fail(d, SL_E_INTERNAL, c->path, 0, "--jobs", "a worker failed (its log is named above)");
    if (!e) {
        /* what the shards hold goes into the main store, after a stop too: a
         * resumed run skips it (on --resume, keys the store holds are not
         * copied twice) */
        const char *shards[64];
        char paths[64][1300];
        for (int i = 0; i < r->nworkers; i++) {
            snprintf(paths[i], sizeof paths[i], "%s/task-%d/shadowlab.db", r->workdir, i);
            shards[i] = paths[i];
        }
        e = shards_merge(shards, r->nworkers, r->store, o->resume ? 0u : SL_MERGE_APPEND, main_st, lost, nlost,
                         &r->merge, d);
        if (!e && c->overlays)
            e = count_missing_overlays(main_st, c, r->store, r, d);
        if (!e && r->merge.nmissing == 0 && r->overlays_missing == 0 && !r->interrupted)
            nftw(r->workdir, rm_cb, 16, FTW_DEPTH | FTW_PHYS);
    }
    if (!e)   /* the main store's .db alone holds everything before "written to" */
        e = sl_store_seal(main_st, d);
    free(lost);
    close(lock);
    sl_store_close(main_st);
    return e;
}

void sl_jobs_result_free(struct sl_jobs_result *r)
{
    sl_shards_result_free(&r->merge);
}
