/*
 * main.c — the command line. The only place that prints errors and exits:
 * 0 success, 1 a check failed, 2 bad input or usage (and any other failure
 * that leaves no result).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "bench.h"
#include "check.h"
#include "config.h"
#include "method.h"
#include "provenance.h"
#include "report.h"
#include "run.h"
#include "scene.h"
#include "scenefile.h"
#include "store.h"
#include "submit.h"
#include "summary.h"
#include "table.h"
#include "util.h"

static const char usage[] =
    "usage: shadowlab <command> [--help] ...\n"
    "  run CONFIG [options]       run an experiment (shadowlab run --help)\n"
    "  validate FILE              check a config or a scene file without GL or Embree\n"
    "  table DB [options]         regenerate tables from a results store\n"
    "  report DB [--out DIR]      HTML and Markdown report of a results store (needs gnuplot)\n"
    "  check DB --baseline FILE   compare a results store with a committed baseline (exit 1 if outside)\n"
    "  bench [CONFIG] [options]   every stage against its plain counterpart, the studies, their targets\n"
    "  submit CONFIG --slurm ...  the sweep as a Slurm job array plus a merge job (shadowlab submit --help)\n"
    "  merge SHARD.db... -o DB    the stores of a split sweep into one; exit 1 if a cell is missing\n"
    "  list methods|scenes        what can be named in a config\n"
    "  version                    the git SHA this binary was built from\n";

static const char usage_run[] =
    "usage: shadowlab run CONFIG [--out DIR] [--cells A:B] [--resume] [--db FILE] [--no-cache]\n"
    "                     [--cache DIR] [--gl osmesa|egl] [--jobs N]\n"
    "  --out DIR     output root (default results/): tables and overlays go to DIR/<name>/\n"
    "  --cells A:B   compute only cells A..B-1 of the sweep (scene x viewport x viewpoint x map x method)\n"
    "  --resume      skip cells the results store already holds for this config\n"
    "  --db FILE     results store (default: the config's 'store', else DIR/shadowlab.db)\n"
    "  --no-cache    trace the truth even when DIR/cache holds it\n"
    "  --cache DIR   the truth cache (default DIR/cache; written atomically, may be shared)\n"
    "  --jobs N      N worker processes over slices of the sweep (whole views kept together), their\n"
    "                stores merged into DB; the same cells as one process\n"
    "  --gl B        the GL context: osmesa (the default where built) or egl (GPU machines;\n"
    "                SHADOWLAB_EGL_DEVICE=N picks an EGL device); replaces the config's 'gl'\n"
    "  One run writes a results store at a time (a lock on DB.lock); a second is refused\n"
    "  with exit 2, naming the holder's pid. Exit codes: 0 done, 1 a check failed, 2 bad input or\n"
    "  usage, 3 a system failure (output not writable, GL, Embree, memory).\n";

static const char usage_validate[] =
    "usage: shadowlab validate FILE\n"
    "  Parses and checks an experiment config or a scene file (scene files have 'meshes',\n"
    "  'light' or 'base'); loads the scenes and model files it names; touches no GL or Embree.\n";

static const char usage_table[] =
    "usage: shadowlab table DB [--format md|csv|latex] [--scene S] [--viewpoint V] [--label L]\n"
    "                          [--map N] [--run ID]\n"
    "                          [--summary FIGURE [--region N|image|contours] [--lower-is-better]\n"
    "                           [--average-case SCENE/VIEWPOINT/N[/MAP]]]\n"
    "  Renders the latest stored cell of each key, filtered, as thesis-style tables; with\n"
    "  --summary, the average, best and worst per map size of one figure's percentage over\n"
    "  the cells of one label (as the theses' summary tables), md or csv.\n";

static const char usage_report[] =
    "usage: shadowlab report RESULTS_DB [--out DIR]\n"
    "  Writes DIR/report.html (self-contained, offline) and DIR/report.md with the thesis-style\n"
    "  tables of every study (and their .tex), the chain's steps and accuracy-vs-cost plots\n"
    "  (gnuplot, SVG), costs, the error overlays and the provenance of every run.\n"
    "  --out DIR     output folder (default: <folder of RESULTS_DB>/report)\n";

static const char usage_check[] =
    "usage: shadowlab check DB --baseline FILE [--study NAME] [--rows N] [--update]\n"
    "  Compares the latest stored cell of each key with the baseline FILE: violations of a\n"
    "  method's exactness always exactly; every count exactly when the store was measured on\n"
    "  the baseline's machine; otherwise each class of figure within the baseline's tolerance\n"
    "  (percentage points). Prints what moved and by how much; exit 1 when anything is outside\n"
    "  tolerance or a baseline cell is missing, 2 on bad input.\n"
    "  --study NAME  only cells of that config name\n"
    "  --rows N      show at most N moved values (default 200)\n"
    "  --update      write FILE from DB instead (keeps FILE's tolerances): a deliberate refresh\n";

static const char usage_bench[] =
    "usage: shadowlab bench [CONFIG] [--only LIST] [--reps N] [--scene S] [--viewport WxH] [--map N]\n"
    "                       [--csv FILE] [--gl osmesa|egl]\n"
    "  Each measurement against its target, as a Markdown table with PASS/MISS:\n"
    "    truth    the truth pass vs a plain Embree rtcOccluded16 loop over the same rays (>= 0.8x)\n"
    "    layers   the G-buffer and every shadow-map layer vs a plain raster of the same mesh, size\n"
    "             and matrix, with GL counters (render time within 2x)\n"
    "    moderno  configs/moderno-2011.yaml end to end, no files, no cache (< 60 s)\n"
    "    morais   configs/morais-2015.yaml end to end, no files, no cache (< 300 s)\n"
    "  and the peak RSS after all of it (< 2 GiB). A missed target exits 0; a failure exits 2.\n"
    "  --only LIST     comma-separated stages (default all); `--only truth,layers` is the quick mode\n"
    "  --reps N        timed repetitions after one warm-up (default 7)\n"
    "  --scene S       scene of the truth and layer stages (default: CONFIG's first scene, else bench)\n"
    "  --viewport WxH  their viewport (default: CONFIG's first, else 1024x1024)\n"
    "  --map N         the layers' map size (default 2048)\n"
    "  --csv FILE      also write the summary rows as CSV\n"
    "  --gl B          the GL context of every stage: osmesa (default where built) or egl\n";

static const char usage_submit[] =
    "usage: shadowlab submit CONFIG --slurm [--tasks N | --cells-per-task K] [--max-running T]\n"
    "                        [--out DIR] [--partition P] [--time HH:MM:SS] [--mem M] [--dry-run]\n"
    "  Writes DIR/slurm/array.sh, an sbatch job array whose task i runs\n"
    "    shadowlab run CONFIG --cells A:B --out DIR/shards/task-i --db DIR/shards/task-i/shadowlab.db\n"
    "                         --cache DIR/cache --resume\n"
    "  and DIR/slurm/merge.sh, which merges the shards into DIR/shadowlab.db; without --dry-run,\n"
    "  submits both (the merge with --dependency=afterok on the array) and prints the job ids.\n"
    "  --tasks N            N tasks (default: one per 256 cells); cuts move to view boundaries\n"
    "  --cells-per-task K   tasks of about K cells\n"
    "  --max-running T      at most T tasks at once (--array=0-(N-1)%T)\n"
    "  --out DIR            default results/; must be on a filesystem every node sees\n";

static const char usage_merge[] =
    "usage: shadowlab merge SHARD.db... -o STORE.db\n"
    "  Copies the runs and cells of each shard (one config, the same in every shard) into STORE.db,\n"
    "  one transaction per shard; a cell already there is a duplicate and is not copied again. The\n"
    "  overlays and EXR files go under STORE.db's folder. Names the cells of the sweep no shard\n"
    "  holds; exit 1 when any is missing, 2 when a shard holds another config or cannot be read.\n";

static const char usage_list[] = "usage: shadowlab list methods|scenes\n";

/* 2: bad input or usage (a config, a scene, a model, an option, a store or
 * file that cannot be read as what it should be); 3: a system failure (an
 * output that cannot be written, GL, Embree, memory, an internal error). */
