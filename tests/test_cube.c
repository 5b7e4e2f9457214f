/* cube::* — a point light's cube of shadow maps (harness/render/lightframe.h, methods/cuberun.h, issue 22):
 * every face holding receivers and casters; lookups across a seam equal to
 * those of one wide frustum along the face's axis; every exactness promise
 * kept on the point scenes at two map sizes through the driver. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include <cglm/clipspace/persp_rh_zo.h>
#include "cuberun.h"
#include "fixture.h"
#include "lightfit.h"
#include "method.h"
#include "run.h"
#include "shadowmap.h"
#include "test_params.h"

struct vbuf {
    struct sl_verdicts vd;
    uint8_t *mem;
};

static void vbuf_init(struct vbuf *b, int w, int h)
{
    size_t n = (size_t)w * (size_t)h;
    memset(b, 0, sizeof *b);
    b->mem = calloc(5 * n, 1);
    assert_non_null(b->mem);
    b->vd.w = w;
    b->vd.h = h;
    b->vd.v = b->mem;
    b->vd.how = b->mem + n;
    b->vd.base = b->mem + 2 * n;
    b->vd.detail = b->mem + 3 * n;
    b->vd.tests = b->mem + 4 * n;
}

static void vbuf_free(struct vbuf *b)
{
    sl_verdicts_drop_frames(&b->vd);
    free(b->mem);
}

static void params_of(const char *method, int texels, struct sl_method_params *p)
{
    const struct sl_method *m = sl_method_find(method);
    assert_non_null(m);
    char spec[32] = "";
    if (texels)
        snprintf(spec, sizeof spec, "texels=%d", texels);
    sl_test_params(m, p, spec);   /* nsm: its default, front_faces */
}

/* A point light with receivers and casters on all six faces: each face's
 * fit holds receivers (PFL pixels whose major axis from the light is its
 * axis), casters, and shadowed pixels in truth; every pixel has one face. */
static void cube_six_faces(void **st)
{
    (void)st;
    struct fixture fx;
    assert_true(fixture_open(&fx, "tests/scenes/cube_six.yaml", 2));
    struct sl_view v;
    assert_true(fixture_view(&fx, 0, 320, 240, &v));
    struct sl_shadowmap_pass sp;
    struct sl_diag d;
    assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
    struct sl_cube cb;
    memset(&cb, 0, sizeof cb);
    const unsigned needs = SL_NEED(SL_LAYER_DEPTH_ID);
    int layers[SL_LAYER_COUNT] = {0};
    struct sl_layer_timing t = {.layers = layers};
    assert_int_equal(sl_cube_ensure(&cb, &sp, &fx.mesh, &fx.scene, &v, 0, 256, needs, needs, &t, NULL, &d), SL_OK);
    uint32_t shadowed[6] = {0}, pfl[6] = {0};
    for (size_t i = 0; i < (size_t)v.w * (size_t)v.h; i++) {
        assert_true(cb.face[i] < 6);
        if (v.cls[i] == SL_C_PFL) {
            pfl[cb.face[i]]++;
            shadowed[cb.face[i]] += v.truth[i] == SL_T_SHADOW;
        }
    }
    uint32_t sum = 0;
    for (int f = 0; f < 6; f++) {
        fprintf(stderr, "face %d: %u receivers, %u casters, %u unmapped, %u shadowed\n", f, cb.cost[f].receivers,
                cb.cost[f].casters, cb.cost[f].unmapped, shadowed[f]);
        assert_int_equal(cb.cost[f].receivers, pfl[f]);
        assert_true(cb.cost[f].receivers > 50);
        assert_true(cb.cost[f].casters > 0);
        assert_true(shadowed[f] > 10);
        assert_int_equal(cb.f[f].size, 256);
        assert_true(cb.f[f].have & needs);
        sum += cb.cost[f].receivers;
    }
    assert_int_equal(sum, v.n_pfl);
    assert_int_equal(layers[SL_LAYER_DEPTH_ID], 6);   /* one render per face */
    sl_cube_drop(&cb);
    sl_shadowmap_free(&sp);
    sl_view_free(&v);
    fixture_close(&fx);
}

/* The room (scenes/room.yaml) from its two corners: between them every
 * face of the light's cube holds receivers, casters and shadowed pixels. */
