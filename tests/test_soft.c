/*
 * soft::* — scenes with an area light through the driver: the area truth
 * once per view (counted), no hard-shadow pass, the soft figures adding up,
 * the hard-shadow approximation (hard_point) scored against the area truth,
 * determinism; a scene without an area light never pays for a soft pass;
 * and the area truths' cache: read back bit for bit, keyed by samples and
 * seed, damaged files refused, off when asked.
 */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "run.h"

/* Every figure of two runs' cells, hard and soft, bit for bit (timings aside). */
static void assert_same_figures(const struct sl_run_result *a, const struct sl_run_result *b)
{
    assert_int_equal(a->ncells, b->ncells);
    for (int i = 0; i < a->ncells; i++) {
        const struct sl_cell *x = &a->cells[i], *y = &b->cells[i];
        assert_memory_equal(x->soft.n, y->soft.n, sizeof x->soft.n);
        assert_memory_equal(x->soft.pct, y->soft.pct, sizeof x->soft.pct);
        assert_int_equal(x->fig.nregions, y->fig.nregions);
        assert_int_equal(x->fig.background, y->fig.background);
        assert_int_equal(x->fig.wrong_image, y->fig.wrong_image);
        assert_memory_equal(x->fig.r, y->fig.r, sizeof x->fig.r);
        assert_memory_equal(x->pattern, y->pattern, sizeof x->pattern);
        assert_int_equal(x->n_truth_lit, y->n_truth_lit);
        assert_int_equal(x->n_truth_shadow, y->n_truth_shadow);
        assert_int_equal(x->n_pfl, y->n_pfl);
        assert_int_equal(x->cost.rays, y->cost.rays);
        assert_int_equal(x->cost.lookups, y->cost.lookups);
        assert_int_equal(x->violations, y->violations);
        assert_int_equal(x->nonfinite, y->nonfinite);
    }
}

static const char *soft_cfg =
    "scenes: [{scene: curtis_box}]\nviewports: [{width: 128, height: 96}]\nmap_sizes: [512, 1024]\n"
    "methods: [{label: point, method: hard_point}]\narea_samples: 8\n";

