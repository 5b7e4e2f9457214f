/*
 * truth::* — the Embree truth against a brute-force test of every triangle in
 * double precision, pixel by pixel.
 *
 * The reference uses the same rays (origin = the G-buffer position, toward the
 * light, from the same tnear) and the same own-triangle rule, but exact
 * arithmetic on every triangle. Where the two disagree, the ray must pass
 * within EPS_REL of a triangle's boundary (the hit point's distance to the
 * nearest edge of the triangle the reference hit, or the smallest distance
 * from the ray's plane crossing to a triangle it missed) — a tie that float
 * rounding may break either way. Anything farther is a real error.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include "sl_test.h"
#include "fixture.h"
#include "raytri.h"

/* relative to the scene's extent: 1e-5 of 600 units is 6e-3 (primitives) */
#define EPS_REL 1e-5

struct check { long pfl, agree, explained, unexplained; double worst; };

static void ld(const float *p, double *o) { o[0] = p[0]; o[1] = p[1]; o[2] = p[2]; }

/* Triangle t's corners (a, b, c) and where the ray o + th L crosses its
 * plane; 0 when the ray runs parallel to it. */
static int crossing(const struct sl_scene *s, uint32_t t, const double o[3], const double L[3], double a[3],
                    double b[3], double c[3], double *th)
{
    double nrm[3], e1[3], e2[3];
    ld(s->pos + 3 * s->idx[3 * t], a);
    ld(s->pos + 3 * s->idx[3 * t + 1], b);
    ld(s->pos + 3 * s->idx[3 * t + 2], c);
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double den = nrm[0] * L[0] + nrm[1] * L[1] + nrm[2] * L[2];
    if (den == 0.0)
        return 0;
    *th = (nrm[0] * (a[0] - o[0]) + nrm[1] * (a[1] - o[1]) + nrm[2] * (a[2] - o[2])) / den;
    return 1;
}

static void brute_force(const struct sl_scene *s, const struct sl_view *v, struct check *c)
{
    double ext = 0;
    for (int k = 0; k < 3; k++)
        ext = fmax(ext, (double)s->hi[k] - s->lo[k]);
    double eps = EPS_REL * ext;
    double L[3] = {-s->light_dir[0], -s->light_dir[1], -s->light_dir[2]};
    memset(c, 0, sizeof *c);
    size_t n = (size_t)v->w * v->h;
    for (size_t i = 0; i < n; i++) {
        if (v->cls[i] != SL_C_PFL)
            continue;
        c->pfl++;
        double o[3];
        ld(v->pos + 3 * i, o);
        double tmin = sl_rt_tnear(v->pos + 3 * i);
        int hit = 0;
        double margin = INFINITY;   /* how close the decision was */
        for (uint32_t t = 0; t < s->nt; t++) {
            if (t + 1 == v->tri[i])
                continue;
            double a[3], b[3], cc[3], th;
            ld(s->pos + 3 * s->idx[3 * t], a);
            ld(s->pos + 3 * s->idx[3 * t + 1], b);
            ld(s->pos + 3 * s->idx[3 * t + 2], cc);
            if (sl_ray_tri_d(o, L, a, b, cc, tmin, &th)) {
                hit = 1;
                double q[3] = {o[0] + th * L[0], o[1] + th * L[1], o[2] + th * L[2]};
                margin = fmin(margin, sl_point_tri_edge_dist_d(q, a, b, cc));
            }
        }
        int embree_shadow = v->truth[i] == SL_T_SHADOW;
        if (hit == embree_shadow) {
            c->agree++;
            continue;
        }
        if (!hit) {
            /* Embree found an occluder the reference missed: how near did the
             * ray pass to any triangle in front of the point? */
            for (uint32_t t = 0; t < s->nt; t++) {
                double a[3], b[3], cc[3], th;
                if (t + 1 == v->tri[i] || !crossing(s, t, o, L, a, b, cc, &th) || th <= 0.0)
                    continue;
                double q[3] = {o[0] + th * L[0], o[1] + th * L[1], o[2] + th * L[2]};
                margin = fmin(margin, sl_point_tri_dist_d(q, a, b, cc));
            }
        }
        if (margin <= eps)
            c->explained++;
        else {
            c->unexplained++;
            if (c->unexplained <= 5)
                fprintf(stderr, "pixel %zu (tri %u): embree %s, reference %s, margin %g\n", i,
                        v->tri[i] - 1, embree_shadow ? "shadow" : "lit", hit ? "shadow" : "lit", margin);
        }
        c->worst = fmax(c->worst, margin);
    }
}

