/* aliasing::* — the aliasing error m (seed 004 appendix A) on constructed
 * cases with known answers, and the figures that sort pixels by it. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "aliasing.h"
#include "provenance.h"
#include "store.h"

#define PI 3.14159265358979323846

/* An orthographic view-projection looking from eye along dir (up given),
 * covering [-half, half]^2 across. */
static void ortho_vp(const float eye[3], const float dir[3], const float up[3], float half, mat4 vp)
{
    mat4 view, proj;
    vec3 e = {eye[0], eye[1], eye[2]}, d = {dir[0], dir[1], dir[2]}, u = {up[0], up[1], up[2]};
    glm_look(e, d, u, view);
    glm_ortho(-half, half, -half, half, 0.1f, 100.0f, proj);
    glm_mat4_mul(proj, view, vp);
}

/* A direction in the y-z plane at angle a from +y toward +z, pointing down
 * onto the plane y = 0 (the beam travels along -that). */
static void down_at(double a, float dir[3])
{
    dir[0] = 0.0f;
    dir[1] = (float)-cos(a);
    dir[2] = (float)-sin(a);
}

/* Camera and light orthographic, both head-on over the plane y = 0: m is
 * the texel's width over the pixel's, exactly. */
static void aliasing_ortho_head_on(void **st)
{
    (void)st;
    const float p[3] = {0.3f, 0.0f, -0.2f}, n[3] = {0, 1, 0}, eye[3] = {0, 10, 0}, down[3] = {0, -1, 0},
                up[3] = {0, 0, -1};
    mat4 cam, lit;
    ortho_vp(eye, down, up, 1.0f, cam);          /* 2 units over 200 px: 0.01 a pixel */
    ortho_vp(eye, down, up, 3.7f, lit);          /* 7.4 units over 200 texels: 0.037 */
    assert_float_equal(sl_alias_m(cam, 200, 200, lit, 200, p, n), 3.7, 1e-4);
    /* the map twice as fine halves m; a texel smaller than a pixel gives m < 1 */
    assert_float_equal(sl_alias_m(cam, 200, 200, lit, 400, p, n), 1.85, 1e-4);
    ortho_vp(eye, down, up, 0.5f, lit);
    assert_float_equal(sl_alias_m(cam, 200, 200, lit, 200, p, n), 0.5, 1e-5);
    /* a light rotated about its own axis changes nothing */
    const float up2[3] = {0.6f, 0.0f, -0.8f};
    ortho_vp(eye, down, up2, 3.7f, lit);
    assert_float_equal(sl_alias_m(cam, 200, 200, lit, 200, p, n), 3.7, 1e-4);
}

/* eq. 56 (exact for parallel beams): the texel's footprint grows as
 * 1 / cos(theta_l); the camera's as 1 / cos(theta_c), which divides it
 * along the shared stretched direction only (m is the largest stretch). */
static void aliasing_cos_theta(void **st)
{
    (void)st;
    const float p[3] = {0, 0, 0}, n[3] = {0, 1, 0}, up[3] = {1, 0, 0};
    const double t_over_p = 2.0;                  /* head-on ratio */
    const double angles[] = {0.0, 30.0, 45.0, 60.0, 75.0};
    for (size_t a = 0; a < sizeof angles / sizeof angles[0]; a++) {
        for (size_t b = 0; b < sizeof angles / sizeof angles[0]; b++) {
            double tl = angles[a] * PI / 180.0, tc = angles[b] * PI / 180.0;
            float dl[3], dc[3], el[3], ec[3];
            down_at(tl, dl);
            down_at(tc, dc);
            for (int k = 0; k < 3; k++) {
                el[k] = -10.0f * dl[k];
                ec[k] = -10.0f * dc[k];
            }
            mat4 cam, lit;
            ortho_vp(ec, dc, up, 1.0f, cam);
            ortho_vp(el, dl, up, 2.0f, lit);
            double m = sl_alias_m(cam, 100, 100, lit, 100, p, n);
            /* in the plane of incidence (y-z): (t / cos tl) / (p / cos tc),
             * eq. 61 with eq. 56; across it (x): t / p */
            double along = t_over_p * cos(tc) / cos(tl), want = fmax(along, t_over_p);
            assert_float_equal(m, want, 1e-4 * want);
        }
    }
}