static int exit_code(enum sl_err e)
{
    switch (e) {
    case SL_E_OUTPUT: case SL_E_GL: case SL_E_EMBREE: case SL_E_NOMEM: case SL_E_IMAGE: case SL_E_INTERNAL:
        return 3;
    default:
        return 2;
    }
}

static int fail(enum sl_err e, const struct sl_diag *d)
{
    char line[1200];
    sl_diag_format(d, e, line, sizeof line);
    fprintf(stderr, "shadowlab: %s\n", line);
    return exit_code(e);
}

static int usage_error(const char *msg, const char *text)
{
    fprintf(stderr, "shadowlab: %s\n%s", msg, text);
    return 2;
}

static int wants_help(int argc, char **argv)
{
    for (int i = 2; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return 1;
    return 0;
}

/* "A:B" -> [A, B); "A:" -> [A, end) */
static int parse_cells(const char *s, int *a, int *b)
{
    char *end;
    long x = strtol(s, &end, 10);
    if (end == s || *end != ':' || x < 0)
        return 0;
    const char *t = end + 1;
    long y = 0;
    if (*t) {
        y = strtol(t, &end, 10);
        if (end == t || *end || y <= x)
            return 0;
    }
    *a = (int)x;
    *b = (int)y;
    return 1;
}

/* What a run says along the way, on stderr: notes, violations and
 * non-finite values always; progress as one rewritten line on a terminal. */
struct event_state {
    int tty;
};

static void print_event(const struct sl_run_event *ev, void *user)
{
    const struct event_state *es = user;
    const struct sl_config *c = ev->config;
    const struct sl_cell *cl = ev->cell;
    switch (ev->kind) {
    case SL_EVENT_FRUSTUM_NOTE:
        fprintf(stderr, "shadowlab: note: %s/%s: the point frustum of the area light's centre leaves %u PFL "
                        "pixel(s) outside its map (the exact methods trace them) and %u triangle(s) out of the "
                        "conservative layers (tested on the CPU instead)\n",
                ev->scene, ev->viewpoint, ev->box->n_outside, ev->box->n_unmapped);
        break;
    case SL_EVENT_VIOLATIONS: {
        static const char *const layer_names[SL_LAYER_COUNT] = {"depth", "depth_back", "bgsm", "bgsm2", "sgsm",
                                                                "sgsm_adj"};
        fprintf(stderr, "shadowlab: VIOLATION: %s/%s %dx%d map %d '%s': %llu pixel(s) break its exactness\n",
                cl->scene, cl->viewpoint, c->viewport_w[cl->key.viewport], c->viewport_h[cl->key.viewport],
                c->maps[cl->key.map], c->methods[cl->key.method].label, (unsigned long long)cl->violations);
        for (uint64_t k = 0; k < cl->violations && k < SL_MAX_VIOLATIONS; k++) {
            const struct sl_violation *o = &cl->violation[k];
            fprintf(stderr, "  pixel (%d, %d): truth %d, verdict %d, how %d, own triangle %u, texel (%d, %d):",
                    o->x, o->y, o->truth, o->verdict, o->how, o->own_tri ? o->own_tri - 1 : 0, o->tx, o->ty);
            for (int l = 0; l < SL_LAYER_COUNT; l++)
                if (o->layer_tri[l])
                    fprintf(stderr, " %s triangle %u", layer_names[l], o->layer_tri[l] - 1);
            fputc('\n', stderr);
        }
        break;
    }
    case SL_EVENT_NONFINITE:
        fprintf(stderr, "shadowlab: NON-FINITE: %s/%s map %d '%s': %llu G-buffer or shadow-map value(s) "
                        "not finite or out of range\n", cl->scene, cl->viewpoint, c->maps[cl->key.map],
                c->methods[cl->key.method].label, (unsigned long long)cl->nonfinite);
        break;
    case SL_EVENT_PROGRESS: {
        if (!es->tty)
            break;
        double el = ev->elapsed_s;
        double eta = ev->done ? el * (double)(ev->total - ev->done) / (double)ev->done : 0.0;
        fprintf(stderr, "\r[%d/%d] %s/%s %d² %-16s %6.1fs elapsed, ~%.0fs left   ", ev->done, ev->total, cl->scene,
                cl->viewpoint, c->maps[cl->key.map], c->methods[cl->key.method].label, el, eta);
        if (ev->done == ev->total)
            fputc('\n', stderr);
        fflush(stderr);
        break;
    }
    }
}

/* What a merge did, shard by shard, and the cells of the sweep it lacks. */
static int print_merge(const char *const *shards, const struct sl_shards_result *r, const char *out)
{
    for (int i = 0; i < r->nshards; i++) {
        const struct sl_merge_shard *s = &r->shard[i];
        if (r->absent[i])
            fprintf(stderr, "shadowlab: merge: %s: not there (its cells are missing below)\n", shards[i]);
        else
            printf("%s: %d cell(s) copied, %d duplicate(s) skipped, %d run(s), %d overlay(s)%s\n", shards[i],
                   s->cells, s->duplicates, s->runs, s->overlays, s->overlays_missing ? " (some not found)" : "");
    }
    const struct sl_config *c = &r->config;
    for (int i = 0; i < r->nmissing && i < 50; i++) {
        struct sl_cell_key k;
        sl_plan_cell(c, r->missing[i], &k);
        fprintf(stderr, "shadowlab: merge: missing cell %d: %s/%s %dx%d map %d '%s'\n", r->missing[i],
                c->scenes[k.scene].name, c->scenes[k.scene].viewpoints[k.vp], c->viewport_w[k.viewport],
                c->viewport_h[k.viewport], c->maps[k.map], c->methods[k.method].label);
    }
    if (r->nmissing > 50)
        fprintf(stderr, "shadowlab: merge: ... and %d more missing\n", r->nmissing - 50);
    printf("merged into %s: %d of %d cell(s) of the sweep stored, %d missing; %d copied, %d duplicate(s), "
           "%.2f s (%.1f ms per 1,000 cells)\n", out, r->total - r->nmissing, r->total, r->nmissing, r->copied,
           r->duplicates, r->seconds, r->copied ? 1e6 * r->seconds / r->copied : 0.0);
    return r->nmissing ? 1 : 0;
}

static int run_jobs(const struct sl_config *c, const struct sl_jobs_opts *o)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_jobs_result r;
    enum sl_err e = sl_jobs_run(c, o, &r, &d);
    for (int i = 0; i < r.nworkers; i++)
        fprintf(stderr, "shadowlab: worker %d: cells %d:%d, exit %d, %.1f s wall, %.1f s CPU%s%s\n", i,
                r.w[i].first, r.w[i].last, r.w[i].status, r.w[i].wall_s, r.w[i].cpu_s,
                r.w[i].status ? ", log " : "", r.w[i].status ? r.w[i].log : "");
    fprintf(stderr, "shadowlab: %d worker(s), %.1f s wall, %.1f s CPU; %d of %d view(s) started twice by the split\n",
            r.nworkers, r.wall_s, r.cpu_s, r.split_views, r.nviews);
    int rc = e ? fail(e, &d) : 0;
    if (!e) {
        const char *shards[64];
        char paths[64][1300];
        for (int i = 0; i < r.nworkers; i++) {
            snprintf(paths[i], sizeof paths[i], "%s/task-%d/shadowlab.db", r.workdir, i);
            shards[i] = paths[i];
        }
        rc = print_merge(shards, &r.merge, r.store);
    }
    sl_jobs_result_free(&r);
    return rc;
}