static void run_scene(const char *scene, int size, long *pfl_out)
{
    struct fixture f;
    assert_true(fixture_open(&f, scene, 2));
    long pfl = 0;
    for (int vp = 0; vp < f.scene.nvp; vp++) {
        struct sl_view v;
        assert_true(fixture_view(&f, vp, size, size, &v));
        struct check c;
        brute_force(&f.scene, &v, &c);
        printf("truth::%s/%s %dx%d: %ld PFL, %ld agree, %ld disagree within eps (worst margin %g), %ld unexplained\n",
               scene, f.scene.vp[vp].name, size, size, c.pfl, c.agree, c.explained, c.worst, c.unexplained);
        assert_int_equal(c.unexplained, 0);
        /* the comparison means something: there are shadows and light */
        assert_true(v.n_shadow > 100 && v.n_lit > 100);
        /* disagreements, if any, are a vanishing share */
        assert_true(c.explained * 10000 <= c.pfl);
        pfl += c.pfl;
        sl_view_free(&v);
    }
    fixture_close(&f);
    *pfl_out = pfl;
}

/* How near the ray of pixel i passes to a triangle boundary, in double
 * precision, as brute_force measures it: the distance of its crossing to
 * the nearest edge of the triangles it hits, or to the nearest triangle
 * in front of the point it misses. */
static double tie_margin(const struct sl_scene *s, const struct sl_view *v, size_t i, double *tcross)
{
    double L[3] = {-s->light_dir[0], -s->light_dir[1], -s->light_dir[2]}, o[3];
    ld(v->pos + 3 * i, o);
    const double tmin = sl_rt_tnear(v->pos + 3 * i);
    double margin = INFINITY;
    *tcross = 0.0;
    for (uint32_t t = 0; t < s->nt; t++) {
        double a[3], b[3], cc[3], th;
        if (t + 1 == v->tri[i] || !crossing(s, t, o, L, a, b, cc, &th) || th <= tmin)
            continue;
        double q[3] = {o[0] + th * L[0], o[1] + th * L[1], o[2] + th * L[2]}, hit_t;
        double m = sl_ray_tri_d(o, L, a, b, cc, tmin, &hit_t) ? sl_point_tri_edge_dist_d(q, a, b, cc)
                                                              : sl_point_tri_dist_d(q, a, b, cc);
        if (m < margin) {
            margin = m;
            *tcross = th;
        }
    }
    return margin;
}

/* Embree's kernels for each ISA this CPU runs (SSE4.2 packets of 4, AVX2
 * of 8, AVX-512 of 16) against the build's own (SHADOWLAB_EMBREE_CONFIG's,
 * else the best), over the views where they were seen to differ (Bench /
 * against and Flowers / side at 1024 x 1024: one pixel each between SSE4.2
 * and AVX2/AVX-512). Every pixel on which two ISAs disagree must be a
 * tie: its ray passes within 16 float steps of its length (16 * 2^-23 *
 * the crossing's distance or coordinate, whichever is larger) of a
 * triangle's boundary, where float rounding decides either way and no ISA
 * is more right than another. A disagreement farther out is a real error
 * (the 16-wide packets' unused lanes on a CPU without AVX-512 were one). */
static void truth_isa_ties(void **st)
{
    (void)st;
    static const char *const isas[] = {"sse4.2", "avx2", "avx512"};
    static const struct { const char *scene; int vp; } cases[] = {{"bench", 2}, {"flowers", 0}};
    uint64_t ties = 0, runs = 0;
    for (int c = 0; c < 2; c++) {
        struct fixture f;
        assert_true(fixture_open(&f, cases[c].scene, 2));
        struct sl_view v;
        assert_true(fixture_view(&f, cases[c].vp, 1024, 1024, &v));
        const size_t n = (size_t)v.w * v.h;
        uint8_t *mine = malloc(n);
        assert_non_null(mine);
        memcpy(mine, v.truth, n);
        for (int k = 0; k < 3; k++) {
            if (!sl_rt_cpu_runs(isas[k]))
                continue;
            struct sl_rt rt;
            struct sl_diag d;
            assert_int_equal(sl_rt_build_isa(&rt, &f.scene, 2, 1, isas[k], &d), SL_OK);
            assert_int_equal(sl_truth_trace(&rt, &f.scene, &v, NULL, &d), SL_OK);
            runs++;
            uint64_t differ = 0;
            for (size_t i = 0; i < n; i++) {
                if (v.truth[i] == mine[i])
                    continue;
                differ++;
                assert_int_equal(v.cls[i], SL_C_PFL);
                double tc, m = tie_margin(&f.scene, &v, i, &tc);
                const float *p = v.pos + 3 * i;
                double span = fmax(tc, fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2]))) + tc);
                double bound = 16.0 * 0x1p-23 * span;
                printf("truth::isa_ties %s/%s 1024x1024: pixel %zu (x %zu, y %zu): %s says %s, the build's kernels "
                       "%s; the ray passes %.3g from a triangle's boundary at t = %.4g (bound %.3g)\n",
                       cases[c].scene, f.scene.vp[cases[c].vp].name, i, i % (size_t)v.w, i / (size_t)v.w, isas[k],
                       v.truth[i] == SL_T_SHADOW ? "shadow" : "lit", mine[i] == SL_T_SHADOW ? "shadow" : "lit", m,
                       tc, bound);
                assert_true(m <= bound);
            }
            printf("truth::isa_ties %s/%s 1024x1024: %s against the build's kernels: %llu pixels differ\n",
                   cases[c].scene, f.scene.vp[cases[c].vp].name, isas[k], (unsigned long long)differ);
            /* a tie is rare: a handful of a million */
            assert_true(differ <= 16);
            ties += differ;
            sl_rt_free(&rt);
        }
        memcpy(v.truth, mine, n);
        free(mine);
        sl_view_free(&v);
        fixture_close(&f);
    }
    printf("truth::isa_ties: %llu ties over %llu traces\n", (unsigned long long)ties, (unsigned long long)runs);
    assert_true(runs >= 2);   /* SSE4.2 and AVX2 run on every x86-64 CPU this project supports */
}

