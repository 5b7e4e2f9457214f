/*
 * motion::* — paths in scene files (pathfile.h), flicker between frames
 * (temporal.h) on constructed frames, and over real paths through the run:
 * a still path flickers nowhere, exact methods flicker nowhere on any path,
 * NSM does flicker on an orbit (so the zero above can fail).
 */
#define _XOPEN_SOURCE 700
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "config.h"
#include "fixture.h"
#include "lightfit.h"
#include "pathfile.h"
#include "shadowmap.h"
#include "run.h"
#include "scenefile.h"
#include "temporal.h"

/* ---- paths in scene files ---- */

static void motion_paths_expand(void **st)
{
    (void)st;
    struct sl_scene s;
    struct sl_diag d;
    assert_int_equal(sl_scene_build("primitives_motion", &s, &d), SL_OK);
    assert_int_equal(s.nvp, 1);
    assert_int_equal(s.npaths, 2);
    assert_int_equal(s.nframes, 120);
    assert_int_equal(sl_scene_find_viewpoint(&s, "orbit.000"), 1);
    assert_int_equal(sl_scene_find_viewpoint(&s, "sun.059"), 120);
    assert_int_equal(sl_scene_find_viewpoint(&s, "sun.060"), -1);
    assert_int_equal(sl_scene_find_path(&s, "sun"), 1);
    const struct sl_viewpoint *o0 = &s.vp[1], *o15 = &s.vp[16], *s0 = &s.vp[61], *s59 = &s.vp[120];
    /* orbit frame 0 at center + (0, 45, 60), frame 15 at 90 degrees: center + (60, 45, 0);
     * positions are relative to the scene's origin (the centre of its bounds) */
    float c[3] = {(float)(-1.0 - s.origin[0]), (float)(0.0 - s.origin[1]), (float)(-5.0 - s.origin[2])};
    assert_float_equal(o0->pos[0], c[0], 1e-3);
    assert_float_equal(o0->pos[1], c[1] + 45.0f, 1e-3);
    assert_float_equal(o0->pos[2], c[2] + 60.0f, 1e-3);
    assert_float_equal(o15->pos[0], c[0] + 60.0f * (float)sin(90.0 * M_PI / 180.0), 1e-3);
    assert_float_equal(o15->pos[2], c[2] + 60.0f * (float)cos(90.0 * M_PI / 180.0), 1e-3);
    for (int k = 0; k < 3; k++)   /* looking at the center */
        assert_float_equal(o15->dir[k], (c[k] - o15->pos[k]) / 75.0f, 1e-4);   /* |(60, 45, 0)| = 75 */
    assert_int_equal(o0->path, 0);
    assert_int_equal(o15->frame, 15);
    assert_false(o0->has_light);
    /* the sun: the side viewpoint held, the light from (25, 20) to (65, 80) degrees */
    assert_int_equal(memcmp(s0->pos, s.vp[0].pos, sizeof s0->pos), 0);
    assert_int_equal(memcmp(s59->dir, s.vp[0].dir, sizeof s0->dir), 0);
    assert_true(s0->has_light && s59->has_light);
    float want[3];
    sl_path_sun(25.0f, 20.0f, want);
    for (int k = 0; k < 3; k++)
        assert_float_equal(s0->light_dir[k], want[k], 1e-6);
    sl_path_sun(65.0f, 80.0f, want);
    for (int k = 0; k < 3; k++)
        assert_float_equal(s59->light_dir[k], want[k], 1e-6);
    assert_float_equal(want[1], -sinf(65.0f * (float)M_PI / 180.0f), 1e-6);   /* the light travels down */
    /* a frame's light replaces the scene's, a named viewpoint puts it back */
    sl_scene_use_view_light(&s, 120);
    assert_int_equal(memcmp(s.light_dir, s59->light_dir, sizeof want), 0);
    sl_scene_use_view_light(&s, 0);
    assert_int_equal(memcmp(s.light_dir, s.base_light_dir, sizeof want), 0);
    sl_scene_free(&s);
}

