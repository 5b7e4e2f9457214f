/* gen::* — the Bench/Trees/Flowers props: documented triangle counts,
 * closed and outward-wound solids (the flowers' thin parts too), determinism
 * by seed, and the sizes that make "Trees" big-triangle and "Flowers"
 * small-triangle scenes. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "gen.h"
#include "adjacency.h"
#include "meshio.h"

#define PI 3.14159265358979323846

static struct sl_scene scene_of(const struct sl_mesh *m)
{
    struct sl_scene s;
    memset(&s, 0, sizeof s);
    s.pos = m->pos;
    s.nv = m->nv;
    s.idx = m->idx;
    s.nt = m->nt;
    return s;
}

static const float *P(const struct sl_mesh *m, uint32_t t, int k)
{
    return m->pos + 3 * (size_t)m->idx[3 * (size_t)t + k];
}

static void tri_normal(const struct sl_mesh *m, uint32_t t, double n[3])
{
    const float *a = P(m, t, 0), *b = P(m, t, 1), *c = P(m, t, 2);
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

static double tri_area(const struct sl_mesh *m, uint32_t t)
{
    double n[3];
    tri_normal(m, t, n);
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

static double edge_len(const struct sl_mesh *m, uint32_t t, int k)
{
    const float *a = P(m, t, k), *b = P(m, t, (k + 1) % 3);
    double s = 0;
    for (int i = 0; i < 3; i++)
        s += ((double)b[i] - a[i]) * ((double)b[i] - a[i]);
    return sqrt(s);
}

/* Signed volume of triangles [t0, t1): positive for a closed surface wound
 * counter-clockwise seen from outside. */
