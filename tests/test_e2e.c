/*
 * e2e::* — the default experiment end to end, its files, and invariants of
 * its figures; the self-shadow policies on one view; determinism.
 */
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
#include "image.h"
#include "method.h"
#include "overlay.h"
#include "view.h"
#include "run.h"

static int exists(const char *dir, const char *name)
{
    char p[1400];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return stat(p, &st) == 0 && st.st_size > 0;
}

static void check_counts(const struct sl_config *c, const struct sl_run_result *r)
{
    for (int i = 0; i < r->ncells; i++) {
        const struct sl_cell *cl = &r->cells[i];
        uint64_t W = (uint64_t)c->viewport_w[cl->key.viewport], H = (uint64_t)c->viewport_h[cl->key.viewport];
        assert_int_equal(cl->n_pfl + cl->n_pnfl + cl->n_background, W * H);
        assert_int_equal(cl->n_truth_lit + cl->n_truth_shadow, cl->n_pfl);
        assert_int_equal(cl->fig.background, cl->n_background);
        for (int k = 0; k < cl->fig.nregions; k++) {
            const uint64_t *n = cl->fig.r[k].n;
            assert_int_equal(n[SL_FIG_pfl] + n[SL_FIG_pnfl], n[SL_FIG_pixels]);
            assert_int_equal(n[SL_FIG_light] + n[SL_FIG_shadow] + n[SL_FIG_uncertain], n[SL_FIG_pixels]);
            assert_int_equal(n[SL_FIG_light_correct] + n[SL_FIG_light_incorrect], n[SL_FIG_light]);
            assert_int_equal(n[SL_FIG_shadow_correct] + n[SL_FIG_shadow_incorrect], n[SL_FIG_shadow]);
            assert_int_equal(n[SL_FIG_light_incorrect] + n[SL_FIG_shadow_incorrect], n[SL_FIG_wrong]);
            assert_true(n[SL_FIG_wrong_caught] <= cl->fig.wrong_image);
            if (k > 0 && cl->fig.r[k].thickness != 0)   /* thicker contours hold more */
                assert_true(n[SL_FIG_pixels] >= cl->fig.r[k - 1].n[SL_FIG_pixels]);
        }
        const struct sl_region_figures *img = &cl->fig.r[cl->fig.nregions - 1];
        assert_int_equal(img->thickness, 0);
        assert_int_equal(img->n[SL_FIG_pixels] + cl->n_background, W * H);
        assert_int_equal(img->n[SL_FIG_pfl], cl->n_pfl);
        assert_int_equal(img->n[SL_FIG_wrong], cl->fig.wrong_image);
        assert_int_equal(cl->cost.lookups, cl->n_pfl);
    }
}