static int cmd_merge(int argc, char **argv)
{
    const char *out = NULL;
    const char **shards = calloc((size_t)argc, sizeof *shards);
    int n = 0;
    if (!shards)
        return 3;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (argv[i][0] == '-') {
            free(shards);
            return usage_error("merge: unknown option", usage_merge);
        } else
            shards[n++] = argv[i];
    }
    if (!out || !n) {
        free(shards);
        return usage_error("merge: wants SHARD.db... and -o STORE.db", usage_merge);
    }
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_shards_result r;
    enum sl_err e = sl_shards_merge(shards, n, out, 0, &r, &d);
    int rc = e ? fail(e, &d) : print_merge(shards, &r, out);
    sl_shards_result_free(&r);
    free(shards);
    return rc;
}

static int cmd_submit(int argc, char **argv)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_submit_opts o;
    enum sl_err e = sl_submit_parse(argc, argv, &o, &d);
    if (e) {
        char line[1200];
        sl_diag_format(&d, e, line, sizeof line);
        return usage_error(line, usage_submit);
    }
    struct sl_config c;
    if ((e = sl_config_load(o.config, &c, &d)))
        return fail(e, &d);
    static struct sl_submit_result r;
    if ((e = sl_submit(&c, &o, &r, &d)))
        return fail(e, &d);
    printf("%d task(s) over %d cell(s):", r.ntasks, r.total);
    for (int i = 0; i < r.ntasks; i++)
        printf(" %d:%d", r.bounds[i], r.bounds[i + 1]);
    printf("\n%d of %d view(s) start in two tasks (their G-buffer and truth are computed twice)\n",
           r.split_views, r.nviews);
    printf("array script: %s\nmerge script: %s\nmerged store: %s\n", r.array_script, r.merge_script, r.merged);
    if (!o.dry_run)
        printf("array job %s, merge job %s (afterok:%s)\n", r.array_job, r.merge_job, r.array_job);
    return 0;
}