static void cube_room_faces(void **st)
{
    (void)st;
    struct fixture fx;
    assert_true(fixture_open(&fx, "room", 2));
    uint32_t shadowed[6] = {0}, receivers[6] = {0}, casters[6] = {0};
    for (int vp = 0; vp < 2; vp++) {
        struct sl_view v;
        assert_true(fixture_view(&fx, vp, 256, 256, &v));
        uint8_t *face = malloc((size_t)v.w * (size_t)v.h);
        assert_non_null(face);
        for (size_t i = 0; i < (size_t)v.w * (size_t)v.h; i++) {
            face[i] = (uint8_t)sl_cube_face_of(fx.scene.light.pos, v.pos + 3 * i);
            shadowed[face[i]] += v.cls[i] == SL_C_PFL && v.truth[i] == SL_T_SHADOW;
        }
        for (int f = 0; f < 6; f++) {
            struct sl_light_box b;
            float axis[3];
            sl_cube_axis(f, axis);
            sl_light_fit_face(&fx.scene, &v, fx.scene.light.pos, axis, face, (uint8_t)f, 512, SL_CUBE_GUARD, &b);
            receivers[f] += b.n_receivers;
            casters[f] += b.n_receivers ? b.n_casters : 0;
            sl_light_box_free(&b);
        }
        free(face);
        sl_view_free(&v);
    }
    for (int f = 0; f < 6; f++) {
        fprintf(stderr, "room face %d: %u receivers, %u casters, %u shadowed\n", f, receivers[f], casters[f],
                shadowed[f]);
        assert_true(receivers[f] > 0 && casters[f] > 0 && shadowed[f] > 0);
    }
    fixture_close(&fx);
}

/* Face f's frame widened by k texels on every side at the same texel size:
 * the texel (i, j) of the face is the texel (i + k, j + k) of the wide one,
 * whose frustum reaches k texels into the neighbouring faces. */
static void wide_of(const struct sl_light_frame *f, int k, struct sl_light_frame *w)
{
    memset(w, 0, sizeof *w);
    w->size = f->size + 2 * k;
    memcpy(w->dir, f->dir, sizeof w->dir);
    w->box = f->box;
    for (int a = 0; a < 2; a++) {
        double t = ((double)f->box.hi[a] - f->box.lo[a]) / f->size;
        w->box.lo[a] = (float)(f->box.lo[a] - k * t);
        w->box.hi[a] = (float)(f->box.hi[a] + k * t);
    }
    float n = w->box.lo[2], fa = w->box.hi[2];
    glm_frustum_rh_zo(w->box.lo[0] * n, w->box.hi[0] * n, w->box.lo[1] * n, w->box.hi[1] * n, n, fa, w->box.proj);
    glm_mat4_mul(w->box.proj, w->box.view, w->box.vp);
    w->texel_world = fmaxf(w->box.hi[0] - w->box.lo[0], w->box.hi[1] - w->box.lo[1]) / (float)w->size;
    w->depth_range = fa - n;
}

/* Cube seams: shadow edges that cross the floor's seams between the -y face
 * and the +x and +z faces. For NSM, texel, neighbours (4 and 9), coherence
 * (9), BGSM, SGSM and CSMa (plain and conservative layers), the
 * cube's verdict of every pixel equals that of one frustum along its face's
 * axis reaching 64 texels beyond the face on every side (same texel grid):
 * a lookup across the face's edge reads the neighbouring geometry, as the
 * wide frustum does, not a border. The seam must be exercised: pixels whose
 * texel lies within the guard band's reach of the face's edge, both lit and
 * shadowed in truth, on the -y face and on a side face. */
