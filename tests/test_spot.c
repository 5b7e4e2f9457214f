/*
 * spot::* — spot lights (issue 22):
 *
 * - lights_exact: configs/lights.yaml's spot scenes (every hard label at
 *   two map sizes; its point scenes are cube::'s) keep every exact promise with 0 violations (bgsm lit
 *   => lit, sgsm/sgsm_adj shadow => shadow, csm, csm_adj, hertel_exact, raytrace
 *   equal to the truth), and every cell names its light and counts the
 *   pixels outside the cone apart, as a part of PnFL;
 * - outside_counted_apart: on views whose cone leaves about half of the view
 *   unlit, the G-buffer's outside-cone count equals a recount with
 *   sl_spot_inside on its positions and a second recount by angle (acos,
 *   independent of the code under test), every such pixel is PnFL for the
 *   methods and the truth, and every label says it shadowed without looking
 *   it up (how = pnfl) and never scores it wrong (the EXR layers, pixel by
 *   pixel), and the overlay hatches exactly those pixels;
 * - near_plane: a caster crossing the spot's plane (the lamp's pole, an
 *   "unmapped" triangle the conservative layers leave to the CPU) keeps
 *   every point inside the receivers' pyramid beyond the frame's near
 *   plane, so the plain layers draw all of it that can shadow a receiver
 *   (sampled on a barycentric grid; the pole must reach the pyramid);
 * - penumbra: the optional key is parsed, checked (spot only, [0, fov/2]),
 *   stated in the heading, and ignored: the same scene without it gives the
 *   same counts.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "arealight.h"
#include "config.h"
#include "fixture.h"
#include "image.h"
#include "lightfit.h"
#include "method.h"
#include "overlay.h"
#include "run.h"
#include "view.h"

static int write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    fputs(text, f);
    return fclose(f) == 0;
}

static const char *label_of(const struct sl_config *c, const struct sl_cell *cl)
{
    return c->methods[cl->key.method].label;
}

static void spot_lights_exact(void **st)
{
    (void)st;
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load("configs/lights.yaml", &c, &d), SL_OK);
    /* its spot scenes only: the point part is cube::'s */
    int ns = 0;
    for (int k = 0; k < c.nscenes; k++)
        if (c.scenes[k].light_type == SL_LIGHT_SPOT)
            c.scenes[ns++] = c.scenes[k];
    assert_int_equal(ns, 3);
    c.nscenes = ns;
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    enum sl_err e = sl_run(&c, &o, &r, &d);
    if (e)
        fprintf(stderr, "lights: %s\n", d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(r.ncells, sl_plan_count(&c));
    int exact = 0, spots = 0;
    for (int i = 0; i < r.ncells; i++) {
        const struct sl_cell *cl = &r.cells[i];
        const char *m = c.methods[cl->key.method].method->name;
        if (cl->violations || cl->nonfinite)
            fprintf(stderr, "lights: %s/%s %d %s: %llu violations, %llu non-finite\n", cl->scene, cl->viewpoint,
                    c.maps[cl->key.map], label_of(&c, cl), (unsigned long long)cl->violations,
                    (unsigned long long)cl->nonfinite);
        assert_int_equal(cl->violations, 0);
        assert_int_equal(cl->nonfinite, 0);
        uint64_t W = (uint64_t)c.viewport_w[cl->key.viewport], H = (uint64_t)c.viewport_h[cl->key.viewport];
        assert_int_equal(cl->n_pfl + cl->n_pnfl + cl->n_background, W * H);
        assert_int_equal(cl->n_truth_lit + cl->n_truth_shadow, cl->n_pfl);
        /* the spot scenes: part of every view is outside the cone, counted
         * apart inside PnFL, and the light named in words */
        if (!strncmp(cl->light, "spot light, ", 12)) {
            spots++;
            assert_true(cl->n_outside_cone > 0);
            assert_true(cl->n_outside_cone <= cl->n_pnfl);
        }
        const struct sl_region_figures *img = &cl->fig.r[cl->fig.nregions - 1];
        assert_int_equal(img->n[SL_FIG_pfl] + img->n[SL_FIG_pnfl], img->n[SL_FIG_pixels]);
        if (!strcmp(m, "bgsm"))
            assert_int_equal(img->n[SL_FIG_light_incorrect], 0);
        if (!strcmp(m, "sgsm") || !strcmp(m, "sgsm_adj"))
            assert_int_equal(img->n[SL_FIG_shadow_incorrect], 0);
        if (!strcmp(m, "csm") || !strcmp(m, "csm_adj") || !strcmp(m, "hertel_exact") || !strcmp(m, "raytrace")) {
            assert_int_equal(img->n[SL_FIG_wrong], 0);
            assert_int_equal(img->n[SL_FIG_uncertain], 0);
            assert_int_equal(cl->fig.wrong_image, 0);
            exact++;
        }
    }
    /* four exact labels on 3 spot scenes x 2 viewpoints at two map sizes; every cell a spot's */
    assert_int_equal(exact, 4 * 3 * 2 * 2);
    assert_int_equal(spots, r.ncells);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* The index of viewpoint `name` in the scene, -1 if none. */
static int vp_index(const struct sl_scene *s, const char *name)
{
    for (int i = 0; i < s->nvp; i++)
        if (!strcmp(s->vp[i].name, name))
            return i;
    return -1;
}

/* One view whose cone excludes about half of it: the counts, recounted two
 * ways, and each label's verdicts there read back from its EXR layers. */
static void outside_view(const char *scene, const char *viewpoint)
{
    enum { W = 256, H = 256 };
    struct fixture f;
    assert_true(fixture_open(&f, scene, 2));
    int vp = vp_index(&f.scene, viewpoint);
    assert_true(vp >= 0);
    assert_int_equal(f.scene.light.type, SL_LIGHT_SPOT);
    struct sl_view v;
    assert_true(fixture_view(&f, vp, W, H, &v));
    assert_non_null(v.outside);
    /* the half-angle's cosine, and the angle of each pixel by acos: pixels
     * within 1e-6 rad of the cone's edge are left out of the second
     * recount (float positions, two formulas) */
    const double half = 0.5 * (double)f.scene.light.fov_deg * (3.14159265358979323846 / 180.0);
    uint64_t recount = 0, by_angle = 0, near_edge = 0, nonbg = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        if (!v.tri[i]) {
            assert_int_equal(v.outside[i], 0);
            continue;
        }
        nonbg++;
        int out = !sl_spot_inside(&f.scene.light, v.pos + 3 * i);
        recount += (uint64_t)out;
        assert_int_equal(v.outside[i], out);
        if (out) {
            assert_int_equal(v.cls[i], SL_C_PNFL);
            assert_int_equal(v.truth[i], SL_T_PNFL);
        }
        double d[3], len = 0.0, dot = 0.0, ld = 0.0;
        for (int k = 0; k < 3; k++) {
            d[k] = (double)v.pos[3 * i + k] - (double)f.scene.light.pos[k];
            len += d[k] * d[k];
            ld += (double)f.scene.light.dir[k] * (double)f.scene.light.dir[k];
        }
        for (int k = 0; k < 3; k++)
            dot += d[k] * (double)f.scene.light.dir[k];
        double ang = acos(fmax(-1.0, fmin(1.0, dot / sqrt(len * ld))));
        if (fabs(ang - half) < 1e-6) {
            near_edge++;
            continue;
        }
        if (ang > half) {
            by_angle++;
            assert_int_equal(out, 1);
        } else {
            assert_int_equal(out, 0);
        }
    }
    assert_int_equal(v.n_outside_cone, recount);
    assert_true(by_angle <= recount && recount <= by_angle + near_edge);
    assert_true(near_edge * 1000 < recount);
    /* about half of the view: between a third and two thirds of the image */
    assert_true(3 * recount > (uint64_t)W * H && 3 * recount < 2 * (uint64_t)W * H);
    assert_true(recount < nonbg);

    /* the overlay: with the truth as verdicts, every outside pixel is drawn
     * hatched dark grey (12 or the stripe's 56), none in an error colour */
    {
        struct sl_verdicts vd;
        memset(&vd, 0, sizeof vd);
        vd.v = calloc((size_t)W * H, 1);
        uint8_t *band = calloc((size_t)W * H, 1), *rgb = malloc(3 * (size_t)W * H);
        assert_true(vd.v && band && rgb);
        for (size_t i = 0; i < (size_t)W * H; i++)
            vd.v[i] = v.truth[i] == SL_T_BACKGROUND ? SL_V_NONE : v.truth[i] == SL_T_LIT ? SL_V_LIT : SL_V_SHADOW;
        uint64_t count[SL_OV_CLASSES];
        sl_overlay_build(&v, f.scene.light_dir, f.scene.light.pos, &vd, band, 2, rgb, NULL, count);
        assert_int_equal(count[SL_OV_OUTSIDE_CONE], recount);
        assert_int_equal(count[SL_OV_LIT_WRONG] + count[SL_OV_SHADOW_WRONG] + count[SL_OV_WRONG_OUTSIDE], 0);
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (v.outside[i]) {
                const uint8_t *o = rgb + 3 * i;
                assert_true(o[0] == o[1] && o[1] == o[2] && (o[0] == 12 || o[0] == 56));
            }
        free(vd.v);
        free(band);
        free(rgb);
    }

    /* every label on this view, with EXR layers: each outside pixel said
     * shadowed, decided as PnFL (never looked up), never an error */
    char path[1400], text[1600];
    snprintf(path, sizeof path, "%s/half-%s.yaml", sl_test_dir, scene);
    snprintf(text, sizeof text,
             "name: half_%s\nscenes: [{scene: %s, viewpoints: [%s]}]\n"
             "viewports: [{width: %d, height: %d}]\nmap_sizes: [512]\ncontours: [2]\n"
             "methods:\n  - {label: nsm, method: nsm, self_shadow: front_faces}\n"
             "  - {label: coherence9, method: coherence, texels: 9}\n  - {label: texel, method: texel}\n"
             "  - {label: neighbours9, method: neighbours, texels: 9}\n"
             "  - {label: adjacency2, method: adjacency, level: 2}\n"
             "  - {label: chain, method: chain, finish: trace}\n  - {label: bgsm, method: bgsm}\n"
             "  - {label: sgsm, method: sgsm}\n  - {label: sgsm_adj, method: sgsm_adj}\n"
             "  - {label: csm, method: csm}\n  - {label: csm_adj, method: csm_adj}\n"
             "  - {label: hertel, method: hertel}\n  - {label: raytrace, method: raytrace}\n"
             "outputs: {tables: false, overlays: false, exr: true}\n",
             scene, scene, viewpoint, W, H);
    assert_true(write_file(path, text));
    struct sl_config c;
    struct sl_diag d;
    assert_int_equal(sl_config_load(path, &c, &d), SL_OK);
    struct sl_run_opts o = {.out_root = sl_test_dir, .write_files = 1, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, 13);
    for (int i = 0; i < r.ncells; i++) {
        const struct sl_cell *cl = &r.cells[i];
        assert_int_equal(cl->n_outside_cone, recount);
        snprintf(path, sizeof path, "%s/half_%s/exr/%s-%s-%dx%d-512-%s.exr", sl_test_dir, scene, scene, viewpoint,
                 W, H, label_of(&c, cl));
        unsigned *verdict, *error, *how;
        int w, h;
        assert_int_equal(sl_image_read_layer(path, "verdict", &w, &h, &verdict, &d), SL_OK);
        assert_int_equal(sl_image_read_layer(path, "error", &w, &h, &error, &d), SL_OK);
        assert_int_equal(sl_image_read_layer(path, "how", &w, &h, &how, &d), SL_OK);
        assert_int_equal(w, W);
        assert_int_equal(h, H);
        uint64_t seen = 0, wrong = 0;
        for (size_t k = 0; k < (size_t)W * H; k++) {
            wrong += error[k] == 1 || error[k] == 2;
            if (!v.outside[k])
                continue;
            seen++;
            if (verdict[k] != SL_V_SHADOW || error[k] != 0 || how[k] != SL_HOW_PNFL)
                fprintf(stderr, "%s/%s %s: outside pixel %zu: verdict %u, error %u, how %u\n", scene, viewpoint,
                        label_of(&c, cl), k, verdict[k], error[k], how[k]);
            assert_int_equal(verdict[k], SL_V_SHADOW);
            assert_int_equal(error[k], 0);
            assert_int_equal(how[k], SL_HOW_PNFL);
        }
        assert_int_equal(seen, recount);
        /* the figures' wrong pixels are the layer's, none of them outside the cone */
        assert_int_equal(wrong, cl->fig.wrong_image);
        free(verdict);
        free(error);
        free(how);
    }
    sl_run_result_free(&r);
    sl_view_free(&v);
    fixture_close(&f);
    sl_config_free(&c);
}

