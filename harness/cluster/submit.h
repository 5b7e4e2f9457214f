/*
 * submit.h — a sweep beyond one process: sliced into tasks (plan.h's
 * sl_plan_slices), run as a Slurm job array (`shadowlab submit --slurm`) or
 * as worker processes on this machine (`shadowlab run --jobs N`), and the
 * tasks' stores merged back into one (`shadowlab merge`, merge.h), with the
 * cells of the sweep that no shard holds named.
 *
 * Every task writes its own store and its own results folder,
 * <out>/shards/task-<i>/ for Slurm, <out>/.jobs-<name>/task-<i>/ for --jobs:
 * no SQLite file is ever written by two processes or hosts. A task runs
 * `shadowlab run CONFIG --cells A:B --out TASKDIR --db TASKDIR/shadowlab.db
 * --cache OUT/cache --resume`, so a requeued or re-run task computes only what
 * it lacks; the truth cache is shared (written atomically, cache.h).
 *
 * Owns: nothing between calls. Does not: print (the results come back for
 * main.c to show; a worker's own output goes to its log file).
 */
#ifndef SL_SUBMIT_H
#define SL_SUBMIT_H
#include "config.h"
#include "merge.h"

#define SL_SUBMIT_MAX_TASKS 4096

/* ---- merge with the sweep ---- */

struct sl_shards_result {
    int    nshards;
    struct sl_merge_shard *shard;   /* per shard given, in order */
    int   *absent;                  /* per shard: 1 when its file is not there */
    int    total;                   /* cells of the sweep (0: no shard held a run) */
    int    nmissing;                /* cells of the sweep the merged store lacks */
    int   *missing;                 /* their sweep indices */
    int    copied, duplicates;
    double seconds;                 /* the merge alone, not the check */
    struct sl_config config;        /* the sweep (from a shard's run), to name missing cells */
};
/* Merge shards[0..n) into out (created; its folder made). A shard file that
 * is not there is noted (absent) and its cells come out as missing; any
 * other shard (a folder, a device, a damaged store, another config) fails
 * the merge before anything is written, and so do shards whose cells come
 * from two git SHAs, GL renderers or ISAs unless flags has
 * SL_MERGE_ALLOW_MIXED (merge.h). SL_MERGE_APPEND: a shard's cell replaces
 * a stored one of its key (a fresh computation, as `run --jobs` makes,
 * supersedes an older one as a second `run` would); else a stored key is a
 * duplicate and is skipped. */
enum sl_err sl_shards_merge(const char *const *shards, int n, const char *out, unsigned flags,
                            struct sl_shards_result *r, struct sl_diag *d);
void sl_shards_result_free(struct sl_shards_result *r);

/* ---- Slurm ---- */

struct sl_submit_opts {
    const char *config;
    int         tasks;            /* 0: from cells_per_task */
    int         cells_per_task;   /* 0: SL_SUBMIT_CELLS_PER_TASK */
    int         max_running;      /* 0: no limit */
    const char *out;              /* NULL: "results" */
    const char *partition, *time, *mem;   /* NULL: the cluster's defaults */
    int         dry_run;
    int         slurm;
};
/* A task of about 256 cells runs minutes on a 2-core machine (the Morais
 * study: 864 cells in about 4 minutes), so its start-up (scene load, BVH, GL
 * context) is a small part of it. */
#define SL_SUBMIT_CELLS_PER_TASK 256

/* The verb's arguments, argv[0] being `submit`; SL_E_USAGE naming the option. */
enum sl_err sl_submit_parse(int argc, char **argv, struct sl_submit_opts *o, struct sl_diag *d);

struct sl_submit_result {
    char array_script[1200], merge_script[1200];
    char array_job[64], merge_job[64];   /* "" with --dry-run */
    char merged[1200];                   /* the store the merge job writes */
    int  ntasks, total, nviews, split_views;
    int  bounds[SL_SUBMIT_MAX_TASKS + 1];
};
/* Write <out>/slurm/array.sh and merge.sh; without dry_run, sbatch the
 * array, then the merge with --dependency=afterok on it. */
enum sl_err sl_submit(const struct sl_config *c, const struct sl_submit_opts *o, struct sl_submit_result *r,
                      struct sl_diag *d);

/* ---- worker processes on this machine ---- */

struct sl_jobs_opts {
    int         jobs;
    const char *out_root;   /* NULL: "results" */
    const char *store;      /* the merged store; NULL: the config's, else <out_root>/shadowlab.db */
    const char *cache;      /* NULL: <out_root>/cache, shared by the workers; "": none */
    const char *gl;         /* "osmesa", "egl" or NULL (the config's) */
    int         resume;     /* skip the cells the run's store holds; the workers resume their
                             * shards of a killed --jobs run */
    const volatile int *stop;   /* set to SIGINT or SIGTERM by a handler: passed on to the workers */
};
struct sl_jobs_worker {
    int    first, last;
    int    status;          /* exit status, or 128 + signal */
    char   log[1200];
    double wall_s, cpu_s;
};
struct sl_jobs_result {
    int    nworkers, nviews, split_views;
    struct sl_jobs_worker w[64];
    double wall_s, cpu_s;   /* the workers, start to last exit; their user+sys */
    char   store[1200], workdir[1200];
    struct sl_shards_result merge;
    int    interrupted;        /* the signal passed on to the workers, 0 none */
    int    overlays_missing;   /* overlays the store's cells of this config name, not on disk */
    char   missing_overlay[10][1300];   /* the first of them */
};
/* Fork `jobs` workers (this binary, /proc/self/exe) over the slices, wait,
 * merge their stores into the run's store (append; with resume only the
 * keys it lacks), and remove their folder when every one succeeded and
 * nothing is missing. The run's store is held open (its writer lock) from
 * the start to the end; the workers die with this process; a stop is
 * passed on to them and what they stored is merged (r->interrupted). A
 * symbolic link where the run writes is refused (SL_E_USAGE). SL_E_INTERNAL
 * when a worker failed (its log is named in r). */
enum sl_err sl_jobs_run(const struct sl_config *c, const struct sl_jobs_opts *o, struct sl_jobs_result *r,
                        struct sl_diag *d);
void sl_jobs_result_free(struct sl_jobs_result *r);

#endif
