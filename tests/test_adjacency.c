/* adjacency::* — edge neighbours, opposite vertices, vertex-neighbour CSR,
 * open and non-manifold counts, each checked against hand-derived values and
 * against a brute-force reference. */
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

static int tri_has(const uint32_t *tri, uint32_t v)
{
    return tri[0] == v || tri[1] == v || tri[2] == v;
}

/* Brute force, O(n^2): every answer of a against a direct search. */
static void check_against_brute(const struct sl_scene *s, const struct sl_adjacency *a)
{
    uint32_t open = 0;
    for (uint32_t t = 0; t < s->nt; t++) {
        const uint32_t *tt = s->idx + 3 * (size_t)t;
        for (int k = 0; k < 3; k++) {
            uint32_t v0 = tt[k], v1 = tt[(k + 1) % 3], found = SL_ADJ_NONE, n = 0;
            for (uint32_t u = 0; u < s->nt; u++)
                if (u != t && tri_has(s->idx + 3 * (size_t)u, v0) && tri_has(s->idx + 3 * (size_t)u, v1)) {
                    found = u;
                    n++;
                }
            uint32_t want = n == 0 ? SL_ADJ_NONE : n == 1 ? found : SL_ADJ_MULTI;
            assert_int_equal(a->edge[3 * t + k], want);
            if (n == 0)
                open++;
            if (n == 1) {
                uint32_t o = a->opposite[3 * t + k];
                assert_true(tri_has(s->idx + 3 * (size_t)found, o));
                assert_true(o != v0 && o != v1);
            } else {
                assert_int_equal(a->opposite[3 * t + k], SL_ADJ_NONE);
            }
        }
        /* vertex neighbours: ascending, unique, not t, exactly the sharers */
        uint32_t b = a->vtx_off[t], e = a->vtx_off[t + 1], cnt = 0;
        for (uint32_t i = b; i < e; i++) {
            assert_true(a->vtx_tris[i] != t);
            if (i > b)
                assert_true(a->vtx_tris[i] > a->vtx_tris[i - 1]);
        }
        for (uint32_t u = 0; u < s->nt; u++) {
            const uint32_t *uu = s->idx + 3 * (size_t)u;
            if (u == t || !(tri_has(uu, tt[0]) || tri_has(uu, tt[1]) || tri_has(uu, tt[2])))
                continue;
            assert_true(b + cnt < e);
            assert_int_equal(a->vtx_tris[b + cnt], u);
            cnt++;
        }
        assert_int_equal(cnt, e - b);
    }
    assert_int_equal(a->open_edges, open);
}

/* If edge k of t names u, u names t on the same undirected edge. */
static void check_symmetric(const struct sl_scene *s, const struct sl_adjacency *a)
{
    for (uint32_t t = 0; t < s->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = a->edge[3 * t + k];
            if (u == SL_ADJ_NONE || u == SL_ADJ_MULTI)
                continue;
            assert_true(u < s->nt && u != t);
            uint32_t v0 = s->idx[3 * t + k], v1 = s->idx[3 * t + (k + 1) % 3];
            int back = 0;
            for (int j = 0; j < 3; j++) {
                uint32_t w0 = s->idx[3 * u + j], w1 = s->idx[3 * u + (j + 1) % 3];
                if (((w0 == v0 && w1 == v1) || (w0 == v1 && w1 == v0)) && a->edge[3 * u + j] == t)
                    back++;
            }
            assert_int_equal(back, 1);
        }
}

static void adjacency_closed_box(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    const float lo[3] = {-1, 0, -2}, hi[3] = {1, 3, 2};
    sl_gen_box(&m, lo, hi);
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    assert_int_equal(a.nt, 12);
    assert_int_equal(a.open_edges, 0);
    assert_int_equal(a.nonmanifold_edges, 0);
    for (uint32_t i = 0; i < 36; i++)
        assert_true(a.edge[i] < 12);
    check_symmetric(&s, &a);
    /* an outward-wound closed surface crosses each edge once each way */
    for (uint32_t t = 0; t < 12; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t u = a.edge[3 * t + k], v0 = m.idx[3 * t + k], v1 = m.idx[3 * t + (k + 1) % 3];
            int opposite_dir = 0;
            for (int j = 0; j < 3; j++)
                if (m.idx[3 * u + j] == v1 && m.idx[3 * u + (j + 1) % 3] == v0)
                    opposite_dir = 1;
            assert_true(opposite_dir);
        }
    /* the diagonal of face -x: triangles 0 = (0,4,6) and 1 = (0,6,2) share
     * edge 6-0; the vertex of 1 off that edge is 2 */
    assert_int_equal(a.edge[3 * 0 + 2], 1);
    assert_int_equal(a.opposite[3 * 0 + 2], 2);
    assert_int_equal(a.opposite[3 * 1 + 0], 4);
    check_against_brute(&s, &a);
    sl_adjacency_free(&a);
    sl_adjacency_free(&a);   /* NULL-safe and idempotent */
    sl_adjacency_free(NULL);
    sl_mesh_free(&m);
}

