/* meshio::* — model files through assimp into welded meshes, and the weld.
 *
 * Real third-party models come from Debian's assimp-testmodels
 * (/usr/share/assimp/models); the bad inputs are hand-made in tests/models/.
 * Counts asserted here were measured with assimp 5.2 and are properties of
 * the files (triangles, distinct positions, zero-area triangles). */
#define _GNU_SOURCE   /* clock_gettime, pause, sched_setaffinity */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <signal.h>
#include <string.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <time.h>
#include <unistd.h>
#include <cmocka.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include "sl_test.h"
#include "gen.h"
#include "adjacency.h"
#include "meshio.h"
#include "meshio_child.h"

#define MODELS "/usr/share/assimp/models"

/* ----------------------------------------------------------------- helpers */

static double tri_area(const struct sl_mesh *m, uint32_t t)
{
    const float *a = m->pos + 3 * (size_t)m->idx[3 * t], *b = m->pos + 3 * (size_t)m->idx[3 * t + 1],
                *c = m->pos + 3 * (size_t)m->idx[3 * t + 2];
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

static const float *g_pos;   /* for cmp_pos */

static int cmp_pos(const void *a, const void *b)
{
    const float *p = g_pos + 3 * (size_t)*(const uint32_t *)a, *q = g_pos + 3 * (size_t)*(const uint32_t *)b;
    return memcmp(p, q, 3 * sizeof(float));
}

/* Every index in range, no repeated index, no zero-area triangle, and no two
 * vertices with the same position (what "welded" means). */
static void assert_welded_clean(const struct sl_mesh *m)
{
    for (uint32_t t = 0; t < m->nt; t++) {
        const uint32_t *ix = m->idx + 3 * (size_t)t;
        assert_true(ix[0] < m->nv && ix[1] < m->nv && ix[2] < m->nv);
        assert_true(ix[0] != ix[1] && ix[1] != ix[2] && ix[0] != ix[2]);
        assert_true(tri_area(m, t) > 0.0);
    }
    uint32_t *ord = malloc((m->nv + 1) * sizeof *ord);
    assert_non_null(ord);
    for (uint32_t i = 0; i < m->nv; i++)
        ord[i] = i;
    g_pos = m->pos;
    qsort(ord, m->nv, sizeof *ord, cmp_pos);
    for (uint32_t i = 1; i < m->nv; i++)
        assert_int_not_equal(cmp_pos(&ord[i - 1], &ord[i]), 0);
    free(ord);
}

static void mesh_bounds(const struct sl_mesh *m, uint32_t v0, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (uint32_t i = v0; i < m->nv; i++)
        for (int k = 0; k < 3; k++) {
            float x = m->pos[3 * (size_t)i + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
}

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

static void load_ok(struct sl_mesh *m, const char *path, struct sl_mesh_load_stats *st)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    enum sl_err e = sl_mesh_load_file(m, path, NULL, st, &d);
    if (e)
        fprintf(stderr, "%s: %s\n", path, d.msg);
    assert_int_equal(e, SL_OK);
}

/* Vertices assimp hands over after JoinIdenticalVertices, counted once per
 * node instance (what our loader would append without its own weld). */
static uint32_t assimp_instanced_vertices(const char *path)
{
    const struct aiScene *s = aiImportFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                     aiProcess_SortByPType);
    assert_non_null(s);
    uint32_t n = 0;
    const struct aiNode *stack[256];
    int top = 0;
    stack[top++] = s->mRootNode;
    while (top) {
        const struct aiNode *nd = stack[--top];
        for (unsigned i = 0; i < nd->mNumMeshes; i++)
            n += s->mMeshes[nd->mMeshes[i]]->mNumVertices;
        for (unsigned i = 0; i < nd->mNumChildren; i++) {
            assert_true(top < 256);
            stack[top++] = nd->mChildren[i];
        }
    }
    aiReleaseImport(s);
    return n;
}

/* ---------------------------------------------------------------- the weld */

/* Two unit quads side by side in z = 0, each with its own 4 vertices (the
 * two on x = 1 duplicated), one written with -0.0. */
static void two_quads(struct sl_mesh *m)
{
    memset(m, 0, sizeof *m);
    sl_mesh_vertex(m, 0, 0, 0);
    sl_mesh_vertex(m, 1, 0, 0);
    sl_mesh_vertex(m, 1, 1, 0);
    sl_mesh_vertex(m, 0, 1, 0);
    sl_mesh_tri(m, 0, 1, 2);
    sl_mesh_tri(m, 0, 2, 3);
    sl_mesh_vertex(m, 1, 0, -0.0f);   /* = vertex 1 once -0 is +0 */
    sl_mesh_vertex(m, 2, 0, 0);
    sl_mesh_vertex(m, 2, 1, 0);
    sl_mesh_vertex(m, 1, 1, 0);       /* = vertex 2 */
    sl_mesh_tri(m, 4, 5, 6);
    sl_mesh_tri(m, 4, 6, 7);
}

static void meshio_weld_two_quads(void **st)
{
    (void)st;
    struct sl_mesh m;
    two_quads(&m);
    assert_int_equal(m.nv, 8);
    assert_int_equal(sl_mesh_weld(&m), 0);
    assert_int_equal(m.nv, 6);
    assert_int_equal(m.nt, 4);
    /* first occurrences keep their place; 4,5,6,7 -> 1,4,5,2 */
    static const uint32_t want[12] = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
    assert_memory_equal(m.idx, want, sizeof want);
    assert_true(m.pos[3 * 4 + 0] == 2.0f && m.pos[3 * 5 + 0] == 2.0f && m.pos[3 * 5 + 1] == 1.0f);
    assert_false(signbit(m.pos[3 * 1 + 2]));
    assert_welded_clean(&m);

    /* the shared edge (1,0,0)-(1,1,0) is now one edge of triangles 0 and 2 */
    struct sl_scene s = scene_of(&m);
    struct sl_adjacency a;
    struct sl_diag d;
    assert_int_equal(sl_adjacency_build(&s, &a, &d), SL_OK);
    assert_int_equal(a.edge[3 * 0 + 1], 3);     /* tri 0 = (0,1,2), edge 1 = 1->2 */
    assert_int_equal(a.edge[3 * 3 + 2], 0);     /* tri 3 = (1,5,2), edge 2 = 2->1 */
    assert_int_equal(a.opposite[3 * 0 + 1], 5);
    assert_int_equal(a.opposite[3 * 3 + 2], 0);
    assert_int_equal(a.open_edges, 6);
    assert_int_equal(a.nonmanifold_edges, 0);
    sl_adjacency_free(&a);

    /* idempotent */
    uint32_t idx_before[12];
    memcpy(idx_before, m.idx, sizeof idx_before);
    assert_int_equal(sl_mesh_weld(&m), 0);
    assert_int_equal(m.nv, 6);
    assert_memory_equal(m.idx, idx_before, sizeof idx_before);
    sl_mesh_free(&m);
}

static void meshio_weld_drops_degenerate_keeps_order(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    uint32_t a = sl_mesh_vertex(&m, 0, 0, 0), b = sl_mesh_vertex(&m, 1, 0, 0);
    uint32_t c = sl_mesh_vertex(&m, 0, 1, 0), e = sl_mesh_vertex(&m, 2, 0, 0);
    uint32_t a2 = sl_mesh_vertex(&m, 0, 0, 0);                      /* same place as a */
    uint32_t f = sl_mesh_vertex(&m, 0, 0, 1);
    sl_mesh_tri(&m, a, b, c);      /* kept */
    sl_mesh_tri(&m, a, a2, b);     /* repeated position -> repeated index */
    sl_mesh_tri(&m, a, b, e);      /* collinear: zero area */
    sl_mesh_tri(&m, c, b, f);      /* kept */
    sl_mesh_tri(&m, b, b, c);      /* repeated index */
    sl_mesh_tri(&m, a, f, 99);     /* indexes a missing vertex */
    sl_mesh_tri(&m, f, c, a2);     /* kept, a2 -> a */
    assert_int_equal(sl_mesh_weld(&m), 4);
    assert_int_equal(m.nt, 3);
    assert_int_equal(m.nv, 5);
    const uint32_t want[9] = {0, 1, 2, 2, 1, 4, 4, 2, 0};   /* f became vertex 4 */
    assert_memory_equal(m.idx, want, sizeof want);
    assert_welded_clean(&m);
    sl_mesh_free(&m);

    struct sl_mesh empty = {0};
    assert_int_equal(sl_mesh_weld(&empty), 0);
    assert_int_equal(sl_mesh_weld(NULL), 0);
}

/* ----------------------------------------------------------- real models */

static void meshio_spider_obj(void **st)
{
    (void)st;
    const char *p = MODELS "/OBJ/spider.obj";
    struct sl_mesh m = {0};
    struct sl_mesh_load_stats s;
    load_ok(&m, p, &s);
    assert_int_equal(s.meshes, 19);
    assert_int_equal(s.triangles, 1312);
    assert_int_equal(s.degenerate, 56);        /* 1368 read, 56 with zero area */
    assert_int_equal(s.vertices, 722);
    assert_int_equal(s.skipped_prims, 0);
    assert_int_equal(m.nt, 1312);
    assert_int_equal(m.nv, 722);
    /* assimp's own join keeps 946 (normals and texture seams split them) */
    uint32_t raw = assimp_instanced_vertices(p);
    assert_int_equal(raw, 946);
    assert_true(m.nv < raw);
    assert_welded_clean(&m);
    float lo[3], hi[3];
    mesh_bounds(&m, 0, lo, hi);
    assert_true(fabsf(lo[0] + 92.6552f) < 1e-3f && fabsf(hi[1] - 37.504f) < 1e-3f);

    /* the same spider as binary and ASCII STL: same triangles and vertices */
    const char *stl[2] = {MODELS "/STL/Spider_binary.stl", MODELS "/STL/Spider_ascii.stl"};
    for (int i = 0; i < 2; i++) {
        struct sl_mesh ms = {0};
        load_ok(&ms, stl[i], &s);
        assert_int_equal(s.triangles, 1312);
        assert_int_equal(s.vertices, 722);
        assert_int_equal(s.degenerate, 56);
        assert_true(assimp_instanced_vertices(stl[i]) > 3800);   /* STL: a soup */
        assert_welded_clean(&ms);
        struct sl_scene sc = scene_of(&ms);
        struct sl_adjacency a;
        struct sl_diag d;
        assert_int_equal(sl_adjacency_build(&sc, &a, &d), SL_OK);
        assert_int_equal(a.open_edges, 72);
        assert_int_equal(a.nonmanifold_edges, 0);
        sl_adjacency_free(&a);
        sl_mesh_free(&ms);
    }
    sl_mesh_free(&m);
}

static void meshio_engine_glb_node_transforms(void **st)
{
    (void)st;
    const char *p = MODELS "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
    struct sl_mesh m = {0};
    struct sl_mesh_load_stats s;
    load_ok(&m, p, &s);
    assert_int_equal(s.meshes, 115);            /* node instances of 29 meshes */
    assert_int_equal(s.triangles, 110336);
    assert_int_equal(s.degenerate, 11160);
    assert_int_equal(s.vertices, 60040);
    uint32_t raw = assimp_instanced_vertices(p);
    assert_true(m.nv < raw);
    assert_welded_clean(&m);

    /* our node walk must put every part where assimp's own
     * PreTransformVertices puts it: compare the bounds */
    const struct aiScene *sc = aiImportFile(p, aiProcess_Triangulate | aiProcess_PreTransformVertices);
    assert_non_null(sc);
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        for (unsigned v = 0; v < sc->mMeshes[i]->mNumVertices; v++) {
            const struct aiVector3D *q = &sc->mMeshes[i]->mVertices[v];
            float c[3] = {q->x, q->y, q->z};
            for (int k = 0; k < 3; k++) {
                if (c[k] < lo[k]) lo[k] = c[k];
                if (c[k] > hi[k]) hi[k] = c[k];
            }
        }
    aiReleaseImport(sc);
    float ml[3], mh[3];
    mesh_bounds(&m, 0, ml, mh);
    for (int k = 0; k < 3; k++) {
        assert_true(fabsf(ml[k] - lo[k]) < 1e-3f);
        assert_true(fabsf(mh[k] - hi[k]) < 1e-3f);
    }
    /* and the box is not the untransformed one: the engine is 743 wide */
    assert_true(fabsf(mh[0] - ml[0] - 743.384f) < 0.01f);
    sl_mesh_free(&m);
}

static void meshio_stl_and_ply(void **st)
{
    (void)st;
    struct sl_mesh_load_stats s;
    struct sl_diag d;
    struct sl_adjacency a;

    /* a sphere with a hole: 9 boundary edges around it */
    struct sl_mesh m = {0};
    load_ok(&m, MODELS "/STL/sphereWithHole.stl", &s);
    assert_int_equal(s.triangles, 285);
    assert_int_equal(s.vertices, 146);
    assert_true(assimp_instanced_vertices(MODELS "/STL/sphereWithHole.stl") == 855);
    struct sl_scene sc = scene_of(&m);
    assert_int_equal(sl_adjacency_build(&sc, &a, &d), SL_OK);
    assert_int_equal(a.open_edges, 9);
    assert_int_equal(a.nonmanifold_edges, 0);
    sl_adjacency_free(&a);
    sl_mesh_free(&m);

    /* binary PLY cube (quads): 12 triangles, 8 corners, closed */
    load_ok(&m, MODELS "/PLY/cube_binary.ply", &s);
    assert_int_equal(s.triangles, 12);
    assert_int_equal(s.vertices, 8);
    sc = scene_of(&m);
    assert_int_equal(sl_adjacency_build(&sc, &a, &d), SL_OK);
    assert_int_equal(a.open_edges, 0);
    sl_adjacency_free(&a);
    sl_mesh_free(&m);

    /* ASCII PLY of Wuson */
    load_ok(&m, MODELS "/PLY/Wuson.ply", &s);
    assert_int_equal(s.triangles, 3732);
    assert_int_equal(s.vertices, 2117);
    assert_int_equal(s.degenerate, 0);
    assert_welded_clean(&m);
    sl_mesh_free(&m);

    /* points and lines are skipped and counted, triangles kept */
    load_ok(&m, MODELS "/OBJ/testmixed.obj", &s);
    assert_int_equal(s.triangles, 12);
    assert_int_equal(s.skipped_prims, 42);
    sl_mesh_free(&m);
}

static void meshio_xform_and_append(void **st)
{
    (void)st;
    const char *p = MODELS "/PLY/cube_binary.ply";   /* unit cube [0,1]^3 */
    struct sl_mesh m = {0};
    struct sl_mesh_load_stats s;
    struct sl_diag d;
    load_ok(&m, p, &s);
    /* column-major: scale 2, then translate (10, -3, 5) */
    const float X[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 10, -3, 5, 1};
    assert_int_equal(sl_mesh_load_file(&m, p, X, &s, &d), SL_OK);
    /* appended after the first cube, indices offset, not welded across calls */
    assert_int_equal(m.nv, 16);
    assert_int_equal(m.nt, 24);
    for (uint32_t i = 36; i < 72; i++)
        assert_true(m.idx[i] >= 8 && m.idx[i] < 16);
    float lo[3], hi[3];
    mesh_bounds(&m, 8, lo, hi);
    assert_true(lo[0] == 10.0f && lo[1] == -3.0f && lo[2] == 5.0f);
    assert_true(hi[0] == 12.0f && hi[1] == -1.0f && hi[2] == 7.0f);
    mesh_bounds(&m, 0, lo, hi);
    assert_true(lo[0] == 0.0f && hi[0] == 12.0f);
    /* a rotation of 90 degrees about y keeps the winding outward: positive volume */
    const float R[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1};
    struct sl_mesh r = {0};
    assert_int_equal(sl_mesh_load_file(&r, p, R, &s, &d), SL_OK);
    double vol = 0;
    for (uint32_t t = 0; t < r.nt; t++) {
        const float *a = r.pos + 3 * r.idx[3 * t], *b = r.pos + 3 * r.idx[3 * t + 1], *c = r.pos + 3 * r.idx[3 * t + 2];
        vol += (a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) - a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
                a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6.0;
    }
    assert_true(fabs(fabs(vol) - 1.0) < 1e-6);
    sl_mesh_free(&r);
    sl_mesh_free(&m);
}

/* The controls of the binary PLY and glTF bad files: the same bytes with
 * the defect taken out load whole (two triangles, four vertices), so the
 * checks refuse the defect, not the format or the byte order. */
static void meshio_binary_ply_and_gltf_controls(void **st)
{
    (void)st;
    static const char *files[] = {"tests/models/quad_le.ply", "tests/models/quad_be.ply",
                                  "tests/models/quad_index.gltf"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        struct sl_mesh m = {0};
        struct sl_mesh_load_stats s;
        load_ok(&m, files[i], &s);
        assert_int_equal(m.nt, 2);
        assert_int_equal(m.nv, 4);
        assert_int_equal(s.degenerate, 0);
        float lo[3], hi[3];
        mesh_bounds(&m, 0, lo, hi);
        assert_true(lo[0] == 0.0f && lo[1] == 0.0f && lo[2] == 0.0f);
        assert_true(hi[0] == 1.0f && hi[1] == 1.0f && hi[2] == 0.0f);
        sl_mesh_free(&m);
    }
}

/* ------------------------------------------------------------- bad input */

struct bad_case { const char *path; const float *xform; const char *msg; };

/* A reader that blocks (no CPU: the hang the wall deadline is for) and one
 * that works, starved: the first is stopped at the wall deadline, not much
 * later, with the wall-clock message; the second needs 1.5 s of CPU while
 * eight spinning threads share its one core, so it takes longer than the
 * 11 s deadline in wall time, and must not be cut short for it (it is using
 * CPU whenever the deadline looks). */
static enum sl_err blocked_reader(struct sl_mesh *m, const char *path, const float xform[16],
                                  struct sl_mesh_load_stats *s, struct sl_diag *d)
{
    (void)m, (void)path, (void)xform, (void)s, (void)d;
    for (;;)
        pause();
    return SL_OK;   /* never reached */
}

static enum sl_err busy_reader(struct sl_mesh *m, const char *path, const float xform[16],
                               struct sl_mesh_load_stats *s, struct sl_diag *d)
{
    (void)path, (void)xform, (void)s, (void)d;
    struct timespec t0, t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t0);
    do   /* under the CPU limit (3 s) */
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    while ((double)(t.tv_sec - t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - t0.tv_nsec) < 1.5);
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    sl_gen_box(m, lo, hi);
    return SL_OK;
}