static void spot_outside_counted_apart(void **st)
{
    (void)st;
    outside_view("lamp", "half");
    outside_view("spot_tight", "low");
    outside_view("primitives_spot", "half");
}

/* A lamp scene file, with `extra` added to its light. */
static void lamp_file(const char *path, const char *light)
{
    char text[1200];
    snprintf(text, sizeof text,
             "name: pen\nlight: %s\nmeshes:\n"
             "  - {name: ground, generator: plane, center: [0, 0, 0], size: 20, grid: 4}\n"
             "  - {name: box, generator: box, min: [-1, 0, -1], max: [1, 2, 1]}\n"
             "viewpoints:\n  - {name: above, position: [-8, 9, 7], direction: [8, -9, -7], fov: 55, near: 1, far: 60}\n",
             light);
    assert_true(write_file(path, text));
}

static void spot_near_plane(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "scenes/lamp.yaml", 2));
    struct sl_view v;
    assert_true(fixture_view(&f, vp_index(&f.scene, "above"), 256, 256, &v));
    struct sl_light_box b;
    sl_light_fit(&f.scene, &v, &b);
    assert_int_equal(b.persp, 1);
    assert_true(b.n_receivers > 1000 && b.n_unmapped > 0);
    const float near = b.lo[2], dmin = b.hi[2] / 4096.0f;
    int crossing_inside = 0, below = 0;
    for (uint32_t t = 0; t < f.scene.nt; t++) {
        float q[3][3];
        int behind = 0;
        for (int k = 0; k < 3; k++) {
            const float *p = f.scene.pos + 3 * f.scene.idx[3 * t + k];
            vec4 w = {p[0], p[1], p[2], 1.0f}, c;
            glm_mat4_mulv(b.view, w, c);
            q[k][0] = c[0], q[k][1] = c[1], q[k][2] = -c[2];
            behind |= !(q[k][2] > 0.0f);
        }
        int inside = 0;
        for (int a = 0; a <= 32; a++)
            for (int c = 0; c <= 32 - a; c++) {
                float u = a / 32.0f, w = c / 32.0f, z = 1.0f - u - w, x[3];
                for (int j = 0; j < 3; j++)
                    x[j] = u * q[0][j] + w * q[1][j] + z * q[2][j];
                if (!(x[2] > 0.0f) || x[0] < b.lo[0] * x[2] || x[0] > b.hi[0] * x[2] || x[1] < b.lo[1] * x[2] ||
                    x[1] > b.hi[1] * x[2])
                    continue;
                inside = 1;
                below += x[2] < near * (1.0f - 1e-3f) && x[2] > dmin;
            }
        crossing_inside += behind && inside;
    }
    fprintf(stderr, "lamp/above: near %g, %u unmapped, %d crossing triangles reach the pyramid, %d points nearer\n",
            (double)near, b.n_unmapped, crossing_inside, below);
    assert_true(crossing_inside > 0);
    assert_int_equal(below, 0);
    sl_light_box_free(&b);
    sl_view_free(&v);
    fixture_close(&f);
}