/* A perspective camera: the footprint of the central pixel of a tilted
 * plane is eq. 58 exactly, and differs from its first-order form eq. 59
 * at a grazing angle; every pixel's spans agree with a footprint found by
 * hand (the pixel's edge rays from the eye, cut with the plane). */
static void aliasing_perspective_exact(void **st)
{
    (void)st;
    const int W = 9, H = 9;                       /* odd: the central pixel sits on the axis */
    const double fov = 60.0 * PI / 180.0, s = 5.0;
    mat4 view, proj, vp;
    vec3 eye = {0, 0, 0}, dir = {0, 0, -1}, up = {0, 1, 0};
    glm_look(eye, dir, up, view);
    glm_perspective((float)fov, 1.0f, 0.5f, 50.0f, proj);
    glm_mat4_mul(proj, view, vp);
    const double nproj = 1.0, d = 2.0 * nproj * tan(fov / 2) / H;   /* a pixel on the plane at distance 1 */
    const double thetas[] = {0.0, 40.0, 70.0, 80.0};
    for (size_t k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
        double th = thetas[k] * PI / 180.0;
        const float nrm[3] = {0.0f, (float)sin(th), (float)cos(th)};
        const float P[3] = {0.0f, 0.0f, (float)-s};
        double a[3], b[3];
        assert_true(sl_alias_spans(vp, W, H, P, nrm, a, b));
        double wy = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        double c = cos(th), sn = sin(th);
        double eq58 = 4.0 * s * d * nproj * c / (4.0 * nproj * nproj * c * c - d * d * sn * sn);
        double eq59 = s * d / (nproj * c);
        assert_float_equal(wy, eq58, 2e-5 * eq58);
        if (thetas[k] >= 80.0)
            assert_true(fabs(eq58 - eq59) > 0.1 * eq59);   /* where eq. 59 breaks down */
        /* x: no tilt across, the beam's width at distance s (eq. 56 with theta 0) */
        double wx = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        assert_float_equal(wx, s * d / nproj, 2e-5 * wx);
    }
    /* off-axis pixels (eq. 60's case), by hand: the edge midpoints' rays
     * from the eye through the image plane at distance 1, cut with the plane */
    const double th = 55.0 * PI / 180.0;
    const float nrm[3] = {(float)(0.3 * sin(th)), (float)(0.95 * sin(th)), (float)cos(th)};
    double nl = sqrt((double)nrm[0] * nrm[0] + (double)nrm[1] * nrm[1] + (double)nrm[2] * nrm[2]);
    const float nu[3] = {(float)(nrm[0] / nl), (float)(nrm[1] / nl), (float)(nrm[2] / nl)};
    const double P0[3] = {0.0, 0.0, -s};
    for (int py = 0; py < H; py += 2)
        for (int px = 0; px < W; px += 3) {
            /* the pixel centre's ray, cut with the plane: the surface point */
            double ray[3] = {((px + 0.5) / W * 2 - 1) * tan(fov / 2), ((py + 0.5) / H * 2 - 1) * tan(fov / 2), -1};
            double t = (P0[0] * nu[0] + P0[1] * nu[1] + P0[2] * nu[2]) /
                       (ray[0] * nu[0] + ray[1] * nu[1] + ray[2] * nu[2]);
            const float P[3] = {(float)(t * ray[0]), (float)(t * ray[1]), (float)(t * ray[2])};
            double hit[4][3];
            const double off[4][2] = {{0.5, 0}, {-0.5, 0}, {0, 0.5}, {0, -0.5}};
            for (int e = 0; e < 4; e++) {
                double r[3] = {((px + 0.5 + off[e][0]) / W * 2 - 1) * tan(fov / 2),
                               ((py + 0.5 + off[e][1]) / H * 2 - 1) * tan(fov / 2), -1};
                double te = (P[0] * nu[0] + P[1] * nu[1] + P[2] * nu[2]) / (r[0] * nu[0] + r[1] * nu[1] + r[2] * nu[2]);
                for (int q = 0; q < 3; q++)
                    hit[e][q] = te * r[q];
            }
            double a[3], b[3];
            assert_true(sl_alias_spans(vp, W, H, P, nu, a, b));
            for (int q = 0; q < 3; q++) {
                assert_float_equal(a[q], hit[0][q] - hit[1][q], 1e-4 * s * d);
                assert_float_equal(b[q], hit[2][q] - hit[3][q], 1e-4 * s * d);
            }
        }
    /* a plane seen edge-on from the eye: the footprint is infinite */
    const float edge[3] = {0, 1, 0}, P[3] = {0, 0, (float)-s};
    double a[3], b[3];
    assert_false(sl_alias_spans(vp, W, H, P, edge, a, b));
}