static void soft_driver(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("soft.yaml", soft_cfg, &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result a, b;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(a.ncells, 2 * 2);
    assert_int_equal(a.passes.soft_truths, 2);            /* once per view, not per map size */
    assert_int_equal(a.passes.truths_traced, 2);
    for (int l = 0; l < SL_LAYER_COUNT; l++)
        assert_int_equal(a.passes.layers[l], 0);            /* hard_point reads no shadow map */
    assert_int_equal(a.passes.soft_layers, 0);
    for (int i = 0; i < a.ncells; i++) {
        const struct sl_cell *cl = &a.cells[i];
        const uint64_t *n = cl->soft.n;
        assert_true(cl->has_soft);
        assert_int_equal(cl->nonfinite, 0);
        assert_int_equal(n[SL_SFIG_soft_pixels], cl->n_pfl + cl->n_pnfl);
        assert_int_equal(n[SL_SFIG_soft_truth_lit] + n[SL_SFIG_soft_truth_umbra] + n[SL_SFIG_soft_truth_penumbra],
                         n[SL_SFIG_soft_pixels]);
        assert_true(n[SL_SFIG_soft_truth_penumbra] > 1000);   /* Curtis's case has wide penumbrae */
        assert_true(n[SL_SFIG_soft_within_005] <= n[SL_SFIG_soft_within_010]);
        /* a point light gives 0 or 1: never a penumbra, so every penumbra pixel is an error */
        assert_int_equal(n[SL_SFIG_soft_penumbra_right], 0);
        assert_true(cl->soft.pct[SL_SFIG_soft_mae] > 1.0);
        assert_true(cl->soft.pct[SL_SFIG_soft_rmse] >= cl->soft.pct[SL_SFIG_soft_mae]);
        /* where the whole light is seen, so is its centre (up to an occluder slipping between
         * every sample but not the centre): at least 99.9% */
        assert_true(n[SL_SFIG_soft_lit_right] * 1000 >= n[SL_SFIG_soft_truth_lit] * 999);
        assert_true(n[SL_SFIG_soft_umbra_right] * 1000 >= n[SL_SFIG_soft_truth_umbra] * 999);
        /* one ray per pixel that faces the light's centre, none for the others */
        assert_true(cl->cost.rays > n[SL_SFIG_soft_pixels] / 2 && cl->cost.rays <= n[SL_SFIG_soft_pixels]);
    }
    /* the same again, bit for bit */
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_same_figures(&a, &b);
    sl_run_result_free(&a);
    sl_run_result_free(&b);
    sl_config_free(&c);
}

/* soft_mc through the driver: its layers once per (view, map size), output
 * in [0, 1], bit for bit again, and closer to the area truth than the
 * hard-shadow approximation on Curtis's case; the single-layer variant and
 * 2x2 grid in between. */
static void soft_mc_driver(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("mc.yaml",
                   "scenes: [{scene: curtis_box}]\nviewports: [{width: 128, height: 96}]\nmap_sizes: [512, 1024]\n"
                   "methods:\n  - {label: point, method: hard_point}\n  - {label: mc3, method: soft_mc}\n"
                   "  - {label: mc2, method: soft_mc, grid: 2}\n  - {label: one, method: soft_mc, layers: 1}\n"
                   "  - {label: lin, method: soft_mc, search: linear}\n  - {label: blur, method: soft_mc, blur: true}\n"
                   "area_samples: 16\n", &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result a, b;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(a.ncells, 2 * 2 * 6);
    assert_int_equal(a.passes.soft_truths, 2);
    assert_int_equal(a.passes.soft_layers, 2 * 2);        /* per (view, map size), shared by 5 labels */
    for (int i = 0; i < a.ncells; i += 6) {
        const struct sl_cell *cl = &a.cells[i];
        double point = cl[0].soft.pct[SL_SFIG_soft_mae], mc3 = cl[1].soft.pct[SL_SFIG_soft_mae],
               mc2 = cl[2].soft.pct[SL_SFIG_soft_mae], one = cl[3].soft.pct[SL_SFIG_soft_mae];
        printf("soft::mc_driver: %s map %d: MAE point %.3f, mc 2x2 %.3f, 3x3 %.3f, one layer %.3f, "
               "linear %.3f, blurred %.3f (%% of visibility)\n", cl->viewpoint, c.maps[cl->key.map], point, mc2,
               mc3, one, cl[4].soft.pct[SL_SFIG_soft_mae], cl[5].soft.pct[SL_SFIG_soft_mae]);
        assert_true(mc3 < mc2 && mc2 < point);
        assert_true(mc3 < one);
        for (int k = 0; k < 6; k++) {
            assert_true(cl[k].has_soft);
            assert_int_equal(cl[k].nonfinite, 0);               /* every fraction in [0, 1] */
        }
        /* soft_mc gives penumbrae; a point light cannot */
        assert_true(cl[1].soft.n[SL_SFIG_soft_penumbra_right] > 0);
        assert_true(cl[1].cost.rays > 0 && cl[1].cost.lookups > 0);
    }
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);
    /* another seed moves the samples of both the truth and soft_mc */
    c.seed = 7;
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    int moved = 0;
    for (int i = 0; i < a.ncells; i++)
        moved += a.cells[i].soft.pct[SL_SFIG_soft_mae] != b.cells[i].soft.pct[SL_SFIG_soft_mae];
    assert_true(moved > a.ncells / 2);
    sl_run_result_free(&a);
    sl_run_result_free(&b);
    sl_config_free(&c);
}

/* soft_mc with layers: 3 (Curtis 3.4, the camera's depth) through the
 * driver. The search defaults to linear with three layers and stays
 * hierarchical with one or two; three layers with search: hierarchical is
 * a config error naming the key. On both area-light scenes: every fraction
 * in [0, 1], the figures bit for bit on a second run and on 1 thread
 * against 2, the layers rendered once per (view, map size) for both
 * labels, and the MAE against the area truth printed beside two layers'
 * (same samples: linear search, same seed). The third layer only removes
 * hits, on the changed pixels only, and a truth off by d moves |a - t| -
 * |b - t| by at most 2|d|: so three layers may look worse than two by at
 * most twice the truth's mean standard error, which is asserted; measured
 * (this build, 160x120, 1024^2): curtis_box equal to the digit, soft_wuson
 * better on both views. */
static void soft_three_layers(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("three.yaml",
                   "scenes: [{scene: curtis_box}, {scene: soft_wuson}]\nviewports: [{width: 160, height: 120}]\n"
                   "map_sizes: [1024]\nmethods:\n  - {label: lin, method: soft_mc, search: linear}\n"
                   "  - {label: three, method: soft_mc, layers: 3}\n  - {label: hier, method: soft_mc}\n"
                   "area_samples: 16\nthreads: 2\n", &c);
    assert_int_equal(sl_params_get(&c.methods[1].params.values, "layers"), 3);
    assert_int_equal(sl_params_get(&c.methods[1].params.values, "search"), 0);        /* linear */
    assert_int_equal(sl_params_get(&c.methods[2].params.values, "layers"), 2);
    assert_int_equal(sl_params_get(&c.methods[2].params.values, "search"), 1);        /* hierarchical, as before */
    struct sl_config one;
    sl_test_config("one.yaml",
                   "scenes: [{scene: curtis_box}]\nmap_sizes: [512]\nmethods: [{method: soft_mc, layers: 1}]\n",
                   &one);
    assert_int_equal(sl_params_get(&one.methods[0].params.values, "search"), 1);
    /* refused, with the key named */
    char path[300];
    snprintf(path, sizeof path, "%s/hier3.yaml", sl_test_dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("scenes: [{scene: curtis_box}]\nmap_sizes: [512]\n"
          "methods:\n  - {method: soft_mc, layers: 3, search: hierarchical}\n", f);
    fclose(f);
    struct sl_config bad;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &bad, &d), SL_E_CONFIG);
    assert_string_equal(d.key, "methods[0].layers");
    assert_int_equal(d.line, 4);
    assert_non_null(strstr(d.msg, "search: linear"));

    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result a, b;
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(a.ncells, 2 * 2 * 3);                  /* 2 scenes x 2 views x 3 labels */
    assert_int_equal(a.passes.soft_layers, 4);              /* once per view: shared by the labels */
    int wuson_better = 0;
    for (int i = 0; i < a.ncells; i += 3) {
        const struct sl_cell *lin = &a.cells[i], *three = &a.cells[i + 1];
        assert_string_equal(c.methods[three->key.method].label, "three");
        for (int k = 0; k < 3; k++) {
            assert_true(a.cells[i + k].has_soft);
            assert_int_equal(a.cells[i + k].nonfinite, 0);   /* every fraction in [0, 1] */
        }
        const double m2 = lin->soft.pct[SL_SFIG_soft_mae], m3 = three->soft.pct[SL_SFIG_soft_mae];
        const double se = lin->soft.pct[SL_SFIG_soft_truth_stderr];
        const char *scene = c.scenes[lin->key.scene].name;
        printf("soft::three_layers: %s / %s: MAE two layers (linear) %.3f, three layers %.3f, hierarchical "
               "%.3f (%% of visibility; truth's mean standard error %.3f)\n", scene, lin->viewpoint, m2, m3,
               a.cells[i + 2].soft.pct[SL_SFIG_soft_mae], se);
        assert_true(m3 <= m2 + 2.0 * se);
        if (!strcmp(scene, "soft_wuson"))
            wuson_better += m3 < m2;
    }
    assert_int_equal(wuson_better, 2);
    /* bit for bit: again, and on one thread */
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);
    c.threads = 1;
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_same_figures(&a, &b);
    sl_run_result_free(&a);
    sl_run_result_free(&b);
    sl_config_free(&bad);
    sl_config_free(&c);
    sl_config_free(&one);
}

