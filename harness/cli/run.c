/*
 * run.c — `shadowlab run`: one config (or a scene's default study) in this
 * process, or split over --jobs worker processes. What a run says along the
 * way goes to stderr (notes, violations, progress); stdout keeps the
 * summary and the "written to" line a script reads. SIGINT / SIGTERM stop
 * the run after the cell under way and say how to --resume.
 */
#define _GNU_SOURCE   /* getopt_long, setenv, sigaction */
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"
#include "config.h"
#include "preview.h"
#include "run.h"
#include "submit.h"

/* "A:B" -> [A, B); "A:" -> [A, end). Each bound a whole number that fits an
 * int (the sweep's size bounds them further once the config is read). */
static int parse_cells(const char *s, int *a, int *b, char *msg, size_t n)
{
    char first[32];
    const char *colon = strchr(s, ':');
    if (!colon || colon == s || (size_t)(colon - s) >= sizeof first) {
        snprintf(msg, n, "--cells wants A:B with 0 <= A < B (or A:)");
        return 0;
    }
    snprintf(first, sizeof first, "%.*s", (int)(colon - s), s);
    long long x, y = 0;
    char m[200];
    /* a whole number past int is past any sweep: INT_MAX stands for it, and
     * the check against the sweep names the text as given */
    const char *t[2] = {first, colon + 1};
    long long *v[2] = {&x, &y};
    for (int i = 0; i < 2 && (i == 0 || colon[1]); i++) {
        size_t k = strlen(t[i]);
        if (k && strspn(t[i], "0123456789") == k && (k > 10 || strtoll(t[i], NULL, 10) > INT_MAX))
            *v[i] = INT_MAX;
        else if (!cli_opt_int(t[i], 0, INT_MAX, v[i], m, sizeof m)) {
            snprintf(msg, n, "--cells %s: %s", s, m);
            return 0;
        }
    }
    if (colon[1] && (y <= x && x != INT_MAX)) {
        snprintf(msg, n, "--cells wants A:B with 0 <= A < B (or A:)");
        return 0;
    }
    *a = (int)x;
    *b = (int)y;
    return 1;
}

/* SIGINT / SIGTERM: the run stops after the cell under way; a second
 * signal kills at once (the default action, restored). */
static volatile int stop_signal;
static void on_stop(int sig)
{
    stop_signal = sig;
    signal(sig, SIG_DFL);
}

/* What a run says along the way, on stderr: notes, violations and
 * non-finite values always; progress as one rewritten line on a terminal,
 * else a line every 10 s or 5% of the cells (CI logs, nohup, batch jobs). */
struct event_state {
    int    tty, quiet;
    int    shown;   /* the live line is on the terminal (clear_progress) */
    double last_s;
    int    last_done;
};

static void fmt_dur(double s, char *out, size_t n)
{
    if (s < 60)
        snprintf(out, n, "%.0fs", s);
    else if (s < 3600)
        snprintf(out, n, "%dm%02ds", (int)s / 60, (int)s % 60);
    else
        snprintf(out, n, "%dh%02dm", (int)s / 3600, ((int)s % 3600) / 60);
}

/* The live line on a terminal is cleared before anything else is printed (a
 * note, the summary, an error): "\r\033[K" goes back to the line's start and
 * erases it, so what follows starts on a clean line and no stale progress
 * is left above the summary. */
static void clear_progress(struct event_state *es)
{
    if (es->tty && es->shown) {
        fputs("\r\033[K", stderr);
        fflush(stderr);
        es->shown = 0;
    }
}

static void print_progress(const struct sl_run_event *ev, struct event_state *es)
{
    const struct sl_config *c = ev->config;
    const struct sl_cell *cl = ev->cell;
    double el = ev->elapsed_s;
    double eta = ev->done ? el * (double)(ev->total - ev->done) / (double)ev->done : 0.0;
    if (es->tty) {
        fprintf(stderr, "\r[%d/%d] %s/%s %d² %-16s %6.1fs elapsed, ~%.0fs left   ", ev->done, ev->total, cl->scene,
                cl->viewpoint, c->maps[cl->key.map], c->methods[cl->key.method].label, el, eta);
        es->shown = 1;
        fflush(stderr);
        return;
    }
    int step = (ev->total + 19) / 20;   /* 5% of the cells, at least one */
    if (ev->done != ev->total && el - es->last_s < 10.0 && ev->done - es->last_done < step)
        return;
    char e1[32], e2[32];
    fmt_dur(el, e1, sizeof e1);
    fmt_dur(eta, e2, sizeof e2);
    fprintf(stderr, "shadowlab: %d/%d cells (%.0f%%), %s elapsed, ~%s left\n", ev->done, ev->total,
            100.0 * ev->done / (ev->total ? ev->total : 1), e1, e2);
    fflush(stderr);
    es->last_s = el;
    es->last_done = ev->done;
}