/* The figures: a 4 x 1 view of PFL pixels with m of 0.5, 3, 3 and 20, the
 * two in the middle wrong (one each way). */
static void aliasing_figures_bands(void **st)
{
    (void)st;
    uint8_t cls[5] = {SL_C_PFL, SL_C_PFL, SL_C_PFL, SL_C_PFL, SL_C_PNFL};
    uint8_t truth[5] = {SL_T_LIT, SL_T_LIT, SL_T_SHADOW, SL_T_SHADOW, SL_T_PNFL};
    uint8_t verd[5] = {SL_V_LIT, SL_V_SHADOW, SL_V_LIT, SL_V_SHADOW, SL_V_SHADOW};
    uint8_t band[5] = {1, 1, 1, 0, 1};
    float m[5] = {0.5f, 3.0f, 5.0f, 20.0f, NAN};
    struct sl_view v;
    memset(&v, 0, sizeof v);
    v.w = 5;
    v.h = 1;
    v.cls = cls;
    v.truth = truth;
    struct sl_verdicts vd;
    memset(&vd, 0, sizeof vd);
    vd.w = 5;
    vd.h = 1;
    vd.v = verd;
    const int regions[2] = {2, 0};
    struct sl_alias_figures f;
    sl_alias_figures_compute(&v, &vd, m, band, regions, 2, &f);
    assert_int_equal(f.nregions, 2);
    /* whole image (region 1) */
    assert_int_equal(f.n[1][SL_AFIG_px_m_le1], 1);
    assert_int_equal(f.n[1][SL_AFIG_px_m_2_4], 1);
    assert_int_equal(f.n[1][SL_AFIG_px_m_4_8], 1);
    assert_int_equal(f.n[1][SL_AFIG_px_m_gt8], 1);
    assert_int_equal(f.n[1][SL_AFIG_wrong_m_2_4], 1);
    assert_int_equal(f.n[1][SL_AFIG_wrong_m_4_8], 1);
    assert_int_equal(f.n[1][SL_AFIG_wrong_m_le1] + f.n[1][SL_AFIG_wrong_m_gt8], 0);
    assert_int_equal(f.n[1][SL_AFIG_m_median_milli], 4000);          /* of 0.5, 3, 5, 20 */
    assert_int_equal(f.n[1][SL_AFIG_wrong_m_median_milli], 4000);    /* of 3, 5 */
    assert_float_equal(f.pct[1][SL_AFIG_px_m_gt8], 25.0, 1e-9);
    assert_float_equal(f.pct[1][SL_AFIG_wrong_m_2_4], 50.0, 1e-9);
    /* the 2-px contour leaves out the last PFL pixel */
    assert_int_equal(f.n[0][SL_AFIG_px_m_gt8], 0);
    assert_int_equal(f.n[0][SL_AFIG_m_median_milli], 3000);
    /* the layer's code: m = 1, 2, 8 at 128, 136, 152; NAN 0 */
    assert_int_equal(sl_alias_code(1.0f), 128);
    assert_int_equal(sl_alias_code(2.0f), 136);
    assert_int_equal(sl_alias_code(8.0f), 152);
    assert_int_equal(sl_alias_code(NAN), 0);
    assert_int_equal(sl_alias_band(1.0), 0);
    assert_int_equal(sl_alias_band(1.0001), 1);
    assert_int_equal(sl_alias_band(8.5), 4);
}