static void spot_penumbra(void **st)
{
    (void)st;
    char a[1200], b[1200], bad[1200];
    struct sl_scene s;
    struct sl_diag d;
    snprintf(a, sizeof a, "%s/pen_a.yaml", sl_test_dir);
    snprintf(b, sizeof b, "%s/pen_b.yaml", sl_test_dir);
    lamp_file(a, "{type: spot, position: [0.5, 6, 0], direction: [0, -1, 0], fov: 60, penumbra: 7.5}");
    lamp_file(b, "{type: spot, position: [0.5, 6, 0], direction: [0, -1, 0], fov: 60}");
    assert_int_equal(sl_scene_load(a, &s, &d), SL_OK);
    assert_true(s.light.penumbra_deg == 7.5f);
    char words[64];
    sl_light_heading(&s.light, words, sizeof words);
    assert_string_equal(words, "spot light, 60\xC2\xB0, penumbra 7.5\xC2\xB0 ignored");
    sl_scene_free(&s);
    assert_int_equal(sl_scene_load(b, &s, &d), SL_OK);
    assert_true(s.light.penumbra_deg == 0.0f);
    sl_light_heading(&s.light, words, sizeof words);
    assert_string_equal(words, "spot light, 60\xC2\xB0");
    sl_scene_free(&s);
    /* refused: on another light, wider than half the cone, negative */
    static const char *const refused[] = {
        "{type: directional, direction: [0, -1, 0], penumbra: 5}",
        "{type: spot, position: [0.5, 6, 0], direction: [0, -1, 0], fov: 60, penumbra: 30.5}",
        "{type: spot, position: [0.5, 6, 0], direction: [0, -1, 0], fov: 60, penumbra: -1}",
    };
    snprintf(bad, sizeof bad, "%s/pen_bad.yaml", sl_test_dir);
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        lamp_file(bad, refused[k]);
        assert_int_equal(sl_scene_load(bad, &s, &d), SL_E_SCENE);
        assert_string_equal(d.key, "light.penumbra");
        assert_int_equal(d.line, 2);
    }
    /* ignored by the hard methods and the truth: the same counts with and without */
    struct sl_run_result r[2];
    const char *files[2] = {a, b};
    for (int k = 0; k < 2; k++) {
        char cpath[1300], text[2000];
        snprintf(cpath, sizeof cpath, "%s/pen_%d.yaml", sl_test_dir, k);
        snprintf(text, sizeof text,
                 "name: pen%d\nscenes: [{scene: %s}]\nviewports: [{width: 160, height: 160}]\n"
                 "map_sizes: [256]\ncontours: [2]\nmethods:\n  - {label: nsm, method: nsm, self_shadow: front_faces}\n"
                 "  - {label: sgsm, method: sgsm}\n  - {label: raytrace, method: raytrace}\n"
                 "outputs: {tables: false, overlays: false}\n",
                 k, files[k]);
        assert_true(write_file(cpath, text));
        struct sl_config c;
        assert_int_equal(sl_config_load(cpath, &c, &d), SL_OK);
        struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
        assert_int_equal(sl_run(&c, &o, &r[k], &d), SL_OK);
        sl_config_free(&c);
    }
    assert_int_equal(r[0].ncells, 3);
    assert_int_equal(r[1].ncells, 3);
    for (int i = 0; i < 3; i++) {
        const struct sl_cell *x = &r[0].cells[i], *y = &r[1].cells[i];
        assert_true(x->n_outside_cone > 0);
        assert_int_equal(x->n_outside_cone, y->n_outside_cone);
        assert_int_equal(x->n_pfl, y->n_pfl);
        assert_int_equal(x->n_truth_shadow, y->n_truth_shadow);
        assert_int_equal(x->fig.wrong_image, y->fig.wrong_image);
        assert_memory_equal(x->fig.r[0].n, y->fig.r[0].n, sizeof x->fig.r[0].n);
        assert_non_null(strstr(x->light, "penumbra"));
        assert_null(strstr(y->light, "penumbra"));
    }
    sl_run_result_free(&r[0]);
    sl_run_result_free(&r[1]);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(spot, lights_exact),
        SL_CASE(spot, outside_counted_apart),
        SL_CASE(spot, near_plane),
        SL_CASE(spot, penumbra),
    };
    return sl_run_group(argc, argv, "spot", tests, sl_test_setup, sl_test_teardown);
}