static void adjacency_box_corner_vertex_neighbours(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    sl_gen_box(&m, lo, hi);
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    /* triangle 0 = corners (0,4,6); the triangles touching 0, 4 or 6 are all
     * but 2 = (1,3,7), 3 = (1,7,5) and 7 = (2,7,3) */
    static const uint32_t want[8] = {1, 4, 5, 6, 8, 9, 10, 11};
    assert_int_equal(a.vtx_off[0], 0);
    assert_int_equal(a.vtx_off[1], 8);
    assert_memory_equal(a.vtx_tris, want, sizeof want);
    check_against_brute(&s, &a);
    sl_adjacency_free(&a);
    sl_mesh_free(&m);
}

static void adjacency_open_plane_grid(void **st)
{
    (void)st;
    for (int g = 1; g <= 7; g += 3) {
        struct sl_mesh m = {0};
        sl_gen_plane(&m, 0, 0, 0, 10, g);
        struct sl_scene s = scene_of(&m);
        struct sl_adjacency a;
        struct sl_diag d;
        assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
        assert_int_equal(a.open_edges, 4u * (uint32_t)g);     /* perimeter segments */
        assert_int_equal(a.nonmanifold_edges, 0);
        uint32_t sides_open = 0;
        for (uint32_t i = 0; i < 3 * m.nt; i++)
            sides_open += a.edge[i] == SL_ADJ_NONE;
        assert_int_equal(sides_open, 4u * (uint32_t)g);
        check_symmetric(&s, &a);
        check_against_brute(&s, &a);
        sl_adjacency_free(&a);
        sl_mesh_free(&m);
    }
}

static void adjacency_nonmanifold_fan(void **st)
{
    (void)st;
    /* three triangles hinged on edge 0-1 (a book of three pages) */
    struct sl_mesh m = {0};
    sl_mesh_vertex(&m, 0, 0, 0);
    sl_mesh_vertex(&m, 0, 1, 0);
    sl_mesh_vertex(&m, 1, 0, 0);
    sl_mesh_vertex(&m, 0, 0, 1);
    sl_mesh_vertex(&m, -1, 0, -1);
    sl_mesh_tri(&m, 0, 1, 2);
    sl_mesh_tri(&m, 1, 0, 3);
    sl_mesh_tri(&m, 4, 0, 1);
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    assert_int_equal(a.nonmanifold_edges, 1);          /* once, not three times */
    assert_int_equal(a.open_edges, 6);
    assert_int_equal(a.edge[0], SL_ADJ_MULTI);         /* 0->1 */
    assert_int_equal(a.edge[3], SL_ADJ_MULTI);         /* 1->0 */
    assert_int_equal(a.edge[7], SL_ADJ_MULTI);         /* 0->1 */
    assert_int_equal(a.opposite[0], SL_ADJ_NONE);
    assert_int_equal(a.opposite[7], SL_ADJ_NONE);
    for (uint32_t t = 0; t < 3; t++) {                 /* each sees the other two */
        assert_int_equal(a.vtx_off[t + 1] - a.vtx_off[t], 2);
    }
    check_against_brute(&s, &a);
    sl_adjacency_free(&a);

    /* a fourth page: still one non-manifold edge */
    sl_mesh_vertex(&m, 0, -0.5f, 2);
    sl_mesh_tri(&m, 0, 1, 5);
    s = scene_of(&m);
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    assert_int_equal(a.nonmanifold_edges, 1);
    assert_int_equal(a.open_edges, 8);
    sl_adjacency_free(&a);
    sl_mesh_free(&m);
}