static void e2e_default_experiment(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/default.yaml", &c, &d), SL_OK);
    struct sl_run_opts o = {.out_root = sl_test_dir, .table_out = NULL, .write_files = 1};
    struct sl_run_result r;
    enum sl_err e = sl_run(&c, &o, &r, &d);
    if (e)
        fprintf(stderr, "%s\n", d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(r.ncells, 3 * 2);
    check_counts(&c, &r);
    for (int i = 0; i < r.ncells; i++) {
        /* with front faces culled, wrong pixels are a few percent of the
         * shadowed ones at most (1.1-1.7% measured; no bias gives ~170%) */
        const struct sl_cell *cl = &r.cells[i];
        const struct sl_region_figures *img = &cl->fig.r[cl->fig.nregions - 1];
        assert_true(cl->fig.wrong_image * 100 < 3 * (cl->n_truth_shadow + cl->n_pnfl));
        assert_true(img->n[SL_FIG_shadow] > 0);
    }

    for (int vp = 0; vp < 3; vp++) {
        const struct sl_cell *m1024 = &r.cells[vp * 2], *m2048 = &r.cells[vp * 2 + 1];
        assert_int_equal(c.maps[m1024->key.map], 1024);
        assert_int_equal(c.maps[m2048->key.map], 2048);
        const struct sl_figures *a = &m1024->fig, *b = &m2048->fig;
        printf("e2e::default %s: wrong %llu (1024²) -> %llu (2048²); caught in 2/4/6 px: "
               "%.2f%% %.2f%% %.2f%% (1024²), %.2f%% %.2f%% %.2f%% (2048²)\n",
               m1024->viewpoint, (unsigned long long)a->wrong_image, (unsigned long long)b->wrong_image,
               a->r[0].pct[SL_FIG_wrong_caught], a->r[1].pct[SL_FIG_wrong_caught],
               a->r[2].pct[SL_FIG_wrong_caught], b->r[0].pct[SL_FIG_wrong_caught],
               b->r[1].pct[SL_FIG_wrong_caught], b->r[2].pct[SL_FIG_wrong_caught]);
        /* aliasing falls with map resolution */
        assert_true(a->wrong_image > 0);
        assert_true(b->wrong_image < a->wrong_image);
        /* the share of wrong pixels inside the 6-px contour is reported */
        assert_int_equal(a->r[2].thickness, 6);
        assert_false(isnan(a->r[2].pct[SL_FIG_wrong_caught]));
        assert_true(a->r[2].pct[SL_FIG_wrong_caught] >= a->r[0].pct[SL_FIG_wrong_caught]);
        assert_true(a->r[2].pct[SL_FIG_wrong_caught] <= 100.0);
    }

    /* files */
    char dir[1200];
    snprintf(dir, sizeof dir, "%s/default", sl_test_dir);
    const char *files[] = {"figures.csv", "costs.csv", "table.md", "config.yaml", "run.yaml"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++)
        assert_true(exists(dir, files[i]));
    char png[1400];
    snprintf(png, sizeof png, "%s/overlays/primitives-side-1024x1024-1024-nsm.png", dir);
    int w, h, v[6];
    unsigned char *rgb;
    char at[200];
    assert_int_equal(sl_image_read_rgb8(png, &w, &h, &rgb, &d), SL_OK);
    /* the sheet: the frame at 1:1 where "shadowlab:view" says (x y w h X Y) */
    assert_int_equal(sl_image_read_attr(png, "shadowlab:view", at, sizeof at, &d), SL_OK);
    assert_int_equal(sscanf(at, "%d %d %d %d %d %d", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]), 6);
    /* the ground fills the frame, the shadows and errors less than half of
     * it: cropped to them (every wrong pixel still in view: counted below) */
    assert_true(v[2] < 1024 && v[3] < 1024 && 2 * v[2] * v[3] < 1024 * 1024);
    assert_true(w > v[2] && h > v[3]);   /* insets beside it, legend below */
    long tint = 0, grey = 0, wrong = 0, white = 0;
    for (int y = 0; y < v[3]; y++)
        for (int x = 0; x < v[2]; x++) {
            const unsigned char *p = rgb + 3 * ((size_t)(v[5] + y) * (size_t)w + (size_t)(v[4] + x));
            int e = 0;
            for (int k = 0; k <= SL_OV_UNCERTAIN; k++)
                e |= !memcmp(p, sl_overlay_colour[k], 3);
            wrong += e;
            white += p[0] == 255 && p[1] == 255 && p[2] == 255;
            grey += p[0] == p[1] && p[1] == p[2] && p[0] > 0 && p[0] < 255;
            tint += !e && p[1] > p[0] && p[2] > p[0];   /* the contour: grey blended with bluish green */
        }
    free(rgb);
    /* the overlay's coloured pixels are the figures' own: every wrong pixel
     * in its colour, the contour's right pixels tinted but where a white
     * inset mark lies over one */
    const struct sl_region_figures *c2 = &r.cells[0].fig.r[0];
    long contour_right = (long)(c2->n[SL_FIG_pixels] - c2->n[SL_FIG_wrong]);
    assert_int_equal(wrong, (long)r.cells[0].fig.wrong_image);
    assert_true(tint <= contour_right && tint + white >= contour_right);
    assert_true(white > 0);
    assert_true(grey > (long)v[2] * v[3] / 2);
    /* no staging folders left behind */
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "ls -A %s | grep -q partial", sl_test_dir);
    assert_int_not_equal(system(cmd), 0);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