static atomic_int spin_stop;

static void *spinner(void *arg)
{
    (void)arg;
    while (!atomic_load_explicit(&spin_stop, memory_order_relaxed))
        ;
    return NULL;
}

static double since(const struct timespec *a)
{
    struct timespec b;
    clock_gettime(CLOCK_MONOTONIC, &b);
    return (double)(b.tv_sec - a->tv_sec) + 1e-9 * (double)(b.tv_nsec - a->tv_nsec);
}

static void meshio_child_deadline_blocked_vs_busy(void **st)
{
    (void)st;
    const char *path = "tests/models/empty.obj";   /* tiny: CPU limit 3 s, deadline 11 s */
    struct sl_mesh m = {0};
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    struct timespec a;
    clock_gettime(CLOCK_MONOTONIC, &a);
    assert_int_equal(sl_mesh_read_in_child(blocked_reader, path, NULL, &m, NULL, &d), SL_E_SCENE);
    double waited = since(&a);
    assert_non_null(strstr(d.msg, "(wall clock)"));
    assert_true(waited >= 10.5 && waited < 22.0);   /* one deadline, no extension: no CPU was used */
    assert_int_equal(m.nt, 0);

    /* one core for this process, its threads and the child it forks */
    cpu_set_t one, was;
    assert_int_equal(sched_getaffinity(0, sizeof was, &was), 0);
    CPU_ZERO(&one);
    CPU_SET(0, &one);
    assert_int_equal(sched_setaffinity(0, sizeof one, &one), 0);
    pthread_t th[8];
    atomic_store(&spin_stop, 0);
    for (int i = 0; i < 8; i++)
        assert_int_equal(pthread_create(&th[i], NULL, spinner, NULL), 0);
    clock_gettime(CLOCK_MONOTONIC, &a);
    memset(&d, 0, sizeof d);
    enum sl_err e = sl_mesh_read_in_child(busy_reader, path, NULL, &m, NULL, &d);
    waited = since(&a);
    atomic_store(&spin_stop, 1);
    for (int i = 0; i < 8; i++)
        pthread_join(th[i], NULL);
    sched_setaffinity(0, sizeof was, &was);
    if (e)
        fprintf(stderr, "busy reader: %s (after %.1f s)\n", d.msg, waited);
    assert_int_equal(e, SL_OK);
    assert_int_equal(m.nt, 12);
    /* it was starved past the deadline: the case tests the extension */
    assert_true(waited > 11.0);
    sl_mesh_free(&m);
}