static double volume(const struct sl_mesh *m, uint32_t t0, uint32_t t1)
{
    double v = 0;
    for (uint32_t t = t0; t < t1; t++) {
        const float *a = P(m, t, 0), *b = P(m, t, 1), *c = P(m, t, 2);
        v += ((double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) -
              (double)a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
              (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6.0;
    }
    return v;
}

/* Weld (which must change nothing: generators share their own vertices and
 * no two parts share a corner) and count open and non-manifold edges. */
static void weld_and_edges(struct sl_mesh *m, uint32_t *open, uint32_t *nonman)
{
    uint32_t nv = m->nv, nt = m->nt;
    assert_int_equal(sl_mesh_weld(m), 0);
    assert_int_equal(m->nv, nv);
    assert_int_equal(m->nt, nt);
    struct sl_scene s = scene_of(m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    *open = a.open_edges;
    *nonman = a.nonmanifold_edges;
    sl_adjacency_free(&a);
}

static void gen_triangle_counts(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    for (int n = 3; n <= 48; n += 15) {
        sl_gen_cone(&m, 1, 2, 3, 1, 2, n);
        assert_int_equal(m.nt, 2 * n);
        assert_int_equal(m.nv, n + 2);
        sl_mesh_free(&m);
    }
    for (uint32_t seed = 0; seed < 3; seed++) {
        sl_gen_tree(&m, 0, 0, 0, 4.0f + 3.0f * seed, seed);
        assert_int_equal(m.nt, 1024);                /* 4*16 trunk + 960 leaves */
        assert_int_equal(m.nv, 34 + 3 * 960);
        sl_mesh_free(&m);
    }
    sl_gen_flowers(&m, 0, 0, 0, 2, 1, 0, 1);
    assert_int_equal(m.nt, 0);
    sl_gen_flowers(&m, 0, 0, 0, 2, 1, 17, 1);
    assert_int_equal(m.nt, 64 * 17);
    sl_mesh_free(&m);
    sl_gen_bench(&m, 0, 0, 0, 1.8f, 1);
    assert_int_equal(m.nt, 240);
    assert_int_equal(m.nv, 160);
    sl_mesh_free(&m);
    sl_gen_lamp(&m, 0, 0, 0, 4);
    assert_int_equal(m.nt, 172);
    sl_mesh_free(&m);
    float soil = sl_gen_flower_box(&m, 0, 1, 0, 4, 1, 0.5f);
    assert_int_equal(m.nt, 28);
    assert_int_equal(m.nv, 16);
    assert_true(fabsf(soil - 1.4f) < 1e-6f);
    sl_mesh_free(&m);
}

static void gen_cone_closed_outward(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    const int n = 24;
    const double r = 1.5, h = 3.0;
    sl_gen_cone(&m, 1, 0.5f, 2, (float)r, (float)h, n);
    /* a pyramid over the n-gon: V = (n/2 r^2 sin(2 pi / n)) h / 3 = 6.98811 */
    double want = 0.5 * n * r * r * sin(2 * PI / n) * h / 3.0;
    assert_true(fabs(volume(&m, 0, m.nt) - want) < 1e-5);
    assert_true(fabs(want - 6.98811) < 1e-5);
    for (uint32_t t = 0; t < m.nt; t++) {
        double nn[3];
        tri_normal(&m, t, nn);
        double cy = (P(&m, t, 0)[1] + P(&m, t, 1)[1] + P(&m, t, 2)[1]) / 3.0;
        if (cy > 0.5 + 1e-6) {   /* side: points away from the axis */
            double cxx = (P(&m, t, 0)[0] + P(&m, t, 1)[0] + P(&m, t, 2)[0]) / 3.0 - 1.0;
            double czz = (P(&m, t, 0)[2] + P(&m, t, 1)[2] + P(&m, t, 2)[2]) / 3.0 - 2.0;
            assert_true(nn[0] * cxx + nn[2] * czz > 0.0);
            assert_true(nn[1] > 0.0);
        } else {                 /* base: faces down */
            assert_true(nn[1] < 0.0 && fabs(nn[0]) < 1e-9 && fabs(nn[2]) < 1e-9);
        }
    }
    uint32_t open, nonman;
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 0);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);
}

static void gen_bench_lamp_box_closed(void **st)
{
    (void)st;
    uint32_t open, nonman;
    struct sl_mesh m = {0};

    /* bench: 20 boxes, each closed and outward (positive volume) */
    sl_gen_bench(&m, 3, 0, -2, 1.8f, 7);
    for (uint32_t b = 0; b < 20; b++)
        assert_true(volume(&m, 12 * b, 12 * b + 12) > 0.0);
    /* seat slat 0 is the full length and about 65 x 35 mm */
    double v0 = volume(&m, 0, 12);
    assert_true(v0 > 1.8 * 0.061 * 0.035 * 0.999 && v0 < 1.8 * 0.069 * 0.035 * 1.001);
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 0);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);

    /* lamp: base, pole, head, roof */
    sl_gen_lamp(&m, -4, 0, 3, 4);
    const uint32_t part[5] = {0, 64, 128, 140, 172};
    for (int i = 0; i < 4; i++)
        assert_true(volume(&m, part[i], part[i + 1]) > 0.0);
    /* the head box is 0.4 x 0.32 x 0.4 for a 4-unit lamp */
    assert_true(fabs(volume(&m, 128, 140) - 0.4 * 0.32 * 0.4) < 1e-5);
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 0);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);

    /* planter: outer 4 x 1 x 0.6 minus the cavity above the soil,
     * (4 - 0.16) x (1 - 0.16) x 0.12 */
    sl_gen_flower_box(&m, 3, 0, 2, 4, 1, 0.6f);
    assert_true(fabs(volume(&m, 0, m.nt) - (2.4 - 3.84 * 0.84 * 0.12)) < 1e-5);
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 0);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);
}