static void print_event(const struct sl_run_event *ev, void *user)
{
    struct event_state *es = user;
    const struct sl_config *c = ev->config;
    const struct sl_cell *cl = ev->cell;
    if (ev->kind != SL_EVENT_PROGRESS)
        clear_progress(es);
    switch (ev->kind) {
    case SL_EVENT_FRUSTUM_NOTE:
        if (es->quiet)
            break;
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
        fprintf(stderr, "shadowlab: NON-FINITE: %s/%s map %d '%s': %llu value(s) not finite or out of range "
                        "(G-buffer, shadow maps, the method's visibility)\n", cl->scene, cl->viewpoint,
                c->maps[cl->key.map],
                c->methods[cl->key.method].label, (unsigned long long)cl->nonfinite);
        break;
    case SL_EVENT_PROGRESS:
        if (!es->quiet)
            print_progress(ev, es);
        break;
    }
}

/* One screen: what ran, how long, one headline figure per label. */
static void print_summary(const struct sl_config *c, const struct sl_run_result *r)
{
    printf("%s: %d cell(s) computed, %d already stored, in %.1f s (%s)\n", c->name, r->ncells, r->skipped,
           r->ms_total / 1e3, r->prov.gl_renderer);
    if (!r->ncells)
        return;
    int timed = 0;   /* none in a --jobs parent: its workers timed the stages */
    for (int k = 0; k < SL_REP_KINDS; k++)
        timed += r->reps.kind[k].stages;
    if (timed) {
        char timing[1024];
        sl_reps_describe(&r->reps, r->ms_total, timing, sizeof timing);
        printf("%s\n", timing);
    }
    printf("%-20s %6s %14s %12s\n", "label", "cells", "wrong pixels", "of pixels");
    for (int m = 0; m < c->nmethods; m++) {
        uint64_t wrong = 0, pixels = 0, nonfinite = 0;
        double mae = 0, frac = 0;
        int n = 0, nsoft = 0, nfrac = 0, nbad = 0;
        for (int i = 0; i < r->ncells; i++) {
            const struct sl_cell *cl = &r->cells[i];
            if (cl->key.method != m)
                continue;
            n++;
            nonfinite += cl->nonfinite;
            nbad += cl->nonfinite > 0;
            if (cl->has_frac) {
                nfrac++;
                frac += cl->soft.pct[SL_SFIG_soft_mae];
            } else if (cl->has_soft) {
                nsoft++;
                mae += cl->soft.pct[SL_SFIG_soft_mae];
                continue;
            }
            const struct sl_region_figures *img = &cl->fig.r[cl->fig.nregions - 1];   /* the whole image */
            wrong += img->n[SL_FIG_wrong];
            pixels += img->n[SL_FIG_pixels];
        }
        if (!n)
            continue;
        if (nsoft == n)
            printf("%-20s %6d %14s %11.3f%% mean absolute error of visibility", c->methods[m].label, n, "-",
                   mae / nsoft);
        else if (nfrac)
            printf("%-20s %6d %14llu %11.3f%%   mean |v - truth| %.3f%% of PFL", c->methods[m].label, n,
                   (unsigned long long)wrong, pixels ? 100.0 * (double)wrong / (double)pixels : 0.0, frac / nfrac);
        else
            printf("%-20s %6d %14llu %11.3f%%", c->methods[m].label, n, (unsigned long long)wrong,
                   pixels ? 100.0 * (double)wrong / (double)pixels : 0.0);
        /* a value not finite is a result of its own, left out of the figures above */
        if (nbad)
            printf("   NON-FINITE: %llu value(s) in %d cell(s)", (unsigned long long)nonfinite, nbad);
        putchar('\n');
    }
}

/* A run stopped by SIGINT or SIGTERM: what is stored and the command that
 * goes on; the exit status 128 + the signal. */
static int say_interrupted(int stored, int total, const char *store_path, int resume, int argc, char **argv)
{
    fflush(stdout);
    fprintf(stderr, "shadowlab: interrupted (%s): %d of %d cell(s) of this config are stored%s%s; "
                    "to go on:\n  shadowlab", stop_signal == SIGTERM ? "SIGTERM" : "SIGINT", stored,
            total, store_path[0] ? " in " : "", store_path);
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        int plain = strspn(a, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:,") ==
                    strlen(a);
        fprintf(stderr, plain ? " %s" : " '%s'", a);
    }
    fprintf(stderr, "%s\n", resume ? "" : " --resume");
    return 128 + (stop_signal == SIGTERM ? SIGTERM : SIGINT);
}

