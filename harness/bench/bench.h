/*
 * bench.h — `shadowlab bench`: each stage of the harness against the plain
 * thing anyone would write for the same job, and the whole studies end to
 * end, each with its target:
 *
 * - truth: the truth pass against a plain Embree packet loop over the very
 *   same rays, both in the device's native width: its filtered trace
 *   against the plain trace (target: at least 0.9x its rays/s), end to end
 *   against the plain set-up + trace (at least 1x), and the trace again at
 *   each narrower width the CPU runs (bench_truth.c);
 * - layers: every shadow-map layer shadowmap.c renders, and the G-buffer,
 *   against a plain raster of the same mesh at the same size and matrix
 *   (depth + one uint, trivial fragment shader, no geometry shader), timed
 *   the same way: render + glFinish, readback apart (target: within 2x);
 *   with the GL counters (GS primitives, fragment shader invocations) so the
 *   comparison carries to a GPU;
 * - backends: context creation, the G-buffer and each layer through OSMesa
 *   and through EGL in the same process, side by side (wall min and median,
 *   CPU, GPU time; target: EGL's min within 5% of OSMesa's per stage);
 *   skipped, with a line, when one of the two is not built;
 * - moderno, morais: configs/moderno-2011.yaml and configs/morais-2015.yaml
 *   through sl_run, no files, no store, no truth cache (targets: 60 s and
 *   300 s of wall time);
 * - jobs: the CONFIG given, else configs/morais-2015.yaml, as one process
 *   against `run --jobs 2`, both with files, store and no truth cache, wall
 *   and CPU time, the views the split computes twice and the merge time per
 *   1,000 cells (target: --jobs 2 no slower than one process; bench_jobs.c);
 * - churn: NSM's layer at the map size S and 2S (2048^2, 4096^2) through the pass's kept render
 *   target and pooled arrays against a target and arrays made afresh, wall,
 *   CPU and minor page faults (target: 2S at most 5x S;
 *   bench_churn.c);
 * - techniques: each technique package of the source tree's techniques/
 *   (pcf at kernel 3 and 5, the others at their defaults) at the layers'
 *   map size and viewport: its map pass against a plain package's writing
 *   the same maps (target: 1.3x), its post passes (blur, mipmaps) on rows of
 *   their own, its lookup against a plain one reading as many texels per
 *   pixel (target: 1.5x); wall, GPU and CPU time (bench_techniques.c);
 * - the studies' CPU time (user + sys), minor page faults and the peak RSS
 *   after each (targets: Moderno 12 s CPU; Morais 90 s CPU, 0.5 M faults,
 *   1 GiB; the RSS is the process's peak so far: run a study alone to read
 *   it as the study's);
 * - startup: `version`, `validate CONFIG` (default configs/default.yaml) and
 *   `help run` as child processes, against the same binary with OpenImageIO,
 *   OSMesa, EGL and Embree preloaded as when they were linked (target:
 *   validate's median under 50 ms; bench_startup.c);
 * - scoring: a cell's contours, figures and exactness count per 1 M pixels
 *   against one histogram pass over them, the fused pass and the one before
 *   it (target: 3x; bench_score.c);
 * - bigmap (only when named: it takes GBs): one view's conservative layers
 *   at 16384^2 (`--map N` for another size) as csm and csm_adj hold them,
 *   peak RSS, wall, CPU, faults, and each layer against a plain render
 *   (target: 6 GB; bench_mem.c);
 * - peak RSS of the process after all of it (target: under 2 GiB).
 *
 * A benchmark, not a test: a missed target is reported (MISS), not an
 * error; only a stage that fails to run returns one. Prints Markdown (and
 * optionally CSV, and the same Markdown under a provenance header into a
 * file: doc/performance.md is written so); the rows are also returned for
 * tests.
 * Owns: its own GL context and BVHs for the truth and layer stages (freed
 * before the studies, which make their own). Does not: write results files.
 */
#ifndef SL_BENCH_H
#define SL_BENCH_H
#include "glctx.h"
#include <stdint.h>
#include <stdio.h>
#include "config.h"

/* Stages, selectable by name (sl_bench_parse_stages). */
#define SL_BENCH_STAGES(X)   \
    X(TRUTH,   "truth")      \
    X(LAYERS,  "layers")     \
    X(BACKENDS, "backends")  \
    X(MODERNO, "moderno")    \
    X(MORAIS,  "morais")     \
    X(JOBS,    "jobs")       \
    X(CHURN,   "churn")      \
    X(TECHNIQUES, "techniques") \
    X(STARTUP, "startup")    \
    X(SCORING, "scoring")    \
    X(LIGHTFIT, "lightfit")  \
    X(BIGMAP,  "bigmap")     \
    X(TIMING,  "timing")

enum sl_bench_stage_bit {
#define SL_BENCH_BIT(id, name) SL_BENCH_BIT_##id,
    SL_BENCH_STAGES(SL_BENCH_BIT)
#undef SL_BENCH_BIT
    SL_BENCH_NSTAGES
};
#define SL_BENCH_STAGE(id) (1u << SL_BENCH_BIT_##id)
#define SL_BENCH_ALL ((1u << SL_BENCH_NSTAGES) - 1u)

struct sl_bench_opts {
    const char *config;    /* scene, viewpoints, viewport and threads of the truth and layer
                            * stages from its first scene; NULL = the defaults below */
    unsigned    stages;    /* SL_BENCH_STAGE bits; 0 = all */
    int         reps;      /* timed repetitions (after one warm-up); 0 = 7 */
    const char *scene;     /* NULL = the config's first scene, else "bench" (54,200 triangles) */
    int         width, height; /* viewport; 0 = the config's first, else 1024x1024 */
    int         map;       /* shadow-map size of the layer stage; 0 = 2048 (bigmap: 0 = 16384) */
    const char *moderno;   /* study configs; NULL = configs/moderno-2011.yaml, */
    const char *morais;    /*                      configs/morais-2015.yaml */
    const char *csv;       /* also write the rows here as CSV; NULL = no */
    const char *markdown;  /* also write the Markdown here, under a header (machine, CPU, GL, git
                            * SHA, load average, the command: /proc/self/cmdline), atomically
                            * (a temporary file renamed) and only when every stage ran; NULL = no */
    FILE       *out;       /* Markdown; NULL = stdout */
    enum sl_gl_backend gl; /* GL context of every stage; SL_GL_DEFAULT = OSMesa where built
                            * (the studies: their config's 'gl') */
};

enum sl_bench_cmp { SL_BENCH_AT_LEAST, SL_BENCH_AT_MOST };

/* One measurement against its target. `plain` is the plain counterpart's
 * value (0 = none); the target applies to `ratio` when there is one, else
 * to `value`. */
struct sl_bench_row {
    char     stage[16];    /* truth, gbuffer, layer, study, memory */
    char     name[64];     /* what was measured */
    char     unit[16];
    double   value, plain, ratio;
    double   target;
    enum sl_bench_cmp cmp;
    int      pass;
    uint64_t gs_prims, fragments, plain_fragments;   /* GL counters (layers, G-buffer) */
    char     note[128];
};

struct sl_bench_result {
    int nrows;
    struct sl_bench_row rows[96];
};

/* "truth,layers" -> bits; SL_E_USAGE naming the unknown one otherwise. */
enum sl_err sl_bench_parse_stages(const char *list, unsigned *out, struct sl_diag *d);

/* res may be NULL. */
enum sl_err sl_bench(const struct sl_bench_opts *o, struct sl_bench_result *res, struct sl_diag *d);

#endif