static void motion_config_paths(void **st)
{
    (void)st;
    struct sl_config c;
    sl_test_config("paths.yaml",
                   "scenes: [{scene: primitives_motion, viewpoints: [side], paths: [sun]}]\n"
                   "map_sizes: [512]\nmethods: [{method: nsm}]\n", &c);
    assert_int_equal(c.scenes[0].nviewpoints, 61);
    assert_int_equal(c.scenes[0].nnamed, 1);
    assert_string_equal(c.scenes[0].viewpoints[1], "sun.000");
    assert_string_equal(c.scenes[0].viewpoints[60], "sun.059");
    assert_int_equal(sl_plan_count(&c), 61);
    sl_config_free(&c);
}

/* ---- flicker on constructed frames ---- */

#define W 8
#define H 8
/* Frame a sees 64 points on one plane (z = 0), one per pixel centre, through
 * an identity camera (NDC = world x, y); frame b's camera moves the image
 * 2 pixels to the right (x + 0.5 in NDC), so pixel (i, j) of a lands on
 * (i + 2, j) of b, and the two columns i = 6, 7 leave the image. */
static void motion_reprojection_count(void **st)
{
    (void)st;
    static float pos[W * H * 3];
    static uint32_t tri_a[W * H], tri_b[W * H];
    static uint8_t truth_a[W * H], truth_b[W * H], va[W * H], vb[W * H];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            int p = j * W + i;
            pos[3 * p] = ((float)i + 0.5f) / W * 2.0f - 1.0f;
            pos[3 * p + 1] = ((float)j + 0.5f) / H * 2.0f - 1.0f;
            pos[3 * p + 2] = 0.0f;
            tri_a[p] = tri_b[p] = 7;
            truth_a[p] = truth_b[p] = SL_T_LIT;
            va[p] = vb[p] = SL_V_LIT;
        }
    struct sl_temporal_frame a = {.w = W, .h = H, .pos = pos, .tri = tri_a, .truth = truth_a};
    struct sl_temporal_frame b = {.w = W, .h = H, .pos = pos, .tri = tri_b, .truth = truth_b};
    glm_mat4_identity(a.vp);
    glm_mat4_identity(b.vp);
    b.vp[3][0] = 0.5f;   /* translation x + 0.5 NDC = 2 pixels */
    uint64_t compared = 0;
    assert_int_equal(sl_temporal_flicker(&a, va, &b, vb, 0, &compared), 0);
    assert_int_equal(compared, 6 * H);   /* columns 0..5 land inside */
    /* the known set: 5 pixels of b that a's pixels land on change verdict */
    const int changed[5][2] = {{2, 0}, {3, 3}, {7, 7}, {5, 1}, {4, 6}};
    for (int k = 0; k < 5; k++)
        vb[changed[k][1] * W + changed[k][0]] = SL_V_SHADOW;
    /* ones nobody lands on (columns 0, 1 of b) do not count */
    vb[0 * W + 0] = SL_V_SHADOW;
    vb[5 * W + 1] = SL_V_UNCERTAIN;
    assert_int_equal(sl_temporal_flicker(&a, va, &b, vb, 0, &compared), 5);
    /* a changed pixel on another triangle, or whose truth changed, is not compared */
    tri_b[3 * W + 3] = 8;
    truth_b[7 * W + 7] = SL_T_SHADOW;
    assert_int_equal(sl_temporal_flicker(&a, va, &b, vb, 0, &compared), 3);
    assert_int_equal(compared, 6 * H - 2);
    /* background pixels of a are never compared */
    tri_a[0 * W + 0] = 0;   /* lands on (2, 0), a changed one */
    assert_int_equal(sl_temporal_flicker(&a, va, &b, vb, 0, &compared), 2);
    /* the same camera: pixel for pixel, whatever the matrices say */
    tri_a[0] = 7;
    /* (2,0) (5,1) (4,6) and (0,0), which nobody landed on; (1,5) is undecided
     * in b, which shows its truth (lit) as a's lit verdict did: no flicker */
    assert_int_equal(sl_temporal_flicker(&a, va, &b, vb, 1, &compared), 4);
    /* undecided against a decided verdict the truth disagrees with: flicker */
    va[5 * W + 1] = SL_V_SHADOW;
    assert_int_equal(sl_temporal_flicker(&a, va, &b, vb, 1, &compared), 5);
    assert_int_equal(compared, W * H - 2);
}