static int cmd_run(int argc, char **argv)
{
    const char *cfg = NULL;
    struct sl_run_opts o = {.table_out = stdout, .write_files = 1, .on_event = print_event};
    struct event_state es = {.tty = isatty(2)};
    o.user = &es;
    int no_cache = 0, jobs = 1;
    enum sl_gl_backend gl = SL_GL_DEFAULT;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            o.out_root = argv[++i];
        else if (strcmp(argv[i], "--gl") == 0 && i + 1 < argc) {
            if (!(gl = sl_gl_backend_parse(argv[++i])))
                return usage_error("run: --gl wants osmesa or egl", usage_run);
        }
        else if (strcmp(argv[i], "--db") == 0 && i + 1 < argc)
            o.store = argv[++i];
        else if (strcmp(argv[i], "--cells") == 0 && i + 1 < argc) {
            if (!parse_cells(argv[++i], &o.first, &o.last))
                return usage_error("run: --cells wants A:B with 0 <= A < B (or A:)", usage_run);
        } else if (strcmp(argv[i], "--resume") == 0)
            o.resume = 1;
        else if (strcmp(argv[i], "--no-cache") == 0)
            no_cache = 1;
        else if (strcmp(argv[i], "--cache") == 0 && i + 1 < argc)
            o.cache_dir = argv[++i];
        else if (strcmp(argv[i], "--jobs") == 0 && i + 1 < argc) {
            if ((jobs = atoi(argv[++i])) < 1 || jobs > 64)
                return usage_error("run: --jobs wants 1..64", usage_run);
        } else if (argv[i][0] == '-')
            return usage_error("run: unknown option", usage_run);
        else if (!cfg)
            cfg = argv[i];
        else
            return usage_error("run: one config at a time", usage_run);
    }
    if (!cfg)
        return usage_error("run: missing CONFIG", usage_run);
    if (no_cache)
        o.cache_dir = "";
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_config c;
    enum sl_err e = sl_config_load(cfg, &c, &d);
    if (e)
        return fail(e, &d);
    if (gl)
        c.gl = gl;
    if (jobs > 1) {
        if (o.first || o.last)
            return usage_error("run: --jobs splits the whole sweep; --cells is for one task", usage_run);
        struct sl_jobs_opts jo = {.jobs = jobs, .out_root = o.out_root, .store = o.store, .cache = o.cache_dir,
                                  .gl = gl ? sl_gl_backend_name(gl) : NULL, .resume = o.resume};
        return run_jobs(&c, &jo);
    }
    struct sl_run_result r;
    e = sl_run(&c, &o, &r, &d);
    sl_run_result_free(&r);
    return e ? fail(e, &d) : 0;
}