static int write_config(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    fputs(text, f);
    fclose(f);
    return 1;
}

/* The self-shadow policies do what they claim on the side view. */
static void e2e_self_shadow_policies(void **st)
{
    (void)st;
    char path[1200];
    snprintf(path, sizeof path, "%s/policies.yaml", sl_test_dir);
    assert_true(write_config(path,
        "scenes: [{scene: primitives, viewpoints: [side]}]\nviewports: [{width: 512, height: 512}]\n"
        "map_sizes: [1024]\nmethods:\n"
        "  - {label: ff, method: nsm, self_shadow: front_faces}\n"
        "  - {label: none, method: nsm, self_shadow: none}\n"
        "  - {label: const, method: nsm, self_shadow: constant, bias: 1.5}\n"
        "  - {label: slope, method: nsm, self_shadow: slope}\n"
        "  - {label: id, method: nsm, self_shadow: triangle_id}\n"));
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    struct sl_run_opts o = {.write_files = 0};
    struct sl_run_result r;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 5);
    check_counts(&c, &r);
    uint64_t w[5], ws[5];
    for (int i = 0; i < 5; i++) {
        const struct sl_region_figures *img = &r.cells[i].fig.r[r.cells[i].fig.nregions - 1];
        w[i] = r.cells[i].fig.wrong_image;
        ws[i] = img->n[SL_FIG_shadow_incorrect];
        printf("e2e::policy %-6s wrong %6llu (wrongly shadowed %6llu, wrongly lit %6llu)\n", c.methods[i].label,
               (unsigned long long)w[i], (unsigned long long)ws[i],
               (unsigned long long)img->n[SL_FIG_light_incorrect]);
    }
    /* no bias: self-shadowing acne, wrongly shadowed pixels everywhere */
    assert_true(ws[1] > 10 * ws[0]);
    /* every remedy removes most of it */
    assert_true(ws[2] * 4 < ws[1]);
    assert_true(ws[3] * 4 < ws[1]);
    assert_true(ws[4] * 4 < ws[1]);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* Same figures on a second run and with one thread instead of two. */
static void e2e_deterministic(void **st)
{
    (void)st;
    char path[1200];
    snprintf(path, sizeof path, "%s/det.yaml", sl_test_dir);
    assert_true(write_config(path,
        "scenes: [{scene: primitives, viewpoints: [against]}]\nviewports: [{width: 384, height: 256}]\n"
        "map_sizes: [512, 2048]\nmethods: [{method: nsm}]\nthreads: 2\n"));
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    struct sl_run_opts o = {.write_files = 0};
    struct sl_run_result a, b, t1;
    assert_int_equal(sl_run(&c, &o, &a, &d), SL_OK);
    assert_int_equal(sl_run(&c, &o, &b, &d), SL_OK);
    c.threads = 1;
    assert_int_equal(sl_run(&c, &o, &t1, &d), SL_OK);
    for (int i = 0; i < a.ncells; i++) {
        assert_memory_equal(a.cells[i].fig.r, b.cells[i].fig.r, sizeof a.cells[i].fig.r);
        assert_memory_equal(a.cells[i].fig.r, t1.cells[i].fig.r, sizeof a.cells[i].fig.r);
    }
    sl_run_result_free(&a);
    sl_run_result_free(&b);
    sl_run_result_free(&t1);
    sl_config_free(&c);
}

