/*
 * runresult.h — what a run computed, as the results' writers read it: the
 * cells scored (cell.h), what was rendered and traced to get them (so tests
 * can prove each shared stage ran once), the provenance and the timings.
 * Filled by the run loop (run.h, sl_run); read by the tables, the staging
 * folder and the motion outputs (outputs.h, motion_run.h).
 *
 * Owns: the cells array (sl_run_result_free). Does not: compute or write
 * anything.
 */
#ifndef SL_RUNRESULT_H
#define SL_RUNRESULT_H
#include "cell.h"
#include "frame.h"
#include "provenance.h"
#include "reps.h"

struct sl_pass_counts {
    int scenes;                        /* scenes loaded (GL upload + BVH) */
    int adjacency;                     /* adjacency tables built (only when a method needs them) */
    int gbuffers;                      /* G-buffer passes */
    int truths_traced, truths_cached;  /* truth passes traced / read from cache */
    int soft_truths;                   /* of those traced, area-light truths (visible fractions) */
    int soft_truths_cached;            /* of those read from cache, area-light truths */
    int cache_rejected;                /* cache files found but not used (cut short, damaged, another
                                        * format or key, or not agreeing with the view): recomputed */
    int soft_layers;                   /* soft_mc's near + far layers and N-buffer, per (view, map size) */
    int layers[SL_LAYER_COUNT];        /* shadow-map layer renders */
    int method_runs;                   /* method invocations, repetitions included */
    int contour_runs;                  /* contour_from nsm: NSM runs made only to draw a contour (none
                                        * where a label of the config is that NSM: its run is reused) */
};

struct sl_run_result {
    struct sl_provenance prov;
    char   out_dir[1024];
    int    ncells;                     /* computed by this invocation */
    struct sl_cell *cells;
    int    skipped;                    /* already in the store (--resume) */
    int    warmed;                     /* path frames scored for the next frame's flicker only (run.c) */
    int    interrupted;                /* stopped by o->stop before the end */
    int    stored_total;               /* cells of this config in the store after the run, -1 unknown */
    char   store_path[1100];           /* the database written, "" none */
    struct sl_pass_counts passes;
    struct sl_reps reps;               /* the repetitions policy and what each timed stage ran, and why */
    double ms_total, ms_scene, ms_bvh;
    int    overlays_written;           /* sheets the writer thread wrote, and its time on them, wall */
    double ms_overlay_writer, ms_overlay_writer_cpu;   /* and CPU, ms (off the cells' path; 0 inline) */
};

void sl_run_result_free(struct sl_run_result *r);

#endif
