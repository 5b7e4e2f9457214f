/*
 * main.c — the command line. The only place that prints errors and exits:
 * 0 success, 1 a check failed, 2 bad input or usage (and any other failure
 * that leaves no result).
 */
#define _GNU_SOURCE   /* getopt_long, setenv, sigaction */
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include "bench.h"
#include "check.h"
#include "config.h"
#include "method.h"
#include "preview.h"
#include "provenance.h"
#include "report.h"
#include "run.h"
#include "scene.h"
#include "scenefile.h"
#include "store.h"
#include "submit.h"
#include "summary.h"
#include "table.h"
#include "usage.h"
#include "util.h"

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

/* ---- options: getopt_long per verb ----
 * Each verb has a table of long options and a short-option string; opt_next
 * returns the next option (as getopt_long does), handles --help itself and
 * turns an unknown option or a missing value into one message that names
 * it. To add an option to a verb: one entry in its `struct option` table
 * (a short letter, or an OPT_* id above 256 for a long-only one) and one
 * case in its switch. */
enum {
    OPT_CELLS = 256, OPT_RESUME, OPT_DB, OPT_NO_CACHE, OPT_GL, OPT_FORMAT, OPT_SCENE, OPT_VIEWPOINT,
    OPT_LABEL, OPT_MAP, OPT_RUN, OPT_SUMMARY, OPT_FIGURES, OPT_REGION, OPT_LOWER, OPT_AVG, OPT_BASELINE, OPT_STUDY,
    OPT_ROWS, OPT_UPDATE, OPT_JSON, OPT_JUNIT, OPT_ONLY, OPT_REPS, OPT_VIEWPORT, OPT_CSV, OPT_SELF_CONTAINED, OPT_LATEX, OPT_CACHE, OPT_JOBS, OPT_SIZE,
    OPT_ALLOW_MIXED, OPT_STORED_IN, OPT_MARKDOWN,
};
#define OPT_HELP {"help", no_argument, NULL, 'h'}
enum { OPT_DONE = -1, OPT_EXIT_OK = -2, OPT_EXIT_USAGE = -3 };

struct opt_parser {
    const char *verb, *shorts, *help;
    const struct option *longs;
};

static int opt_next(const struct opt_parser *p, int argc, char **argv)
{
    char shorts[64];
    snprintf(shorts, sizeof shorts, ":h%s", p->shorts);   /* ':' = say which value is missing */
    int c = getopt_long(argc, argv, shorts, p->longs, NULL);
    if (c == 'h') {
        fputs(p->help, stdout);
        return OPT_EXIT_OK;
    }
    if (c == '?' || c == ':') {
        char what[128];
        if (c == '?' && optopt && optopt < 256)   /* an unknown letter, maybe inside -abc */
            snprintf(what, sizeof what, "-%c", optopt);
        else
            snprintf(what, sizeof what, "%s", argv[optind - 1]);
        fprintf(stderr, "shadowlab %s: %s '%s'\n%s", p->verb, c == '?' ? "unknown option" : "missing value for",
                what, p->help);
        return OPT_EXIT_USAGE;
    }
    return c;
}

static int opt_exit(int c) { return c == OPT_EXIT_OK ? 0 : 2; }

/* -D KEY=VALUE, repeatable */
struct overrides {
    const char *v[64];
    int n;
};
static int add_override(struct overrides *o, const char *verb, const char *arg, const char *help)
{
    if (o->n == (int)(sizeof o->v / sizeof o->v[0]) || !strchr(arg, '=')) {
        fprintf(stderr, "shadowlab %s: -D wants KEY=VALUE (at most 64): '%s'\n%s", verb, arg, help);
        return 0;
    }
    o->v[o->n++] = arg;
    return 1;
}

/* An integer an option takes: decimal digits (a sign allowed), all of the
 * text, in lo..hi; no atoi (4294967297 would be 1) and no float ("7.9").
 * Returns 0 with msg in the form of a config key's ("'7.9' is not a whole
 * number", "... must be in 1..64"). */