/* point_map, the light as a point through a shadow map, is hard_point plus
 * the map's aliasing: 0 or 1 everywhere, and on Curtis's case within a
 * fraction of a point of hard_point's error. */
static void soft_point_map(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("pm.yaml",
                   "scenes: [{scene: curtis_box}]\nviewports: [{width: 128, height: 96}]\nmap_sizes: [1024]\n"
                   "methods:\n  - {label: point, method: hard_point}\n  - {label: map, method: point_map}\n"
                   "area_samples: 8\n", &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 2 * 2);
    for (int i = 0; i < r.ncells; i += 2) {
        const struct sl_cell *point = &r.cells[i], *map = &r.cells[i + 1];
        assert_int_equal(map->soft.n[SL_SFIG_soft_penumbra_right], 0);   /* a point gives no penumbra */
        assert_int_equal(map->nonfinite, 0);
        double dm = map->soft.pct[SL_SFIG_soft_mae] - point->soft.pct[SL_SFIG_soft_mae];
        printf("soft::point_map: %s: MAE hard_point %.3f, point_map %.3f\n", point->viewpoint,
               point->soft.pct[SL_SFIG_soft_mae], map->soft.pct[SL_SFIG_soft_mae]);
        assert_true(fabs(dm) < 0.5);
        /* one ray per pixel at most: the centre (classified pixels need none) */
        assert_true(map->cost.rays <= map->soft.n[SL_SFIG_soft_pixels]);
    }
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* The hard-shadow methods under an area light taken as a point at its
 * centre: a perspective frustum from the centre, rays to the centre. Their
 * hard figures answer to the point's truth, so the exact ones are exact and
 * make no wrong pixel, and their visible fraction (0/1) scored against the
 * area truth is hard_point's, figure for figure; the plain map's aliasing
 * falls with the map size, and the conservative layers do decide pixels
 * (a frustum that missed receivers or casters would break one or the
 * other). The soft figures of every hard cell add up as a soft cell's. */
static void soft_hard_methods(void **st)
{
    (void)st;
    struct sl_config c;
    static const char *const labels[] = {"point", "nsm", "slope", "coherence", "texel", "neighbours",
                                         "adjacency", "chain", "bgsm", "sgsm", "sgsm_adj", "csm", "csm_adj",
                                         "hertel_exact", "raytrace"};
    enum { NL = sizeof labels / sizeof labels[0] };
    sl_test_config("hardarea.yaml",
                   "scenes: [{scene: curtis_box}]\nviewports: [{width: 160, height: 120}]\nmap_sizes: [256, 2048]\n"
                   "methods:\n  - {label: point, method: hard_point}\n  - {label: nsm, method: nsm}\n"
                   "  - {label: slope, method: nsm, self_shadow: slope, bias: 1, slope: 1}\n"
                   "  - {label: coherence, method: coherence, texels: 9}\n  - {label: texel, method: texel}\n"
                   "  - {label: neighbours, method: neighbours, texels: 9}\n"
                   "  - {label: adjacency, method: adjacency, level: 2}\n  - {label: chain, method: chain}\n"
                   "  - {label: bgsm, method: bgsm}\n  - {label: sgsm, method: sgsm}\n"
                   "  - {label: sgsm_adj, method: sgsm_adj}\n  - {label: csm, method: csm}\n"
                   "  - {label: csm_adj, method: csm_adj}\n  - {label: hertel_exact, method: hertel_exact}\n"
                   "  - {label: raytrace, method: raytrace}\n"
                   "area_samples: 8\n", &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 2 * 2 * NL);                 /* 2 views x 2 map sizes x every label */
    assert_int_equal(r.passes.soft_truths, 2);
    assert_int_equal(r.passes.truths_traced, 2);
    assert_int_equal(r.passes.layers[SL_LAYER_BGSM], 4);    /* once per (view, map size) */
    assert_int_equal(r.passes.soft_layers, 0);
    for (int i = 0; i < r.ncells; i += NL) {
        const struct sl_cell *point = &r.cells[i];
        assert_string_equal(c.methods[point->key.method].label, "point");
        int map = c.maps[point->key.map];
        for (int k = 1; k < NL; k++) {
            const struct sl_cell *cl = &r.cells[i + k];
            const char *label = c.methods[cl->key.method].label;
            assert_string_equal(label, labels[k]);
            assert_true(cl->has_soft);
            assert_true(cl->fig.nregions > 0);
            assert_int_equal(cl->violations, 0);
            assert_int_equal(cl->nonfinite, 0);
            const struct sl_region_figures *img = &cl->fig.r[cl->fig.nregions - 1];
            const uint64_t *n = cl->soft.n;
            assert_int_equal(n[SL_SFIG_soft_pixels], cl->n_pfl + cl->n_pnfl);
            assert_int_equal(n[SL_SFIG_soft_truth_lit] + n[SL_SFIG_soft_truth_umbra] +
                             n[SL_SFIG_soft_truth_penumbra], n[SL_SFIG_soft_pixels]);
            int exact = !strcmp(label, "chain") || !strcmp(label, "csm") || !strcmp(label, "csm_adj") ||
                        !strcmp(label, "hertel_exact") || !strcmp(label, "raytrace");
            printf("soft::hard_methods: %s %d %-10s wrong %5llu uncertain %5llu MAE %.3f (hard_point %.3f)\n",
                   cl->viewpoint, map, label, (unsigned long long)img->n[SL_FIG_wrong],
                   (unsigned long long)img->n[SL_FIG_uncertain], cl->soft.pct[SL_SFIG_soft_mae],
                   point->soft.pct[SL_SFIG_soft_mae]);
            if (exact) {
                assert_int_equal(img->n[SL_FIG_wrong], 0);
                assert_int_equal(img->n[SL_FIG_uncertain], 0);
                assert_memory_equal(cl->soft.n, point->soft.n, sizeof cl->soft.n);
                assert_memory_equal(cl->soft.pct, point->soft.pct, sizeof cl->soft.pct);
            }
            if (!strcmp(label, "bgsm")) {
                /* conservative, and deciding most lit pixels at 2048² */
                assert_int_equal(img->n[SL_FIG_light_incorrect], 0);
                if (map == 2048)
                    assert_true(img->n[SL_FIG_light] * 10 >= cl->n_truth_lit * 8);
            }
            if (!strcmp(label, "sgsm") || !strcmp(label, "sgsm_adj"))
                assert_int_equal(img->n[SL_FIG_shadow_incorrect], 0);   /* its shadow is proved */
            if (!strcmp(label, "nsm")) {
                /* aliasing: some at 256², under 1% of the PFL pixels at 2048² */
                if (map == 256)
                    assert_true(img->n[SL_FIG_wrong] > 0);
                else
                    assert_true(img->n[SL_FIG_wrong] * 100 < cl->n_pfl);
            }
        }
    }
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* No area light, no soft pass. */
static void soft_none_without_area_light(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("hard.yaml", "scenes: [{scene: blocks}]\nviewports: [{width: 64, height: 64}]\n"
                   "map_sizes: [256]\nmethods: [{method: nsm}]\n", &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.passes.soft_truths, 0);
    assert_int_equal(r.passes.soft_layers, 0);
    assert_int_equal(r.passes.truths_traced, 1);
    assert_false(r.cells[0].has_soft);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* Files in `dir` whose name starts with `prefix` and ends in .bin (no temporaries). */
static int count_files(const char *dir, const char *prefix)
{
    DIR *dp = opendir(dir);
    if (!dp)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(dp))) {
        size_t l = strlen(e->d_name);
        n += strncmp(e->d_name, prefix, strlen(prefix)) == 0 && l > 4 && strcmp(e->d_name + l - 4, ".bin") == 0;
    }
    closedir(dp);
    return n;
}

/* The one file in `dir` starting with `prefix`, into path; its size. */
static long one_file(const char *dir, const char *prefix, char *path, size_t size)
{
    DIR *dp = opendir(dir);
    assert_non_null(dp);
    struct dirent *e;
    long len = -1;
    while ((e = readdir(dp)))
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0) {
            snprintf(path, size, "%s/%s", dir, e->d_name);
            struct stat sb;
            assert_int_equal(stat(path, &sb), 0);
            len = (long)sb.st_size;
            break;
        }
    closedir(dp);
    assert_true(len > 0);
    return len;
}