/* A scene file has a top-level meshes, light or base key; a config has not. */
static int looks_like_scene(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char line[512];
    int scene = 0;
    while (!scene && fgets(line, sizeof line, f))
        scene = strncmp(line, "meshes:", 7) == 0 || strncmp(line, "light:", 6) == 0 ||
                strncmp(line, "base:", 5) == 0;
    fclose(f);
    return scene;
}

static int cmd_validate(int argc, char **argv)
{
    if (argc != 3)
        return usage_error("validate: one FILE", usage_validate);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (looks_like_scene(argv[2])) {
        struct sl_scene s;
        enum sl_err e = sl_scene_load(argv[2], &s, &d);
        if (e)
            return fail(e, &d);
        printf("%s: ok: scene '%s', %u triangles, %u vertices, %d mesh(es), %d viewpoint(s), "
               "bounds (%g, %g, %g) .. (%g, %g, %g)\n", argv[2], s.name, s.nt, s.nv, s.nranges, s.nvp,
               s.origin[0] + s.lo[0], s.origin[1] + s.lo[1], s.origin[2] + s.lo[2], s.origin[0] + s.hi[0],
               s.origin[1] + s.hi[1], s.origin[2] + s.hi[2]);
        sl_scene_free(&s);
        return 0;
    }
    struct sl_config c;
    enum sl_err e = sl_config_load(argv[2], &c, &d);
    if (e)
        return fail(e, &d);
    printf("%s: ok: %d scene(s), %d cell(s)\n", argv[2], c.nscenes, sl_plan_count(&c));
    sl_config_write(&c, stdout);
    return 0;
}