static int cmp_f(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* The reference: the median of x[0..n) by a full sort (sorted in place),
 * x 1000 rounded as the figures store it (an infinite one capped). */
static uint64_t sorted_median_milli(float *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, cmp_f);
    double want = n % 2 ? x[n / 2] : 0.5 * ((double)x[n / 2 - 1] + (double)x[n / 2]);
    return isinf(want) ? 9000000000000000ull : (uint64_t)floor(want * 1000.0 + 0.5);
}

/* The medians come from a linear-time select: they equal a full sort's
 * middle (the mean of the two middles for an even count) on values with
 * many ties, zeros of both signs, subnormals and infinities, for odd and
 * even counts. m is rounded to 1/1000 in the figures, so the values are
 * spread far wider than that: a neighbour taken for the middle shows. */
static void aliasing_median_select(void **st)
{
    (void)st;
    enum { N = 4099 };
    static float m[N], ref[N];
    static uint8_t cls[N], truth[N], verd[N], band[N];
    unsigned r = 12345u;
    for (int trial = 0; trial < 12; trial++) {
        int n = N - trial % 2 - 40 * trial;   /* odd and even counts */
        for (int i = 0; i < n; i++) {
            r = r * 1103515245u + 12345u;
            unsigned k = (r >> 8) % 1000u;
            m[i] = k < 50 ? 0.0f : k < 60 ? -0.0f : k < 70 ? 1e-40f : k < 70 + 30 * (unsigned)trial ? INFINITY
                 : (float)(k % 97) * 0.37f + (trial > 6 ? 1e5f : 0.0f);
            cls[i] = SL_C_PFL;
            band[i] = 1;
            truth[i] = SL_T_LIT;
            verd[i] = i % 3 ? SL_V_LIT : SL_V_SHADOW;   /* every third pixel wrong */
        }
        struct sl_view v;
        memset(&v, 0, sizeof v);
        v.w = n;
        v.h = 1;
        v.cls = cls;
        v.truth = truth;
        struct sl_verdicts vd;
        memset(&vd, 0, sizeof vd);
        vd.w = n;
        vd.h = 1;
        vd.v = verd;
        const int regions[1] = {0};
        struct sl_alias_figures f;
        sl_alias_figures_compute(&v, &vd, m, band, regions, 1, &f);
        memcpy(ref, m, (size_t)n * sizeof *ref);
        assert_int_equal(f.n[0][SL_AFIG_m_median_milli], sorted_median_milli(ref, n));
        int nb = 0;
        for (int i = 0; i < n; i += 3)
            ref[nb++] = m[i];
        assert_int_equal(f.n[0][SL_AFIG_wrong_m_median_milli], sorted_median_milli(ref, nb));
    }
}

/* m in lanes (sl_alias_image under one frame) against the scalar sl_alias_m
 * of each pixel, bit for bit: a perspective camera over points in front of
 * it, beside it and behind it, normals of every kind (ties between axes,
 * edge-on to the camera or the light), under a perspective light, an
 * orthographic one and a singular one; 37 x 23 pixels, so the lanes' tail
 * is scalar. */