static void truth_blocks_matches_brute_force(void **st)
{
    (void)st;
    long pfl;
    run_scene("blocks", 256, &pfl);
    assert_true(pfl > 10000);
}

static void truth_primitives_matches_brute_force(void **st)
{
    (void)st;
    long pfl;
    run_scene("primitives", 256, &pfl);
    assert_true(pfl > 10000);
}

/* Same answer with 1 and 2 tracing threads, pixel for pixel. */
/* The truth streams chunks of 32 4x4 packets along each 4-row strip: a
 * viewport that is no multiple of 4 nor of a chunk (203 = 50 tiles + 3
 * pixels: one full chunk, one cut short, a last tile 3 wide; 77 rows: a
 * last strip one pixel high) must still match the brute force; a subset
 * traced through sl_rt_trace gets the truth's very answers and leaves every
 * other pixel alone; the set-up and trace clocks are both running and, summed
 * over the threads, within the pass's wall time times its threads. */
static void truth_odd_size_subset_times(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "primitives", 2));
    const int W = 203, H = 77;
    struct sl_view v;
    struct sl_diag d;
    assert_int_equal(sl_gbuffer_render(&f.gp, &f.mesh, &f.scene, 0, W, H, &v, NULL, NULL, NULL, &d), SL_OK);
    struct sl_truth_stats ts;
    assert_int_equal(sl_truth_trace(&f.rt, &f.scene, &v, &ts, &d), SL_OK);
    struct check c;
    brute_force(&f.scene, &v, &c);
    assert_int_equal(c.unexplained, 0);
    assert_true(v.n_shadow > 100 && v.n_lit > 100);
    assert_int_equal(ts.rays, (uint64_t)c.pfl);
    assert_true(ts.ms_setup > 0 && ts.ms_rays > 0);
    assert_true(ts.ms_setup + ts.ms_rays <= 2 * ts.ms_trace + 1e-3);

    size_t n = (size_t)W * H;
    uint8_t *sel = calloc(n, 1), *out = malloc(n);
    assert_non_null(sel);
    assert_non_null(out);
    memset(out, 0xEE, n);
    uint64_t want = 0, want_shadow = 0;
    for (size_t i = 0; i < n; i++)
        if (v.cls[i] == SL_C_PFL && i % 3 == 0) {
            sel[i] = 1;
            want++;
            want_shadow += v.truth[i] == SL_T_SHADOW;
        }
    uint64_t rays = 0, shadow = 0;
    assert_int_equal(sl_rt_trace(&f.rt, &f.scene, &v, sel, out, &rays, &shadow, &d), SL_OK);
    assert_int_equal(rays, want);
    assert_int_equal(shadow, want_shadow);
    for (size_t i = 0; i < n; i++)
        assert_int_equal(out[i], sel[i] ? v.truth[i] : 0xEE);
    free(sel);
    free(out);
    sl_view_free(&v);
    fixture_close(&f);
}

static void truth_thread_count_invariant(void **st)
{
    (void)st;
    struct fixture f1, f2;
    assert_true(fixture_open(&f1, "primitives", 1));
    assert_true(fixture_open(&f2, "primitives", 2));
    struct sl_view a, b;
    assert_true(fixture_view(&f1, 0, 256, 256, &a));
    assert_true(fixture_view(&f2, 0, 256, 256, &b));
    assert_memory_equal(a.truth, b.truth, (size_t)256 * 256);
    sl_view_free(&a);
    sl_view_free(&b);
    fixture_close(&f2);
    fixture_close(&f1);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(truth, blocks_matches_brute_force),
        SL_CASE(truth, primitives_matches_brute_force),
        SL_CASE(truth, thread_count_invariant),
        SL_CASE(truth, odd_size_subset_times),
        SL_CASE(truth, isa_ties),
    };
    return sl_run_group(argc, argv, "truth", tests, NULL, NULL);
}
