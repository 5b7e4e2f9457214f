/*
 * conservative::* — the conservative shadow maps are exact by construction:
 * bgsm lit => lit, sgsm / sgsm_adj shadow => shadow, csm and csm_adj equal
 * the truth, on every scene of the study at two map sizes, and so does
 * hertel_exact (hertel, as published, traces fewer rays, counted as its
 * traced pixels, and makes no promise); the geometry
 * shader's enlargement stays finite and near its triangle at sharp angles;
 * the adjacency cases all occur and never cost undecided pixels.
 * A violation prints its pixel, scene, layer and triangle ids (run.c).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "scenefile.h"
#include "sl_test.h"
#include "adjacency.h"
#include "config.h"
#include "fixture.h"
#include "lightfit.h"
#include "run.h"
#include "shadowmap.h"


static int label_is(const struct sl_config *c, const struct sl_cell *cl, const char *label)
{
    return strcmp(c->methods[cl->key.method].label, label) == 0;
}

/* Every scene of the study, two map sizes, every conservative method. */
static void conservative_invariants_on_every_scene(void **st)
{
    (void)st;
    char cwd[900], text[4096];
    assert_non_null(getcwd(cwd, sizeof cwd));
    snprintf(text, sizeof text,
             "scenes:\n  - {scene: primitives}\n  - {scene: bench}\n  - {scene: trees}\n  - {scene: flowers}\n"
             "  - {scene: spider}\n  - {scene: %s/tests/scenes/slivers.yaml}\n"
             "viewports: [{width: 192, height: 160}]\nmap_sizes: [256, 2048]\n"
             "methods:\n  - {method: bgsm}\n  - {method: sgsm}\n  - {method: sgsm_adj}\n"
             "  - {method: csm}\n  - {method: csm_adj}\n  - {method: hertel_exact}\n  - {method: hertel}\n", cwd);
    struct sl_config c;
    sl_test_config("c.yaml", text, &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    assert_int_equal(r.ncells, (3 + 3 + 3 + 3 + 2 + 1) * 2 * 7);
    uint64_t violations = 0, traced_csm = 0, traced_adj = 0, pfl = 0, rays_paper = 0, rays_exact = 0, wrong_paper = 0;
    for (int i = 0; i < r.ncells; i++) {
        const struct sl_cell *cl = &r.cells[i];
        const struct sl_region_figures *img = &cl->fig.r[cl->fig.nregions - 1];
        violations += cl->violations;
        if (label_is(&c, cl, "bgsm"))
            assert_int_equal(img->n[SL_FIG_light_incorrect], 0);
        if (label_is(&c, cl, "sgsm") || label_is(&c, cl, "sgsm_adj"))
            assert_int_equal(img->n[SL_FIG_shadow_incorrect], 0);
        if (label_is(&c, cl, "csm") || label_is(&c, cl, "csm_adj") || label_is(&c, cl, "hertel_exact")) {
            assert_int_equal(cl->fig.wrong_image, 0);                 /* the truth, pixel for pixel */
            assert_int_equal(img->n[SL_FIG_uncertain], 0);
            assert_int_equal(cl->cost.rays, img->n[SL_FIG_traced]);
        }
        if (label_is(&c, cl, "csm")) {
            traced_csm += img->n[SL_FIG_traced];
            pfl += cl->n_pfl;
            /* the maps decide most pixels: rays for a minority only */
            assert_true(img->n[SL_FIG_traced] * 2 < cl->n_pfl);
            /* and csm_adj, the next cell, never needs more */
            const struct sl_cell *adj = &r.cells[i + 1];
            assert_true(label_is(&c, adj, "csm_adj"));
            assert_true(adj->fig.r[adj->fig.nregions - 1].n[SL_FIG_traced] <= img->n[SL_FIG_traced]);
        }
        if (label_is(&c, cl, "csm_adj"))
            traced_adj += img->n[SL_FIG_traced];
        if (label_is(&c, cl, "hertel")) {
            /* every pixel decided, every ray a traced pixel, and never more
             * rays than hertel_exact (the cell before) spends */
            const struct sl_cell *ex = &r.cells[i - 1];
            assert_true(label_is(&c, ex, "hertel_exact"));
            assert_int_equal(img->n[SL_FIG_uncertain], 0);
            assert_int_equal(cl->cost.rays, img->n[SL_FIG_traced]);
            assert_true(cl->cost.rays <= ex->cost.rays);
            rays_paper += cl->cost.rays;
            rays_exact += ex->cost.rays;
            wrong_paper += cl->fig.wrong_image;
        }
    }
    printf("conservative::invariants: %d cells, %llu violations; csm traced %llu of %llu PFL pixels, "
           "csm_adj %llu\n", r.ncells, (unsigned long long)violations, (unsigned long long)traced_csm,
           (unsigned long long)pfl, (unsigned long long)traced_adj);
    printf("conservative::invariants: hertel %llu rays (%llu wrong pixels), hertel_exact %llu rays\n",
           (unsigned long long)rays_paper, (unsigned long long)wrong_paper, (unsigned long long)rays_exact);
    assert_int_equal(violations, 0);
    assert_true(traced_adj < traced_csm);
    assert_true(rays_paper < rays_exact);
    /* bgsm, csm, csm_adj, hertel_exact and hertel share one BGSM layer per view and map */
    assert_int_equal(r.passes.layers[SL_LAYER_BGSM], 15 * 2);
    assert_int_equal(r.passes.layers[SL_LAYER_BGSM2], 15 * 2);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

/* Exact square-triangle overlap in double, with the layers' margin. */
static int texel_touches(const double v[3][2], int tx, int ty, double eps)
{
    double c[4][2] = {{tx, ty}, {tx + 1, ty}, {tx, ty + 1}, {tx + 1, ty + 1}};
    double lo[2] = {fmin(v[0][0], fmin(v[1][0], v[2][0])), fmin(v[0][1], fmin(v[1][1], v[2][1]))};
    double hi[2] = {fmax(v[0][0], fmax(v[1][0], v[2][0])), fmax(v[0][1], fmax(v[1][1], v[2][1]))};
    if (hi[0] < tx - eps || lo[0] > tx + 1 + eps || hi[1] < ty - eps || lo[1] > ty + 1 + eps)
        return 0;
    double area = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[2][0] - v[0][0]) * (v[1][1] - v[0][1]);
    double s = area >= 0 ? 1 : -1;
    for (int i = 0; i < 3; i++) {
        double ex = v[(i + 1) % 3][0] - v[i][0], ey = v[(i + 1) % 3][1] - v[i][1];
        double len = sqrt(ex * ex + ey * ey);
        if (len == 0)
            continue;
        double nx = s * ey / len, ny = -s * ex / len, dmin = 1e300;
        for (int k = 0; k < 4; k++)
            dmin = fmin(dmin, nx * (c[k][0] - v[i][0]) + ny * (c[k][1] - v[i][1]));
        if (dmin > eps)
            return 0;
    }
    return 1;
}

/* Slivers of aspect 1e5 at twelve angles and a needle along the light: the
 * BGSM layer covers every texel each one touches (coverage is conservative
 * whichever way the geometry shader took), writes finite depths no farther
 * than the triangle's nearest vertex, and stores a sliver nowhere farther
 * than two texels from it (no vertex flung away). */
static void conservative_slivers_stay_finite_and_near(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "tests/scenes/slivers.yaml", 2));
    struct sl_view v;
    assert_true(fixture_view(&f, 0, 128, 128, &v));
    struct sl_shadowmap_pass sp;
    struct sl_diag d;
    assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
    const struct sl_mesh_range *sl = &f.scene.ranges[1];
    assert_string_equal(sl->name, "slivers");
    for (int size = 512; size <= 4096; size *= 8) {
        struct sl_light_frame fr;
        memset(&fr, 0, sizeof fr);
        fr.size = size;
        sl_light_fit(&f.scene, &v, &fr.box);
        assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &fr, SL_NEED(SL_LAYER_BGSM), &d), SL_OK);
        const struct sl_depth_layer *b = &fr.layer[SL_LAYER_BGSM];
        long covered = 0, missed = 0, far = 0, deep = 0;
        for (size_t k = 0; k < (size_t)size * size; k++)
            assert_true(isfinite(b->depth[k]) && b->depth[k] >= 0.0f && b->depth[k] <= 1.0f);
        for (uint32_t t = sl->first; t < sl->first + sl->count; t++) {
            double w[3][2];
            for (int c = 0; c < 3; c++) {
                const float *p = f.scene.pos + 3 * f.scene.idx[3 * t + c];
                float u, vv, z;
                sl_frame_project(&fr, p, &u, &vv, &z);
                w[c][0] = u;
                w[c][1] = vv;
                (void)z;
            }
            int x0 = (int)floor(fmin(w[0][0], fmin(w[1][0], w[2][0]))) - 3;
            int x1 = (int)ceil(fmax(w[0][0], fmax(w[1][0], w[2][0]))) + 3;
            int y0 = (int)floor(fmin(w[0][1], fmin(w[1][1], w[2][1]))) - 3;
            int y1 = (int)ceil(fmax(w[0][1], fmax(w[1][1], w[2][1]))) + 3;
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++) {
                    if (x < 0 || y < 0 || x >= size || y >= size)
                        continue;
                    size_t k = (size_t)y * size + x;
                    if (texel_touches(w, x, y, 0.0)) {
                        covered++;
                        if (!b->id[k])
                            missed++;
                    } else if ((b->id[k] & ~SL_FULL) == t + 1 && !texel_touches(w, x, y, 2.0)) {
                        far++;
                    }
                }
            /* depth: sample the sliver (barycentric grid, in the world); the
             * value stored where a sample lands must not exceed it */
            const int G = 96;
            for (int i = 0; i <= G; i++)
                for (int j = 0; j <= G - i; j++) {
                    float q[3];
                    for (int c = 0; c < 3; c++) {
                        const float *p0 = f.scene.pos + 3 * f.scene.idx[3 * t];
                        const float *p1 = f.scene.pos + 3 * f.scene.idx[3 * t + 1];
                        const float *p2 = f.scene.pos + 3 * f.scene.idx[3 * t + 2];
                        q[c] = (float)(((double)(G - i - j) * p0[c] + (double)i * p1[c] + (double)j * p2[c]) / G);
                    }
                    float u, vv, z;
                    sl_frame_project(&fr, q, &u, &vv, &z);
                    int x = (int)floorf(u), y = (int)floorf(vv);
                    if (x < 0 || y < 0 || x >= size || y >= size)
                        continue;
                    size_t k = (size_t)y * size + x;
                    if (!(b->depth[k] <= z + 1e-6f))
                        deep++;
                }
            /* nothing of this sliver outside the box scanned: count its texels there */
            for (size_t k = 0; k < (size_t)size * size; k++)
                if ((b->id[k] & ~SL_FULL) == t + 1) {
                    int x = (int)(k % size), y = (int)(k / size);
                    if (x < x0 || x > x1 || y < y0 || y > y1)
                        far++;
                }
        }
        printf("conservative::slivers %d²: %ld texels touched, %ld missed, %ld samples nearer than stored, "
               "%ld stored far away; %llu GS primitives\n", size, covered, missed, deep, far,
               (unsigned long long)b->gs_prims);
        assert_true(covered > 100);
        assert_int_equal(missed, 0);
        assert_int_equal(deep, 0);
        assert_int_equal(far, 0);
        /* one primitive per triangle, two where a sharp vertex took the
         * bounding-box fallback, which the slivers must exercise */
        assert_true(b->gs_prims > f.scene.nt && b->gs_prims <= 2u * f.scene.nt);
        sl_frame_free(&fr);
    }
    sl_shadowmap_free(&sp);
    sl_view_free(&v);
    fixture_close(&f);
}