static int opt_int(const char *s, long long lo, long long hi, long long *out, char *msg, size_t n)
{
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end == s || *end || (*s != '-' && *s != '+' && (*s < '0' || *s > '9'))) {
        snprintf(msg, n, "'%s' is not a whole number (an integer in decimal digits is expected)", s);
        return 0;
    }
    if (errno == ERANGE || v < lo || v > hi) {
        snprintf(msg, n, "'%s' must be in %lld..%lld", s, lo, hi);
        return 0;
    }
    *out = v;
    return 1;
}

/* usage_error for an integer option: "VERB: --OPT: MSG" */
static int opt_int_or_usage(const char *verb, const char *opt, const char *s, long long lo, long long hi,
                            long long *out, const char *help)
{
    char msg[200], line[300];
    if (opt_int(s, lo, hi, out, msg, sizeof msg))
        return 1;
    snprintf(line, sizeof line, "%s: %s %s", verb, opt, msg);
    usage_error(line, help);
    return 0;
}

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
        else if (!opt_int(t[i], 0, INT_MAX, v[i], m, sizeof m)) {
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

/* "WxH", each a whole number in lo..hi */
static int parse_wxh(const char *s, long long lo, long long hi, int *w, int *h)
{
    char a[32];
    const char *x = strchr(s, 'x');
    long long vw, vh;
    char msg[200];
    if (!x || x == s || (size_t)(x - s) >= sizeof a)
        return 0;
    snprintf(a, sizeof a, "%.*s", (int)(x - s), s);
    if (!opt_int(a, lo, hi, &vw, msg, sizeof msg) || !opt_int(x + 1, lo, hi, &vh, msg, sizeof msg))
        return 0;
    *w = (int)vw;
    *h = (int)vh;
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

static void print_progress(const struct sl_run_event *ev, struct event_state *es)
{
    const struct sl_config *c = ev->config;
    const struct sl_cell *cl = ev->cell;
    double el = ev->elapsed_s;
    double eta = ev->done ? el * (double)(ev->total - ev->done) / (double)ev->done : 0.0;
    if (es->tty) {
        fprintf(stderr, "\r[%d/%d] %s/%s %d² %-16s %6.1fs elapsed, ~%.0fs left   ", ev->done, ev->total, cl->scene,
                cl->viewpoint, c->maps[cl->key.map], c->methods[cl->key.method].label, el, eta);
        if (ev->done == ev->total)
            fputc('\n', stderr);
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
        fprintf(stderr, "shadowlab: NON-FINITE: %s/%s map %d '%s': %llu G-buffer or shadow-map value(s) "
                        "not finite or out of range\n", cl->scene, cl->viewpoint, c->maps[cl->key.map],
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
    printf("%-20s %6s %14s %12s\n", "label", "cells", "wrong pixels", "of pixels");
    for (int m = 0; m < c->nmethods; m++) {
        uint64_t wrong = 0, pixels = 0;
        double mae = 0;
        int n = 0, nsoft = 0;
        for (int i = 0; i < r->ncells; i++) {
            const struct sl_cell *cl = &r->cells[i];
            if (cl->key.method != m)
                continue;
            n++;
            if (cl->has_soft) {
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
            printf("%-20s %6d %14s %11.3f%% mean absolute error of visibility\n", c->methods[m].label, n, "-",
                   mae / nsoft);
        else
            printf("%-20s %6d %14llu %11.3f%%\n", c->methods[m].label, n, (unsigned long long)wrong,
                   pixels ? 100.0 * (double)wrong / (double)pixels : 0.0);
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
    int rc = e ? fail(e, &d) : 0;
    if (!e) {
        const char *shards[64];
        char paths[64][1300];
        for (int i = 0; i < r.nworkers; i++) {
            snprintf(paths[i], sizeof paths[i], "%s/task-%d/shadowlab.db", r.workdir, i);
            shards[i] = paths[i];
        }
        rc = print_merge(shards, &r.merge, r.store);
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

static int cmd_merge(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"out", required_argument, NULL, 'o'},
                                       {"allow-mixed", no_argument, NULL, OPT_ALLOW_MIXED}, {0, 0, 0, 0}};
    const struct opt_parser p = {"merge", "o:", sl_usage_merge, lo};
    const char *out = NULL;
    unsigned flags = 0;
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == OPT_ALLOW_MIXED)
            flags |= SL_MERGE_ALLOW_MIXED;
        else if (c != 'o')
            return opt_exit(c);
        else
            out = optarg;
    }
    int n = argc - optind;
    if (!out || n < 1)
        return usage_error("merge: wants SHARD.db... and -o STORE.db", sl_usage_merge);
    const char **shards = (const char **)(argv + optind);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_shards_result r;
    enum sl_err e = sl_shards_merge(shards, n, out, flags, &r, &d);
    int rc = e ? fail(e, &d) : print_merge(shards, &r, out);
    sl_shards_result_free(&r);
    return rc;
}

/* Every cell against its digest: exit 0 intact, 2 naming each damaged cell. */
static int cmd_verify(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {0, 0, 0, 0}};
    const struct opt_parser p = {"verify", "", sl_usage_verify, lo};
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;)
        return opt_exit(c);
    if (argc - optind != 1)
        return usage_error("verify: wants one STORE.db", sl_usage_verify);
    const char *db = argv[optind];
    struct sl_diag d = {0};
    struct sl_store *st = NULL;
    struct sl_store_verify v = {0};
    enum sl_err e = sl_store_open_existing(db, &st, &d);
    e = e ? e : sl_store_verify(st, &v, &d);
    sl_store_close(st);
    for (int i = 0; !e && i < v.ndamaged; i++)
        fprintf(stderr, "shadowlab: verify: %s: damaged cell %s (cell %lld, run %lld): its rows no longer match "
                "their digest\n", db, v.damaged[i].key, (long long)v.damaged[i].cell_id, (long long)v.damaged[i].run_id);
    if (!e)
        printf("%s: %ld cell(s), %ld figure row(s) checked in %.3f s (%.1f us per cell): %d damaged\n", db, v.cells,
               v.figures, v.seconds, v.cells ? 1e6 * v.seconds / (double)v.cells : 0.0, v.ndamaged);
    int rc = e ? fail(e, &d) : v.ndamaged ? 2 : 0;
    sl_store_verify_free(&v);
    return rc;
}

static int cmd_submit(int argc, char **argv)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_submit_opts o;
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(sl_usage_submit, stdout);
            return 0;
        }
    enum sl_err e = sl_submit_parse(argc, argv, &o, &d);
    if (e) {
        char line[1200];
        sl_diag_format(&d, e, line, sizeof line);
        return usage_error(line, sl_usage_submit);
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
    const struct opt_parser p = {"run", "o:j:qvD:", sl_usage_run, lo};
    struct sl_run_opts o = {.write_files = 1, .on_event = print_event, .stop = &stop_signal};
    struct event_state es = {.tty = isatty(2)};
    o.user = &es;
    int no_cache = 0, verbose = 0, threads = 0, jobs = 1;
    const char *cells = NULL;
    enum sl_gl_backend gl = SL_GL_DEFAULT;
    struct overrides ov = {.n = 0};
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case 'o': o.out_root = optarg; break;
        case OPT_GL:
            if (!(gl = sl_gl_backend_parse(optarg)))
                return usage_error("run: --gl wants osmesa or egl", sl_usage_run);
            break;
        case OPT_DB: o.store = optarg; break;
        case OPT_CELLS: {
            char msg[300], line[320];
            if (!parse_cells(optarg, &o.first, &o.last, msg, sizeof msg)) {
                snprintf(line, sizeof line, "run: %s", msg);
                return usage_error(line, sl_usage_run);
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
            if (!opt_int_or_usage("run", "--jobs", optarg, 1, 64, &v, sl_usage_run))
                return 2;
            jobs = (int)v;
            break;
        }
        case 'j': {
            long long v;
            if (!opt_int_or_usage("run", "-j/--threads", optarg, 1, 256, &v, sl_usage_run))
                return 2;
            threads = (int)v;
            break;
        }
        case 'q': es.quiet = 1; break;
        case 'v': verbose = 1; break;
        case 'D':
            if (!add_override(&ov, "run", optarg, sl_usage_run))
                return 2;
            break;
        default: return opt_exit(c);
        }
    }
    if (optind >= argc)
        return usage_error("run: missing CONFIG", sl_usage_run);
    if (optind + 1 < argc)
        return usage_error("run: one config at a time", sl_usage_run);
    if (o.stored_in && !o.resume)
        return usage_error("run: --stored-in goes with --resume", sl_usage_run);
    const char *cfg = argv[optind];
    if (no_cache)
        o.cache_dir = "";
    if (verbose && !es.quiet)
        o.table_out = stdout;
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
            return fail(SL_E_IO, &d);
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
        return fail(e, &d);
    if (cells && (o.first >= sl_plan_count(&c) || o.last > sl_plan_count(&c))) {
        /* checked here, where the text is at hand: --cells 0:99999999999 names itself */
        sl_fail(&d, SL_E_USAGE, c.path, 0, "--cells", "cells %s outside the sweep of %d cells (0:%d)", cells,
                sl_plan_count(&c), sl_plan_count(&c));
        return fail(SL_E_USAGE, &d);
    }
    if (gl)
        c.gl = gl;
    if (threads)
        c.threads = threads;
    if (jobs > 1) {
        /* the workers read the config file again: what only this command line says cannot reach them */
        if (o.first || o.last)
            return usage_error("run: --jobs splits the whole sweep; --cells is for one task", sl_usage_run);
        if (ov.n || study[0] || threads)
            return usage_error("run: --jobs runs the config file as it is: no -D, -j or scene file with it",
                               sl_usage_run);
        if (o.stored_in)
            return usage_error("run: --stored-in is for a --jobs worker, not with --jobs", sl_usage_run);
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
        return run_jobs(&c, &jo, argc, argv);
    }
    struct sl_run_result r;
    e = sl_run(&c, &o, &r, &d);
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
        return fail(e, &d);
    if (interrupted)
        return say_interrupted(stored, sl_plan_count(&c), store_path, o.resume, argc, argv);
    return 0;
}

static int cmd_validate(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"define", required_argument, NULL, 'D'}, {0, 0, 0, 0}};
    const struct opt_parser p = {"validate", "D:", sl_usage_validate, lo};
    struct overrides ov = {.n = 0};
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c != 'D')
            return opt_exit(c);
        if (!add_override(&ov, "validate", optarg, sl_usage_validate))
            return 2;
    }
    if (optind + 1 != argc)
        return usage_error("validate: one FILE", sl_usage_validate);
    const char *file = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (sl_file_is_scene(file)) {
        if (ov.n)
            return usage_error("validate: -D applies to a config, not to a scene file", sl_usage_validate);
        struct sl_scene s;
        enum sl_err e = sl_scene_load(file, &s, &d);
        if (e)
            return fail(e, &d);
        printf("%s: ok: scene '%s', %u triangles, %u vertices, %d mesh(es), %d viewpoint(s), "
               "bounds (%g, %g, %g) .. (%g, %g, %g)\n", file, s.name, s.nt, s.nv, s.nranges, s.nvp,
               s.origin[0] + s.lo[0], s.origin[1] + s.lo[1], s.origin[2] + s.lo[2], s.origin[0] + s.hi[0],
               s.origin[1] + s.hi[1], s.origin[2] + s.hi[2]);
        /* per mesh, in world units, to frame viewpoints without a run */
        for (int m = 0; m < s.nranges; m++) {
            const struct sl_mesh_range *r = &s.ranges[m];
            double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
            for (uint32_t t = r->first; t < r->first + r->count; t++)
                for (int k = 0; k < 3; k++) {
                    const float *v = &s.pos[3 * s.idx[3 * t + k]];
                    for (int a = 0; a < 3; a++) {
                        lo[a] = v[a] < lo[a] ? v[a] : lo[a];
                        hi[a] = v[a] > hi[a] ? v[a] : hi[a];
                    }
                }
            printf("  mesh %-16s %8u triangles, bounds (%g, %g, %g) .. (%g, %g, %g)\n", r->name, r->count,
                   s.origin[0] + lo[0], s.origin[1] + lo[1], s.origin[2] + lo[2], s.origin[0] + hi[0],
                   s.origin[1] + hi[1], s.origin[2] + hi[2]);
        }
        sl_scene_free(&s);
        return 0;
    }
    struct sl_config c;
    enum sl_err e = sl_config_load_with(file, ov.v, ov.n, &c, &d);
    if (e)
        return fail(e, &d);
    printf("%s: ok: %d scene(s), %d cell(s)\n", file, c.nscenes, sl_plan_count(&c));
    sl_config_write(&c, stdout);
    return 0;
}