static const char *cache_cfg =
    "scenes: [{scene: curtis_box}]\nviewports: [{width: 64, height: 48}]\nmap_sizes: [256]\n"
    "methods:\n  - {label: point, method: hard_point}\n  - {label: nsm, method: nsm}\n"
    "  - {label: mc, method: soft_mc, grid: 2}\narea_samples: 4\nseed: 3\n";

/* An area light's truths (visible fraction, standard error, the centre's
 * hard truth) come from the cache on a second run, counted, with every
 * figure as traced; another sample count or seed is another file; a file
 * cut short or with a flipped byte is refused, recomputed and replaced. */
static void soft_truth_cache(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("cache.yaml", cache_cfg, &c);
    char cache[300], cmd[400];
    snprintf(cache, sizeof cache, "%s/softcache", sl_test_dir);
    snprintf(cmd, sizeof cmd, "mkdir -p %s", cache);
    assert_int_equal(system(cmd), 0);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = cache};
    struct sl_run_result a, b;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(a.ncells, 2 * 3);
    assert_int_equal(a.passes.soft_truths, 2);
    assert_int_equal(a.passes.truths_traced, 2);
    assert_int_equal(a.passes.truths_cached, 0);
    assert_int_equal(a.passes.soft_truths_cached, 0);
    assert_int_equal(a.passes.cache_rejected, 0);
    assert_int_equal(count_files(cache, "area-"), 2);     /* one per view */
    assert_int_equal(count_files(cache, "truth-"), 0);    /* the centre's truth lives in the area file */
    for (int i = 0; i < a.ncells; i++) {
        assert_int_equal(a.cells[i].truth_cached, 0);
        assert_true(a.cells[i].truth_rays > 0);
    }

    /* the same run again: read, not traced, and the same to the bit */
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.truths_traced, 0);
    assert_int_equal(b.passes.soft_truths, 0);
    assert_int_equal(b.passes.truths_cached, 2);
    assert_int_equal(b.passes.soft_truths_cached, 2);
    assert_int_equal(b.passes.cache_rejected, 0);
    assert_int_equal(b.passes.gbuffers, 2);               /* methods still need the G-buffer */
    for (int i = 0; i < b.ncells; i++) {
        assert_int_equal(b.cells[i].truth_cached, 1);
        /* a count is the computation's, not the cache's (issue 34): the
         * rays the truth read from the file took to trace */
        assert_int_equal(b.cells[i].truth_rays, a.cells[i].truth_rays);
    }
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);

    /* another sample count, another seed: other truths, other files */
    c.area_samples = 6;
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths, 2);
    assert_int_equal(b.passes.truths_cached, 0);
    assert_int_equal(b.passes.cache_rejected, 0);
    int moved = 0;
    for (int i = 0; i < b.ncells; i++)
        moved += a.cells[i].soft.pct[SL_SFIG_soft_mae] != b.cells[i].soft.pct[SL_SFIG_soft_mae];
    assert_true(moved > 0);
    sl_run_result_free(&b);
    c.area_samples = 4;
    c.seed = 4;
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths, 2);
    assert_int_equal(b.passes.truths_cached, 0);
    assert_int_equal(b.passes.cache_rejected, 0);
    sl_run_result_free(&b);
    assert_int_equal(count_files(cache, "area-"), 6);
    /* the first files are still there and still read */
    c.seed = 3;
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths_cached, 2);
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);

    /* a file cut short: refused, traced again, rewritten whole */
    snprintf(cmd, sizeof cmd, "rm -rf %s && mkdir -p %s", cache, cache);
    assert_int_equal(system(cmd), 0);
    o.last = 3;                                           /* the first view's cells */
    sl_run_result_free(&a);
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(a.passes.soft_truths, 1);
    char path[600];
    long len = one_file(cache, "area-", path, sizeof path);
    assert_int_equal(truncate(path, len - 100), 0);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.cache_rejected, 1);
    assert_int_equal(b.passes.soft_truths, 1);
    assert_int_equal(b.passes.truths_cached, 0);
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);
    assert_int_equal(one_file(cache, "area-", path, sizeof path), len);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths_cached, 1);
    sl_run_result_free(&b);

    /* one byte of the payload flipped, the length unchanged: the checksum refuses it */
    FILE *f = fopen(path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, len / 2, SEEK_SET), 0);
    int byte = fgetc(f);
    assert_int_equal(fseek(f, len / 2, SEEK_SET), 0);
    fputc(byte ^ 0x10, f);
    fclose(f);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.cache_rejected, 1);
    assert_int_equal(b.passes.soft_truths, 1);
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);

    /* a foreign file of the right length under the name: refused */
    f = fopen(path, "wb");
    assert_non_null(f);
    for (long i = 0; i < len; i++)
        fputc((int)(i * 7 & 0xff), f);
    fclose(f);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.cache_rejected, 1);
    assert_int_equal(b.passes.soft_truths, 1);
    assert_same_figures(&a, &b);
    sl_run_result_free(&b);
    sl_run_result_free(&a);
    sl_config_free(&c);
}

