/*
 * cellcols.h — the columns of one cell of results, listed once, and the
 * plain record that carries them.
 *
 * SL_CELL_COLUMNS is the one list of a cell's key, counts and costs. From it
 * come the fields of struct sl_cell_record, the results store's `cells`
 * table (schema, INSERT, SELECT: store.c), the run's costs.csv (header and
 * row: outputs.c), the copy of a scored cell into its record (sl_out_record,
 * outputs.c) and the counters a baseline compares (check.c). Adding a
 * counter is one line here (a stored column also changes the store's schema
 * text: bump its version, see store.c).
 *
 * X(name, kind, size, csv, head, check, key, from):
 *   name   the record's field and the store's column;
 *   kind   how it is held, stored and written:
 *            text      char[size], TEXT NOT NULL
 *            path      char[size], TEXT, NULL when "" (the error overlay PNG: relative
 *                      to the database's folder in the store, to the run's folder
 *                      in a run)
 *            dim       int, INTEGER NOT NULL CHECK (name > 0)
 *            index     int, INTEGER NOT NULL
 *            runs      int, INTEGER NOT NULL CHECK (name >= 0)
 *            count     uint64_t, INTEGER NOT NULL CHECK (name >= 0)
 *            ms        double, REAL (a wall time in ms, or ms_gpu_*: the GPU time of
 *                      the same passes from GL_TIME_ELAPSED queries, median over
 *                      the same repetitions; NULL/NAN = not measured)
 *            viewport  no field: "vw x vh", stored for the figure queries
 *            wrong     no field: fig.wrong_image (the whole image's wrong pixels)
 *            flag      int, not stored (the run's costs.csv only)
 *   size   char array size of text and path, else 0;
 *   csv    position in costs.csv (1 = first), 0 = not written there, under
 *          the header `head`; git_sha, config_hash and machine follow;
 *   check  class of check.h a baseline compares it under (none = not
 *          compared), as the counter `key`;
 *   from   where a run takes the value from its scored cell, an expression
 *          in cl (const struct sl_cell *, score/cell.h), s (&cl->ms), k
 *          (&cl->key), c (the config) and cm (the cell's config method);
 *          _ for the kinds with no field (viewport, wrong) and for the
 *          overlay's path, which names where the run writes the PNG and is
 *          set by the caller that knows it (outputs.c).
 * flicker, flicker_compared: a path's frame against the frame before it
 * (temporal.h); compared 0 = not measured (no frame, or its path's first in
 * the run that computed it).
 * faces, ms_face_max: under a point light, the faces of its cube that hold
 * a map (harness/render/lightframe.h) and the method's time on the slowest of them (its
 * ms_method is the sum over the faces); 0 and NULL under any other light.
 * n_outside_cone: the part of n_pnfl outside a spot light's cone (view.h),
 * 0 under other lights; light: the scene's light in words for headings
 * ("spot light, 70°": sl_light_heading). Not compared by check: baselines
 * written before them have neither, and n_pnfl already holds the pixels.
 * frac: 1 when the cell's soft figures are a hard light's fractional
 * errors (a method that writes a visibility, a technique package: its
 * visibility against the 0/1 truth over the PFL pixels, score/cell.c), not
 * an area light's; 0 otherwise.
 * family, beside: the cell's method's sl_method.family and .beside (method.h,
 * "" for none): where it comes from, which the report reads to decide a
 * study's thesis sections (it keeps no list of methods). display: the
 * label's name for people (config.h: `display:`, else the method's own,
 * else the label), which LaTeX tables print.
 * nonfinite: values of the cell not finite (cell.h: the G-buffer's, the
 * layers' depths outside [0, 1], the method's visibility, a package's map
 * texels); a result, not a shadow: the pixels are left out of the figures
 * (a package's verdict there is uncertain), the cell is flagged NON-FINITE
 * in the run's summary, the tables and the report, and check compares it
 * exactly (a baseline without the key holds 0).
 * The cost model (one definition for every method, C or package; cell.h
 * sl_stage_ms): a cell's cost is its stages, ms_map (the shadow-map
 * passes: the driver's layers the method reads, ms_map_render, plus any
 * map pass of its own: a package's, zpart's slices), ms_post (its post
 * passes: blur, mipmaps), ms_lookup (its per-pixel lookup), ms_readback
 * (the maps' or its visibility's way back to the CPU: ms_map_readback
 * plus its own) and ms_ray_step (its rays), each the median of its timed
 * runs, and ms_cost their whole with ms_cost_min, ms_cost_max (the layers'
 * and the method's runs' extremes summed). ms_method is the per-pixel
 * step, lookup and rays, for every method. ms_gpu_map, ms_gpu_post and
 * ms_gpu_lookup are the GL stages' GL_TIME_ELAPSED beside (NULL where no
 * GL pass ran). runs, runs_map: how many runs of the method and of the
 * layers it reads were timed (the repetitions policy, reps.h; 1 is "timed
 * once"; runs_map 0: it reads no layer of the driver's).
 * The list is in the order of the store's columns.
 *
 * The record is what the store returns and takes, what the tables, the
 * summaries, the report and the baseline check read, and what the run builds
 * from its cells; its regions (fig.r[].thickness) have one name everywhere
 * they are written or read (sl_region_name). Does not: read, write or format
 * a record (the store, the tables and the run's outputs do); decide a cell's
 * figures (figures.h).
 */