static int cmd_table(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"format", required_argument, NULL, OPT_FORMAT},     {"scene", required_argument, NULL, OPT_SCENE},
        {"viewpoint", required_argument, NULL, OPT_VIEWPOINT}, {"label", required_argument, NULL, OPT_LABEL},
        {"map", required_argument, NULL, OPT_MAP},           {"run", required_argument, NULL, OPT_RUN},
        {"summary", required_argument, NULL, OPT_SUMMARY},   {"region", required_argument, NULL, OPT_REGION},
        {"figures", required_argument, NULL, OPT_FIGURES},
        {"lower-is-better", no_argument, NULL, OPT_LOWER},   {"average-case", required_argument, NULL, OPT_AVG},
        {0, 0, 0, 0},
    };
    const struct opt_parser p = {"table", "", sl_usage_table, lo};
    struct sl_store_filter f = {0};
    int fmt = SL_TABLE_MD;
    struct sl_summary_opts so = {.figure = -1, .region = -1};
    const char *summary = NULL, *figures = NULL;
    char avg_scene[64] = "", avg_vp[32] = "";
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        const char *v = optarg;
        switch (c) {
        case OPT_FORMAT:
            fmt = sl_table_format_parse(v);
            if (fmt < 0)
                return usage_error("table: --format md, csv or latex", sl_usage_table);
            break;
        case OPT_SCENE: f.scene = v; break;
        case OPT_VIEWPOINT: f.viewpoint = v; break;
        case OPT_LABEL: f.label = v; break;
        case OPT_MAP: {
            long long x;
            if (!opt_int_or_usage("table", "--map", v, 1, 16384, &x, sl_usage_table))
                return 2;
            f.map_size = (int)x;
            break;
        }
        case OPT_RUN: {
            long long x;
            if (!opt_int_or_usage("table", "--run", v, 1, LLONG_MAX, &x, sl_usage_table))
                return 2;
            f.run_id = x;
            break;
        }
        case OPT_SUMMARY: summary = v; break;
        case OPT_FIGURES: figures = v; break;
        case OPT_REGION:
            if (!strcmp(v, "image") || !strcmp(v, "contours"))
                so.region = !strcmp(v, "image") ? 0 : -1;
            else {
                long long x;
                if (!opt_int_or_usage("table", "--region", v, 0, 64, &x, sl_usage_table))
                    return 2;
                so.region = (int)x;
            }
            if (so.region > 0 && so.region % 2)
                return usage_error("table: --region N (even), image or contours", sl_usage_table);
            break;
        case OPT_LOWER: so.lower_is_better = 1; break;
        case OPT_AVG:
        {
            char nr[32] = "", nm[32] = "";
            long long x;
            int k = sscanf(v, "%63[^/]/%31[^/]/%31[^/]/%31s", avg_scene, avg_vp, nr, nm);
            if (k < 3)
                return usage_error("table: --average-case SCENE/VIEWPOINT/N[/MAP]", sl_usage_table);
            if (!opt_int_or_usage("table", "--average-case N", nr, 0, 64, &x, sl_usage_table))
                return 2;
            so.avg_region = (int)x;
            if (k == 4) {
                if (!opt_int_or_usage("table", "--average-case MAP", nm, 1, 16384, &x, sl_usage_table))
                    return 2;
                so.avg_map = (int)x;
            }
        }
            so.avg_scene = avg_scene;
            so.avg_viewpoint = avg_vp;
            break;
        default: return opt_exit(c);
        }
    }
    if (optind >= argc)
        return usage_error("table: missing DB", sl_usage_table);
    if (optind + 1 < argc)
        return usage_error("table: one DB", sl_usage_table);
    const char *db = argv[optind];
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
        /* the terminal's tables: only what the methods produce, unless --figures says */
        struct sl_table_rows rows = {0};
        e = sl_table_figures_parse(figures, &rows, &d);
        if (!figures)
            rows.produced = fmt != SL_TABLE_CSV;
        if (!e)
            e = sl_table_write_rows(stdout, (enum sl_table_format)fmt, db, cells, n, &rows, &d);
    }
    free(cells);
    sl_store_close(st);
    return e ? fail(e, &d) : 0;
}

