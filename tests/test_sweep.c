/*
 * sweep::* — a config as a sweep of addressable cells; each shared stage
 * computed once (counted); the truth cache; --cells and --resume against an
 * uninterrupted run.
 */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "run.h"
#include "store.h"


static const char *two_scenes =
    "scenes:\n  - {scene: primitives, viewpoints: [side, with]}\n  - {scene: blocks}\n"
    "viewports: [{width: 96, height: 64}, {width: 64, height: 64}]\nmap_sizes: [256, 512]\n"
    "methods:\n  - {label: ff, method: nsm}\n  - {label: none, method: nsm, self_shadow: none}\n"
    "  - {label: ff2, method: nsm, self_shadow: front_faces}\n";

static void sweep_plan_order(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("c.yaml", two_scenes, &c);
    /* (2 + 1 viewpoints) x 2 viewports x 2 maps x 3 methods */
    assert_int_equal(sl_plan_count(&c), 3 * 2 * 2 * 3);
    struct sl_cell_key k;
    sl_plan_cell(&c, 0, &k);
    assert_int_equal(k.scene + k.viewport + k.vp + k.map + k.method, 0);
    sl_plan_cell(&c, 1, &k);                      /* method varies fastest */
    assert_int_equal(k.method, 1);
    sl_plan_cell(&c, 3, &k);                      /* then the map size */
    assert_int_equal(k.map, 1);
    assert_int_equal(k.method, 0);
    sl_plan_cell(&c, 6, &k);                      /* then the viewpoint */
    assert_int_equal(k.vp, 1);
    assert_int_equal(k.map, 0);
    sl_plan_cell(&c, 12, &k);                     /* then the viewport */
    assert_int_equal(k.viewport, 1);
    assert_int_equal(k.vp, 0);
    sl_plan_cell(&c, 24, &k);                     /* then the scene */
    assert_int_equal(k.scene, 1);
    assert_int_equal(k.viewport, 0);
    sl_plan_cell(&c, 35, &k);
    assert_int_equal(k.scene, 1);
    assert_int_equal(k.viewport, 1);
    assert_int_equal(k.map, 1);
    assert_int_equal(k.method, 2);
    sl_config_free(&c);
}

/* A scene with map sizes of its own: swept at those only, the others at the
 * config's; the union is the config's list of map sizes. */
static void sweep_scene_map_sizes(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("c.yaml",
                   "scenes:\n  - {scene: primitives, viewpoints: [side, with]}\n"
                   "  - {scene: blocks, map_sizes: [1024, 256, 8192]}\n"
                   "viewports: [{width: 64, height: 64}]\nmap_sizes: [256, 512]\n"
                   "methods: [{label: a, method: nsm}, {label: b, method: nsm, self_shadow: none}]\n", &c);
    assert_int_equal(c.nmaps, 4);
    assert_int_equal(c.maps[2], 1024);
    assert_int_equal(c.maps[3], 8192);
    assert_int_equal(c.scenes[0].map_mask, 0x3u);
    assert_int_equal(c.scenes[1].map_mask, 0x1u | 0x4u | 0x8u);
    /* 2 viewpoints x 2 maps x 2 methods, then 1 x 3 x 2 */
    assert_int_equal(sl_plan_count(&c), 8 + 6);
    struct sl_cell_key k;
    int seen[4] = {0};
    for (int i = 0; i < sl_plan_count(&c); i++) {
        sl_plan_cell(&c, i, &k);
        assert_true(c.scenes[k.scene].map_mask & (1u << k.map));
        if (k.scene == 1)
            seen[k.map]++;
    }
    assert_int_equal(seen[0], 2);
    assert_int_equal(seen[1], 0);
    assert_int_equal(seen[2], 2);
    assert_int_equal(seen[3], 2);
    sl_plan_cell(&c, 8, &k);                      /* blocks, its first map size (256), method a */
    assert_int_equal(k.scene, 1);
    assert_int_equal(k.map, 0);
    sl_plan_cell(&c, 10, &k);                     /* then 1024 */
    assert_int_equal(k.map, 2);
    sl_plan_cell(&c, 13, &k);                     /* 8192, method b */
    assert_int_equal(k.map, 3);
    assert_int_equal(k.method, 1);

    /* a subset of the labels for one scene */
    sl_config_free(&c);
    sl_test_config("m.yaml",
                   "scenes:\n  - {scene: primitives, viewpoints: [side]}\n"
                   "  - {scene: blocks, map_sizes: [1024], methods: [c, a]}\n"
                   "viewports: [{width: 64, height: 64}]\nmap_sizes: [256]\n"
                   "methods: [{label: a, method: nsm}, {label: b, method: bgsm}, {label: c, method: texel}]\n", &c);
    assert_int_equal(c.scenes[0].method_mask, 0x7u);
    assert_int_equal(c.scenes[1].method_mask, 0x5u);
    assert_int_equal(sl_plan_count(&c), 3 + 2);
    sl_plan_cell(&c, 3, &k);
    assert_int_equal(k.scene, 1);
    assert_int_equal(k.method, 0);
    assert_int_equal(c.maps[k.map], 1024);
    sl_plan_cell(&c, 4, &k);
    assert_int_equal(k.method, 2);
    /* and the sweep runs exactly those cells, with no BGSM layer for blocks */
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = "", .first = 3};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 2);
    assert_int_equal(r.passes.layers[SL_LAYER_BGSM], 0);
    assert_int_equal(r.passes.layers[SL_LAYER_DEPTH_ID_BACK], 1);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* Every stage once: per view one G-buffer and one truth, per (view, map)
 * each layer once however many methods read it, no layer nobody reads. */