static void adjacency_bad_and_empty(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    sl_mesh_vertex(&m, 0, 0, 0);
    sl_mesh_vertex(&m, 1, 0, 0);
    sl_mesh_vertex(&m, 0, 1, 0);
    sl_mesh_tri(&m, 0, 1, 3);            /* vertex 3 does not exist */
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_E_SCENE);
    assert_null(a.edge);
    assert_null(a.vtx_tris);
    sl_mesh_free(&m);

    struct sl_scene empty;
    memset(&empty, 0, sizeof empty);
    assert_int_equal(sl_adjacency_build(&empty, &a, &d), SL_OK);
    assert_int_equal(a.nt, 0);
    assert_int_equal(a.vtx_off[0], 0);
    assert_int_equal(a.open_edges, 0);
    sl_adjacency_free(&a);
}

/* Brute force over a mixed mesh: sphere poles (valence 24), a tree's loose
 * leaves, a welded bench and a fan with a non-manifold edge. */
static void adjacency_matches_brute_force_mixed(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    sl_gen_sphere(&m, 0, 0, 0, 1, 24, 8);
    sl_gen_bench(&m, 3, 0, 0, 1.2f, 5);
    sl_gen_cone(&m, -3, 0, 0, 1, 2, 12);
    sl_gen_flowers(&m, 0, 0, 4, 1, 1, 3, 9);
    sl_mesh_vertex(&m, 0, 5, 0);
    uint32_t hinge = m.nv - 1;
    sl_mesh_tri(&m, 0, 1, hinge);       /* a third triangle on a sphere edge */
    assert_int_equal(sl_mesh_weld(&m), 0);
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    assert_int_equal(a.nonmanifold_edges, 1);
    /* open: the hinge triangle's 2 (flowers are closed solids) */
    assert_int_equal(a.open_edges, 2);
    check_symmetric(&s, &a);
    check_against_brute(&s, &a);
    sl_adjacency_free(&a);
    sl_mesh_free(&m);
}

/* The Bench scene's size (54,968 triangles): counts equal the sum of the
 * parts' documented open edges, symmetric everywhere. The sort is O(n); a
 * quadratic build would take minutes here, not milliseconds. */
static void adjacency_bench_scene_scale(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    sl_gen_plane(&m, 0, 0, 0, 100, 16);
    sl_gen_tree(&m, -8, 0, -6, 8, 1);
    sl_gen_tree(&m, 9, 0, -7, 7, 2);
    sl_gen_lamp(&m, -4, 0, 3, 4);
    float soil = sl_gen_flower_box(&m, 3, 0, 2, 4, 1, 0.6f);
    sl_gen_flowers(&m, 3, soil, 2, 3.84f, 0.84f, 812, 3);
    sl_gen_bench(&m, 0, 0, 5, 1.8f, 4);
    assert_int_equal(m.nt, 54968);
    assert_int_equal(sl_mesh_weld(&m), 0);
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    /* plane 4*16, leaves 3 each, flowers and solids none */
    assert_int_equal(a.open_edges, 64 + 2 * 960 * 3);
    assert_int_equal(a.nonmanifold_edges, 0);
    check_symmetric(&s, &a);
    uint32_t sides_open = 0;
    for (uint32_t i = 0; i < 3 * m.nt; i++)
        sides_open += a.edge[i] == SL_ADJ_NONE;
    assert_int_equal(sides_open, a.open_edges);
    for (uint32_t t = 0; t < m.nt; t++)
        for (uint32_t i = a.vtx_off[t]; i < a.vtx_off[t + 1]; i++)
            assert_true(a.vtx_tris[i] != t && (i == a.vtx_off[t] || a.vtx_tris[i] > a.vtx_tris[i - 1]));
    sl_adjacency_free(&a);
    sl_mesh_free(&m);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(adjacency, closed_box),
        SL_CASE(adjacency, box_corner_vertex_neighbours),
        SL_CASE(adjacency, open_plane_grid),
        SL_CASE(adjacency, nonmanifold_fan),
        SL_CASE(adjacency, bad_and_empty),
        SL_CASE(adjacency, matches_brute_force_mixed),
        SL_CASE(adjacency, bench_scene_scale),
    };
    return sl_run_group(argc, argv, "adjacency", tests, NULL, NULL);
}