static int run_jobs(const struct sl_config *c, const struct sl_jobs_opts *o, int argc, char **argv)
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
    int rc = e ? cli_fail(e, &d) : 0;
    if (!e) {
        const char *shards[64];
        char paths[64][1300];
        for (int i = 0; i < r.nworkers; i++) {
            snprintf(paths[i], sizeof paths[i], "%s/task-%d/shadowlab.db", r.workdir, i);
            shards[i] = paths[i];
        }
        rc = cli_print_merge(shards, &r.merge, r.store);
        for (int i = 0; i < r.overlays_missing && i < 10; i++)
            fprintf(stderr, "shadowlab: missing overlay: %s\n", r.missing_overlay[i]);
        if (r.overlays_missing) {
            fprintf(stderr, "shadowlab: %d overlay(s) the store's cells of this config name are not on disk\n",
                    r.overlays_missing);
            rc = 1;
        }
        if (r.interrupted) {
            fflush(stdout);
            fprintf(stderr, "shadowlab: the workers' shards are kept in %s\n", r.workdir);
            rc = say_interrupted(r.merge.total - r.merge.nmissing, r.merge.total, r.store, o->resume, argc, argv);
        }
    }
    sl_jobs_result_free(&r);
    return rc;
}

int cli_run(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"out", required_argument, NULL, 'o'},      {"cells", required_argument, NULL, OPT_CELLS},
        {"resume", no_argument, NULL, OPT_RESUME},  {"db", required_argument, NULL, OPT_DB},
        {"no-cache", no_argument, NULL, OPT_NO_CACHE}, {"gl", required_argument, NULL, OPT_GL},
        {"threads", required_argument, NULL, 'j'},  {"quiet", no_argument, NULL, 'q'},
        {"verbose", no_argument, NULL, 'v'},        {"define", required_argument, NULL, 'D'},
        {"cache", required_argument, NULL, OPT_CACHE}, {"jobs", required_argument, NULL, OPT_JOBS},
        {"stored-in", required_argument, NULL, OPT_STORED_IN},
        {0, 0, 0, 0},
    };
    const struct cli_parser p = {"run", "o:j:qvD:", cli_usage_run, lo};
    struct sl_run_opts o = {.write_files = 1, .on_event = print_event, .stop = &stop_signal};
    struct event_state es = {.tty = isatty(2)};
    o.user = &es;
    int no_cache = 0, verbose = 0, threads = 0, jobs = 1;
    const char *cells = NULL;
    enum sl_gl_backend gl = SL_GL_DEFAULT;
    struct cli_overrides ov = {.n = 0};
    for (int c; (c = cli_opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case 'o': o.out_root = optarg; break;
        case OPT_GL:
            if (!(gl = sl_gl_backend_parse(optarg)))
                return cli_usage_error("run: --gl wants osmesa or egl", cli_usage_run);
            break;
        case OPT_DB: o.store = optarg; break;
        case OPT_CELLS: {
            char msg[300], line[320];
            if (!parse_cells(optarg, &o.first, &o.last, msg, sizeof msg)) {
                snprintf(line, sizeof line, "run: %s", msg);
                return cli_usage_error(line, cli_usage_run);
            }
            cells = optarg;
            break;
        }
        case OPT_RESUME: o.resume = 1; break;
        case OPT_STORED_IN: o.stored_in = optarg; break;
        case OPT_NO_CACHE: no_cache = 1; break;
        case OPT_CACHE: o.cache_dir = optarg; break;
        case OPT_JOBS: {
            long long v;
            if (!cli_opt_int_or_usage("run", "--jobs", optarg, 1, 64, &v, cli_usage_run))
                return 2;
            jobs = (int)v;
            break;
        }
        case 'j': {
            long long v;
            if (!cli_opt_int_or_usage("run", "-j/--threads", optarg, 1, 256, &v, cli_usage_run))
                return 2;
            threads = (int)v;
            break;
        }
        case 'q': es.quiet = 1; break;
        case 'v': verbose = 1; break;
        case 'D':
            if (!cli_add_override(&ov, "run", optarg, cli_usage_run))
                return 2;
            break;
        default: return cli_opt_exit(c);
        }
    }
    if (optind >= argc)
        return cli_usage_error("run: missing CONFIG", cli_usage_run);
    if (optind + 1 < argc)
        return cli_usage_error("run: one config at a time", cli_usage_run);
    if (o.stored_in && !o.resume)
        return cli_usage_error("run: --stored-in goes with --resume", cli_usage_run);
    const char *cfg = argv[optind];
    if (no_cache)
        o.cache_dir = "";
    if (threads) {
        /* llvmpipe reads it when the GL context is made */
        char t[8];
        snprintf(t, sizeof t, "%d", threads);
        setenv("LP_NUM_THREADS", t, 1);
    }
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_config c;
    char study[64] = "";
    if (sl_file_is_scene(cfg)) {
        if (!sl_scene_default_study(cfg, study, sizeof study)) {
            sl_fail(&d, SL_E_IO, cfg, 0, NULL, "cannot write a default study for this scene");
            return cli_fail(SL_E_IO, &d);
        }
    }
    enum sl_err e = sl_config_load_with(study[0] ? study : cfg, ov.v, ov.n, &c, &d);
    if (study[0]) {
        unlink(study);
        if (!e) {
            snprintf(c.path, sizeof c.path, "%s", cfg);
            if (!es.quiet) {
                fprintf(stderr, "shadowlab: %s is a scene: a default study of it, with this config "
                                "(save it as a .yaml file to edit it):\n", cfg);
                sl_config_write(&c, stderr);
            }
        }
    }
    if (e)
        return cli_fail(e, &d);
    if (!es.quiet)
        cli_note_left_out(&c);
    int rc = 0;
    if (cells && (o.first >= sl_plan_count(&c) || o.last > sl_plan_count(&c))) {
        /* checked here, where the text is at hand: --cells 0:99999999999 names itself */
        sl_fail(&d, SL_E_USAGE, c.path, 0, "--cells", "cells %s outside the sweep of %d cells (0:%d)", cells,
                sl_plan_count(&c), sl_plan_count(&c));
        rc = cli_fail(SL_E_USAGE, &d);
        goto out;
    }
    if (gl)
        c.gl = gl;
    if (threads)
        c.threads = threads;
    if (jobs > 1) {
        /* the workers read the config file again: what only this command line says cannot reach them */
        const char *why = o.first || o.last ? "run: --jobs splits the whole sweep; --cells is for one task"
                          : ov.n || study[0] || threads
                              ? "run: --jobs runs the config file as it is: no -D, -j or scene file with it"
                          : o.stored_in ? "run: --stored-in is for a --jobs worker, not with --jobs"
                                        : NULL;
        if (why) {
            rc = cli_usage_error(why, cli_usage_run);
            goto out;
        }
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    if (jobs > 1) {
        struct sl_jobs_opts jo = {.jobs = jobs, .out_root = o.out_root, .store = o.store, .cache = o.cache_dir,
                                  .gl = gl ? sl_gl_backend_name(gl) : NULL, .resume = o.resume,
                                  .stop = &stop_signal};
        rc = run_jobs(&c, &jo, argc, argv);
        goto out;
    }
    /* -v's tables: gathered in memory and printed after the run, once the
     * live progress line (stderr, on the same terminal) is cleared */
    char *tables = NULL;
    size_t tables_len = 0;
    FILE *tables_f = NULL;
    if (verbose && !es.quiet) {
        tables_f = open_memstream(&tables, &tables_len);
        o.table_out = tables_f ? tables_f : stdout;
    }
    struct sl_run_result r;
    e = sl_run(&c, &o, &r, &d);
    clear_progress(&es);   /* before the tables, the summary, an error or the interrupted note */
    if (tables_f) {
        fclose(tables_f);
        if (!e && tables)
            fwrite(tables, 1, tables_len, stdout);
        free(tables);
    }
    if (!e) {
        if (!es.quiet && !verbose)
            print_summary(&c, &r);
        else if (verbose)
            printf("\n%s: %d cell(s) computed, %d already stored, in %.1f s\n", c.name, r.ncells, r.skipped,
                   r.ms_total / 1e3);
        /* the one line a script or a redirected log needs, even with -q */
        printf("written to %s/%s%s\n", r.out_dir, r.store_path[0] ? " and " : "", r.store_path);
    }
    int interrupted = r.interrupted;
    int stored = r.stored_total;
    char store_path[sizeof r.store_path];
    snprintf(store_path, sizeof store_path, "%s", r.store_path);
    sl_run_result_free(&r);
    if (e)
        rc = cli_fail(e, &d);
    else if (interrupted)
        rc = say_interrupted(stored, sl_plan_count(&c), store_path, o.resume, argc, argv);
out:
    sl_config_free(&c);
    return rc;
}