static int cmd_report(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"out", required_argument, NULL, 'o'},
                                       {"self-contained", no_argument, NULL, OPT_SELF_CONTAINED},
                                       {"latex", no_argument, NULL, OPT_LATEX}, {0, 0, 0, 0}};
    const struct opt_parser p = {"report", "o:", sl_usage_report, lo};
    struct sl_report_opts o = {0};
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == 'o')
            o.out_dir = optarg;
        else if (c == OPT_SELF_CONTAINED)
            o.self_contained = 1;
        else if (c == OPT_LATEX)
            o.latex = 1;
        else
            return opt_exit(c);
    }
    if (optind >= argc)
        return usage_error("report: missing RESULTS_DB", sl_usage_report);
    if (optind + 1 < argc)
        return usage_error("report: one RESULTS_DB", sl_usage_report);
    o.db = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    char dir[1100];
    enum sl_err e = sl_report_write(&o, dir, sizeof dir, &d);
    if (e)
        return fail(e, &d);
    printf("report: %s/report.html, %s/report.md%s%s%s%s\n", dir, dir, o.self_contained ? ", " : "",
           o.self_contained ? "(self-contained)" : "", o.latex ? ", " : "", o.latex ? "report.tex" : "");
    return 0;
}

static int cmd_check(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"baseline", required_argument, NULL, OPT_BASELINE}, {"study", required_argument, NULL, OPT_STUDY},
        {"rows", required_argument, NULL, OPT_ROWS},         {"update", no_argument, NULL, OPT_UPDATE},
        {"format", required_argument, NULL, OPT_FORMAT},     {"json", required_argument, NULL, OPT_JSON},
        {"junit", required_argument, NULL, OPT_JUNIT},       {0, 0, 0, 0},
    };
    const struct opt_parser p = {"check", "", sl_usage_check, lo};
    const char *baseline = NULL, *json = NULL, *junit = NULL;
    struct sl_check_opts o = {0};
    int update = 0;
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case OPT_BASELINE: baseline = optarg; break;
        case OPT_STUDY: o.study = optarg; break;
        case OPT_ROWS: {
            long long v;
            if (!opt_int_or_usage("check", "--rows", optarg, 1, 1000000, &v, sl_usage_check))
                return 2;
            o.max_rows = (int)v;
            break;
        }
        case OPT_UPDATE: update = 1; break;
        case OPT_FORMAT:
            if (strcmp(optarg, "text") && strcmp(optarg, "md"))
                return usage_error("check: --format text or md", sl_usage_check);
            o.format = strcmp(optarg, "md") ? SL_CHECK_TEXT : SL_CHECK_MD;
            break;
        case OPT_JSON: json = optarg; break;
        case OPT_JUNIT: junit = optarg; break;
        default: return opt_exit(c);
        }
    }
    if (optind + 1 < argc)
        return usage_error("check: one results store at a time", sl_usage_check);
    const char *db = optind < argc ? argv[optind] : NULL;
    if (!db || !baseline)
        return usage_error("check: wants DB and --baseline FILE", sl_usage_check);
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    if (update) {
        enum sl_err e = sl_check_write_baseline(db, baseline, o.study, &d);
        if (e)
            return fail(e, &d);
        fprintf(stderr, "shadowlab: wrote %s from %s\n", baseline, db);
        return 0;
    }
    /* colour only for a person at a terminal (https://no-color.org) */
    const char *nc = getenv("NO_COLOR");
    o.color = o.format == SL_CHECK_TEXT && isatty(1) && !(nc && nc[0]);
    struct { const char *path; FILE **f; } outs[] = {{json, &o.json}, {junit, &o.junit}};
    for (int i = 0; i < 2; i++)
        if (outs[i].path && !(*outs[i].f = fopen(outs[i].path, "w"))) {
            sl_fail(&d, SL_E_OUTPUT, outs[i].path, 0, NULL, "cannot write");
            if (o.json)
                fclose(o.json);
            return fail(SL_E_OUTPUT, &d);
        }
    struct sl_check_result r;
    enum sl_err e = sl_check(db, baseline, &o, stdout, &r, &d);
    for (int i = 0; i < 2; i++)
        if (*outs[i].f && fclose(*outs[i].f) != 0 && !e)
            e = sl_fail(&d, SL_E_OUTPUT, outs[i].path, 0, NULL, "cannot write");
    if (e)
        return fail(e, &d);
    return r.failed || r.missing ? 1 : 0;
}

