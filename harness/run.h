/*
 * run.h — the experiment driver: expands a validated config into cells
 * (viewport x viewpoint x map size x method label), computes each shared
 * stage once (G-buffer and truth per view, light fit per view, each layer once
 * per map size), runs the methods, and writes the figures, tables, costs and
 * overlays.
 *
 * Output: <out_root>/<name>/{figures.csv, costs.csv, table.md, config.yaml,
 * run.yaml, overlays/<cell>.png}. Everything is written into a hidden staging
 * folder first and renamed into place at the end, so a failed or killed run
 * leaves nothing half-written under the final name.
 */
#ifndef SL_RUN_H
#define SL_RUN_H
#include <stdio.h>
#include "config.h"
#include "figures.h"
#include "provenance.h"

struct sl_run_opts {
    const char *out_root;   /* NULL = "results" */
    FILE       *table_out;  /* Markdown tables echoed here; NULL = none */
    int         write_files;/* 0 = compute only (tests, bench) */
};

/* Wall times of the stages of one cell, ms; view stages are shared by every
 * cell of the view and reported with each. */
struct sl_stage_ms {
    double gbuffer_render, gbuffer_readback, truth, fit;
    double map_render, map_readback;
    double method, contours, figures, overlay;
};

struct sl_cell {
    int vp, viewport, map, method;     /* indices into the config / scene */
    char viewpoint[32];
    struct sl_figures  fig;
    struct sl_cost     cost;
    struct sl_stage_ms ms;
    uint64_t truth_rays;
    uint64_t n_pfl, n_pnfl, n_background, n_truth_lit, n_truth_shadow;
};

struct sl_run_result {
    struct sl_provenance prov;
    char   out_dir[1024];
    int    ncells;
    struct sl_cell *cells;
    double ms_total, ms_scene, ms_bvh;
};

enum sl_err sl_run(const struct sl_config *c, const struct sl_run_opts *o, struct sl_run_result *res,
                   struct sl_diag *d);
void        sl_run_result_free(struct sl_run_result *r);

#endif