static void sweep_each_pass_once(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("c.yaml", two_scenes, &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 36);
    assert_int_equal(r.passes.scenes, 2);
    assert_int_equal(r.passes.adjacency, 0);        /* no method here reads adjacency */
    assert_int_equal(r.passes.gbuffers, 6);         /* 3 viewpoints x 2 viewports */
    assert_int_equal(r.passes.truths_traced, 6);
    assert_int_equal(r.passes.truths_cached, 0);
    assert_int_equal(r.passes.layers[SL_LAYER_DEPTH_ID_BACK], 12);   /* ff and ff2 share it */
    assert_int_equal(r.passes.layers[SL_LAYER_DEPTH_ID], 12);        /* none */
    /* each method computed once per cell, its runs as the repetitions
     * decided them (reps.h: the run's account counts each) */
    assert_int_equal(r.reps.kind[SL_REP_METHOD].stages, 36);
    assert_int_equal(r.passes.method_runs, (int)r.reps.kind[SL_REP_METHOD].runs);
    assert_true(r.passes.method_runs >= 36 && r.passes.method_runs <= 36 * (1 + c.runs));
    sl_run_result_free(&r);

    /* only the front-face methods of one (view, map): no plain depth layer */
    o.first = 0;
    o.last = 1;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 1);
    assert_int_equal(r.passes.layers[SL_LAYER_DEPTH_ID], 0);
    assert_int_equal(r.passes.layers[SL_LAYER_DEPTH_ID_BACK], 1);
    assert_int_equal(r.passes.gbuffers, 1);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* Repetitions time each stage again but compute it once: the pass counts
 * and the figures are those of a single run; each repeated stage keeps
 * min <= median <= max over its timed runs. */