static int cmd_bench(int argc, char **argv)
{
    static const struct option lo[] = {
        OPT_HELP,
        {"reps", required_argument, NULL, OPT_REPS},         {"only", required_argument, NULL, OPT_ONLY},
        {"scene", required_argument, NULL, OPT_SCENE},       {"viewport", required_argument, NULL, OPT_VIEWPORT},
        {"map", required_argument, NULL, OPT_MAP},           {"csv", required_argument, NULL, OPT_CSV},
        {"gl", required_argument, NULL, OPT_GL}, {"markdown", required_argument, NULL, OPT_MARKDOWN}, {0, 0, 0, 0},
    };
    const struct opt_parser p = {"bench", "", sl_usage_bench, lo};
    struct sl_bench_opts o = {.config = NULL, .reps = 0, .out = stdout};
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        switch (c) {
        case OPT_REPS: {
            long long v;
            if (!opt_int_or_usage("bench", "--reps", optarg, 1, 1000, &v, sl_usage_bench))
                return 2;
            o.reps = (int)v;
            break;
        }
        case OPT_ONLY:
            if (sl_bench_parse_stages(optarg, &o.stages, &d))
                return usage_error(d.msg, sl_usage_bench);
            break;
        case OPT_SCENE: o.scene = optarg; break;
        case OPT_VIEWPORT: {
            if (!parse_wxh(optarg, 1, 16384, &o.width, &o.height))
                return usage_error("bench: --viewport wants WxH, 1..16384 each", sl_usage_bench);
            break;
        }
        case OPT_MAP: {
            long long v;
            if (!opt_int_or_usage("bench", "--map", optarg, 16, 16384, &v, sl_usage_bench))
                return 2;
            o.map = (int)v;
            break;
        }
        case OPT_CSV: o.csv = optarg; break;
        case OPT_MARKDOWN: o.markdown = optarg; break;
        case OPT_GL:
            if (!(o.gl = sl_gl_backend_parse(optarg)))
                return usage_error("bench: --gl wants osmesa or egl", sl_usage_bench);
            break;
        default: return opt_exit(c);
        }
    }
    if (optind + 1 < argc)
        return usage_error("bench: one CONFIG at most", sl_usage_bench);
    o.config = optind < argc ? argv[optind] : NULL;
    enum sl_err e = sl_bench(&o, NULL, &d);
    return e ? fail(e, &d) : 0;
}