static int cmd_table(int argc, char **argv)
{
    const char *db = NULL;
    struct sl_store_filter f = {0};
    int fmt = SL_TABLE_MD;
    struct sl_summary_opts so = {.figure = -1, .region = -1};
    const char *summary = NULL;
    char avg_scene[64] = "", avg_vp[32] = "";
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--format") == 0 && v) {
            fmt = sl_table_format_parse(v);
            if (fmt < 0)
                return usage_error("table: --format md, csv or latex", usage_table);
            i++;
        } else if (strcmp(a, "--scene") == 0 && v) {
            f.scene = v; i++;
        } else if (strcmp(a, "--viewpoint") == 0 && v) {
            f.viewpoint = v; i++;
        } else if (strcmp(a, "--label") == 0 && v) {
            f.label = v; i++;
        } else if (strcmp(a, "--map") == 0 && v) {
            f.map_size = atoi(v); i++;
        } else if (strcmp(a, "--run") == 0 && v) {
            f.run_id = atoll(v); i++;
        } else if (strcmp(a, "--summary") == 0 && v) {
            summary = v; i++;
        } else if (strcmp(a, "--region") == 0 && v) {
            so.region = !strcmp(v, "image") ? 0 : !strcmp(v, "contours") ? -1 : atoi(v);
            if (so.region < -1 || (so.region > 0 && so.region % 2))
                return usage_error("table: --region N (even), image or contours", usage_table);
            i++;
        } else if (strcmp(a, "--lower-is-better") == 0) {
            so.lower_is_better = 1;
        } else if (strcmp(a, "--average-case") == 0 && v) {
            if (sscanf(v, "%63[^/]/%31[^/]/%d/%d", avg_scene, avg_vp, &so.avg_region, &so.avg_map) < 3)
                return usage_error("table: --average-case SCENE/VIEWPOINT/N[/MAP]", usage_table);
            so.avg_scene = avg_scene;
            so.avg_viewpoint = avg_vp;
            i++;
        } else if (a[0] == '-') {
            return usage_error("table: unknown option", usage_table);
        } else if (!db) {
            db = a;
        } else {
            return usage_error("table: one DB", usage_table);
        }
    }
    if (!db)
        return usage_error("table: missing DB", usage_table);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    FILE *probe = fopen(db, "rb");
    if (!probe) {
        sl_fail(&d, SL_E_IO, db, 0, NULL, "cannot read the results store");
        return fail(SL_E_IO, &d);
    }
    fclose(probe);
    struct sl_store *st = NULL;
    struct sl_cell_record *cells = NULL;
    int n = 0;
    enum sl_err e = sl_store_open_existing(db, &st, &d);
    if (!e)
        e = sl_store_query(st, &f, &cells, &n, &d);
    if (!e && n == 0)
        e = sl_fail(&d, SL_E_USAGE, db, 0, NULL, "no stored cell matches");
    if (!e && summary) {
        for (int k = 0; k < SL_FIG_COUNT; k++)
            if (!strcmp(sl_figure_name((enum sl_figure)k), summary))
                so.figure = k;
        if (so.figure < 0)
            e = sl_fail(&d, SL_E_USAGE, NULL, 0, "--summary", "unknown figure '%s'", summary);
        else
            e = sl_summary_write(stdout, (enum sl_table_format)fmt, cells, n, &so, &d);
    } else if (!e) {
        e = sl_table_write(stdout, (enum sl_table_format)fmt, db, cells, n, &d);
    }
    free(cells);
    sl_store_close(st);
    return e ? fail(e, &d) : 0;
}