static void aliasing_image_lanes_match(void **st)
{
    (void)st;
    enum { W = 37, H = 23, N = W * H };
    static float pos[3 * N], nrm[3 * N], got[N];
    static uint8_t cls[N];
    struct sl_view v;
    memset(&v, 0, sizeof v);
    v.w = W;
    v.h = H;
    v.pos = pos;
    v.nrm = nrm;
    v.cls = cls;
    vec3 e = {0.5f, 4.0f, 6.0f}, dv = {-0.1f, -0.5f, -1.0f}, u = {0, 1, 0};
    glm_look(e, dv, u, v.view);
    glm_perspective(0.9f, (float)W / H, 0.1f, 50.0f, v.proj);
    mat4 cam;
    glm_mat4_mul(v.proj, v.view, cam);
    uint32_t r = 12345u;
#define RND() ((r = r * 1664525u + 1013904223u) >> 8) * (1.0f / 16777216.0f)
    for (int i = 0; i < N; i++) {
        float *p = pos + 3 * i, *n = nrm + 3 * i;
        for (int k = 0; k < 3; k++)
            p[k] = 8.0f * RND() - 4.0f;
        if (i % 7 == 3)
            p[2] = 9.0f;                                   /* behind the camera */
        switch (i % 6) {
        case 0: n[0] = 0.0f, n[1] = 1.0f, n[2] = 0.0f; break;
        case 1: n[0] = n[1] = n[2] = 0.57735026f; break;   /* ties between the axes */
        case 2: n[0] = 0.0f, n[1] = 0.0f, n[2] = -1.0f; break;
        case 3: n[0] = -0.70710678f, n[1] = 0.0f, n[2] = 0.70710678f; break;
        default: {
            float a = RND() - 0.5f, b = RND() - 0.5f, c = RND() - 0.5f, l = sqrtf(a * a + b * b + c * c);
            n[0] = a / l, n[1] = b / l, n[2] = c / l;
        }
        }
        if (i % 11 == 5) {                                 /* edge-on to the camera's beam */
            vec3 d = {p[0] - e[0], p[1] - e[1], p[2] - e[2]}, q;
            glm_vec3_cross(d, (vec3){0, 1, 0}, q);
            glm_vec3_normalize(q);
            memcpy(n, q, sizeof q);
        }
        cls[i] = i % 9 == 4 ? SL_C_PNFL : i % 13 == 6 ? SL_C_BACKGROUND : SL_C_PFL;
    }
#undef RND
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    f.size = 256;
    mat4 lview, lproj;
    for (int light = 0; light < 3; light++) {
        if (light == 0) {                                  /* a spot over the scene */
            glm_look((vec3){2.0f, 9.0f, 1.0f}, (vec3){-0.2f, -1.0f, -0.1f}, (vec3){0, 0, 1}, lview);
            glm_perspective(1.2f, 1.0f, 0.5f, 30.0f, lproj);
            glm_mat4_mul(lproj, lview, f.box.vp);
        } else if (light == 1) {                           /* a directional light */
            const float eye[3] = {0, 10, 0}, down[3] = {0.3f, -1.0f, 0.2f}, up[3] = {0, 0, -1};
            ortho_vp(eye, down, up, 5.0f, f.box.vp);
        } else {
            glm_mat4_zero(f.box.vp);                       /* singular: no texel anywhere */
        }
        sl_alias_image(&v, &f, NULL, 2, got);
        int finite = 0;
        for (int i = 0; i < N; i++) {
            if (cls[i] != SL_C_PFL) {
                assert_true(isnan(got[i]));
                continue;
            }
            float want = (float)sl_alias_m(cam, W, H, f.box.vp, f.size, pos + 3 * i, nrm + 3 * i);
            if (isnan(want)) {
                assert_true(isnan(got[i]));
            } else {
                uint32_t a, b;
                memcpy(&a, &got[i], 4);
                memcpy(&b, &want, 4);
                if (a != b)
                    fail_msg("light %d pixel %d: m %.9g in lanes, %.9g alone", light, i, got[i], want);
            }
            finite += isfinite(want) && want > 0.0f;
        }
        /* the cases are not all degenerate: most pixels have an m */
        if (light < 2)
            assert_true(finite > N / 3);
        else
            assert_int_equal(finite, 0);
    }
}

/* The m kept for a view's cells: the same values sl_alias_image writes;
 * computed again for another frame (projection or size) or another view
 * (serial), and not for the same ones. */