/* The scene built for it has away-facing triangles with 0, 1, 2 and 3
 * away-facing neighbours; sgsm_adj proves at least as many shadowed pixels
 * as sgsm, and csm_adj traces no more than csm, with no violation. */
static void conservative_adjacency_cases(void **st)
{
    (void)st;
    struct sl_scene s;
    struct sl_diag d;
    assert_int_equal(sl_scene_build("tests/scenes/adjacency.yaml", &s, &d), SL_OK);
    struct sl_adjacency a;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    const float *L = s.light_dir;
    int hist[4] = {0, 0, 0, 0};
    for (uint32_t t = 0; t < s.nt; t++) {
        const float *n = s.fn + 3 * t;
        if (n[0] * L[0] + n[1] * L[1] + n[2] * L[2] <= 0.0f)
            continue;                                   /* faces the light */
        int kept = 0;
        for (int k = 0; k < 3; k++) {
            uint32_t u = a.edge[3 * t + k];
            if (u == SL_ADJ_NONE || u == SL_ADJ_MULTI)
                continue;
            const float *m = s.fn + 3 * u;
            kept += m[0] * L[0] + m[1] * L[1] + m[2] * L[2] > 0.0f;
        }
        hist[kept]++;
    }
    printf("conservative::adjacency: away-facing triangles with 0/1/2/3 away-facing neighbours: %d %d %d %d\n",
           hist[0], hist[1], hist[2], hist[3]);
    for (int k = 0; k < 4; k++)
        assert_true(hist[k] > 0);
    sl_adjacency_free(&a);
    sl_scene_free(&s);

    char cwd[900], text[2048];
    assert_non_null(getcwd(cwd, sizeof cwd));
    snprintf(text, sizeof text,
             "scenes: [{scene: %s/tests/scenes/adjacency.yaml}]\nviewports: [{width: 256, height: 256}]\n"
             "map_sizes: [512, 2048]\nmethods:\n  - {method: sgsm}\n  - {method: sgsm_adj}\n"
             "  - {method: csm}\n  - {method: csm_adj}\n", cwd);
    struct sl_config c;
    sl_test_config("c.yaml", text, &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    for (int i = 0; i < r.ncells; i += 4) {
        const struct sl_figures *sg = &r.cells[i].fig, *sa = &r.cells[i + 1].fig;
        const struct sl_figures *cs = &r.cells[i + 2].fig, *ca = &r.cells[i + 3].fig;
        int g = sg->nregions - 1;
        printf("conservative::adjacency map %d: shadow proved sgsm %llu, sgsm_adj %llu; traced csm %llu, "
               "csm_adj %llu\n", c.maps[r.cells[i].key.map], (unsigned long long)sg->r[g].n[SL_FIG_shadow],
               (unsigned long long)sa->r[g].n[SL_FIG_shadow], (unsigned long long)cs->r[g].n[SL_FIG_traced],
               (unsigned long long)ca->r[g].n[SL_FIG_traced]);
        assert_true(sa->r[g].n[SL_FIG_shadow] >= sg->r[g].n[SL_FIG_shadow]);
        assert_true(ca->r[g].n[SL_FIG_traced] <= cs->r[g].n[SL_FIG_traced]);
        for (int k = 0; k < 4; k++)
            assert_int_equal(r.cells[i + k].violations, 0);
    }
    /* on these closed meshes adjacency proves strictly more somewhere */
    assert_true(r.cells[1].fig.r[r.cells[1].fig.nregions - 1].n[SL_FIG_shadow] >
                r.cells[0].fig.r[r.cells[0].fig.nregions - 1].n[SL_FIG_shadow]);
    sl_run_result_free(&r);
    sl_config_free(&c);
}



int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(conservative, invariants_on_every_scene),
        SL_CASE(conservative, slivers_stay_finite_and_near),
        SL_CASE(conservative, adjacency_cases),
    };
    return sl_run_group(argc, argv, "conservative", tests, sl_test_setup, sl_test_teardown);
}