static int cmd_report(int argc, char **argv)
{
    struct sl_report_opts o = {0};
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            o.out_dir = argv[++i];
        else if (argv[i][0] == '-')
            return usage_error("report: unknown option", usage_report);
        else if (!o.db)
            o.db = argv[i];
        else
            return usage_error("report: one RESULTS_DB", usage_report);
    }
    if (!o.db)
        return usage_error("report: missing RESULTS_DB", usage_report);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    char dir[1100];
    enum sl_err e = sl_report_write(&o, dir, sizeof dir, &d);
    if (e)
        return fail(e, &d);
    printf("report: %s/report.html, %s/report.md\n", dir, dir);
    return 0;
}

static int cmd_check(int argc, char **argv)
{
    const char *db = NULL, *baseline = NULL;
    struct sl_check_opts o = {0};
    int update = 0;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--baseline") == 0 && i + 1 < argc)
            baseline = argv[++i];
        else if (strcmp(argv[i], "--study") == 0 && i + 1 < argc)
            o.study = argv[++i];
        else if (strcmp(argv[i], "--rows") == 0 && i + 1 < argc) {
            char *end;
            long v = strtol(argv[++i], &end, 10);
            if (*end || v < 1 || v > 1000000)
                return usage_error("check: --rows wants a positive number", usage_check);
            o.max_rows = (int)v;
        } else if (strcmp(argv[i], "--update") == 0)
            update = 1;
        else if (argv[i][0] == '-')
            return usage_error("check: unknown option", usage_check);
        else if (!db)
            db = argv[i];
        else
            return usage_error("check: one results store at a time", usage_check);
    }
    if (!db || !baseline)
        return usage_error("check: wants DB and --baseline FILE", usage_check);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (update) {
        enum sl_err e = sl_check_write_baseline(db, baseline, o.study, &d);
        if (e)
            return fail(e, &d);
        fprintf(stderr, "shadowlab: wrote %s from %s\n", baseline, db);
        return 0;
    }
    struct sl_check_result r;
    enum sl_err e = sl_check(db, baseline, &o, stdout, &r, &d);
    if (e)
        return fail(e, &d);
    return r.failed || r.missing ? 1 : 0;
}