static void aliasing_cache_keyed(void **st)
{
    (void)st;
    enum { W = 16, H = 12 };
    static float pos[3 * W * H], nrm[3 * W * H], want[W * H];
    static uint8_t cls[W * H];
    const float eye[3] = {0, 10, 0}, down[3] = {0, -1, 0}, up[3] = {0, 0, -1};
    struct sl_view v;
    memset(&v, 0, sizeof v);
    v.w = W;
    v.h = H;
    v.pos = pos;
    v.nrm = nrm;
    v.cls = cls;
    v.serial = 7;
    vec3 e = {0, 10, 0}, dv = {0, -1, 0}, u = {0, 0, -1};
    glm_look(e, dv, u, v.view);
    glm_ortho(-1.0f, 1.0f, -0.75f, 0.75f, 0.1f, 100.0f, v.proj);
    for (int i = 0; i < W * H; i++) {
        float x = -1.0f + 2.0f * ((float)(i % W) + 0.5f) / W, z = -0.75f + 1.5f * ((float)(i / W) + 0.5f) / H;
        pos[3 * i] = x, pos[3 * i + 1] = 0.0f, pos[3 * i + 2] = -z;
        nrm[3 * i] = 0.0f, nrm[3 * i + 1] = 1.0f, nrm[3 * i + 2] = 0.0f;
        cls[i] = i % 5 ? SL_C_PFL : SL_C_PNFL;
    }
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    f.size = 64;
    ortho_vp(eye, down, up, 3.0f, f.box.vp);
    struct sl_alias_cache c;
    memset(&c, 0, sizeof c);
    const float *m = sl_alias_cached(&c, &v, &f, 1);
    assert_non_null(m);
    sl_alias_image(&v, &f, NULL, 1, want);
    for (int i = 0; i < W * H; i++) {
        if (i % 5 == 0) {
            assert_true(isnan(m[i]));
        } else {
            assert_float_equal(m[i], want[i], 0.0);
            assert_float_equal(m[i], (6.0 / 64.0) / (2.0 / W), 1e-4);   /* texel 6/64 over pixel 2/16: 0.75 */
        }
    }
    float first = m[1];
    /* the same view and frame: the kept values, not computed again */
    c.m[1] = -1.0f;
    assert_float_equal(sl_alias_cached(&c, &v, &f, 1)[1], -1.0f, 0.0);
    /* a map twice as fine: computed again, m halves */
    f.size = 128;
    m = sl_alias_cached(&c, &v, &f, 1);
    assert_float_equal(m[1], 0.5f * first, 1e-5);
    /* another projection of the same size */
    ortho_vp(eye, down, up, 1.5f, f.box.vp);
    m = sl_alias_cached(&c, &v, &f, 1);
    assert_float_equal(m[1], 0.25f * first, 1e-5);
    /* another view (serial), same frame: computed again */
    c.m[1] = -1.0f;
    v.serial = 8;
    m = sl_alias_cached(&c, &v, &f, 1);
    assert_float_equal(m[1], 0.25f * first, 1e-5);
    sl_alias_cache_free(&c);
    assert_null(c.m);
}


/* The PFL side of the figures kept for the next cell: with other verdicts
 * on the same bands every figure equals a fresh count; with other bands,
 * other regions or a recomputed m (another frame) it is counted again. */
