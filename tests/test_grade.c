/*
 * grade::* (unit) — registration of an external image against a view
 * (methods/external.h) on hand-made 64 x 64 views, and the depth
 * conventions (harness/run/grade.h) against cglm's own projections.
 * The view: a disc of radius 12 centred at (40, 36) on background, its
 * positions at eye-space depth 10 (identity view matrix: z = -10).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include <cglm/cglm.h>
#include <cglm/clipspace/persp_rh_zo.h>   /* Vulkan / D3D depth: not in cglm.h by default */
#include "external.h"
#include "grade.h"
#include "sl_test.h"

#define W 64
#define H 64

struct rig {
    struct sl_view v;
    uint32_t tri[W * H];
    float pos[3 * W * H];
    uint8_t bg[W * H];
    float depth[W * H];
    struct sl_external e;
    struct sl_external_report r;
};

static int in_disc(double x, double y, double cx, double cy, double rad)
{
    return (x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= rad * rad;
}

static void rig_init(struct rig *g)
{
    memset(g, 0, sizeof *g);
    g->v.w = W;
    g->v.h = H;
    glm_mat4_identity(g->v.view);
    g->v.tri = g->tri;
    g->v.pos = g->pos;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            g->tri[i] = in_disc(x, y, 40, 36, 12) ? 1 : 0;
            g->pos[3 * i + 0] = (float)x, g->pos[3 * i + 1] = (float)y, g->pos[3 * i + 2] = -10.0f;
        }
    g->e = (struct sl_external){.w = W, .h = H, .bg = g->bg, .has_bg = 1, .threshold = 0.5, .tolerance = 0.01,
                                .depth_tolerance = 0.01, .image = "img"};
}

/* the image's background: the view's disc moved by (dx, dy), flipped in y,
 * or grown to radius rad */
static void image_disc(struct rig *g, double dx, double dy, int flip_y, double rad)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int yy = flip_y ? H - 1 - y : y;
            g->bg[y * W + x] = !in_disc(x - dx, yy - dy, 40, 36, rad);
        }
}

static void grade_registered(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    image_disc(g, 0, 0, 0, 12);
    struct sl_diag d;
    assert_int_equal(sl_external_register(&g->e, &g->v, &g->r, &d), SL_OK);
    assert_int_equal(g->r.checked, 1);
    assert_int_equal(g->r.misregistered, 0);
    assert_int_equal(g->r.pixels, W * H);
    free(g);
}

static void expect_cause(struct rig *g, const char *cause)
{
    struct sl_diag d;
    memset(&d, 0, sizeof d);
    assert_int_equal(sl_external_register(&g->e, &g->v, &g->r, &d), SL_E_USAGE);
    assert_true(g->r.misregistered > 0);
    if (strncmp(g->r.cause, cause, strlen(cause)) != 0)
        fail_msg("cause '%s', want '%s...'", g->r.cause, cause);
    assert_non_null(strstr(d.msg, "likely cause: "));
    assert_non_null(strstr(d.msg, " % of the pixels ("));
}

static void grade_flipped(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    image_disc(g, 0, 0, 1, 12);
    expect_cause(g, "y flipped");
    assert_true(g->r.share > 0.05);
    free(g);
}

/* one pixel right: a sliver along two silhouettes, under the 1 %
 * tolerance, refused because moving it back explains it */
static void grade_shifted(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    image_disc(g, 1, 0, 0, 12);
    expect_cause(g, "off by one pixel: the image is shifted one pixel right");
    image_disc(g, 0, -1, 0, 12);
    expect_cause(g, "off by one pixel: the image is shifted one pixel down");
    free(g);
}

static void grade_field_of_view(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    image_disc(g, 0, 0, 0, 16);   /* 1.8x the area: a wider disc, another fov */
    expect_cause(g, "another field of view");
    free(g);
}

/* half a pixel wider all round: only silhouette pixels differ, no shift
 * explains it; refused under a tolerance below the ring's share */
static void grade_jitter(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    image_disc(g, 0, 0, 0, 12.7);
    g->e.tolerance = 0.001;
    expect_cause(g, "sub-pixel offset");
    /* the same ring under the default tolerance is graded */
    g->e.tolerance = 0.05;
    struct sl_diag d;
    assert_int_equal(sl_external_register(&g->e, &g->v, &g->r, &d), SL_OK);
    assert_true(g->r.misregistered > 0);
    free(g);
}