static void meshio_bad_files_fail_and_leave_mesh(void **st)
{
    (void)st;
    static const float inf_x[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, INFINITY};
    static const float huge_x[16] = {1e38f, 0, 0, 0, 0, 1e38f, 0, 0, 0, 0, 1e38f, 0, 0, 0, 0, 1};
    const struct bad_case cases[] = {
        {"tests/models/empty.obj", NULL, "no triangles"},
        {"tests/models/lines_only.obj", NULL, "no triangles"},
        {MODELS "/OBJ/testpoints.obj", NULL, "no triangles"},
        {"tests/models/nan_vertex.obj", NULL, "non-finite vertex"},
        {"tests/models/zero_area.obj", NULL, "only zero-area triangles"},
        {"tests/models/truncated_binary.ply", NULL, "truncated file: the header declares 6 'face' elements"},
        {"tests/models/truncated_binary.stl", NULL, "STL"},
        {"tests/models/not_a_model.xyz", NULL, "No suitable reader"},
        {"tests/models/does_not_exist.obj", NULL, "cannot open"},
        {"tests/models", NULL, "cannot read"},
        {MODELS "/PLY/cube_binary.ply", inf_x, "non-finite transform"},
        /* finite file and transform whose product overflows float */
        {MODELS "/OBJ/spider.obj", huge_x, "non-finite vertex"},
        /* issue 15: files that crashed, hung or were silently repaired */
        {"tests/bad/models/empty_solid.stl", NULL, "no triangles"},
        /* issue 34: PLY headers no reader can take are refused by the byte
         * check (assimp looped on these until the child was stopped) */
        {"tests/bad/models/header_only.ply", NULL, "corrupt PLY header: the header has no end_header line"},
        {"tests/bad/models/ply25.ply", NULL, "corrupt PLY header: the header has no end_header line"},
        {"tests/bad/models/short_vertices.ply", NULL, "truncated file"},
        {"tests/bad/models/bad_index.off", NULL, "Vertex index is out of range"},
        {"tests/bad/models/bad_vt.obj", NULL, "face names texture coordinate 5 of 1"},
        /* binary PLY, both byte orders: fewer bytes than declared, an index
         * out of range (controls: tests/models/quad_le.ply, quad_be.ply) */
        {"tests/bad/models/short_binary_le.ply", NULL,
         "truncated file: the header declares 40 'vertex' elements (12 bytes each), the file holds 6"},
        {"tests/bad/models/short_binary_be.ply", NULL,
         "truncated file: the header declares 5 'face' elements, the data ends in element 2"},
        {"tests/bad/models/bad_index_le.ply", NULL,
         "corrupt file: face 1 names vertex 7, the header declares 4 vertices"},
        {"tests/bad/models/bad_index_be.ply", NULL,
         "corrupt file: face 1 names vertex -1, the header declares 4 vertices"},
        /* glTF indices beyond the POSITION accessor: assimp drops those
         * faces with a warning (control: tests/models/quad_index.gltf) */
        {"tests/bad/models/bad_index.gltf", NULL, "face index out of range in mesh 'quad'"},
        {"tests/bad/models/bad_index_all.gltf", NULL, "face index out of range"},
        /* found by fuzz_mesh_ply: assimp's PLY reader crashes on it (alone,
         * outside shadowlab too); the byte check refuses its format line
         * first (issue 34; meshio::child_crash_is_an_error keeps the
         * child's crash path tested) */
        {"tests/bad/models/fuzz_crash_format.ply", NULL,
         "corrupt PLY header: format 'binary_littla_endian' is none of ascii"},
        /* found by the in-process mesh entries (issue 34), each refused by
         * a byte check of its class before assimp reads it: a binary PLY
         * header with a property before any element (assimp read past the
         * end), an ASCII one whose end_header is not a token and one whose
         * magic is "plyy" with no end_header (assimp looped, 25 s and
         * more), a glTF skin without inverseBindMatrices (assimp read
         * through a NULL pointer) */
        {"tests/bad/models/fuzz_crash_noelem.ply", NULL,
         "corrupt PLY header: line 3: a property before any element"},
        {"tests/bad/models/fuzz_loop_end_header.ply", NULL,
         "corrupt PLY header: the header has no end_header line"},
        {"tests/bad/models/fuzz_loop_plyy.ply", NULL, "corrupt PLY header: a NUL byte in the header (at byte 197)"},
        {"tests/bad/models/fuzz_crash_skin.gltf", NULL, "skin 0 (line 28) has no inverseBindMatrices"},
        /* a second format line naming no format, no end_header token */
        {"tests/bad/models/fuzz_crash_format2.ply", NULL, "corrupt PLY header: format '' is none of ascii"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct sl_mesh m = {0};
        const float lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
        sl_gen_box(&m, lo, hi);
        uint32_t nv = m.nv, nt = m.nt;
        float pos[24];
        uint32_t idx[36];
        memcpy(pos, m.pos, sizeof pos);
        memcpy(idx, m.idx, sizeof idx);
        struct sl_mesh_load_stats s;
        memset(&s, 0xab, sizeof s);
        struct sl_diag d;
        memset(&d, 0, sizeof d);
        enum sl_err e = sl_mesh_load_file(&m, cases[i].path, cases[i].xform, &s, &d);
        if (e != SL_E_SCENE || !strstr(d.msg, cases[i].msg))
            fprintf(stderr, "case %s: err %d msg '%s'\n", cases[i].path, e, d.msg);
        assert_int_equal(e, SL_E_SCENE);
        assert_non_null(strstr(d.msg, cases[i].msg));
        assert_string_equal(d.file, cases[i].path);
        assert_int_equal(m.nv, nv);
        assert_int_equal(m.nt, nt);
        assert_memory_equal(m.pos, pos, sizeof pos);
        assert_memory_equal(m.idx, idx, sizeof idx);
        assert_int_equal(s.triangles, 0xabababab);   /* stats untouched */
        sl_mesh_free(&m);
    }
}

static enum sl_err crash_reader(struct sl_mesh *m, const char *path, const float xform[16],
                                struct sl_mesh_load_stats *s, struct sl_diag *d)
{
    (void)m, (void)path, (void)xform, (void)s, (void)d;
    raise(SIGSEGV);
    return SL_OK;   /* never reached */
}

/* A reader that crashes ends its child by the signal: an error naming it,
 * the parent unharmed, the mesh untouched. */
static void meshio_child_crash_is_an_error(void **st)
{
    (void)st;
    struct sl_mesh m = {0};
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    assert_int_equal(sl_mesh_read_in_child(crash_reader, "tests/models/empty.obj", NULL, &m, NULL, &d), SL_E_SCENE);
    assert_non_null(strstr(d.msg, "the reader crashed (signal 11, SIGSEGV"));
    assert_int_equal(m.nt, 0);
}

/* The fuzz entries' in-process reader (sl_mesh_load_file_here) reads what
 * the child reads, and refuses what it refuses, with the same message. */
static void meshio_in_process_reader_matches_child(void **st)
{
    (void)st;
    static const char *const files[] = {"tests/models/quad_le.ply", "tests/models/quad_index.gltf",
                                        "tests/bad/models/bad_vt.obj", "tests/bad/models/ply25.ply"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        struct sl_mesh a = {0}, b = {0};
        struct sl_mesh_load_stats sa, sb;
        struct sl_diag da, db;
        memset(&da, 0, sizeof da);
        memset(&db, 0, sizeof db);
        enum sl_err ea = sl_mesh_load_file(&a, files[i], NULL, &sa, &da);
        enum sl_err eb = sl_mesh_load_file_here(&b, files[i], NULL, &sb, &db);
        assert_int_equal(ea, eb);
        assert_int_equal(a.nt, b.nt);
        assert_int_equal(a.nv, b.nv);
        if (a.nv)
            assert_memory_equal(a.pos, b.pos, (size_t)a.nv * 3 * sizeof(float));
        if (ea)
            assert_string_equal(da.msg, db.msg);
        sl_mesh_free(&a);
        sl_mesh_free(&b);
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(meshio, weld_two_quads),
        SL_CASE(meshio, weld_drops_degenerate_keeps_order),
        SL_CASE(meshio, spider_obj),
        SL_CASE(meshio, engine_glb_node_transforms),
        SL_CASE(meshio, stl_and_ply),
        SL_CASE(meshio, xform_and_append),
        SL_CASE(meshio, bad_files_fail_and_leave_mesh),
        SL_CASE(meshio, child_deadline_blocked_vs_busy),
        SL_CASE(meshio, binary_ply_and_gltf_controls),
        SL_CASE(meshio, child_crash_is_an_error),
        SL_CASE(meshio, in_process_reader_matches_child),
    };
    return sl_run_group(argc, argv, "meshio", tests, NULL, NULL);
}