static void sweep_repetitions(void **st)
{
    (void)st;
    static const char *cfg =
        "scenes: [{scene: primitives, viewpoints: [side]}]\nviewports: [{width: 96, height: 64}]\n"
        "map_sizes: [256]\nmethods:\n  - {label: ff, method: nsm}\n  - {label: b, method: bgsm}\n"
        "  - {label: c, method: csm}\n";
    char text[600];
    struct sl_config one, rep;
    snprintf(text, sizeof text, "%srepetitions: {warmup: 0, runs: 1}\n", cfg);
    sl_test_config("one.yaml", text, &one);
    snprintf(text, sizeof text, "%srepetitions: {mode: fixed, warmup: 1, runs: 4}\n", cfg);
    sl_test_config("rep.yaml", text, &rep);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result a, b;
    struct sl_diag d;
    assert_int_equal(sl_run(&one, &o, &a, &d), SL_OK);
    assert_int_equal(sl_run(&rep, &o, &b, &d), SL_OK);
    assert_int_equal(b.ncells, 3);
    assert_int_equal(b.passes.gbuffers, a.passes.gbuffers);
    assert_int_equal(b.passes.truths_traced, a.passes.truths_traced);
    assert_memory_equal(b.passes.layers, a.passes.layers, sizeof a.passes.layers);
    assert_int_equal(a.passes.method_runs, 3);
    assert_int_equal(b.passes.method_runs, 3 * 5);
    for (int i = 0; i < b.ncells; i++) {
        const struct sl_stage_ms *m = &b.cells[i].ms;
        const double *t[] = {m->gbuffer_render, m->truth, m->map_render, m->method};
        for (int k = 0; k < 4; k++) {
            assert_true(t[k][SL_MIN] > 0.0);
            assert_true(t[k][SL_MIN] <= t[k][SL_MED] && t[k][SL_MED] <= t[k][SL_MAX]);
        }
        /* a single run has nothing to spread */
        const struct sl_stage_ms *s = &a.cells[i].ms;
        assert_true(s->map_render[SL_MIN] == s->map_render[SL_MAX]);
        assert_int_equal(b.cells[i].truth_rays, a.cells[i].truth_rays);
        assert_int_equal(b.cells[i].gs_prims, a.cells[i].gs_prims);
        assert_memory_equal(b.cells[i].fig.r, a.cells[i].fig.r, sizeof a.cells[i].fig.r);
    }
    sl_run_result_free(&a);
    sl_run_result_free(&b);
    sl_config_free(&one);
    sl_config_free(&rep);
}

/* A second run reads every truth from the cache, and gets the same figures;
 * a damaged or older file is refused and traced again. */
static void sweep_truth_cache(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("c.yaml", "scenes: [{scene: primitives}]\nviewports: [{width: 128, height: 96}]\nmap_sizes: [512]\n"
         "methods: [{method: nsm}]\n", &c);
    char cache[300];
    snprintf(cache, sizeof cache, "%s/cache", sl_test_dir);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = cache};
    struct sl_run_result a, b;
    struct sl_diag d;
    char cmd[400];
    snprintf(cmd, sizeof cmd, "mkdir -p %s", cache);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(a.passes.truths_traced, 3);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.truths_traced, 0);
    assert_int_equal(b.passes.truths_cached, 3);
    assert_int_equal(b.passes.gbuffers, 3);          /* methods still need the G-buffer */
    for (int i = 0; i < a.ncells; i++) {
        assert_int_equal(a.cells[i].n_truth_shadow, b.cells[i].n_truth_shadow);
        assert_memory_equal(a.cells[i].fig.r, b.cells[i].fig.r, sizeof a.cells[i].fig.r);
    }
    /* a file cut short, and one in the older layout (magic, size, truth
     * with no checksum): both refused and traced again, same figures */
    char path[700];
    DIR *dp = opendir(cache);
    assert_non_null(dp);
    int files = 0;
    for (struct dirent *e; (e = readdir(dp));)
        if (strncmp(e->d_name, "truth-", 6) == 0) {
            snprintf(path, sizeof path, "%s/%s", cache, e->d_name);
            if (files == 0) {
                assert_int_equal(truncate(path, 48 + 128 * 96 - 1), 0);
            } else if (files == 1) {
                FILE *f = fopen(path, "wb");
                assert_non_null(f);
                const int32_t wh[2] = {128, 96};
                fwrite("SLTRUTH1", 1, 8, f);
                fwrite(wh, sizeof wh, 1, f);
                for (int i = 0; i < 128 * 96; i++)
                    fputc(0, f);
                fclose(f);
            }
            files++;
        }
    closedir(dp);
    assert_int_equal(files, 3);
    sl_run_result_free(&b);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.cache_rejected, 2);
    assert_int_equal(b.passes.truths_traced, 2);
    assert_int_equal(b.passes.truths_cached, 1);
    for (int i = 0; i < a.ncells; i++)
        assert_memory_equal(a.cells[i].fig.r, b.cells[i].fig.r, sizeof a.cells[i].fig.r);
    sl_run_result_free(&b);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.truths_cached, 3);          /* rewritten whole */
    /* a different viewport is a different truth: traced, not read */
    c.viewport_w[0] = 120;
    sl_run_result_free(&b);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.truths_traced, 3);
    assert_int_equal(b.passes.cache_rejected, 0);
    sl_run_result_free(&a);
    sl_run_result_free(&b);
    sl_config_free(&c);
}