/* The EXR layers hold the very pixels the figures count. */
static void e2e_exr_layers(void **st)
{
    (void)st;
    char path[1200];
    snprintf(path, sizeof path, "%s/exr.yaml", sl_test_dir);
    assert_true(write_config(path,
        "name: exr\nscenes: [{scene: blocks}]\nviewports: [{width: 96, height: 64}]\n"
        "map_sizes: [256]\nmethods: [{method: nsm}]\noutputs: {exr: true, overlays: false}\n"));
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    struct sl_run_opts o = {.out_root = sl_test_dir, .write_files = 1, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    snprintf(path, sizeof path, "%s/exr/exr/blocks-above-96x64-256-nsm.exr", sl_test_dir);
    unsigned *truth, *verdict, *contour;
    int w, h;
    assert_int_equal(sl_image_read_layer(path, "truth", &w, &h, &truth, &d), SL_OK);
    assert_int_equal(w, 96);
    assert_int_equal(h, 64);
    assert_int_equal(sl_image_read_layer(path, "verdict", &w, &h, &verdict, &d), SL_OK);
    assert_int_equal(sl_image_read_layer(path, "contour", &w, &h, &contour, &d), SL_OK);
    uint64_t lit = 0, wrong = 0, bg = 0, in2 = 0;
    for (int i = 0; i < w * h; i++) {
        lit += verdict[i] == SL_V_LIT;
        bg += truth[i] == SL_T_BACKGROUND;
        wrong += (verdict[i] == SL_V_LIT && truth[i] == SL_T_SHADOW) ||
                 (verdict[i] == SL_V_SHADOW && truth[i] == SL_T_LIT);
        in2 += contour[i] == 1;
    }
    const struct sl_figures *f = &r.cells[0].fig;
    assert_int_equal(lit, f->r[f->nregions - 1].n[SL_FIG_light]);
    assert_int_equal(bg, f->background);
    assert_int_equal(wrong, f->wrong_image);
    assert_int_equal(in2, f->r[0].n[SL_FIG_pixels]);
    assert_true(lit > 0 && bg > 0);
    /* the mesh layer: 0 on background alone, else the pixel's mesh in the
     * scene file's order, named in the header; the blocks' four meshes
     * all seen from above, the ground most */
    unsigned *mesh;
    assert_int_equal(sl_image_read_layer(path, "mesh", &w, &h, &mesh, &d), SL_OK);
    char legend[256];
    assert_int_equal(sl_image_read_attr(path, "shadowlab:mesh", legend, sizeof legend, &d), SL_OK);
    assert_string_equal(legend, "0 background, 1 ground, 2 block, 3 slab, 4 pyramid");
    uint64_t on[5] = {0, 0, 0, 0, 0};
    for (int i = 0; i < w * h; i++) {
        assert_true(mesh[i] <= 4);
        assert_int_equal(mesh[i] == 0, truth[i] == SL_T_BACKGROUND);
        on[mesh[i]]++;
    }
    assert_true(on[1] > on[2] && on[2] > 0 && on[3] > 0 && on[4] > 0);
    free(mesh);
    free(truth);
    free(verdict);
    free(contour);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* A two-sided leaf facing the light stays in the front-face-culled map; the
 * same leaf one-sided is culled and casts no shadow at all. */
static void e2e_two_sided_leaf(void **st)
{
    (void)st;
    /* the config lives in a temporary folder: name the scenes by absolute
     * path (ctest runs the tests from the source tree) */
    char cwd[900], path[1200], text[2048];
    assert_non_null(getcwd(cwd, sizeof cwd));
    snprintf(path, sizeof path, "%s/leaf.yaml", sl_test_dir);
    uint64_t wrong[2], shadow[2];
    for (int one = 0; one < 2; one++) {
        snprintf(text, sizeof text,
                 "scenes: [{scene: %s/tests/scenes/%s.yaml}]\nviewports: [{width: 256, height: 256}]\n"
                 "map_sizes: [512]\nmethods: [{method: nsm, self_shadow: front_faces}]\n",
                 cwd, one ? "leaf_one_sided" : "leaf");
        assert_true(write_config(path, text));
        struct sl_config c;
        struct sl_diag d;
        assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
        struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
        struct sl_run_result r;
        assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
        /* wrongly lit: the ground the leaf shades but the map misses (a
         * two-sided leaf also shadows itself here, acne the front-face
         * policy cannot prevent on surfaces it does not cull: that is
         * wrongly shadowed, counted apart) */
        const struct sl_figures *f = &r.cells[0].fig;
        wrong[one] = f->r[f->nregions - 1].n[SL_FIG_light_incorrect];
        shadow[one] = r.cells[0].n_truth_shadow;
        sl_run_result_free(&r);
        sl_config_free(&c);
    }
    printf("e2e::two_sided_leaf: truth shadow %llu px; wrongly lit two-sided %llu, one-sided %llu\n",
           (unsigned long long)shadow[0], (unsigned long long)wrong[0], (unsigned long long)wrong[1]);
    assert_int_equal(shadow[0], shadow[1]);          /* the truth does not cull */
    assert_true(shadow[0] > 500);
    assert_true(wrong[0] * 10 < shadow[0]);          /* two-sided: only edge aliasing */
    assert_true(wrong[1] * 10 > shadow[1] * 9);      /* one-sided: the shadow is lost */
}



/* Each scene file is read once, by the config's load (plan/session.h): the
 * run takes the scene the load read, so the file gone after the load does
 * not stop it, and the scene's reading time is still the run's ms_scene; a
 * second run of the same config reads the file again (the first took the
 * scene), and so fails once it is gone, naming the file. */
static void e2e_scene_read_once(void **st)
{
    (void)st;
    char scene[1200], path[1200];
    snprintf(scene, sizeof scene, "%s/once.yaml", sl_test_dir);
    snprintf(path, sizeof path, "%s/once-config.yaml", sl_test_dir);
    assert_true(write_config(scene,
        "name: once\nlight: {type: directional, direction: [0.5, -0.7, 0.5]}\nmeshes:\n"
        "  - {name: ground, generator: plane, center: [0, 0, 0], size: 40, grid: 2}\n"
        "  - {name: box, generator: sphere, center: [0, 4, 0], radius: 3, segments: 8, rings: 8}\n"
        "viewpoints:\n  - {name: top, position: [0, 30, -30], direction: [0, -1, 1], fov: 60, near: 1, far: 100}\n"));
    assert_true(write_config(path,
        "scenes: [{scene: once.yaml}]\nviewports: [{width: 64, height: 64}]\nmap_sizes: [256]\n"
        "methods: [{method: nsm}]\n"));
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    assert_int_equal(remove(scene), 0);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    enum sl_err e = sl_run(&c, &o, &r, &d);
    if (e)
        fprintf(stderr, "e2e::scene_read_once: %s: %s\n", d.file, d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(r.ncells, 1);
    assert_true(r.ms_scene > 0);   /* the load's reading, counted for the run */
    sl_run_result_free(&r);
    memset(&d, 0, sizeof d);
    assert_int_not_equal(sl_run(&c, &o, &r, &d), SL_OK);
    printf("e2e::scene_read_once: a second run reads the file again: %s: %s\n", d.file, d.msg);
    assert_non_null(strstr(d.file, "once.yaml"));
    sl_run_result_free(&r);
    sl_config_free(&c);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(e2e, default_experiment),
        SL_CASE(e2e, self_shadow_policies),
        SL_CASE(e2e, deterministic),
        SL_CASE(e2e, exr_layers),
        SL_CASE(e2e, two_sided_leaf),
        SL_CASE(e2e, scene_read_once),
    };
    return sl_run_group(argc, argv, "e2e", tests, sl_test_setup, sl_test_teardown);
}