static void cube_seams(void **st)
{
    (void)st;
    struct fixture fx;
    assert_true(fixture_open(&fx, "tests/scenes/cube_seam.yaml", 2));
    struct sl_view v;
    assert_true(fixture_view(&fx, 0, 384, 384, &v));
    struct sl_view mv = v;
    mv.truth = NULL;
    const size_t n = (size_t)v.w * (size_t)v.h;
    struct sl_shadowmap_pass sp;
    struct sl_diag d;
    assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
    const char *methods[] = {"nsm", "texel", "neighbours", "neighbours", "coherence", "bgsm", "sgsm", "csm"};
    const int texels[] = {0, 0, 4, 9, 9, 0, 0, 0};
    enum { NM = sizeof methods / sizeof methods[0] };
    const int sizes[] = {256, 1024};
    uint8_t *cls = malloc(n);
    assert_non_null(cls);
    for (int si = 0; si < 2; si++) {
        const int size = sizes[si];
        struct sl_cube cb;
        memset(&cb, 0, sizeof cb);
        unsigned needs = 0;
        struct sl_method_params p[NM];
        for (int k = 0; k < NM; k++) {
            params_of(methods[k], texels[k], &p[k]);
            needs |= sl_method_find(methods[k])->needs(&p[k]);
        }
        struct sl_layer_timing t = {0};
        assert_int_equal(sl_cube_ensure(&cb, &sp, &fx.mesh, &fx.scene, &v, 0, size, needs, needs, &t, NULL, &d),
                         SL_OK);
        /* the seam exercised: edge pixels (texel within 2 of the band) lit and shadowed, per face */
        int edge_lit[6] = {0}, edge_shadow[6] = {0};
        for (size_t i = 0; i < n; i++) {
            if (v.cls[i] != SL_C_PFL)
                continue;
            const struct sl_light_frame *F = &cb.f[cb.face[i]];
            float u, w, z;
            sl_frame_project(F, v.pos + 3 * i, &u, &w, &z);
            const float lo = SL_CUBE_GUARD, hi = (float)(F->size - SL_CUBE_GUARD);
            if (u < lo + 2 || w < lo + 2 || u > hi - 2 || w > hi - 2) {
                edge_lit[cb.face[i]] += v.truth[i] == SL_T_LIT;
                edge_shadow[cb.face[i]] += v.truth[i] == SL_T_SHADOW;
            }
        }
        const int faces[] = {3, 0, 4};   /* -y, +x, +z */
        for (int q = 0; q < 3; q++) {
            fprintf(stderr, "map %d face %d: %d edge pixels lit, %d shadowed\n", size, faces[q],
                    edge_lit[faces[q]], edge_shadow[faces[q]]);
            assert_true(edge_lit[faces[q]] > 0 && edge_shadow[faces[q]] > 0);
        }
        for (int k = 0; k < NM; k++) {
            const struct sl_method *m = sl_method_find(methods[k]);
            struct vbuf cube, wide;
            vbuf_init(&cube, v.w, v.h);
            vbuf_init(&wide, v.w, v.h);
            struct sl_method_args a = {.scene = &fx.scene, .view = &mv, .frame = &cb.f[0], .params = &p[k],
                                       .rt = &fx.rt, .threads = 2};
            struct sl_cost c = {0};
            assert_int_equal(sl_cube_method_run(&cb, m, &a, &cube.vd, &c, &d), SL_OK);
            assert_int_equal(cube.vd.nframes, 6);
            int compared = 0, differ = 0, boundary = 0;
            for (int q = 0; q < 3; q++) {
                const int f = faces[q];
                struct sl_light_frame W;
                wide_of(&cb.f[f], 64, &W);
                assert_int_equal(sl_shadowmap_render(&sp, &fx.mesh, &W, needs, &d), SL_OK);
                struct sl_view fv = mv;
                for (size_t i = 0; i < n; i++)
                    cls[i] = cb.face[i] == f ? v.cls[i] : (uint8_t)SL_C_BACKGROUND;
                fv.cls = cls;
                struct sl_method_args wa = a;
                wa.view = &fv;
                wa.frame = &W;
                struct sl_cost wc = {0};
                assert_int_equal(m->run(&wa, &wide.vd, &wc, &d), SL_OK);
                for (size_t i = 0; i < n; i++) {
                    if (cls[i] != SL_C_PFL)
                        continue;
                    /* the two frames' matrices round differently (~1e-5 texel): a pixel
                     * within 1e-4 texel of a texel boundary may fall either side in
                     * either frame; it is counted apart, not compared */
                    float u, w, z;
                    sl_frame_project(&cb.f[f], v.pos + 3 * i, &u, &w, &z);
                    if (fabsf(u - roundf(u)) < 1e-4f || fabsf(w - roundf(w)) < 1e-4f) {
                        boundary++;
                        continue;
                    }
                    compared++;
                    differ += cube.vd.v[i] != wide.vd.v[i];
                }
                sl_frame_free(&W);
            }
            fprintf(stderr, "map %d %s%d: %d pixels compared, %d differ, %d on a texel boundary\n", size, methods[k],
                    texels[k], compared, differ, boundary);
            assert_true(compared > 1000 && boundary < compared / 500);
            assert_int_equal(differ, 0);
            vbuf_free(&cube);
            vbuf_free(&wide);
        }
        sl_cube_drop(&cb);
    }
    free(cls);
    sl_shadowmap_free(&sp);
    sl_view_free(&v);
    fixture_close(&fx);
}

