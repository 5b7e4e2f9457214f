/*
 * run.h — the experiment driver.
 *
 * A config expands to a sweep of independent cells, in this order:
 * scene x viewport x viewpoint x map size x method label. Each cell has an
 * index (sl_plan_cell), so `--cells A:B` can split a sweep across machines.
 *
 * Each shared stage is computed once for the cells that need it: the scene
 * (GL mesh, BVH) per scene; the G-buffer, the truth (or its on-disk cache)
 * and the light fit per view; each shadow-map layer once per (view, map
 * size), and only the layers the methods of the selected cells declare.
 * sl_run_result.passes counts what was computed, so tests can prove it.
 *
 * Output: <out_root>/<name>/{figures.csv, costs.csv, table.md, table.tex,
 * config.yaml, run.yaml, overlays/<cell>.png, exr/<cell>.exr (when asked)} for
 * the cells this invocation
 * computed, written into a hidden staging folder and renamed into place at
 * the end; and, when a store is used, one transaction per cell in SQLite,
 * so a killed run leaves no partial cell and `--resume` redoes only the
 * missing ones (`shadowlab table` renders everything stored).
 */
#ifndef SL_RUN_H
#define SL_RUN_H
#include <stdio.h>
#include "config.h"
#include "figures.h"
#include "frame.h"
#include "plan.h"
#include "provenance.h"
#include "softfig.h"
#include "table.h"

struct sl_cell;
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
    const char *store;      /* database path; NULL = config's, else <out_root>/shadowlab.db
                             * when write_files; "" = no store */
    const char *cache_dir;  /* truth cache; NULL = <out_root>/cache when write_files; "" = none */
    /* What happens along the way, for the caller to show (the library never
     * prints): NULL = nothing is said. */
    void      (*on_event)(const struct sl_run_event *ev, void *user);
    void       *user;
};

/* Wall times of the stages of one cell, ms; view stages are shared by every
 * cell of the view and reported with each. The G-buffer render, the truth
 * (when traced, not cached), each shadow-map layer render and the method are
 * repeated as the config says (warm-up + runs): each keeps the median of the
 * timed runs with their min and max. The layers the method reads add up
 * (sum of medians, of mins, of maxes). The rest is timed once. */
struct sl_stage_ms {
    double gbuffer_render[3], gbuffer_readback, truth[3], fit;   /* [SL_MED], [SL_MIN], [SL_MAX] */
    double map_render[3], map_readback;
    double method[3], contours, figures, overlay;
};

/* A pixel where a method broke the guarantee it declares (method.h
 * SL_EXACT_*): where, what, and which triangles its texel holds. */
struct sl_violation {
    int      x, y;                     /* pixel, y = 0 the bottom row */
    uint8_t  truth, verdict, how;
    uint32_t own_tri;                  /* triangle + 1 the pixel lies on */
    int      tx, ty;                   /* its texel */
    uint32_t layer_tri[SL_LAYER_COUNT];/* triangle + 1 each rendered layer holds there, 0 none */
};
#define SL_MAX_VIOLATIONS 4

struct sl_cell {
    int index;                         /* in the sweep */
    struct sl_cell_key key;
    char scene[64];
    char viewpoint[32];
    struct sl_figures  fig;
    struct sl_cost     cost;
    struct sl_stage_ms ms;
    uint64_t gs_prims, fragments;      /* of the layers the method reads (GL queries) */
    int      truth_cached;
    uint64_t truth_rays;
    uint64_t n_pfl, n_pnfl, n_background, n_truth_lit, n_truth_shadow;
    int      has_soft;                 /* an area light's cell: soft figures instead of fig's regions */
    struct sl_soft_figures soft;
    uint64_t violations;               /* of the method's declared exactness; must be 0 */
    uint64_t nonfinite;                /* G-buffer values not finite, depths of the layers it reads
                                        * outside [0, 1]; must be 0 */
    /* texel coherence (Moderno 2011 Tables 20/22): per region, PFL pixels by
     * how many of the tested texels say shadow, and of those how many are
     * shadowed in truth; has_patterns when the method reports it */
    int      has_patterns;
    uint64_t pattern[SL_MAX_REGIONS][10][2];
    struct sl_violation violation[SL_MAX_VIOLATIONS];
};

/* What was computed, to prove nothing is computed twice or needlessly. */
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
};

struct sl_run_result {
    struct sl_provenance prov;
    char   out_dir[1024];
    int    ncells;                     /* computed by this invocation */
    struct sl_cell *cells;
    int    skipped;                    /* already in the store (--resume) */
    char   store_path[1100];           /* the database written, "" none */
    struct sl_pass_counts passes;
    double ms_total, ms_scene, ms_bvh;
};

enum sl_err sl_run(const struct sl_config *c, const struct sl_run_opts *o, struct sl_run_result *res,
                   struct sl_diag *d);
void        sl_run_result_free(struct sl_run_result *r);

#endif