/* The state across views: consecutive frames compare, a gap or another
 * view forgets the previous frame. */
static void motion_state_frames(void **st)
{
    (void)st;
    static float pos[W * H * 3], nrm[W * H * 3];
    static uint32_t tri[W * H];
    static uint8_t cls[W * H], truth[W * H], v0[W * H], v1[W * H];
    for (int p = 0; p < W * H; p++) {
        tri[p] = 1;
        cls[p] = SL_C_PFL;
        truth[p] = SL_T_LIT;
        v0[p] = v1[p] = SL_V_LIT;
    }
    v1[9] = v1[10] = v1[33] = SL_V_SHADOW;
    struct sl_view view = {.w = W, .h = H, .pos = pos, .nrm = nrm, .tri = tri, .cls = cls, .truth = truth};
    glm_mat4_identity(view.view);
    glm_mat4_identity(view.proj);
    struct sl_viewpoint vp = {.path = 0, .frame = 0};
    struct sl_temporal t;
    memset(&t, 0, sizeof t);
    struct sl_diag d;
    int measured;
    uint64_t fl, cmp;
    assert_int_equal(sl_temporal_view(&t, 0, 0, &vp, &view, &d), SL_OK);
    assert_int_equal(sl_temporal_cell(&t, 1, 2, v0, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 0);   /* the path's first frame */
    vp.frame = 1;
    assert_int_equal(sl_temporal_view(&t, 0, 0, &vp, &view, &d), SL_OK);
    assert_int_equal(sl_temporal_cell(&t, 1, 2, v1, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 1);
    assert_int_equal(fl, 3);
    assert_int_equal(cmp, W * H);
    assert_int_equal(sl_temporal_cell(&t, 0, 2, v1, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 0);   /* another map size: frame 0 had none */
    vp.frame = 3;                    /* a gap: frame 2 not run */
    assert_int_equal(sl_temporal_view(&t, 0, 0, &vp, &view, &d), SL_OK);
    assert_int_equal(sl_temporal_cell(&t, 1, 2, v1, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 0);
    vp.frame = 4;
    assert_int_equal(sl_temporal_view(&t, 0, 0, &vp, &view, &d), SL_OK);
    assert_int_equal(sl_temporal_cell(&t, 1, 2, v1, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 1);
    assert_int_equal(fl, 0);
    struct sl_viewpoint named = {.path = -1};   /* a named viewpoint between: forgets */
    assert_int_equal(sl_temporal_view(&t, 0, 0, &named, &view, &d), SL_OK);
    assert_int_equal(sl_temporal_cell(&t, 1, 2, v1, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 0);
    vp.frame = 5;
    assert_int_equal(sl_temporal_view(&t, 0, 0, &vp, &view, &d), SL_OK);
    assert_int_equal(sl_temporal_cell(&t, 1, 2, v1, &measured, &fl, &cmp, NULL, &d), SL_OK);
    assert_int_equal(measured, 0);
    sl_temporal_free(&t);
}

/* ---- over real paths, through the run ---- */

static const char *motion_scene =
    "name: motion_small\nbase: primitives\n"
    "viewpoints:\n  - {name: side, position: [35, 50, -43], direction: [-1, -1.2, 1], fov: 60, near: 20, far: 250}\n"
    "paths:\n"
    "  - name: still\n    frames: 4\n    camera:\n      keyframes:\n"
    "        - {position: [30, 40, -40], direction: [-1, -1.1, 1]}\n"
    "        - {position: [30, 40, -40], direction: [-1, -1.1, 1]}\n"
    "      near: 20\n      far: 250\n"
    "  - name: orbit\n    frames: 6\n    camera:\n"
    "      orbit: {center: [-1, 0, -5], radius: 60, height: 45, degrees: [0, 10]}\n"
    "      near: 20\n      far: 250\n"
    "  - name: sun\n    frames: 5\n    camera: {viewpoint: side}\n"
    "    light: {elevation: [25, 29], azimuth: [30, 34]}\n";

static void run_paths_of(const char *paths, const char *methods, struct sl_run_result *res)
{
    char path[400], text[1600];
    snprintf(path, sizeof path, "%s/motion_small.yaml", sl_test_dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(motion_scene, f);
    fclose(f);
    snprintf(text, sizeof text,
             "scenes: [{scene: motion_small.yaml, paths: [%s]}]\n"
             "viewports: [{width: 128, height: 128}]\nmap_sizes: [256]\nmethods: [%s]\n", paths, methods);
    struct sl_config c;
    sl_test_config("motion.yaml", text, &c);
    struct sl_run_opts o = {.store = "", .cache_dir = ""};
    struct sl_diag d;
    enum sl_err e = sl_run(&c, &o, res, &d);
    if (e)
        fprintf(stderr, "%s:%d '%s': %s\n", d.file, d.line, d.key, d.msg);
    assert_int_equal(e, SL_OK);
    assert_int_equal(res->ncells, sl_plan_count(&c));
    sl_config_free(&c);
}

static void run_paths(const char *methods, struct sl_run_result *res)
{
    run_paths_of("still, orbit, sun", methods, res);
}

/* A still path flickers nowhere, for every method; exact methods flicker
 * nowhere on any path; every frame after a path's first is compared. */
static void motion_run_flicker(void **st)
{
    (void)st;
    struct sl_run_result res;
    run_paths("{label: nsm, method: nsm}, {label: chain, method: chain}, {label: coherence, method: coherence}, "
              "{label: csm, method: csm}, {label: hertel, method: hertel_exact}", &res);
    uint64_t nsm_moving = 0;
    int compared = 0;
    for (int i = 0; i < res.ncells; i++) {
        const struct sl_cell *cl = &res.cells[i];
        const char *label = cl->key.method == 0 ? "nsm" : cl->key.method == 1 ? "chain"
                            : cl->key.method == 2 ? "coherence" : cl->key.method == 3 ? "csm" : "hertel";
        const int first = strstr(cl->viewpoint, ".000") != NULL;
        if (first)
            assert_int_equal(cl->flicker_compared, 0);
        else
            assert_true(cl->flicker_compared > 1000);
        compared += !first;
        if (strncmp(cl->viewpoint, "still.", 6) == 0 || cl->key.method >= 3) {
            if (cl->flicker)
                fprintf(stderr, "%s %s: flicker %llu\n", cl->viewpoint, label, (unsigned long long)cl->flicker);
            assert_int_equal(cl->flicker, 0);
        }
        if (cl->key.method == 0 && strncmp(cl->viewpoint, "still.", 6) != 0)
            nsm_moving += cl->flicker;
    }
    assert_int_equal(compared, 5 * (3 + 5 + 4));
    /* the test can fail: NSM's verdicts do move with the camera and the sun */
    assert_true(nsm_moving > 0);
    sl_run_result_free(&res);
}

/* ---- stabilised frames ---- */

/* Texels of layer b at (i - dx, j - dy) that differ from a at (i, j), over
 * the overlap: by triangle id, or by depth more than tol; *overlap: how many
 * were compared, *maxdiff the largest depth difference where ids agree. */
static uint64_t shifted_mismatch(const struct sl_depth_layer *a, const struct sl_depth_layer *b, int size, int dx,
                                 int dy, double tol, uint64_t *overlap, double *maxdiff)
{
    uint64_t bad = 0, n = 0;
    *maxdiff = 0.0;
    for (int j = 0; j < size; j++)
        for (int i = 0; i < size; i++) {
            int bi = i - dx, bj = j - dy;
            if (bi < 0 || bj < 0 || bi >= size || bj >= size)
                continue;
            size_t ta = (size_t)j * size + i, tb = (size_t)bj * size + bi;
            n++;
            double diff = fabs((double)a->depth[ta] - (double)b->depth[tb]);
            if (a->id[ta] == b->id[tb] && diff > *maxdiff)
                *maxdiff = diff;
            bad += a->id[ta] != b->id[tb] || diff > tol;
        }
    *overlap = n;
    return bad;
}

/* A camera moving across the light (in the light's image plane) by 7.3 and
 * -4.6 texels: the snapped sphere frame moves by whole texels and its NSM
 * depth layer is the same image shifted by them; the unsnapped one moves by
 * the fraction too, and no whole-texel shift matches it. */
/* The shifted image is the same up to the rasterizer's float rounding: it
 * interpolates depth from window coordinates that moved by whole texels, and
 * the barycentrics round differently with them (measured on llvmpipe: depths
 * within 9.2e-7 of window depth on the steep ground plane, 2^-18 = 3.8e-6
 * allowed), and a sample lying on a shared edge within that rounding may go
 * to the other triangle (measured: 1 texel of 126,561 covered; at most 1 in
 * 10,000 allowed). Unsnapped, every edge moves by a fraction of a texel and
 * thousands of texels change triangle under any whole-texel shift. */
#define TOL 0x1p-18

static void motion_snap_shift(void **st)
{
    (void)st;
    struct fixture f;
    assert_true(fixture_open(&f, "primitives", 2));
    struct sl_view v;
    assert_true(fixture_view(&f, 0, 96, 96, &v));
    struct sl_shadowmap_pass sp;
    struct sl_diag d;
    assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
    const int S = 512;
    for (int snap = 1; snap >= 0; snap--) {
        struct sl_fit_opts o = {.fit = SL_FIT_SPHERE, .snap = snap};
        struct sl_light_frame fa, fb;
        memset(&fa, 0, sizeof fa);
        memset(&fb, 0, sizeof fb);
        fa.size = fb.size = S;
        memcpy(fa.dir, f.scene.light_dir, sizeof fa.dir);
        memcpy(fb.dir, f.scene.light_dir, sizeof fb.dir);
        sl_light_fit_stable(&f.scene, &v, &o, S, &fa.box);
        const double texel = (double)(fa.box.hi[0] - fa.box.lo[0]) / S;
        /* the light's image plane: the light view's x and y axes in the world */
        const float saved[3] = {f.scene.vp[0].pos[0], f.scene.vp[0].pos[1], f.scene.vp[0].pos[2]};
        for (int k = 0; k < 3; k++)
            f.scene.vp[0].pos[k] += (float)(7.3 * texel * fa.box.view[k][0] - 4.6 * texel * fa.box.view[k][1]);
        sl_light_fit_stable(&f.scene, &v, &o, S, &fb.box);
        memcpy(f.scene.vp[0].pos, saved, sizeof saved);
        /* same size and depth range; the corner moves by the shift */
        assert_float_equal(fb.box.hi[0] - fb.box.lo[0], fa.box.hi[0] - fa.box.lo[0], 1e-3);
        assert_true(fa.box.lo[2] == fb.box.lo[2] && fa.box.hi[2] == fb.box.hi[2]);
        double sx = (fb.box.lo[0] - fa.box.lo[0]) / texel, sy = (fb.box.lo[1] - fa.box.lo[1]) / texel;
        int dx = (int)lround(sx), dy = (int)lround(sy);
        if (snap) {
            assert_true(fabs(sx - dx) < 1e-3 && fabs(sy - dy) < 1e-3);
            assert_true((dx == 7 || dx == 8) && (dy == -4 || dy == -5));
        } else {
            assert_true(fabs(sx - 7.3) < 1e-2 && fabs(sy + 4.6) < 1e-2);
        }
        const int L = SL_LAYER_DEPTH_ID;   /* both faces: the ground too */
        assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &fa, SL_NEED(L), &d), SL_OK);
        assert_int_equal(sl_shadowmap_render(&sp, &f.mesh, &fb, SL_NEED(L), &d), SL_OK);
        uint64_t overlap = 0, covered = 0;
        for (size_t t = 0; t < (size_t)S * S; t++)
            covered += fa.layer[L].depth[t] < 1.0f;
        uint64_t best = UINT64_MAX;
        for (int ex = -1; ex <= 1; ex++)
            for (int ey = -1; ey <= 1; ey++) {
                double maxdiff;
                uint64_t m = shifted_mismatch(&fa.layer[L], &fb.layer[L], S, dx + ex, dy + ey, TOL, &overlap,
                                              &maxdiff);
                if (ex == 0 && ey == 0)
                    printf("motion::snap_shift snap %d: shift (%d, %d) texels, %llu of %llu texels differ "
                           "(%llu covered), largest depth difference where the triangle agrees %.3g\n", snap, dx,
                           dy, (unsigned long long)m, (unsigned long long)overlap, (unsigned long long)covered,
                           maxdiff);
                best = m < best ? m : best;
            }
        assert_true(covered > (uint64_t)S * S / 4);   /* the map holds geometry to compare */
        if (snap)
            assert_true(best <= covered / 10000);   /* the same image, moved by whole texels */
        else
            assert_true(best > 1000);     /* resampled: edges moved by a fraction of a texel */
        sl_frame_free(&fa);
        sl_frame_free(&fb);
    }
    sl_shadowmap_free(&sp);
    sl_view_free(&v);
    fixture_close(&f);
}

/* On an orbit, a snapped sphere frame flickers less than the same frame
 * unsnapped. */
static void motion_snap_flicker(void **st)
{
    (void)st;
    struct sl_run_result res;
    run_paths("{label: sphere, method: nsm, light_frame: {fit: sphere}}, "
              "{label: snap, method: nsm, light_frame: {fit: sphere, snap: true}}", &res);
    uint64_t fl[2] = {0, 0};
    for (int i = 0; i < res.ncells; i++)
        if (strncmp(res.cells[i].viewpoint, "orbit.", 6) == 0)
            fl[res.cells[i].key.method] += res.cells[i].flicker;
    printf("motion::snap_flicker orbit: unsnapped %llu, snapped %llu\n", (unsigned long long)fl[0],
           (unsigned long long)fl[1]);
    assert_true(fl[1] < fl[0]);
    sl_run_result_free(&res);
}

/* A label's own fixed-size frame is rendered once where the camera holds
 * still (the same box every frame) and again for every frame of an orbit;
 * the shared tight frame is fitted and rendered per view. */
static void motion_frame_shared(void **st)
{
    (void)st;
    const int L = SL_LAYER_DEPTH_ID_BACK;
    struct sl_run_result res;
    run_paths_of("still", "{label: nsm, method: nsm}, {label: snap, method: nsm, light_frame: {fit: sphere, snap: "
                 "true}}", &res);
    assert_int_equal(res.ncells, 8);
    assert_int_equal(res.passes.layers[L], 4 + 1);
    for (int i = 0; i < res.ncells; i++)
        assert_int_equal(res.cells[i].flicker, 0);
    sl_run_result_free(&res);
    run_paths_of("orbit", "{label: nsm, method: nsm}, {label: snap, method: nsm, light_frame: {fit: sphere, snap: "
                 "true}}", &res);
    /* 2 degrees apart at 60 units the camera moves about 2 units a frame,
     * about one texel of a 256² sphere frame (1.85 units): most frames
     * move the snapped frame, one that moves it less than a texel keeps it
     * (seen: 4 renders for the 6 frames) */
    printf("motion::frame_shared orbit: %d renders of the layer\n", res.passes.layers[L]);
    assert_true(res.passes.layers[L] > 6 + 1 && res.passes.layers[L] <= 6 + 6);
    sl_run_result_free(&res);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(motion, paths_expand),
        SL_CASE(motion, config_paths),
        SL_CASE(motion, reprojection_count),
        SL_CASE(motion, state_frames),
        SL_CASE(motion, run_flicker),
        SL_CASE(motion, snap_shift),
        SL_CASE(motion, snap_flicker),
        SL_CASE(motion, frame_shared),
    };
    return sl_run_group(argc, argv, "motion", tests, sl_test_setup, sl_test_teardown);
}