static void aliasing_figures_cached(void **st)
{
    (void)st;
    enum { W = 24, H = 20 };
    static float pos[3 * W * H], nrm[3 * W * H];
    static uint8_t cls[W * H], truth[W * H], v1[W * H], v2[W * H], band[W * H], band2[W * H];
    const float eye[3] = {0, 10, 0}, down[3] = {0, -1, 0}, up[3] = {0, 0, -1};
    struct sl_view v;
    memset(&v, 0, sizeof v);
    v.w = W, v.h = H, v.pos = pos, v.nrm = nrm, v.cls = cls, v.truth = truth, v.serial = 3;
    vec3 e = {0, 10, 0}, dv = {0, -1, 0}, u = {0, 0, -1};
    glm_look(e, dv, u, v.view);
    glm_perspective(1.0f, (float)W / H, 0.1f, 100.0f, v.proj);
    for (int i = 0; i < W * H; i++) {
        float x = (float)(i % W) - W / 2, z = (float)(i / W) - H / 2;
        pos[3 * i] = 0.4f * x, pos[3 * i + 1] = 0.02f * x * z, pos[3 * i + 2] = 0.4f * z;
        float nx = -0.02f * z, nz = -0.02f * x, l = sqrtf(nx * nx + 1.0f + nz * nz);
        nrm[3 * i] = nx / l, nrm[3 * i + 1] = 1.0f / l, nrm[3 * i + 2] = nz / l;
        cls[i] = i % 7 ? SL_C_PFL : SL_C_PNFL;
        truth[i] = i % 3 ? SL_T_LIT : SL_T_SHADOW;
        v1[i] = i % 5 ? SL_V_LIT : SL_V_SHADOW;
        v2[i] = i % 4 ? SL_V_SHADOW : SL_V_LIT;
        band[i] = (uint8_t)(i % 4);
        band2[i] = (uint8_t)((i / 3) % 4);
    }
    struct sl_light_frame f;
    memset(&f, 0, sizeof f);
    f.size = 32;
    ortho_vp(eye, down, up, 6.0f, f.box.vp);
    struct sl_alias_cache c;
    memset(&c, 0, sizeof c);
    const int regions[3] = {2, 4, 0}, regions2[2] = {2, 0};
    struct sl_verdicts vd;
    memset(&vd, 0, sizeof vd);
    vd.w = W, vd.h = H;
    struct sl_alias_figures got, want;
    const uint8_t *vs[2] = {v1, v2}, *bands[3] = {band, band, band2};
    uint64_t px[6];
    for (int step = 0; step < 6; step++) {
        if (step == 4)
            ortho_vp(eye, down, up, 3.0f, f.box.vp);   /* another frame: m again, the PFL side again */
        const float *m = sl_alias_cached(&c, &v, &f, 1);
        assert_non_null(m);
        vd.v = (uint8_t *)vs[step % 2];
        const uint8_t *b = bands[step % 3];
        const int *rg = step == 5 ? regions2 : regions;
        int nr = step == 5 ? 2 : 3;
        sl_alias_figures_cached(&c, &v, &vd, m, b, rg, nr, &got);
        sl_alias_figures_compute(&v, &vd, m, b, rg, nr, &want);
        assert_int_equal(got.nregions, want.nregions);
        for (int r = 0; r < nr; r++) {
            assert_int_equal(got.thickness[r], want.thickness[r]);
            for (int k = 0; k < SL_AFIG_COUNT; k++) {
                assert_int_equal(got.n[r][k], want.n[r][k]);
                if (isnan(want.pct[r][k]))
                    assert_true(isnan(got.pct[r][k]));
                else
                    assert_float_equal(got.pct[r][k], want.pct[r][k], 0.0);
            }
        }
        px[step] = got.n[1][SL_AFIG_px_m_le1] + 2 * got.n[1][SL_AFIG_px_m_1_2] + 3 * got.n[1][SL_AFIG_px_m_2_4];
    }
    /* other bands, another frame, other regions count otherwise: a PFL side
     * kept where it does not fit would show above */
    assert_int_not_equal(px[2], px[1]);
    assert_int_not_equal(px[4], px[3]);
    assert_int_not_equal(px[5], px[4]);
    sl_alias_cache_free(&c);
}

/* The aliasing figures and the texels column go into the store with the
 * cell and come back as they were; a cell without them stays without. */
