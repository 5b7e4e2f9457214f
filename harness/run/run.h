/*
 * run.h — the experiment driver's loop.
 *
 * A config expands to a sweep of independent cells (plan.h). Each shared
 * stage is computed once for the cells that need it: the scene (GL mesh,
 * BVH) per scene; the G-buffer, the truth (or its on-disk cache, cache.h)
 * and the light fit per view; each shadow-map layer once per (view, map
 * size), and only the layers the methods of the selected cells declare.
 * sl_run_result.passes counts what was computed, so tests can prove it.
 * Each cell's method runs, then the cell is scored (cell.h) and put into the
 * store, one transaction per cell, so a killed run leaves no partial cell
 * and `--resume` redoes only the missing ones.
 *
 * Output (outputs.h): <out_root>/<name>/{figures.csv, costs.csv, table.md,
 * table.tex, config.yaml, run.yaml, patterns.csv, overlays/<cell>.png,
 * exr/<cell>.exr (when asked)} for the cells this invocation computed,
 * written into a hidden staging folder and renamed into place at the end;
 * then, when the store holds more cells of this config than this run
 * computed (--resume, --cells, an interrupt), figures.csv and the tables
 * are rebuilt from the store so the folder covers every stored cell.
 *
 * Owns: the GL context, the BVH, the current scene, view and frame while a
 * run lasts. Does not: print (notes, violations and progress go to the
 * caller's on_event), or exit.
 */
#ifndef SL_RUN_H
#define SL_RUN_H
#include <stdio.h>
#include "config.h"
#include "figures.h"
#include "frame.h"
#include "cell.h"
#include "plan.h"
#include "provenance.h"
#include "runresult.h"
#include "softfig.h"
#include "table.h"

struct sl_light_box;

/* What a run says along the way. */
enum sl_run_event_kind {
    SL_EVENT_FRUSTUM_NOTE,   /* a point frustum left pixels outside its map or triangles out of its
                              * conservative layers: scene, viewpoint, box */
    SL_EVENT_VIOLATIONS,     /* a cell broke its method's declared exactness (a bug): cell */
    SL_EVENT_NONFINITE,      /* a cell read values not finite or out of range: cell */
    SL_EVENT_PROGRESS,       /* a cell is done: cell, done of total, elapsed seconds */
};
struct sl_run_event {
    enum sl_run_event_kind      kind;
    const struct sl_config     *config;
    const struct sl_cell       *cell;
    const char                 *scene, *viewpoint;
    const struct sl_light_box  *box;
    int                         done, total;   /* cells, skipped ones included */
    double                      elapsed_s;
};

struct sl_run_opts {
    const char *out_root;   /* NULL = "results" */
    FILE       *table_out;  /* Markdown tables echoed here; NULL = none */
    int         write_files;/* 0 = compute only (tests, bench) */
    int         first, last;/* cells [first, last); last <= 0 = to the end */
    int         resume;     /* skip cells the store already holds */
    const char *stored_in;  /* with resume: skip the cells this store holds too, opened
                             * read-only (a --jobs worker: the run's main store) */
    const char *store;      /* database path; NULL = config's, else <out_root>/shadowlab.db
                             * when write_files; "" = no store */
    const char *cache_dir;  /* truth cache; NULL = <out_root>/cache when write_files; "" = none */
    /* What happens along the way, for the caller to show (the library never
     * prints): NULL = nothing is said. */
    void      (*on_event)(const struct sl_run_event *ev, void *user);
    void       *user;
    /* Set (by a signal handler) to stop after the cell under way: the run then
     * writes its folder as usual and returns SL_OK with res->interrupted. */
    const volatile int *stop;
    int         overlay_inline;   /* 1: each cell writes its overlay itself, not the run's
                                   * writer thread (tests: the files must be the same) */
};

/* What was computed, to prove nothing is computed twice or needlessly. */
enum sl_err sl_run(const struct sl_config *c, const struct sl_run_opts *o, struct sl_run_result *res,
                   struct sl_diag *d);

#endif