static void gen_deterministic_by_seed(void **st)
{
    (void)st;
    for (int kind = 0; kind < 3; kind++) {
        struct sl_mesh a = {0}, b = {0}, c = {0};
        for (int i = 0; i < 3; i++) {
            struct sl_mesh *m = i == 0 ? &a : i == 1 ? &b : &c;
            uint32_t seed = i == 2 ? 43 : 42;
            if (kind == 0)
                sl_gen_tree(m, 1, 0, 2, 8, seed);
            else if (kind == 1)
                sl_gen_flowers(m, 1, 0, 2, 3, 1, 50, seed);
            else
                sl_gen_bench(m, 1, 0, 2, 1.8f, seed);
        }
        assert_int_equal(a.nv, b.nv);
        assert_int_equal(a.nt, b.nt);
        assert_memory_equal(a.pos, b.pos, (size_t)a.nv * 3 * sizeof(float));
        assert_memory_equal(a.idx, b.idx, (size_t)a.nt * 3 * sizeof(uint32_t));
        /* another seed: same counts and topology, other positions */
        assert_int_equal(c.nv, a.nv);
        assert_memory_equal(c.idx, a.idx, (size_t)a.nt * 3 * sizeof(uint32_t));
        assert_memory_not_equal(c.pos, a.pos, (size_t)a.nv * 3 * sizeof(float));
        sl_mesh_free(&a);
        sl_mesh_free(&b);
        sl_mesh_free(&c);
    }
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* A shadow-map texel over a 100-unit scene at 1024^2 is ~0.1 unit wide, 0.01
 * square units (the Bench scenes scale the bed 16.3 times: this is about
 * the generator, not those scenes). Bounds on the petals, leaves, blossom
 * and the stems' caps: median triangle area below 3e-4 (3% of a texel),
 * every one below 5e-4 (5%) and no edge longer than 0.07 unit. The stems'
 * 6 sides are one segment, long slivers never wider than 1.05 cm. */
static void gen_flowers_far_below_a_texel(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    const float cx = 20, y0 = 0.48f, cz = -30, w = 3.84f, d = 0.84f;
    sl_gen_flowers(&m, cx, y0, cz, w, d, 812, 11);
    assert_int_equal(m.nt, 51968);
    double *ar = malloc(m.nt * sizeof *ar), emax = 0;
    assert_non_null(ar);
    uint32_t n = 0;
    for (uint32_t t = 0; t < m.nt; t++) {
        assert_true(tri_area(&m, t) > 1e-6);
        if (t % 64 < 6) {   /* a stem's side: its shortest edge is across the stem */
            double e = fmin(edge_len(&m, t, 0), fmin(edge_len(&m, t, 1), edge_len(&m, t, 2)));
            assert_true(e < 0.0105);
            continue;
        }
        ar[n++] = tri_area(&m, t);
        for (int k = 0; k < 3; k++)
            if (edge_len(&m, t, k) > emax)
                emax = edge_len(&m, t, k);
    }
    assert_int_equal(n, 58 * 812);
    qsort(ar, n, sizeof *ar, cmp_double);
    double median = ar[n / 2];
    assert_true(median < 3e-4);      /* measured 1.6e-4 */
    assert_true(median > 5e-5);      /* not degenerate slivers either */
    assert_true(ar[n - 1] < 5e-4);   /* measured 2.8e-4 */
    assert_true(emax < 0.07);        /* measured 0.058 */
    free(ar);
    /* planted in the bed: stems start 1 cm under y0, every flower inside
     * the bed's rectangle, nothing taller than 0.45 */
    for (uint32_t v = 0; v < m.nv; v++) {
        const float *p = m.pos + 3 * (size_t)v;
        assert_true(p[0] > cx - 0.5f * w && p[0] < cx + 0.5f * w);
        assert_true(p[2] > cz - 0.5f * d && p[2] < cz + 0.5f * d);
        assert_true(p[1] >= y0 - 0.0101f && p[1] < y0 + 0.45f);
    }
    uint32_t open, nonman;
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 0);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);
}

/* The flowers are drawn one-sided, so front-face culling must find a face
 * behind every lit one (gen.c, "closed thin solids"): each flower is 12
 * closed convex parts, every face wound away from its part's inside: the
 * stem [0, 8), two leaves [8, 12) and [12, 16), the double cone [16, 32)
 * (8 faces up, 8 down) and 8 petals [32 + 4i, 36 + 4i). A leaf or petal is
 * a tetrahedron whose two diagonals, (v0, v2) across it on top and
 * (v1, v3) along it underneath, cross over the same point of its diamond
 * 1.5 mm apart: its top and underside are back to back at the thickness.
 * The open flowers (one surface, two-sided) had 54 open edges a flower and
 * no volume. */