static int cmd_preview(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {"out", required_argument, NULL, 'o'},
                                       {"viewpoint", required_argument, NULL, OPT_VIEWPOINT},
                                       {"size", required_argument, NULL, OPT_SIZE},
                                       {"gl", required_argument, NULL, OPT_GL}, {0, 0, 0, 0}};
    const struct opt_parser p = {"preview", "o:", sl_usage_preview, lo};
    struct sl_preview_opts o = {0};
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;) {
        if (c == 'o')
            o.out_dir = optarg;
        else if (c == OPT_VIEWPOINT)
            o.viewpoint = optarg;
        else if (c == OPT_SIZE) {
            if (!parse_wxh(optarg, 16, 8192, &o.w, &o.h))
                return usage_error("preview: --size wants WxH, 16..8192 each", sl_usage_preview);
        } else if (c == OPT_GL) {
            if (!(o.gl = sl_gl_backend_parse(optarg)))
                return usage_error("preview: --gl wants osmesa or egl", sl_usage_preview);
        } else
            return opt_exit(c);
    }
    if (optind + 1 != argc)
        return usage_error("preview: one SCENE", sl_usage_preview);
    o.scene = argv[optind];
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct sl_preview_result r;
    enum sl_err e = sl_preview(&o, &r, &d);
    for (int i = 0; i < r.n; i++)
        printf("%s\n", r.path[i]);
    if (e)
        return fail(e, &d);
    fprintf(stderr, "shadowlab: %d preview(s) in %.0f ms (%s)\n", r.n, r.ms_total, r.renderer);
    return 0;
}