/* Every hard label on the point scenes (the room, the grazing light, the
 * six faces, the seams) at two map sizes through the driver: no exactness
 * violation, no value out of range, and the six faces' maps counted. */
static void cube_exact_point_scenes(void **st)
{
    (void)st;
    struct sl_config c;
    char cwd[512], text[4096];
    assert_non_null(getcwd(cwd, sizeof cwd));
    snprintf(text, sizeof text,
                   "name: points\n"
                   "scenes:\n"
                   "  - {scene: room}\n"
                   "  - {scene: grazing}\n"
                   "  - {scene: %s/tests/scenes/cube_six.yaml}\n"
                   "  - {scene: %s/tests/scenes/cube_seam.yaml}\n"
                   "viewports: [{width: 160, height: 120}]\n"
                   "map_sizes: [128, 512]\n"
                   "contours: [2]\n"
                   "methods:\n"
                   "  - {label: nsm, method: nsm, self_shadow: front_faces}\n"
                   "  - {label: coherence4, method: coherence, texels: 4}\n"
                   "  - {label: coherence9, method: coherence, texels: 9}\n"
                   "  - {label: texel, method: texel}\n"
                   "  - {label: neighbours4, method: neighbours, texels: 4}\n"
                   "  - {label: neighbours9, method: neighbours, texels: 9}\n"
                   "  - {label: adjacency1, method: adjacency, level: 1}\n"
                   "  - {label: adjacency2, method: adjacency, level: 2}\n"
                   "  - {label: chain, method: chain, finish: trace}\n"
                   "  - {label: bgsm, method: bgsm}\n"
                   "  - {label: sgsm, method: sgsm}\n"
                   "  - {label: sgsm_adj, method: sgsm_adj}\n"
                   "  - {label: csm, method: csm}\n"
                   "  - {label: csm_adj, method: csm_adj}\n"
                   "  - {label: hertel, method: hertel}\n"
                   "  - {label: hertel_exact, method: hertel_exact}\n"
                   "  - {label: raytrace, method: raytrace}\n"
                   "outputs: {tables: false, overlays: false}\n",
                   cwd, cwd);
    sl_test_config("points.yaml", text, &c);
    struct sl_run_opts o = {.write_files = 0, .store = "", .cache_dir = ""};
    struct sl_run_result r;
    struct sl_diag d;
    assert_int_equal(sl_run(&c, &o, &r, &d), SL_OK);
    const int views = 2 + 2 + 1 + 1;
    assert_int_equal(r.ncells, views * 2 * 17);
    uint64_t lit_claims = 0, shadow_claims = 0;
    for (int i = 0; i < r.ncells; i++) {
        const struct sl_cell *cl = &r.cells[i];
        if (cl->violations)
            fprintf(stderr, "%s/%s map %d %s: %llu violations\n", cl->scene, cl->viewpoint, c.maps[cl->key.map],
                    c.methods[cl->key.method].label, (unsigned long long)cl->violations);
        assert_int_equal(cl->violations, 0);
        assert_int_equal(cl->nonfinite, 0);
        assert_true(cl->n_pfl > 0);
        const char *label = c.methods[cl->key.method].label;
        if (strcmp(label, "bgsm") == 0)
            lit_claims += cl->fig.r[cl->fig.nregions - 1].n[SL_FIG_light];
        if (strcmp(label, "sgsm") == 0)
            shadow_claims += cl->fig.r[cl->fig.nregions - 1].n[SL_FIG_shadow];
    }
    /* the promises were put to the test: bgsm claimed light, sgsm shadow */
    assert_true(lit_claims > 1000 && shadow_claims > 1000);
    sl_run_result_free(&r);
    sl_config_free(&c);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(cube, six_faces),
        SL_CASE(cube, room_faces),
        SL_CASE(cube, seams),
        SL_CASE(cube, exact_point_scenes),
    };
    return sl_run_group(argc, argv, "cube", tests, sl_test_setup, sl_test_teardown);
}