static void gen_flowers_closed_thin_solids(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    const int count = 60;
    sl_gen_flowers(&m, 1, 0.5f, -2, 1.3f, 0.45f, count, 7);
    assert_int_equal(m.nt, 64 * count);
    for (uint32_t f = 0; f < (uint32_t)count; f++) {
        uint32_t part[13] = {0, 8, 12, 16, 32};
        for (int i = 1; i <= 8; i++)
            part[4 + i] = 32 + 4 * (uint32_t)i;
        for (int p = 0; p < 12; p++) {
            uint32_t t0 = 64 * f + part[p], t1 = 64 * f + part[p + 1];
            assert_true(volume(&m, t0, t1) > 0.0);
            /* convex: every face looks away from the part's centre */
            double c[3] = {0, 0, 0};
            for (uint32_t t = t0; t < t1; t++)
                for (int k = 0; k < 3; k++)
                    for (int j = 0; j < 3; j++)
                        c[j] += P(&m, t, k)[j] / (3.0 * (t1 - t0));
            int ups = 0;
            for (uint32_t t = t0; t < t1; t++) {
                double nn[3], dot = 0;
                tri_normal(&m, t, nn);
                for (int j = 0; j < 3; j++)
                    dot += nn[j] * ((P(&m, t, 0)[j] + P(&m, t, 1)[j] + P(&m, t, 2)[j]) / 3.0 - c[j]);
                assert_true(dot > 0.0);
                ups += nn[1] > 0.0;
            }
            if (p == 3)
                assert_int_equal(ups, 8);
            if (p == 1 || p == 2 || p >= 4) {
                uint32_t v0 = m.idx[3 * (size_t)t0];
                for (uint32_t t = t0; t < t1; t++)
                    for (int k = 0; k < 3; k++)
                        v0 = m.idx[3 * (size_t)t + k] < v0 ? m.idx[3 * (size_t)t + k] : v0;
                const float *q[4];
                for (int k = 0; k < 4; k++)
                    q[k] = m.pos + 3 * (size_t)(v0 + (uint32_t)k);
                double d1[3], d2[3], mid[3], n[3];
                for (int j = 0; j < 3; j++) {
                    d1[j] = (double)q[2][j] - q[0][j];
                    d2[j] = (double)q[3][j] - q[1][j];
                    mid[j] = 0.5 * ((double)q[0][j] + q[2][j] - q[1][j] - q[3][j]);
                }
                n[0] = d1[1] * d2[2] - d1[2] * d2[1];
                n[1] = d1[2] * d2[0] - d1[0] * d2[2];
                n[2] = d1[0] * d2[1] - d1[1] * d2[0];
                double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                double along = fabs(mid[0] * n[0] + mid[1] * n[1] + mid[2] * n[2]) / ln;
                double gap = sqrt(mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2]);
                assert_true(mid[1] > 0.0);                        /* v0-v2 on top */
                assert_true(fabs(gap - 0.0015) < 2e-5);           /* 1.5 mm apart */
                assert_true(along > 0.999 * gap);                 /* straight across */
                assert_true(fabs(volume(&m, t0, t1) - ln * 0.0015 / 6.0) < 0.01 * ln * 0.0015 / 6.0);
            }
        }
    }
    uint32_t open, nonman;
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 0);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);
}

/* Leaves are many texels wide: every leaf edge > 0.0625 of the tree height
 * (0.5 unit for an 8-unit tree). The trunk is closed, leaves open. */
static void gen_tree_leaves_are_large(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    const float H = 8;
    sl_gen_tree(&m, 5, 1, -5, H, 99);
    assert_true(volume(&m, 0, 64) > 0.0);
    double emin = 1e9;
    for (uint32_t t = 64; t < m.nt; t++) {
        for (int k = 0; k < 3; k++)
            if (edge_len(&m, t, k) < emin)
                emin = edge_len(&m, t, k);
        for (int k = 0; k < 3; k++)
            assert_true(P(&m, t, k)[1] > 1 + 0.29f * H && P(&m, t, k)[1] < 1 + 1.03f * H);
    }
    assert_true(emin > 0.0625 * H);
    uint32_t open, nonman;
    weld_and_edges(&m, &open, &nonman);
    assert_int_equal(open, 3 * 960);
    assert_int_equal(nonman, 0);
    sl_mesh_free(&m);
}

/* The recommended Bench scene: ~55,000 triangles, flowers carry most. */
static void gen_bench_scene_budget(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    sl_gen_plane(&m, 0, 0, 0, 100, 16);
    sl_gen_tree(&m, -8, 0, -6, 8, 1);
    sl_gen_tree(&m, 9, 0, -7, 7, 2);
    sl_gen_lamp(&m, -4, 0, 3, 4);
    float soil = sl_gen_flower_box(&m, 3, 0, 2, 4, 1, 0.6f);
    uint32_t before = m.nt;
    sl_gen_flowers(&m, 3, soil, 2, 3.84f, 0.84f, 812, 3);
    uint32_t flowers = m.nt - before;
    sl_gen_bench(&m, 0, 0, 5, 1.8f, 4);
    assert_int_equal(m.nt, 512 + 2 * 1024 + 172 + 28 + 51968 + 240);
    assert_int_equal(m.nt, 54968);
    assert_true(flowers * 100 > 94 * m.nt);
    sl_mesh_free(&m);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(gen, triangle_counts),
        SL_CASE(gen, cone_closed_outward),
        SL_CASE(gen, bench_lamp_box_closed),
        SL_CASE(gen, deterministic_by_seed),
        SL_CASE(gen, flowers_far_below_a_texel),
        SL_CASE(gen, flowers_closed_thin_solids),
        SL_CASE(gen, tree_leaves_are_large),
        SL_CASE(gen, bench_scene_budget),
    };
    return sl_run_group(argc, argv, "gen", tests, NULL, NULL);
}