/* Cells 0..4, then --resume: the store ends with the cells of one
 * uninterrupted run, figure for figure. */
static void sweep_cells_then_resume(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("c.yaml", "scenes: [{scene: primitives, viewpoints: [side, against]}]\n"
         "viewports: [{width: 128, height: 128}]\nmap_sizes: [256, 1024]\n"
         "methods: [{label: a, method: nsm}, {label: b, method: nsm, self_shadow: slope}]\n", &c);
    char db1[300], db2[300];
    snprintf(db1, sizeof db1, "%s/split.db", sl_test_dir);
    snprintf(db2, sizeof db2, "%s/whole.db", sl_test_dir);
    struct sl_diag d;
    struct sl_run_result r;
    struct sl_run_opts o = {.write_files = 0, .store = db1, .cache_dir = "", .first = 0, .last = 5};
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 5);
    sl_run_result_free(&r);
    struct sl_run_opts res = {.write_files = 0, .store = db1, .cache_dir = "", .resume = 1};
    assert_int_equal(sl_run(&c, &res, &r, &d), SL_OK);
    assert_int_equal(r.skipped, 5);
    assert_int_equal(r.ncells, 3);
    sl_run_result_free(&r);
    struct sl_run_opts whole = {.write_files = 0, .store = db2, .cache_dir = ""};
    assert_int_equal(sl_run(&c, &whole, &r, &d), SL_OK);
    sl_run_result_free(&r);

    struct sl_store *s1, *s2;
    assert_int_equal(sl_store_open(db1, &s1, &d), SL_OK);
    assert_int_equal(sl_store_open(db2, &s2, &d), SL_OK);
    assert_int_equal(sl_store_count(s1, "cells"), 8);
    assert_int_equal(sl_store_count(s1, "figures"), sl_store_count(s2, "figures"));
    struct sl_store_filter f = {0};
    struct sl_cell_record *a, *b;
    int na, nb;
    assert_int_equal(sl_store_query(s1, &f, &a, &na, &d), SL_OK);
    assert_int_equal(sl_store_query(s2, &f, &b, &nb, &d), SL_OK);
    assert_int_equal(na, 8);
    assert_int_equal(nb, 8);
    for (int i = 0; i < na; i++) {
        int found = 0;
        for (int k = 0; k < nb; k++)
            if (!strcmp(a[i].viewpoint, b[k].viewpoint) && !strcmp(a[i].label, b[k].label) &&
                a[i].map_size == b[k].map_size) {
                found = 1;
                for (int g = 0; g < a[i].fig.nregions; g++)
                    assert_memory_equal(a[i].fig.r[g].n, b[k].fig.r[g].n, sizeof a[i].fig.r[g].n);
            }
        assert_true(found);
    }
    free(a);
    free(b);
    sl_store_close(s1);
    sl_store_close(s2);
    sl_config_free(&c);
}



int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(sweep, plan_order),
        SL_CASE(sweep, scene_map_sizes),
        SL_CASE(sweep, each_pass_once),
        SL_CASE(sweep, repetitions),
        SL_CASE(sweep, truth_cache),
        SL_CASE(sweep, cells_then_resume),
    };
    return sl_run_group(argc, argv, "sweep", tests, sl_test_setup, sl_test_teardown);
}