static int cmd_list(int argc, char **argv)
{
    static const struct option lo[] = {OPT_HELP, {0, 0, 0, 0}};
    const struct opt_parser p = {"list", "", sl_usage_list, lo};
    for (int c; (c = opt_next(&p, argc, argv)) != OPT_DONE;)
        return opt_exit(c);
    argc -= optind - 1;
    argv += optind - 1;
    if (argc == 2 && strcmp(argv[1], "methods") == 0) {
        for (int i = 0; i < sl_method_count(); i++)
            printf("%-12s %s\n", sl_method_at(i)->name, sl_method_at(i)->summary);
        return 0;
    }
    if (argc == 2 && strcmp(argv[1], "scenes") == 0) {
        static char names[256][64], descr[256][160], paths[256][1024];
        static const char *origin[256];
        int n = sl_scene_list_where(names, descr, paths, origin, 256);
        for (int i = 0; i < n; i++)
            printf("%-14s %-50s [%s: %s]\n", names[i], descr[i], origin[i], paths[i]);
        if (n == 0) {
            char dirs[16][1024];
            const char *o[16];
            int nd = sl_scene_dirs(NULL, dirs, o, 16);
            fprintf(stderr, "shadowlab: no scene files in");
            for (int i = 0; i < nd; i++)
                fprintf(stderr, "%s %s (%s)", i ? "," : "", dirs[i], o[i]);
            fputc('\n', stderr);
        }
        return 0;
    }
    return usage_error("list: methods or scenes", sl_usage_list);
}