static void aliasing_store_round_trip(void **st)
{
    (void)st;
    char db[200];
    snprintf(db, sizeof db, "%s/alias.db", sl_test_dir);
    struct sl_diag d;
    struct sl_store *s = NULL;
    assert_int_equal(sl_store_open(db, &s, &d), SL_OK);
    struct sl_provenance p;
    memset(&p, 0, sizeof p);
    snprintf(p.git_sha, sizeof p.git_sha, "abc1234");
    snprintf(p.time_utc, sizeof p.time_utc, "2024-01-02T03:04:05Z");
    snprintf(p.host, sizeof p.host, "h");
    int64_t run = 0;
    assert_int_equal(sl_store_begin_run(s, &p, "al", "configs/aliasing.yaml", 0x1234ull, "name: al\n", &run, &d),
                     SL_OK);
    struct sl_cell_record c[2];
    for (int k = 0; k < 2; k++) {
        sl_cell_record_init(&c[k]);
        snprintf(c[k].scene, sizeof c[k].scene, "street");
        snprintf(c[k].viewpoint, sizeof c[k].viewpoint, "along");
        snprintf(c[k].method, sizeof c[k].method, "zpart");
        snprintf(c[k].label, sizeof c[k].label, "z%d", k);
        c[k].vw = c[k].vh = 64;
        c[k].map_size = 512;
        c[k].cell_index = k;
        c[k].fig.nregions = 2;
        c[k].fig.r[0].thickness = 2;
        c[k].fig.r[1].thickness = 0;
        for (int r = 0; r < 2; r++)
            for (int f = 0; f < SL_FIG_COUNT; f++)
                c[k].fig.r[r].pct[f] = NAN;
    }
    c[0].texels = 4u * 512u * 512u;
    c[0].has_alias = 1;
    c[0].alias.nregions = 2;
    c[0].alias.thickness[0] = 2;
    c[0].alias.thickness[1] = 0;
    for (int r = 0; r < 2; r++)
        for (int f = 0; f < SL_AFIG_COUNT; f++) {
            c[0].alias.n[r][f] = (uint64_t)(100 * r + f + 1);
            c[0].alias.pct[r][f] = sl_alias_figure_of((enum sl_alias_figure)f)[0] ? 0.5 * f : NAN;
        }
    c[0].alias.n[1][SL_AFIG_wrong_m_median_milli] = 9000000000000000ull;   /* the cap milli() keeps to */
    for (int k = 0; k < 2; k++)
        assert_int_equal(sl_store_put_cell(s, run, 0x1234ull, &c[k], &d), SL_OK);
    struct sl_cell_record *got = NULL;
    int n = 0;
    assert_int_equal(sl_store_query(s, NULL, &got, &n, &d), SL_OK);
    assert_int_equal(n, 2);
    const struct sl_cell_record *a = strcmp(got[0].label, "z0") == 0 ? &got[0] : &got[1];
    const struct sl_cell_record *b = a == got ? &got[1] : &got[0];
    assert_int_equal(a->texels, 4u * 512u * 512u);
    assert_true(a->has_alias);
    assert_int_equal(a->alias.nregions, 2);
    for (int r = 0; r < 2; r++) {
        assert_int_equal(a->alias.thickness[r], r ? 0 : 2);
        for (int f = 0; f < SL_AFIG_COUNT; f++) {
            assert_int_equal(a->alias.n[r][f], c[0].alias.n[r][f]);
            if (isnan(c[0].alias.pct[r][f]))
                assert_true(isnan(a->alias.pct[r][f]));
            else
                assert_float_equal(a->alias.pct[r][f], c[0].alias.pct[r][f], 0.0);
        }
    }
    assert_false(b->has_alias);
    assert_int_equal(b->alias.nregions, 0);
    assert_int_equal(b->texels, 0);
    free(got);
    sl_store_close(s);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(aliasing, ortho_head_on),
        SL_CASE(aliasing, cos_theta),
        SL_CASE(aliasing, perspective_exact),
        SL_CASE(aliasing, figures_bands),
        SL_CASE(aliasing, store_round_trip),
        SL_CASE(aliasing, median_select),
        SL_CASE(aliasing, cache_keyed),
        SL_CASE(aliasing, figures_cached),
        SL_CASE(aliasing, image_lanes_match),
    };
    return sl_run_group(argc, argv, "aliasing", tests, sl_test_setup, sl_test_teardown);
}