/* neither side has background: nothing is checked */
static void grade_unchecked(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    for (int i = 0; i < W * H; i++)
        g->tri[i] = 1;
    struct sl_diag d;
    assert_int_equal(sl_external_register(&g->e, &g->v, &g->r, &d), SL_OK);
    assert_int_equal(g->r.checked, 0);
    /* but background registration of an image whose alpha says "all
     * surface" against a view with background is checked, and refused */
    rig_init(g);
    g->e.tolerance = 0.01;
    assert_int_equal(sl_external_register(&g->e, &g->v, &g->r, &d), SL_E_USAGE);
    assert_int_equal(g->r.checked, 1);
    free(g);
}

static void grade_depth(void **st)
{
    (void)st;
    struct rig *g = malloc(sizeof *g);
    rig_init(g);
    g->e.depth = g->depth;
    for (int i = 0; i < W * H; i++)
        g->depth[i] = g->tri[i] ? 10.0f : NAN;
    struct sl_diag d;
    assert_int_equal(sl_external_register(&g->e, &g->v, &g->r, &d), SL_OK);
    assert_int_equal(g->r.by_depth, 1);
    assert_int_equal(g->r.misregistered, 0);
    /* 5 % deeper everywhere: the depths disagree, the silhouettes do not */
    for (int i = 0; i < W * H; i++)
        g->depth[i] = g->tri[i] ? 10.5f : NAN;
    expect_cause(g, "another camera, viewpoint or scene, or another depth convention");
    uint64_t fg = 0;
    for (int i = 0; i < W * H; i++)
        fg += g->tri[i] != 0;
    assert_int_equal(g->r.misregistered, fg);
    free(g);
}

/* a point at eye depth 10 through cglm's projections, as an engine's depth
 * buffer holds it, comes back as 10 */
static void grade_depth_conventions(void **st)
{
    (void)st;
    const double n = 0.5, f = 200.0;
    mat4 gl;
    glm_perspective_rh_no(glm_rad(60.0f), 1.0f, (float)n, (float)f, gl);
    mat4 zo;
    glm_perspective_rh_zo(glm_rad(60.0f), 1.0f, (float)n, (float)f, zo);
    for (double z = 1.0; z < 190.0; z *= 1.7) {
        vec4 p = {0.0f, 0.0f, (float)-z, 1.0f}, c1, c2;
        glm_mat4_mulv(gl, p, c1);
        glm_mat4_mulv(zo, p, c2);
        double w_gl = 0.5 * (c1[2] / c1[3]) + 0.5, w_zo = c2[2] / c2[3];
        /* OpenGL's window depth and Vulkan / D3D's NDC z are one number */
        assert_true(fabs(w_gl - w_zo) < 1e-5);
        assert_true(fabs(sl_grade_linear_depth(SL_DEPTH_WINDOW, 0, n, f, w_gl) - z) < 2e-3 * z);
        assert_true(fabs(sl_grade_linear_depth(SL_DEPTH_WINDOW, 0, n, f, w_zo) - z) < 2e-3 * z);
        assert_true(fabs(sl_grade_linear_depth(SL_DEPTH_WINDOW, 1, n, f, 1.0 - w_zo) - z) < 2e-3 * z);
        /* the wrong convention is wrong: reversed read as forward, window
         * read as linear (at z = 1, w is near 1/2, where reversed and
         * forward cross) */
        if (z > 1.5) {
            assert_true(fabs(sl_grade_linear_depth(SL_DEPTH_WINDOW, 0, n, f, 1.0 - w_zo) - z) > 0.01 * z);
            assert_true(fabs(sl_grade_linear_depth(SL_DEPTH_LINEAR, 0, n, f, w_zo) - z) > 0.01 * z);
        }
        assert_true(fabs(sl_grade_linear_depth(SL_DEPTH_LINEAR, 0, n, f, z) - z) == 0.0);
    }
    assert_true(isnan(sl_grade_linear_depth(SL_DEPTH_WINDOW, 0, n, f, 1.0)));    /* the far plane: nothing */
    assert_true(isnan(sl_grade_linear_depth(SL_DEPTH_WINDOW, 1, n, f, 0.0)));    /* reversed: 0 is far */
    assert_true(isnan(sl_grade_linear_depth(SL_DEPTH_LINEAR, 0, n, f, NAN)));
    assert_true(isnan(sl_grade_linear_depth(SL_DEPTH_LINEAR, 0, n, f, 0.0)));
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(grade, registered),
        SL_CASE(grade, flipped),
        SL_CASE(grade, shifted),
        SL_CASE(grade, field_of_view),
        SL_CASE(grade, jitter),
        SL_CASE(grade, unchecked),
        SL_CASE(grade, depth),
        SL_CASE(grade, depth_conventions),
    };
    return sl_run_group(argc, argv, "grade", tests, NULL, NULL);
}