/* OpenMP's idle threads spin between parallel regions by default (libgomp:
 * for up to GOMP_SPINCOUNT turns), burning a core while the main thread
 * renders or scores alone. On a shared machine that costs: the Morais
 * study's last 64 cells, alternating, at load 5-7 on this 2-core VM, took
 * 24.1-27.7 s CPU spinning and 16.5-19.0 s waiting passively, and less wall
 * time too (README, Performance). libgomp reads its policy once, as it loads,
 * before main: so a rendering verb whose environment sets neither
 * OMP_WAIT_POLICY nor GOMP_SPINCOUNT runs itself again with
 * OMP_WAIT_POLICY=passive. Either variable set keeps the user's choice. */
static void wait_passively(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return;
    if (setenv("OMP_WAIT_POLICY", "passive", 1))
        return;
    execv("/proc/self/exe", argv);
    unsetenv("OMP_WAIT_POLICY");   /* no /proc: go on as the runtime already is */
}

int main(int argc, char **argv)
{
    if (argc >= 2 && (!strcmp(argv[1], "run") || !strcmp(argv[1], "bench")))
        wait_passively(argv);
    if (argc < 2)
        return usage_error("missing command", sl_usage);
    static const struct {
        const char *name;
        int (*fn)(int, char **);
        const char *help;
    } verbs[] = {
        {"run", cmd_run, sl_usage_run},
        {"validate", cmd_validate, sl_usage_validate},
        {"table", cmd_table, sl_usage_table},
        {"report", cmd_report, sl_usage_report},
        {"check", cmd_check, sl_usage_check},
        {"bench", cmd_bench, sl_usage_bench},
        {"submit", cmd_submit, sl_usage_submit},
        {"merge", cmd_merge, sl_usage_merge},
        {"verify", cmd_verify, sl_usage_verify},
        {"preview", cmd_preview, sl_usage_preview},
        {"list", cmd_list, sl_usage_list},
    };
    const char *cmd = argv[1];
    if (!strcmp(cmd, "version") || !strcmp(cmd, "-V") || !strcmp(cmd, "--version")) {
        printf("shadowlab %s\n", sl_git_sha());
        return 0;
    }
    int help = !strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help");
    if (help && argc == 2) {
        fputs(sl_usage, stdout);
        return 0;
    }
    if (help)
        cmd = argv[2];   /* help VERB = VERB --help */
    for (size_t i = 0; i < sizeof verbs / sizeof verbs[0]; i++)
        if (strcmp(cmd, verbs[i].name) == 0) {
            if (help) {
                fputs(verbs[i].help, stdout);
                return 0;
            }
            /* the verb sees itself as argv[0], as getopt_long expects */
            return verbs[i].fn(argc - 1, argv + 1);
        }
    fprintf(stderr, "shadowlab: unknown command '%s'\n%s", cmd, sl_usage);
    return 2;
}