static int cmd_bench(int argc, char **argv)
{
    struct sl_bench_opts o = {.config = NULL, .reps = 0, .out = stdout};
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--reps") == 0 && val) {
            o.reps = atoi(argv[++i]);
            if (o.reps < 1 || o.reps > 1000)
                return usage_error("bench: --reps must be 1..1000", usage_bench);
        } else if (strcmp(a, "--only") == 0 && val) {
            enum sl_err e = sl_bench_parse_stages(argv[++i], &o.stages, &d);
            if (e)
                return usage_error(d.msg, usage_bench);
        } else if (strcmp(a, "--scene") == 0 && val) {
            o.scene = argv[++i];
        } else if (strcmp(a, "--viewport") == 0 && val) {
            char tail;
            if (sscanf(argv[++i], "%dx%d%c", &o.width, &o.height, &tail) != 2 || o.width < 1 || o.height < 1 ||
                o.width > 16384 || o.height > 16384)
                return usage_error("bench: --viewport wants WxH, 1..16384 each", usage_bench);
        } else if (strcmp(a, "--map") == 0 && val) {
            o.map = atoi(argv[++i]);
            if (o.map < 16 || o.map > 16384)
                return usage_error("bench: --map must be 16..16384", usage_bench);
        } else if (strcmp(a, "--csv") == 0 && val) {
            o.csv = argv[++i];
        } else if (strcmp(a, "--gl") == 0 && val) {
            if (!(o.gl = sl_gl_backend_parse(argv[++i])))
                return usage_error("bench: --gl wants osmesa or egl", usage_bench);
        } else if (a[0] == '-') {
            return usage_error("bench: unknown option or missing value", usage_bench);
        } else if (!o.config) {
            o.config = a;
        } else {
            return usage_error("bench: one CONFIG at most", usage_bench);
        }
    }
    enum sl_err e = sl_bench(&o, NULL, &d);
    return e ? fail(e, &d) : 0;
}

static int cmd_list(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[2], "methods") == 0) {
        for (int i = 0; i < sl_method_count(); i++)
            printf("%-12s %s\n", sl_method_at(i)->name, sl_method_at(i)->summary);
        return 0;
    }
    if (argc == 3 && strcmp(argv[2], "scenes") == 0) {
        static char names[256][64], descr[256][160];
        int n = sl_scene_list(names, descr, 256);
        for (int i = 0; i < n; i++)
            printf("%-12s %s\n", names[i], descr[i]);
        if (n == 0)
            fprintf(stderr, "shadowlab: no scene files in %s\n", sl_scenes_dir());
        return 0;
    }
    return usage_error("list: methods or scenes", usage_list);
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return usage_error("missing command", usage);
    const char *cmd = argv[1];
    static const struct {
        const char *name;
        int (*fn)(int, char **);
        const char *help;
    } verbs[] = {
        {"run", cmd_run, usage_run},
        {"validate", cmd_validate, usage_validate},
        {"table", cmd_table, usage_table},
        {"report", cmd_report, usage_report},
        {"check", cmd_check, usage_check},
        {"bench", cmd_bench, usage_bench},
        {"submit", cmd_submit, usage_submit},
        {"merge", cmd_merge, usage_merge},
        {"list", cmd_list, usage_list},
    };
    for (size_t i = 0; i < sizeof verbs / sizeof verbs[0]; i++)
        if (strcmp(cmd, verbs[i].name) == 0) {
            if (wants_help(argc, argv)) {
                fputs(verbs[i].help, stdout);
                return 0;
            }
            return verbs[i].fn(argc, argv);
        }
    if (strcmp(cmd, "version") == 0) {
        printf("shadowlab %s\n", sl_git_sha());
        return 0;
    }
    if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
        fputs(usage, stdout);
        return 0;
    }
    return usage_error("unknown command", usage);
}