#ifndef SL_CELLCOLS_H
#define SL_CELLCOLS_H
#include <stddef.h>
#include <stdint.h>
#include "figrec.h"
#include "softfig.h"

/* Stages timed over the config's repetitions keep {median, min, max}. */
enum { SL_MED = 0, SL_MIN = 1, SL_MAX = 2 };

/* clang-format off */
#define SL_CELL_COLUMNS(X)                                                                  \
    /* name                kind      size  csv  head                  check      key            from */    \
    X(scene,               text,     64,   2,   "scene",              none,      _,              cl->scene) \
    X(viewpoint,           text,     32,   3,   "viewpoint",          none,      _,              cl->viewpoint) \
    X(viewport,            viewport, 0,    4,   "viewport",           none,      _,              _) \
    X(vw,                  dim,      0,    0,   "",                   none,      _,              c->viewport_w[k->viewport]) \
    X(vh,                  dim,      0,    0,   "",                   none,      _,              c->viewport_h[k->viewport]) \
    X(map_size,            dim,      0,    5,   "map_size",           none,      _,              c->maps[k->map]) \
    X(method,              text,     32,   0,   "",                   none,      _,              cm->method->name) \
    X(label,               text,     48,   6,   "label",              none,      _,              cm->label) \
    X(contour_from,        text,     8,    0,   "",                   none,      _,              sl_contour_from_name(c->contour_from)) \
    X(cell_index,          index,    0,    1,   "cell",               none,      _,              cl->index) \
    X(n_pfl,               count,    0,    0,   "",                   view,      n_pfl,          cl->n_pfl) \
    X(n_pnfl,              count,    0,    0,   "",                   view,      n_pnfl,         cl->n_pnfl) \
    X(n_background,        count,    0,    0,   "",                   view,      n_background,   cl->n_background) \
    X(n_truth_lit,         count,    0,    0,   "",                   view,      n_truth_lit,    cl->n_truth_lit) \
    X(n_truth_shadow,      count,    0,    0,   "",                   view,      n_truth_shadow, cl->n_truth_shadow) \
    X(n_wrong_image,       wrong,    0,    0,   "",                   error,     wrong_image,    _) \
    X(truth_rays,          count,    0,    16,  "truth_rays",         cost,      truth_rays,     cl->truth_rays) \
    X(runs,                runs,     0,    7,   "runs",               none,      _,              s->runs_method) \
    X(lookups,             count,    0,    30,  "lookups",            cost,      lookups,        cl->cost.lookups) \
    X(rays,                count,    0,    31,  "rays",               cost,      rays,           cl->cost.rays) \
    X(tri_tests,           count,    0,    32,  "tri_tests",          cost,      tri_tests,      cl->cost.tri_tests) \
    X(gs_prims,            count,    0,    33,  "gs_prims",           cost,      gs_prims,       cl->gs_prims) \
    X(fragments,           count,    0,    34,  "fragments",          cost,      fragments,      cl->fragments) \
    X(violations,          count,    0,    35,  "violations",         invariant, violations,     cl->violations) \
    X(flicker,             count,    0,    0,   "",                   none,      _,              cl->flicker) \
    X(flicker_compared,    count,    0,    0,   "",                   none,      _,              cl->flicker_compared) \
    X(ms_gbuffer_render,   ms,       0,    8,   "ms_gbuffer_render",  none,      _,              s->gbuffer_render[SL_MED]) \
    X(ms_gbuffer_render_min, ms,     0,    9,   "ms_gbuffer_render_min", none,   _,              s->gbuffer_render[SL_MIN]) \
    X(ms_gbuffer_render_max, ms,     0,    10,  "ms_gbuffer_render_max", none,   _,              s->gbuffer_render[SL_MAX]) \
    X(ms_gbuffer_readback, ms,       0,    11,  "ms_gbuffer_readback", none,     _,              s->gbuffer_readback) \
    X(ms_truth,            ms,       0,    12,  "ms_truth",           none,      _,              s->truth[SL_MED]) \
    X(ms_truth_min,        ms,       0,    13,  "ms_truth_min",       none,      _,              s->truth[SL_MIN]) \
    X(ms_truth_max,        ms,       0,    14,  "ms_truth_max",       none,      _,              s->truth[SL_MAX]) \
    X(ms_fit,              ms,       0,    17,  "ms_fit",             none,      _,              s->fit) \
    X(ms_map_render,       ms,       0,    18,  "ms_map_render",      none,      _,              s->map_render[SL_MED]) \
    X(ms_map_render_min,   ms,       0,    19,  "ms_map_render_min",  none,      _,              s->map_render[SL_MIN]) \
    X(ms_map_render_max,   ms,       0,    20,  "ms_map_render_max",  none,      _,              s->map_render[SL_MAX]) \
    X(ms_map_readback,     ms,       0,    21,  "ms_map_readback",    none,      _,              s->map_readback) \
    X(ms_method,           ms,       0,    22,  "ms_method",          none,      _,              s->method[SL_MED]) \
    X(ms_method_min,       ms,       0,    23,  "ms_method_min",      none,      _,              s->method[SL_MIN]) \
    X(ms_method_max,       ms,       0,    24,  "ms_method_max",      none,      _,              s->method[SL_MAX]) \
    X(ms_ray_step,         ms,       0,    25,  "ms_ray_step",        none,      _,              cl->cost.ms_trace) \
    X(ms_step1,            ms,       0,    26,  "ms_step1",           none,      _,              cl->cost.ms_step[0]) \
    X(ms_step2,            ms,       0,    27,  "ms_step2",           none,      _,              cl->cost.ms_step[1]) \
    X(ms_step3,            ms,       0,    28,  "ms_step3",           none,      _,              cl->cost.ms_step[2]) \
    X(ms_step4,            ms,       0,    29,  "ms_step4",           none,      _,              cl->cost.ms_step[3]) \
    X(ms_contours,         ms,       0,    36,  "ms_contours",        none,      _,              s->contours) \
    X(ms_figures,          ms,       0,    37,  "ms_figures",         none,      _,              s->figures) \
    X(ms_overlay,          ms,       0,    38,  "ms_overlay",         none,      _,              s->overlay) \
    X(ms_gpu_gbuffer,      ms,       0,    39,  "ms_gpu_gbuffer",     none,      _,              s->gpu_gbuffer[SL_MED]) \
    X(ms_gpu_map,          ms,       0,    40,  "ms_gpu_map",         none,      _,              s->gpu_map[SL_MED]) \
    X(ms_flicker,          ms,       0,    41,  "ms_flicker",         none,      _,              s->flicker) \
    X(texels,              count,    0,    42,  "texels",             none,      _,              cl->texels) \
    X(faces,               count,    0,    43,  "faces",              none,      _,              cl->faces) \
    X(ms_face_max,         ms,       0,    44,  "ms_face_max",        none,      _,              cl->ms_face_max) \
    X(overlay,             path,     1500, 0,   "",                   none,      _,              _) \
    X(truth_cached,        flag,     0,    15,  "truth_cached",       none,      _,              cl->truth_cached) \
    X(n_outside_cone,      count,    0,    0,   "",                   none,      _,              cl->n_outside_cone) \
    X(light,               text,     48,   0,   "",                   none,      _,              cl->light) \
    X(frac,                runs,     0,    0,   "",                   none,      _,              cl->has_frac) \
    X(family,              text,     40,   0,   "",                   none,      _,              sl_method_family(cm->method)) \
    X(beside,              text,     64,   0,   "",                   none,      _,              sl_method_beside(cm->method)) \
    X(display,             text,     64,   0,   "",                   none,      _,              cm->display) \
    X(nonfinite,           count,    0,    45,  "nonfinite",          invariant, nonfinite,      cl->nonfinite) \
    X(ms_map,              ms,       0,    46,  "ms_map",             none,      _,              s->st_map) \
    X(ms_post,             ms,       0,    47,  "ms_post",            none,      _,              s->st_post) \
    X(ms_lookup,           ms,       0,    48,  "ms_lookup",          none,      _,              s->st_lookup) \
    X(ms_readback,         ms,       0,    49,  "ms_readback",        none,      _,              s->st_readback) \
    X(ms_cost,             ms,       0,    50,  "ms_cost",            none,      _,              s->total[SL_MED]) \
    X(ms_cost_min,         ms,       0,    51,  "ms_cost_min",        none,      _,              s->total[SL_MIN]) \
    X(ms_cost_max,         ms,       0,    52,  "ms_cost_max",        none,      _,              s->total[SL_MAX]) \
    X(ms_gpu_post,         ms,       0,    53,  "ms_gpu_post",        none,      _,              s->gpu_post) \
    X(ms_gpu_lookup,       ms,       0,    54,  "ms_gpu_lookup",      none,      _,              s->gpu_lookup) \
    X(runs_map,            runs,     0,    55,  "runs_map",           none,      _,              s->runs_map)