/* No cache ("" — what `run --no-cache` passes): a filled cache is not read
 * and nothing is written, neither to the default folder. */
static void soft_truth_no_cache(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("nocache.yaml", cache_cfg, &c);
    char root[300], cache[400], cmd[500];
    snprintf(root, sizeof root, "%s/nocache", sl_test_dir);
    snprintf(cache, sizeof cache, "%s/cache", root);
    /* the default folder, <out_root>/cache, filled by a run that writes files */
    struct sl_run_opts w = {.out_root = root, .write_files = 1, .store = ""};
    struct sl_run_result a, b;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &w, &a, &d), SL_OK);
    assert_int_equal(a.passes.soft_truths, 2);
    assert_int_equal(count_files(cache, "area-"), 2);
    sl_run_result_free(&a);
    assert_int_equal(sl_run(&c, &w, &a, &d), SL_OK);
    assert_int_equal(a.passes.soft_truths_cached, 2);
    sl_run_result_free(&a);
    /* the same with the cache off: traced, although the files are there */
    w.cache_dir = "";
    assert_int_equal(sl_run(&c, &w, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths, 2);
    assert_int_equal(b.passes.truths_cached, 0);
    assert_int_equal(b.passes.soft_truths_cached, 0);
    assert_int_equal(b.passes.cache_rejected, 0);
    sl_run_result_free(&b);
    /* and an empty output root gets no cache folder */
    snprintf(cmd, sizeof cmd, "rm -rf %s", cache);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(sl_run(&c, &w, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths, 2);
    assert_int_equal(count_files(cache, ""), -1);          /* no folder */
    sl_run_result_free(&b);
    /* compute-only runs have no cache by default either */
    struct sl_run_opts o = {.write_files = 0, .store = ""};
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    assert_int_equal(b.passes.soft_truths, 2);
    assert_int_equal(b.passes.truths_cached, 0);
    sl_run_result_free(&b);
    sl_config_free(&c);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(soft, driver),
        SL_CASE(soft, mc_driver),
        SL_CASE(soft, three_layers),
        SL_CASE(soft, point_map),
        SL_CASE(soft, hard_methods),
        SL_CASE(soft, none_without_area_light),
        SL_CASE(soft, truth_cache),
        SL_CASE(soft, truth_no_cache),
    };
    return sl_run_group(argc, argv, "soft", tests, sl_test_setup, sl_test_teardown);
}