/* clang-format on */

/* One enumerator per column: SL_COL_<name>. */
enum sl_cell_col {
#define SL_COL_ENUM(name, kind, size, csv, head, check, key, from) SL_COL_##name,
    SL_CELL_COLUMNS(SL_COL_ENUM)
#undef SL_COL_ENUM
    SL_COL_COUNT
};

/* The record's field of each kind (none for viewport and wrong). */
#define SL_CELL_FIELD_text(name, size)     char name[size];
#define SL_CELL_FIELD_path(name, size)     char name[size];
#define SL_CELL_FIELD_dim(name, size)      int name;
#define SL_CELL_FIELD_index(name, size)    int name;
#define SL_CELL_FIELD_runs(name, size)     int name;
#define SL_CELL_FIELD_count(name, size)    uint64_t name;
#define SL_CELL_FIELD_ms(name, size)       double name;
#define SL_CELL_FIELD_viewport(name, size)
#define SL_CELL_FIELD_wrong(name, size)
#define SL_CELL_FIELD_flag(name, size)     int name;

/* The value of a count of record r (kinds count and wrong). */
#define SL_CELL_U64_count(r, name) ((r)->name)
#define SL_CELL_U64_wrong(r, name) ((r)->fig.wrong_image)

struct sl_cell_record {
    /* key, counts and costs: one field per column above */
#define SL_CELL_FIELD(name, kind, size, csv, head, check, key, from) SL_CELL_FIELD_##kind(name, size)
    SL_CELL_COLUMNS(SL_CELL_FIELD)
#undef SL_CELL_FIELD
    struct sl_figures fig;             /* hard shadows (fig.nregions = 0 for a soft method's cell) */
    int      has_soft;                 /* an area light: the soft figures below; a hard method's cell
                                        * has both, its hard figures against the light's centre */
    struct sl_soft_figures soft;
    int      has_alias;                /* a hard cell's pixels by aliasing error m (aliasing.h), per region */
    struct sl_alias_figures alias;
    /* the run's, not columns of the cell */
    char     study[64];                /* the config's name */
    int64_t  run_id;                   /* 0 when not from the store */
    /* provenance of the numbers, printed under each table and in CSV rows */
    char     git_sha[48], config_hash[24], machine[256];
    char     gl_renderer[128];         /* GL_RENDERER of the run: what its GL times were measured on */
};

/* *r with nothing known: zero keys and counts, every stage time NAN (not
 * measured), no figures. */
void sl_cell_record_init(struct sl_cell_record *r);

/* A region's name in the tables, the summaries, the store's figures and the
 * baselines: "image" for the whole image (thickness 0), else "<t>px". */
void sl_region_name(int thickness, char *out, size_t n);
/* The thickness a region name stands for; -1 if it names none (NULL too). */
int sl_region_thickness(const char *name);

#endif
