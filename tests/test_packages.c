/*
 * packages::* — the shipped technique packages (techniques/vsm, esm, evsm,
 * msm, pcss) on the GL: hand-made map texels uploaded through the runner
 * (sl_techpass_upload, which also runs the package's post passes), then the
 * package's lookup at chosen points (sl_techpass_lookup), compared with the
 * technique's formula evaluated here in double precision. Each expected value
 * is one the shader could not produce with its math wrong (a Chebyshev bound
 * of a known two-depth texel, the exponential of a known occluder, EVSM's two
 * warped bounds, MSM's Hamburger reconstruction, PCSS's penumbra of a known
 * blocker), and each package's lookup is checked to read nothing beyond its
 * declared reach plus its blur.
 *
 * The light frame is the simplest there is: directional, its box matrix the
 * identity, so a world point (x, y, z) lands at texel coordinates
 * ((x + 1) S / 2, (y + 1) S / 2) of the frame and window depth z; texel
 * (i, j) of the frame is texel (i + g, j + g) of the guarded maps.
 *
 * Maps are made of half planes and quadrants meeting at the frame's centre,
 * and points are looked up on those edges: the box blur and the mipmaps are
 * linear, symmetric and keep sums, so after any blur radius or mip level the
 * bilinear read at the meeting point sees each part with the same weight
 * (1/2 for two halves, 1/4 for four quadrants) — the expected moments do
 * not depend on the post passes. Each point fills a 2 x 2 quad of the lookup
 * grid, so its screen-space derivatives are 0 and the mip level 0, except in
 * the reach test, which wants the coarsest level the lookup allows.
 *
 * The rendered cases run the packages over a scene against the truth; the
 * traced case runs vsm_rt (vsm with a traced band) as the run does, through
 * its method, beside vsm: the band's pixels the truth's, the rest vsm's.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <cmocka.h>
#include "sl_test.h"
#include "fixture.h"
#include "frame.h"
#include "lightfit.h"
#include "package.h"
#include "shadowmap.h"
#include "glctx.h"
#include "techcheck.h"
#include "technique.h"
#include "techpass.h"

#define S 64            /* the frame's texels per side */
#define EDGE (S / 2)    /* the column (and row) where the halves meet */

/* The process's GL context: opened by the first case that needs it, closed
 * before the rendered case, whose fixture opens its own. */
static struct sl_gl gl;
static int gl_is_open;

static void gl_open(void)
{
    if (gl_is_open)
        return;
    struct sl_diag d;
    enum sl_err e = sl_gl_init(&gl, &d);
    if (e)
        fprintf(stderr, "gl: %s\n", d.msg);
    assert_int_equal(e, SL_OK);
    gl_is_open = 1;
    char what[400];
    sl_gl_describe(&gl, what, sizeof what);
    printf("  GL: %s, %s (%s)\n", gl.renderer, gl.version, what);
}

static void gl_close(void)
{
    if (gl_is_open)
        sl_gl_free(&gl);
    gl_is_open = 0;
}

static int group_teardown(void **st)
{
    gl_close();
    return sl_test_teardown(st);
}

/* ---- one package on the GL ---- */

struct pkg {
    struct sl_technique t;
    struct sl_techpass p;
    struct sl_params v;
    struct sl_light_frame f;
    int g, n;           /* guard band, guarded map size */
    int channels;       /* of map 0 */
};

static void diag_print(enum sl_err e, const struct sl_diag *d)
{
    if (e) {
        char buf[1200];
        sl_diag_format(d, e, buf, sizeof buf);
        fprintf(stderr, "%s\n", buf);
    }
}

/* The package in folder dir on the identity frame (above), defaults set. */
static void pkg_open_dir(struct pkg *k, const char *dir)
{
    gl_open();
    memset(k, 0, sizeof *k);
    struct sl_diag d;
    enum sl_err e = sl_tech_load(dir, &k->t, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    e = sl_techpass_init(&k->p, &k->t, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    sl_tech_defaults(&k->t, &k->v);
    static const int ch[] = {1, 2, 4, 4};
    k->channels = ch[k->t.map[0].format];
    struct sl_light_frame *f = &k->f;
    f->size = S;
    f->dir[2] = 1.0f;                       /* light travels +z: toward the light is -z */
    glm_mat4_identity(f->box.view);
    glm_mat4_identity(f->box.proj);
    glm_mat4_identity(f->box.vp);
    f->box.lo[0] = f->box.lo[1] = -1.0f;
    f->box.hi[0] = f->box.hi[1] = f->box.hi[2] = 1.0f;
    f->texel_world = 2.0f / (float)S;
    f->depth_range = 1.0f;
}

/* A shipped package, techniques/<name>. */
static void pkg_open(struct pkg *k, const char *name)
{
    char dir[300];
    snprintf(dir, sizeof dir, "techniques/%s", name);
    pkg_open_dir(k, dir);
}

static void pkg_close(struct pkg *k)
{
    sl_techpass_free(&k->p);
    sl_tech_free(&k->t);
}

static void pkg_set(struct pkg *k, const char *name, double x)
{
    struct sl_diag d;
    enum sl_err e = sl_params_put(&k->v, name, x, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
}

/* The depth of the scene at frame texel (i, j) (may lie in the guard band:
 * i, j in [-g, S + g)). */
typedef double (*depth_fn)(int i, int j, const void *arg);

/* The map texel a package's sl_map writes for depth z, in double (each
 * package's map.glsl, repeated; the GPU computes it in float). */
static void map_texel(const struct pkg *k, double z, float *out)
{
    const char *name = k->t.name;
    double v[4] = {0, 0, 0, 0};
    if (!strcmp(name, "vsm")) {
        v[0] = z, v[1] = z * z;
    } else if (!strcmp(name, "esm")) {
        v[0] = exp(k->v.v[sl_tech_param_index(&k->t, "c")] * (z - 0.5));
    } else if (!strcmp(name, "evsm")) {
        double w = 2 * z - 1;
        double ep = exp(k->v.v[sl_tech_param_index(&k->t, "positive")] * w);
        double en = exp(-k->v.v[sl_tech_param_index(&k->t, "negative")] * w);
        v[0] = ep, v[1] = ep * ep, v[2] = -en, v[3] = en * en;
    } else if (!strcmp(name, "msm")) {
        v[0] = z, v[1] = z * z, v[2] = z * z * z, v[3] = z * z * z * z;
    } else {
        v[0] = z;   /* pcss */
    }
    for (int c = 0; c < k->channels; c++)
        out[c] = (float)v[c];
}

/* Size the maps for the current values, fill them from fn and upload them
 * (the post passes run). Texels beyond `keep` texels (Chebyshev distance) of
 * frame texel (ki, kj) get depth `poison` instead, when keep >= 0. */
static void pkg_upload_poisoned(struct pkg *k, depth_fn fn, const void *arg, int keep, int ki, int kj,
                                double poison)
{
    struct sl_diag d;
    enum sl_err e = sl_techpass_size(&k->p, &k->f, &k->v, &k->g, &k->n, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    assert_int_equal(k->n, S + 2 * k->g);
    size_t nn = (size_t)k->n * (size_t)k->n;
    float *tex = malloc(nn * (size_t)k->channels * sizeof *tex);
    assert_non_null(tex);
    for (int jg = 0; jg < k->n; jg++)
        for (int ig = 0; ig < k->n; ig++) {
            int i = ig - k->g, j = jg - k->g;
            int far = keep >= 0 && (abs(i - ki) > keep || abs(j - kj) > keep);
            double z = far ? poison : fn(i, j, arg);
            map_texel(k, z, tex + ((size_t)jg * (size_t)k->n + (size_t)ig) * (size_t)k->channels);
        }
    const float *maps[SL_TECH_MAX_MAPS] = {tex};
    e = sl_techpass_upload(&k->p, &k->f, &k->v, maps, &d);
    diag_print(e, &d);
    free(tex);
    assert_int_equal(e, SL_OK);
}

static void pkg_upload(struct pkg *k, depth_fn fn, const void *arg)
{
    pkg_upload_poisoned(k, fn, arg, -1, 0, 0, 0);
}

/* Visibility at frame texel coordinates (u, v) and window depth z, the
 * surface facing the light (ndotl = 1). The point fills a 4 x 2 grid, two
 * 2 x 2 quads: zero derivatives, mip level 0; the eight results must agree.
 * (4 wide, not 2: the runner uploads the byte mask with the default unpack
 * alignment of 4, so a grid less than 4 wide reads its mask's second row
 * from beyond the array and loses points at random.) */
#define QW 4
#define QH 2
static void quad_grid(double u, double v, double z, float *pos, float *nrm)
{
    for (int q = 0; q < QW * QH; q++) {
        pos[3 * q + 0] = (float)(u / S * 2 - 1);
        pos[3 * q + 1] = (float)(v / S * 2 - 1);
        pos[3 * q + 2] = (float)z;
        nrm[3 * q + 0] = nrm[3 * q + 1] = 0.0f;
        nrm[3 * q + 2] = -1.0f;
    }
}

static double pkg_lookup(struct pkg *k, double u, double v, double z)
{
    float pos[QW * QH * 3], nrm[QW * QH * 3], vis[QW * QH];
    quad_grid(u, v, z, pos, nrm);
    struct sl_diag d;
    enum sl_err e = sl_techpass_lookup(&k->p, &k->f, &k->v, pos, nrm, NULL, QW, QH, vis, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    for (int q = 1; q < QW * QH; q++) {
        if (vis[q] != vis[0])
            fprintf(stderr, "lookup %d of the grid: %.9g, lookup 0: %.9g\n", q, vis[q], vis[0]);
        assert_true(vis[q] == vis[0]);
    }
    return vis[0];
}

static void expect_near(const char *what, double got, double want, double tol)
{
    printf("    %-44s got %.7f  want %.7f  (|diff| %.2e, tol %.1e)\n", what, got, want, fabs(got - want), tol);
    assert_true(fabs(got - want) <= tol);
}

/* ---- maps ---- */

/* columns i < EDGE at a[0], the rest at a[1] */
static double halves(int i, int j, const void *arg)
{
    (void)j;
    const double *a = arg;
    return i < EDGE ? a[0] : a[1];
}

/* quadrants: a[0] (i < EDGE, j < EDGE), a[1] (i >= EDGE, j < EDGE), a[2], a[3] above */
static double quadrants(int i, int j, const void *arg)
{
    const double *a = arg;
    return a[(i >= EDGE) + 2 * (j >= EDGE)];
}

/* a fixed pseudo-random field of depths in [0.2, 0.8] */
static double noise(int i, int j, const void *arg)
{
    (void)arg;
    uint32_t h = (uint32_t)(i + 1000) * 2654435761u ^ (uint32_t)(j + 1000) * 2246822519u;
    h ^= h >> 15;
    h *= 2654435761u;
    h ^= h >> 13;
    return 0.2 + 0.6 * (double)(h & 0xffff) / 65535.0;
}

/* ---- references, double precision ---- */

/* Chebyshev's one-tailed bound of a distribution with mean m1 and second
 * moment m2 at x, variance clamped at min_var. */
static double chebyshev(double m1, double m2, double x, double min_var)
{
    if (x <= m1)
        return 1;
    double var = fmax(m2 - m1 * m1, min_var);
    return var / (var + (x - m1) * (x - m1));
}

static double linstep(double lo, double x)
{
    return fmin(fmax((x - lo) / (1 - lo), 0), 1);
}

/* Peters & Klein 2015, Algorithm 2 (Hamburger 4MSM) for depth in [0, 1]:
 * the shadow intensity G of moments b at depth zf with moment bias alpha.
 * Written from the paper (solve B c = (1, zf, zf^2) for the Hankel matrix
 * B, roots of c3 z^2 + c2 z + c1, three cases), by Cramer's rule rather
 * than the shader's Cholesky so the two share no code path. */
static double msm_reference(const double m[4], double zf, double alpha)
{
    double b[4];
    for (int i = 0; i < 4; i++)
        b[i] = (1 - alpha) * m[i] + alpha * 0.5;
    double B[3][3] = {{1, b[0], b[1]}, {b[0], b[1], b[2]}, {b[1], b[2], b[3]}};
    double r[3] = {1, zf, zf * zf};
#define DET3(M) (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) + \
                 M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
    double det = DET3(B), c[3];
    for (int col = 0; col < 3; col++) {
        double M[3][3];
        memcpy(M, B, sizeof M);
        for (int row = 0; row < 3; row++)
            M[row][col] = r[row];
        c[col] = DET3(M) / det;
    }
#undef DET3
    double disc = sqrt(fmax(c[1] * c[1] - 4 * c[2] * c[0], 0));
    double z2 = (-c[1] - disc) / (2 * c[2]), z3 = (-c[1] + disc) / (2 * c[2]);
    if (z2 > z3) {
        double t = z2;
        z2 = z3, z3 = t;
    }
    if (zf <= z2)
        return 0;
    if (zf <= z3)
        return (zf * z3 - b[0] * (zf + z3) + b[1]) / ((z3 - z2) * (zf - z2));
    return 1 - (z2 * z3 - b[0] * (z2 + z3) + b[1]) / ((zf - z2) * (zf - z3));
}

/* the moments of n depths of equal weight */
static void moments_of(const double *z, int n, double m[4])
{
    memset(m, 0, 4 * sizeof *m);
    for (int i = 0; i < n; i++)
        for (int p = 0; p < 4; p++)
            m[p] += pow(z[i], p + 1) / n;
}

/* ---- the cases ---- */

/* The loader takes every shipped package; their parameters' defaults are the
 * literature's; guard bands and taps are what their reach promises. */
static void packages_load(void **st)
{
    (void)st;
    static const struct {
        const char *pkg, *param;
        double def;
    } defs[] = {
        {"vsm", "blur", 1},           {"vsm", "min_variance", 1e-5}, {"vsm", "bleed", 0.2},
        {"esm", "c", 80},             {"esm", "blur", 1},            {"evsm", "positive", 40},
        {"evsm", "negative", 5},      {"evsm", "moments", 4},        {"evsm", "min_variance", 1e-6},
        {"msm", "moment_bias", 3e-5}, {"msm", "bleed", 0},           {"msm", "blur", 1},
        {"pcss", "light_size", 0},    {"pcss", "search", 4},         {"pcss", "max_filter", 8},
    };
    for (size_t i = 0; i < sizeof defs / sizeof defs[0]; i++) {
        struct sl_technique t;
        struct sl_diag d;
        char dir[300];
        snprintf(dir, sizeof dir, "techniques/%s", defs[i].pkg);
        enum sl_err e = sl_tech_load(dir, &t, &d);
        diag_print(e, &d);
        assert_int_equal(e, SL_OK);
        assert_string_equal(t.name, defs[i].pkg);
        int p = sl_tech_param_index(&t, defs[i].param);
        assert_true(p >= 0);
        assert_true(t.param[p].def == defs[i].def);
        struct sl_params v;
        sl_tech_defaults(&t, &v);
        if (!strcmp(defs[i].pkg, "pcss")) {
            assert_int_equal(sl_tech_guard(&t, &v), 16);        /* max(search, max_filter) at their maxima */
            assert_true(sl_tech_taps(&t, &v) == 64.0);          /* (2 search)^2 */
        } else {
            /* reach blur + 1 (the mip levels it may read), guard + the blur's own radius */
            assert_int_equal(sl_tech_reach(&t, &v), 2);
            assert_int_equal(sl_tech_guard(&t, &v), 3);
            assert_true(sl_tech_taps(&t, &v) == 1.0);
        }
        sl_tech_free(&t);
    }
}

/* VSM: half the texels at 0.3, half at 0.7: mean 0.5, E[z^2] = 0.29,
 * variance 0.04. A receiver at 0.9: 0.04 / (0.04 + 0.16) = 0.2; at 0.6:
 * 0.04 / 0.05 = 0.8; at 0.5 and in front: 1. bleed 0.1 maps 0.2 to
 * 0.1 / 0.9 = 0.111; the default 0.2 maps it to 0.
 * Tolerance 1e-4: E[z^2] - E[z]^2 in float32 loses about 2^-24 * 0.29 / 0.04
 * relative (~1e-6) and the blur's sums a few ulps more. */
static void packages_vsm_chebyshev(void **st)
{
    (void)st;
    static const double a[2] = {0.3, 0.7};
    const int blurs[] = {0, 1, 4};
    for (int bi = 0; bi < 3; bi++) {
        struct pkg k;
        pkg_open(&k, "vsm");
        pkg_set(&k, "blur", blurs[bi]);
        pkg_set(&k, "bleed", 0);
        pkg_upload(&k, halves, a);
        printf("  vsm blur %d (guard %d, map %d)\n", blurs[bi], k.g, k.n);
        expect_near("z = 0.9: 0.04 / (0.04 + 0.16)", pkg_lookup(&k, EDGE, 20.5, 0.9), 0.2, 1e-4);
        expect_near("z = 0.6: 0.04 / (0.04 + 0.01)", pkg_lookup(&k, EDGE, 20.5, 0.6), 0.8, 1e-4);
        expect_near("z = 0.5 (the mean): lit", pkg_lookup(&k, EDGE, 20.5, 0.5), 1.0, 1e-6);
        expect_near("inside a half, z = 0.3 on it: lit", pkg_lookup(&k, 10.5, 20.5, 0.3), 1.0, 1e-6);
        /* inside the 0.3 half the variance is 0, clamped at min_variance 1e-5: a receiver 0.1 behind */
        expect_near("inside a half, z = 0.4", pkg_lookup(&k, 10.5, 20.5, 0.4), 1e-5 / (1e-5 + 0.01), 1e-4);
        pkg_set(&k, "bleed", 0.1);
        expect_near("bleed 0.1: (0.2 - 0.1) / 0.9", pkg_lookup(&k, EDGE, 20.5, 0.9), linstep(0.1, 0.2), 1e-4);
        pkg_set(&k, "bleed", 0.2);
        expect_near("bleed 0.2: 0", pkg_lookup(&k, EDGE, 20.5, 0.9), linstep(0.2, 0.2), 1e-4);
        pkg_close(&k);
    }
}

/* ESM: an occluder at 0.4 everywhere; a receiver at 0.45 gets
 * exp(-c (0.45 - 0.4)): c = 80 -> e^-4 = 0.0183156, c = 20 -> e^-1. Two
 * halves 0.3 / 0.7 filter in exponential space: at 0.72 with c = 20,
 * (e^(20 (0.3 - 0.72)) + e^(20 (0.7 - 0.72))) / 2 = 0.3352 (a depth average,
 * 0.5, would give e^-4.4 = 0.0123). Tolerance: relative 1e-4 (log and exp in
 * float32, the exponent's argument ~4 with an error of a few ulps). */
static void packages_esm_exp(void **st)
{
    (void)st;
    static const double occ[2] = {0.4, 0.4}, two[2] = {0.3, 0.7};
    struct pkg k;
    pkg_open(&k, "esm");
    pkg_upload(&k, halves, occ);
    printf("  esm (guard %d, map %d)\n", k.g, k.n);
    double want = exp(-80 * 0.05);
    expect_near("c 80, occluder 0.4, z 0.45: e^-4", pkg_lookup(&k, 20.5, 20.5, 0.45), want, 1e-4 * want);
    expect_near("c 80, z 0.4 (on it): 1", pkg_lookup(&k, 20.5, 20.5, 0.4), 1.0, 1e-4);
    expect_near("c 80, z 0.3 (in front): 1", pkg_lookup(&k, 20.5, 20.5, 0.3), 1.0, 0);
    pkg_set(&k, "c", 20);
    pkg_upload(&k, halves, occ);
    want = exp(-1.0);
    expect_near("c 20, occluder 0.4, z 0.45: e^-1", pkg_lookup(&k, 20.5, 20.5, 0.45), want, 1e-4 * want);
    pkg_upload(&k, halves, two);
    want = 0.5 * (exp(20 * (0.3 - 0.72)) + exp(20 * (0.7 - 0.72)));
    expect_near("c 20, halves 0.3 / 0.7, z 0.72", pkg_lookup(&k, EDGE, 20.5, 0.72), want, 1e-4 * want);
    /* c = 88, the top of the range: the warp's extremes stay finite, and a
     * receiver far behind a near occluder is dark, not NaN */
    pkg_set(&k, "c", 88);
    static const double near[2] = {0.0, 1.0};
    pkg_upload(&k, halves, near);
    expect_near("c 88, occluder 0, z 0.2: e^-17.6", pkg_lookup(&k, 20.5, 20.5, 0.2), exp(-88 * 0.2),
                1e-4 * exp(-88 * 0.2));
    expect_near("c 88, empty (1), z 0.99: 1", pkg_lookup(&k, 50.5, 20.5, 0.99), 1.0, 1e-4);
    pkg_close(&k);
}

/* EVSM on halves 0.3 / 0.7 at the edge: each warp's moments are the means of
 * the two warped depths; the visibility is the smaller Chebyshev bound,
 * computed here in double from the warps (w = 2z - 1). Exponents 5 / 5
 * keep the bounds away from 0 and 1, where they would test nothing. The
 * float32 moments have ~1e-7 relative error; the variances are not small
 * against the moments (no cancellation: var / E[x^2] > 0.1 here), so 1e-4. */
static double evsm_reference(double cp, double cn, int nmom, double min_var, double zr)
{
    double ep[2], en[2];
    const double z[2] = {0.3, 0.7};
    for (int i = 0; i < 2; i++)
        ep[i] = exp(cp * (2 * z[i] - 1)), en[i] = -exp(-cn * (2 * z[i] - 1));
    double w = 2 * zr - 1, xp = exp(cp * w), xn = -exp(-cn * w);
    double sp = 2 * cp * xp, sn = 2 * cn * xn;
    double p = chebyshev((ep[0] + ep[1]) / 2, (ep[0] * ep[0] + ep[1] * ep[1]) / 2, xp, min_var * sp * sp);
    if (nmom >= 4)
        p = fmin(p, chebyshev((en[0] + en[1]) / 2, (en[0] * en[0] + en[1] * en[1]) / 2, xn, min_var * sn * sn));
    return p;
}

static void packages_evsm_bound(void **st)
{
    (void)st;
    static const double a[2] = {0.3, 0.7};
    struct pkg k;
    pkg_open(&k, "evsm");
    pkg_set(&k, "positive", 5);
    pkg_set(&k, "negative", 5);
    pkg_upload(&k, halves, a);
    printf("  evsm 5/5 (guard %d, map %d)\n", k.g, k.n);
    const double zs[] = {0.55, 0.75, 0.9};
    char what[80];
    for (int i = 0; i < 3; i++) {
        double want4 = evsm_reference(5, 5, 4, 1e-6, zs[i]), want2 = evsm_reference(5, 5, 2, 1e-6, zs[i]);
        snprintf(what, sizeof what, "4 moments, z %.2f", zs[i]);
        pkg_set(&k, "moments", 4);
        expect_near(what, pkg_lookup(&k, EDGE, 20.5, zs[i]), want4, 1e-4);
        snprintf(what, sizeof what, "2 moments, z %.2f", zs[i]);
        pkg_set(&k, "moments", 2);
        expect_near(what, pkg_lookup(&k, EDGE, 20.5, zs[i]), want2, 1e-4);
    }
    /* the negative warp must be what tightens the bound somewhere, or the
     * 4-moment path is untested: at 0.55 the two differ */
    assert_true(evsm_reference(5, 5, 4, 1e-6, 0.55) < evsm_reference(5, 5, 2, 1e-6, 0.55) - 0.01);
    /* the default 40 / 5 and the largest exponents: finite, lit in front, dark far behind */
    pkg_set(&k, "moments", 4);
    pkg_set(&k, "positive", 42);
    pkg_set(&k, "negative", 42);
    pkg_upload(&k, halves, a);
    expect_near("42/42, z 0.2 (in front): 1", pkg_lookup(&k, EDGE, 20.5, 0.2), 1.0, 0);
    double far = pkg_lookup(&k, 10.5, 20.5, 0.95);
    expect_near("42/42, occluder 0.3, z 0.95: dark", far, 0.0, 1e-3);
    pkg_close(&k);
}

/* MSM on four quadrants 0.2 / 0.4 / 0.6 / 0.8 meeting at the centre: the
 * bilinear read there has the moments of four depths of weight 1/4 each,
 * a distribution the Hankel matrix sees as non-singular (4 atoms > 3), so
 * the reconstruction is well conditioned and comparable across precisions.
 * The reference is Algorithm 2 in double (msm_reference: Cramer's rule, not
 * the shader's Cholesky). Tolerance: the moments reach the shader as float32
 * after blur sums (relative error <= ~4 * 2^-24 each); the test measures
 * the reference's sensitivity to that (the largest change of G when one
 * moment moves by 1e-6 relative, ~16 ulps) and allows 4 times it, at least 1e-4. */
static void packages_msm_hamburger(void **st)
{
    (void)st;
    static const double a[4] = {0.2, 0.4, 0.6, 0.8};
    double m[4];
    moments_of(a, 4, m);
    struct pkg k;
    pkg_open(&k, "msm");
    pkg_upload(&k, quadrants, a);
    printf("  msm (guard %d, map %d), moments %.6f %.6f %.6f %.6f\n", k.g, k.n, m[0], m[1], m[2], m[3]);
    const double zs[] = {0.3, 0.5, 0.7, 0.9};
    const double alpha = 3e-5;
    for (int i = 0; i < 4; i++) {
        double G = msm_reference(m, zs[i], alpha);
        double sens = 0;
        for (int p = 0; p < 4; p++)
            for (int sgn = -1; sgn <= 1; sgn += 2) {
                double mm[4];
                memcpy(mm, m, sizeof mm);
                mm[p] *= 1 + sgn * 1e-6;
                sens = fmax(sens, fabs(msm_reference(mm, zs[i], alpha) - G));
            }
        char what[80];
        snprintf(what, sizeof what, "z %.1f: 1 - G (sensitivity %.1e)", zs[i], sens);
        expect_near(what, pkg_lookup(&k, EDGE, EDGE, zs[i]), 1 - fmin(fmax(G, 0), 1), fmax(1e-4, 4 * sens));
    }
    /* a non-trivial bound: between the atoms the reconstruction is neither 0 nor 1 */
    double G5 = msm_reference(m, 0.5, alpha);
    assert_true(G5 > 0.05 && G5 < 0.95);
    /* in front of everything: lit */
    expect_near("z 0.1 (in front of all): 1", pkg_lookup(&k, EDGE, EDGE, 0.1), 1.0, 1e-4);
    /* an empty region (all depth 1, the far plane): with the bias its moments
     * are those of depths 0 and 1, a singular Hankel matrix; a receiver in it
     * is lit, not NaN. And one depth with no bias at all: a step. */
    static const double empty[4] = {1, 1, 1, 1}, one[4] = {0.4, 0.4, 0.4, 0.4};
    pkg_upload(&k, quadrants, empty);
    expect_near("empty region, z 0.5: 1", pkg_lookup(&k, EDGE, EDGE, 0.5), 1.0, 1e-4);
    pkg_set(&k, "moment_bias", 0);
    pkg_upload(&k, quadrants, one);
    expect_near("no bias, one depth 0.4, z 0.5: 0", pkg_lookup(&k, EDGE, EDGE, 0.5), 0.0, 1e-4);
    expect_near("no bias, one depth 0.4, z 0.3: 1", pkg_lookup(&k, EDGE, EDGE, 0.3), 1.0, 1e-4);
    pkg_close(&k);
}

/* PCSS, directional: a blocker at 0.2 over the columns left of the edge, a
 * receiver plane at 0.6 (facing the light) right of it. A point 1.25 texels
 * right of the edge: the 8 x 8 search grid at offsets -3.5 .. 3.5 covers
 * columns EDGE - 3 .. EDGE + 4, finds the blocker at 0.2 (3 columns), so
 * with light_size L the penumbra is w = L (0.6 - 0.2) * depth_range texels
 * (depth_range 1 here): L = 20 gives w = 8, a PCF of radius 4 on an 8 x 8
 * grid over the same columns: 5 of 8 lit, 0.625. max_filter 3: radius 3,
 * 6 columns EDGE - 2 .. EDGE + 3, 4 lit: 0.6667. L = 0: no penumbra, the
 * receiver's own texel: lit. A point 1.75 texels left of the edge (on the
 * blocked side): columns EDGE - 6 .. EDGE + 1, 2 of 8 lit: 0.25.
 * PCF fractions of whole taps: exact (tolerance 0). */
static void packages_pcss_penumbra(void **st)
{
    (void)st;
    static const double a[2] = {0.2, 0.6};
    struct pkg k;
    pkg_open(&k, "pcss");
    pkg_set(&k, "light_size", 20);
    pkg_upload(&k, halves, a);
    printf("  pcss (guard %d, map %d)\n", k.g, k.n);
    expect_near("L 20: w 8, radius 4: 5/8", pkg_lookup(&k, EDGE + 1.25, 20.5, 0.6), 0.625, 0);
    expect_near("L 20, blocked side: 2/8", pkg_lookup(&k, EDGE - 1.75, 20.5, 0.6), 0.25, 0);
    expect_near("L 20, far from the edge: lit", pkg_lookup(&k, EDGE + 10.25, 20.5, 0.6), 1.0, 0);
    expect_near("L 20, under the blocker: dark", pkg_lookup(&k, EDGE - 10.25, 20.5, 0.6), 0.0, 0);
    pkg_set(&k, "max_filter", 3);
    expect_near("L 20, max_filter 3: 4/6", pkg_lookup(&k, EDGE + 1.25, 20.5, 0.6), 4.0 / 6.0, 1e-6);
    pkg_set(&k, "max_filter", 8);
    pkg_set(&k, "light_size", 10);   /* w = 4, radius 2: columns EDGE - 1 .. EDGE + 2 at steps of 1 */
    expect_near("L 10: w 4, radius 2: 3/4", pkg_lookup(&k, EDGE + 1.25, 20.5, 0.6), 0.75, 0);
    pkg_set(&k, "light_size", 0);
    expect_near("L 0: hard, lit", pkg_lookup(&k, EDGE + 1.25, 20.5, 0.6), 1.0, 0);
    expect_near("L 0: hard, shadowed", pkg_lookup(&k, EDGE - 1.75, 20.5, 0.6), 0.0, 0);
    pkg_close(&k);
}

/* PCSS, perspective: the light at the origin looking along +z, near 1, far
 * 10, half-width tan 0.5 (a texel at depth 1 is 1 / S world units wide). A
 * blocker at distance 2.5 left of the edge, a receiver plane at 5 right of
 * it, both as window depths d = A + B / z. Fernando's penumbra in texels of
 * the receiver, w = light_size (5 - 2.5) / (2.5 * 5) = light_size / 5:
 * light_size 40 gives w = 8, the 5/8 of the directional case; 20 gives
 * w = 4, 3/4. The shader recovers the distances from sl_light_vp alone. */
/* The light at the origin looking along +z, near 1, far 10, half-width
 * tan 0.5 (a texel at depth 1 is 1 / S world units wide). */
#define PN 1.0
#define PF 10.0
#define PT 0.5
#define PA (PF / (PF - PN))          /* window depth d = PA + PB / z */
#define PB (-PF * PN / (PF - PN))

static void persp_frame(struct pkg *k)
{
    struct sl_light_frame *f = &k->f;
    glm_mat4_zero(f->box.proj);
    f->box.proj[0][0] = f->box.proj[1][1] = (float)(1 / PT);
    f->box.proj[2][2] = (float)PA;
    f->box.proj[3][2] = (float)PB;
    f->box.proj[2][3] = 1.0f;
    glm_mat4_copy(f->box.proj, f->box.vp);
    f->box.persp = 1;
    f->box.lo[0] = f->box.lo[1] = (float)-PT;
    f->box.hi[0] = f->box.hi[1] = (float)PT;
    f->box.lo[2] = (float)PN;
    f->box.hi[2] = (float)PF;
    f->texel_world = (float)(2 * PT / S);
    f->depth_range = (float)(PF - PN);
}

/* a 4 x 2 grid of one point at distance z through frame texel (u, v) */
static double persp_lookup(struct pkg *k, double u, double v, double z)
{
    float pos[QW * QH * 3], nrm[QW * QH * 3], vis[QW * QH];
    quad_grid(0, 0, z, pos, nrm);
    for (int q = 0; q < QW * QH; q++) {
        pos[3 * q + 0] = (float)((u / S * 2 - 1) * PT * z);
        pos[3 * q + 1] = (float)((v / S * 2 - 1) * PT * z);
    }
    struct sl_diag d;
    enum sl_err e = sl_techpass_lookup(&k->p, &k->f, &k->v, pos, nrm, NULL, QW, QH, vis, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    for (int q = 1; q < QW * QH; q++)
        assert_true(vis[q] == vis[0]);
    return vis[0];
}

static void packages_pcss_perspective(void **st)
{
    (void)st;
    const double a[2] = {PA + PB / 2.5, PA + PB / 5};
    struct pkg k;
    pkg_open(&k, "pcss");
    persp_frame(&k);
    pkg_set(&k, "light_size", 40);
    pkg_upload(&k, halves, a);
    printf("  pcss perspective (guard %d, map %d), blocker %.7f, receiver %.7f\n", k.g, k.n, a[0], a[1]);
    const double us[] = {EDGE + 1.25, EDGE - 1.75, EDGE + 1.25}, ls[] = {40, 40, 20}, want[] = {0.625, 0.25, 0.75};
    for (int i = 0; i < 3; i++) {
        pkg_set(&k, "light_size", ls[i]);
        char what[80];
        snprintf(what, sizeof what, "light_size %.0f, u %.2f", ls[i], us[i]);
        expect_near(what, persp_lookup(&k, us[i], 20.5, 5), want[i], 0);
    }
    pkg_close(&k);
}

/* The filtered packages under a perspective light take their moments of the
 * distance normalised between the near and far planes, not of window depth:
 * halves at distances 3 and 7 (normalised 2/9, 6/9: mean 4/9, variance
 * 4/81), a receiver at 9 (8/9) gets VSM's 0.2 again, (4/81) / (4/81 +
 * 16/81); of window depths (0.741, 0.952, 0.988) it would be 0.36. ESM with
 * c = 20 on the same: (e^(20 (2/9 - 8/9)) + e^(20 (6/9 - 8/9))) / 2. */
static double persp_norm(double z)
{
    return (z - PN) / (PF - PN);
}

static void packages_perspective_depth(void **st)
{
    (void)st;
    /* the map holds what sl_map writes: the test gives it window depths and
     * map_texel applies the package's warp to the normalised distance */
    const double zn[2] = {persp_norm(3), persp_norm(7)};
    struct pkg k;
    pkg_open(&k, "vsm");
    persp_frame(&k);
    pkg_set(&k, "bleed", 0);
    pkg_upload(&k, halves, zn);
    printf("  vsm perspective (guard %d, map %d)\n", k.g, k.n);
    expect_near("distances 3 | 7, receiver 9", persp_lookup(&k, EDGE, 20.5, 9), 0.2, 1e-4);
    expect_near("distances 3 | 7, receiver 5 (the mean)", persp_lookup(&k, EDGE, 20.5, 5), 1.0, 1e-4);
    pkg_close(&k);
    pkg_open(&k, "esm");
    persp_frame(&k);
    pkg_set(&k, "c", 20);
    pkg_upload(&k, halves, zn);
    double want = 0.5 * (exp(20 * (zn[0] - persp_norm(9))) + exp(20 * (zn[1] - persp_norm(9))));
    expect_near("esm c 20, distances 3 | 7, receiver 9", persp_lookup(&k, EDGE, 20.5, 9), want, 1e-4 * want);
    pkg_close(&k);
}

/* pcf's depth bias off a perspective light's axis: a plane facing the light
 * (its normal toward the light) through the point at distance 5 on the ray
 * of frame texel (56, 32), 21 degrees off the axis. Along it the distance
 * along the axis falls with u, so a receiver on it at u = 56.05 lies behind
 * the depth its texel's centre stored, by 0.45 texel of the plane's slope:
 * the plain test (bias 0) shadows it, bias 1 must light it. tan of the
 * light's angle to the normal alone is about 0 there and gave it no bias
 * (acne under spot lights); the plane's own gradient does. A receiver at
 * u = 56.95 lies in front and is lit either way. */
static const double off_r0[3] = {(56.5 / S * 2 - 1) * PT, (32.5 / S * 2 - 1) * PT, 1};

/* the axis distance where the ray through frame texel coordinates (u, v)
 * meets the plane */
static double off_axis_t(double u, double v, double r[3])
{
    r[0] = (u / S * 2 - 1) * PT, r[1] = (v / S * 2 - 1) * PT, r[2] = 1;
    /* the plane: n . p = n . P0 with n along -P0, P0 = 5 r0: n . P0 = -5 |r0|^2 / |r0| */
    double l = sqrt(off_r0[0] * off_r0[0] + off_r0[1] * off_r0[1] + 1), np0 = -5 * l;
    double nr = -(off_r0[0] * r[0] + off_r0[1] * r[1] + r[2]) / l;
    return np0 / nr;
}

static double off_axis_plane(int i, int j, const void *arg)
{
    (void)arg;
    double r[3];
    return PA + PB / off_axis_t(i + 0.5, j + 0.5, r);
}

static double off_axis_lookup(struct pkg *k, double u)
{
    double r[3], t = off_axis_t(u, 32.5, r);
    const double l = sqrt(off_r0[0] * off_r0[0] + off_r0[1] * off_r0[1] + 1);
    float pos[QW * QH * 3], nrm[QW * QH * 3], vis[QW * QH];
    for (int q = 0; q < QW * QH; q++)
        for (int c = 0; c < 3; c++) {
            pos[3 * q + c] = (float)(t * r[c]);
            nrm[3 * q + c] = (float)(-off_r0[c] / l);
        }
    struct sl_diag d;
    enum sl_err e = sl_techpass_lookup(&k->p, &k->f, &k->v, pos, nrm, NULL, QW, QH, vis, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    for (int q = 1; q < QW * QH; q++)
        assert_true(vis[q] == vis[0]);
    return vis[0];
}

static void packages_pcf_off_axis(void **st)
{
    (void)st;
    struct pkg k;
    pkg_open(&k, "pcf");
    persp_frame(&k);
    pkg_set(&k, "kernel", 1);
    pkg_upload(&k, off_axis_plane, NULL);
    pkg_set(&k, "bias", 0);
    expect_near("bias 0, behind its texel's centre", off_axis_lookup(&k, 56.05), 0, 0);
    expect_near("bias 0, in front of it", off_axis_lookup(&k, 56.95), 1, 0);
    pkg_set(&k, "bias", 1);
    expect_near("bias 1 (default), behind its texel's centre", off_axis_lookup(&k, 56.05), 1, 0);
    expect_near("bias 1, in front of it", off_axis_lookup(&k, 56.95), 1, 0);
    pkg_close(&k);
}

/* Each package reads nothing beyond its guard band (reach + blur) around
 * the point's texel: the same lookup on a map whose texels farther than the
 * guard are replaced by depth 0.05 (a near occluder everywhere else) must
 * give the same visibility. The point's quad neighbours sit 24 texels away,
 * so the screen-space derivatives ask for a coarse mip level and the lookup's
 * clamp to its reach is what keeps the result. */
/* a receiver depth where the package's visibility over the noise field is
 * neither 0 nor 1 (ESM's exponential is 1 unless the receiver is behind
 * nearly everything) */
static double z_of(const char *name)
{
    return !strcmp(name, "esm") ? 0.8 : 0.55;
}

static void packages_reach(void **st)
{
    (void)st;
    static const struct {
        const char *name;
        int blur;   /* -1: none */
    } runs[] = {{"vsm", 0}, {"vsm", 1}, {"vsm", 4}, {"esm", 1}, {"esm", 8}, {"evsm", 1},
                {"evsm", 3}, {"msm", 1}, {"msm", 2}, {"pcss", -1}};
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        const char *const name = runs[i].name;
        struct pkg k;
        pkg_open(&k, name);
        if (runs[i].blur >= 0)
            pkg_set(&k, "blur", runs[i].blur);
        else
            pkg_set(&k, "light_size", 40);
        int ki = 20, kj = 21;   /* the point's frame texel */
        /* the point at grid (0, 0); its quad's other three 24 texels off in u, v or both */
        float pos[QW * QH * 3], nrm[QW * QH * 3], vis[2][QW * QH];
        quad_grid(0, 0, z_of(name), pos, nrm);
        for (int y = 0; y < QH; y++)
            for (int x = 0; x < QW; x++) {
                double u = ki + 0.3 + 24 * (x & 1), v = kj + 0.6 + 24 * y;
                pos[3 * (y * QW + x) + 0] = (float)(u / S * 2 - 1);
                pos[3 * (y * QW + x) + 1] = (float)(v / S * 2 - 1);
            }
        for (int poisoned = 0; poisoned < 2; poisoned++) {
            struct sl_diag d;
            if (poisoned)
                pkg_upload_poisoned(&k, noise, NULL, k.g, ki, kj, 0.05);   /* keep exactly the guard band */
            else
                pkg_upload(&k, noise, NULL);
            enum sl_err e = sl_techpass_lookup(&k.p, &k.f, &k.v, pos, nrm, NULL, QW, QH, vis[poisoned], &d);
            diag_print(e, &d);
            assert_int_equal(e, SL_OK);
        }
        printf("  %-5s blur %2d guard %2d: %.7f clean, %.7f with everything beyond the guard at 0.05\n", name,
               runs[i].blur, k.g, vis[0][0], vis[1][0]);
        assert_true(vis[0][0] == vis[1][0]);
        /* and the poison does change the result once it comes close (the
         * home texel alone kept): the comparison above can fail */
        pkg_upload_poisoned(&k, noise, NULL, 0, ki, kj, 0.05);
        struct sl_diag d;
        float near[QW * QH];
        assert_int_equal(sl_techpass_lookup(&k.p, &k.f, &k.v, pos, nrm, NULL, QW, QH, near, &d), SL_OK);
        assert_true(near[0] != vis[0][0]);
        pkg_close(&k);
    }
}

/* The worked example of doc/techniques.md, as printed there: its
 * technique.yaml and two GLSL blocks written into a package folder, loaded,
 * compiled and looked up. A tent-weighted 3 x 3 PCF at a texel whose left
 * column is blocked (halves 0.2 | 0.6, receiver 0.5): weights 1 2 1 / 2 4 2
 * / 1 2 1, the left column's 4 of 16 in shadow: 0.75. */
static char *doc_block(const char *text, const char *lang, int nth)
{
    char fence[32];
    snprintf(fence, sizeof fence, "```%s\n", lang);
    const char *p = text;
    for (int i = 0; i <= nth; i++) {
        p = strstr(p, fence);
        if (!p)
            return NULL;
        p += strlen(fence);
    }
    const char *end = strstr(p, "```");
    if (!end)
        return NULL;
    char *out = malloc((size_t)(end - p) + 1);
    memcpy(out, p, (size_t)(end - p));
    out[end - p] = 0;
    return out;
}

static void packages_doc_example(void **st)
{
    (void)st;
    FILE *f = fopen("doc/techniques.md", "r");
    assert_non_null(f);
    static char doc[1 << 17];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = 0;
    const char *ex = strstr(doc, "## Worked example");
    assert_non_null(ex);
    char *yaml = doc_block(ex, "yaml", 0), *map = doc_block(ex, "glsl", 0), *lookup = doc_block(ex, "glsl", 1);
    assert_true(yaml && map && lookup);
    char dir[600];
    snprintf(dir, sizeof dir, "%s/my_techniques", sl_test_dir);
    mkdir(dir, 0755);
    snprintf(dir, sizeof dir, "%s/my_techniques/my_pcf", sl_test_dir);
    mkdir(dir, 0755);
    sl_test_write(dir, "technique.yaml", yaml);
    sl_test_write(dir, "map.glsl", map);
    sl_test_write(dir, "lookup.glsl", lookup);
    free(yaml);
    free(map);
    free(lookup);
    struct pkg k;
    pkg_open_dir(&k, dir);
    assert_string_equal(k.t.name, "my_pcf");
    static const double a[2] = {0.2, 0.6};
    pkg_upload(&k, halves, a);
    expect_near("doc's my_pcf, kernel 3, left column blocked", pkg_lookup(&k, EDGE + 0.5, 20.5, 0.5), 0.75, 0);
    pkg_set(&k, "kernel", 5);   /* h = 2: columns -2, -1 blocked: (1 2 3 2 1) x (1 + 2) / 81 */
    expect_near("kernel 5, two columns blocked", pkg_lookup(&k, EDGE + 0.5, 20.5, 0.5), 1 - 3.0 * 9 / 81, 1e-6);
    pkg_close(&k);
}

/* sl_pixel, the view pixel the lookup shades: tests/techniques/pixel
 * returns 0.75 (x & 1) + 0.25 (y & 1) of it, so each of its four values
 * over an 8 x 4 grid names the pixel's column and row parity; glslang
 * compiles it as validate does. */
static void packages_pixel(void **st)
{
    (void)st;
    struct pkg k;
    pkg_open_dir(&k, "tests/techniques/pixel");
    struct sl_diag d;
    enum sl_err e = sl_techcheck(&k.t, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    static const double a[2] = {0.3, 0.7};
    pkg_upload(&k, halves, a);
    enum { W = 8, H = 4 };
    float pos[W * H * 3], nrm[W * H * 3], vis[W * H];
    for (int i = 0; i < W * H; i++) {
        pos[3 * i + 0] = pos[3 * i + 1] = 0.0f;
        pos[3 * i + 2] = 0.5f;
        nrm[3 * i + 0] = nrm[3 * i + 1] = 0.0f;
        nrm[3 * i + 2] = -1.0f;
    }
    e = sl_techpass_lookup(&k.p, &k.f, &k.v, pos, nrm, NULL, W, H, vis, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float want = 0.75f * (float)(x & 1) + 0.25f * (float)(y & 1);
            if (vis[y * W + x] != want)
                fprintf(stderr, "pixel (%d, %d): %.9g, not %.9g\n", x, y, vis[y * W + x], want);
            assert_true(vis[y * W + x] == want);
        }
    printf("    sl_pixel: 0.75 (x & 1) + 0.25 (y & 1) at each of %d x %d pixels\n", W, H);
    pkg_close(&k);
}

/* The packages on real scenes against the ray-traced truth: Primitives
 * under its directional light and under a spot light (the perspective
 * path), a 1024 map, every PFL pixel's hard verdict (visibility >= 0.5)
 * compared with the truth and with NSM's on the same frame (the C depth layer
 * with front faces culled, Moderno's default policy; without culling or a
 * bias NSM self-shadows half the lit pixels). The filtered packages soften edges and may
 * lose thin shadows but must neither self-shadow lit surfaces wholesale nor
 * light shadowed ones: each must be wrong on at most 2 % of the PFL pixels
 * more than NSM (the numbers are printed), and every visibility is finite. */
static void packages_rendered(void **st)
{
    (void)st;
    gl_close();
    static const char *const scenes[] = {"scenes/primitives.yaml", "scenes/primitives_spot.yaml"};
    static const char *const names[] = {"vsm", "esm", "evsm", "msm", "pcss"};
    for (int si = 0; si < 2; si++) {
        struct fixture fx;
        assert_true(fixture_open(&fx, scenes[si], 2));
        struct sl_view v;
        assert_true(fixture_view(&fx, 0, 256, 192, &v));
        struct sl_diag d;
        struct sl_light_frame fr;
        memset(&fr, 0, sizeof fr);
        fr.size = 1024;
        memcpy(fr.dir, fx.scene.light_dir, sizeof fr.dir);
        sl_light_fit(&fx.scene, &v, &fr.box);
        fr.texel_world = fmaxf(fr.box.hi[0] - fr.box.lo[0], fr.box.hi[1] - fr.box.lo[1]) / (float)fr.size;
        fr.depth_range = fr.box.hi[2] - fr.box.lo[2];
        struct sl_shadowmap_pass sp;
        assert_int_equal(sl_shadowmap_init(&sp, &d), SL_OK);
        assert_int_equal(sl_shadowmap_render(&sp, &fx.mesh, &fr, SL_NEED(SL_LAYER_DEPTH_ID_BACK), &d), SL_OK);
        const size_t n = (size_t)v.w * (size_t)v.h;
        uint8_t *mask = malloc(n);
        float *vis = malloc(n * sizeof *vis);
        assert_true(mask && vis);
        size_t pfl = 0, nsm_wrong = 0;
        const float *depth = fr.layer[SL_LAYER_DEPTH_ID_BACK].depth;
        for (size_t i = 0; i < n; i++) {
            mask[i] = v.cls[i] == SL_C_PFL;
            if (!mask[i])
                continue;
            pfl++;
            float u, w, z;
            sl_frame_project(&fr, v.pos + 3 * i, &u, &w, &z);
            nsm_wrong += (z <= depth[sl_frame_texel(&fr, u, w)]) != (v.truth[i] == SL_T_LIT);
        }
        printf("  %s: %zu PFL pixels (%llu lit, %llu shadowed); nsm (front faces culled) wrong %zu (%.2f %%)\n", scenes[si], pfl,
               (unsigned long long)v.n_lit, (unsigned long long)v.n_shadow, nsm_wrong, 100.0 * nsm_wrong / pfl);
        assert_true(v.n_lit > 500 && v.n_shadow > 500);
        for (int pi = 0; pi < 5; pi++) {
            struct pkg k;
            memset(&k, 0, sizeof k);
            char dir[300];
            snprintf(dir, sizeof dir, "techniques/%s", names[pi]);
            assert_int_equal(sl_tech_load(dir, &k.t, &d), SL_OK);
            sl_tech_defaults(&k.t, &k.v);
            enum sl_err e = sl_techpass_init(&k.p, &k.t, &d);
            if (!e)
                e = sl_techpass_render(&k.p, &fx.mesh, &fr, &k.v, &d);
            if (!e)
                e = sl_techpass_lookup(&k.p, &fr, &k.v, v.pos, v.nrm, mask, v.w, v.h, vis, &d);
            diag_print(e, &d);
            assert_int_equal(e, SL_OK);
            size_t wrong = 0, lit_s = 0, shadow_l = 0, bad = 0, soft = 0;
            for (size_t i = 0; i < n; i++) {
                if (!mask[i])
                    continue;
                bad += !(vis[i] >= 0.0f && vis[i] <= 1.0f);
                soft += vis[i] > 0.0f && vis[i] < 1.0f;
                int lit = vis[i] >= (float)k.t.threshold, t_lit = v.truth[i] == SL_T_LIT;
                wrong += lit != t_lit;
                lit_s += lit && !t_lit;
                shadow_l += !lit && t_lit;
            }
            printf("    %-5s wrong %5zu (%5.2f %%: %zu lit in shadow, %zu shadowed in light), %zu soft, map %d, "
                   "map %.1f ms, post %.1f ms, lookup %.1f ms\n",
                   names[pi], wrong, 100.0 * wrong / pfl, lit_s, shadow_l, soft, k.p.costs.map_size, k.p.costs.ms_map,
                   k.p.costs.ms_post, k.p.costs.ms_lookup);
            assert_int_equal(bad, 0);
            assert_true(wrong <= nsm_wrong + pfl / 50);
            sl_techpass_free(&k.p);
            sl_tech_free(&k.t);
        }
        free(mask);
        free(vis);
        sl_shadowmap_free(&sp);
        sl_light_box_free(&fr.box);
        sl_frame_free(&fr);
        sl_view_free(&v);
        fixture_close(&fx);
    }
}

/* One package method run as the driver runs it (methods/package.c: maps,
 * lookup, verdicts, and a hybrid's traced band), the truth hidden from it. */
static void method_run(struct fixture *fx, const struct sl_view *v, const struct sl_light_frame *fr,
                       const struct sl_method *m, struct sl_verdicts *vd, struct sl_cost *c)
{
    struct sl_method_params p;
    struct sl_diag d;
    sl_method_params_init(m, &p);
    p.tech = sl_package_of(m);
    assert_non_null(p.tech);
    assert_int_equal(sl_method_configure(m, &p, &d), SL_OK);
    struct sl_view mv = *v;
    mv.truth = NULL;
    struct sl_method_args a = {.scene = &fx->scene, .view = &mv, .frame = fr, .params = &p, .rt = &fx->rt,
                               .mesh = &fx->mesh, .threads = 2};
    const size_t n = (size_t)v->w * (size_t)v->h;
    memset(vd, 0, sizeof *vd);
    vd->w = v->w;
    vd->h = v->h;
    vd->v = calloc(n, 1);
    vd->how = calloc(n, 1);
    vd->base = calloc(n, 1);
    vd->detail = calloc(n, 1);
    vd->tests = calloc(n, 1);
    vd->vis = calloc(n, sizeof *vd->vis);
    assert_true(vd->v && vd->how && vd->base && vd->detail && vd->tests && vd->vis);
    memset(c, 0, sizeof *c);
    enum sl_err e = m->run(&a, vd, c, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    assert_int_equal(vd->has_vis, 1);
}

static void verdicts_free(struct sl_verdicts *vd)
{
    free(vd->v);
    free(vd->how);
    free(vd->base);
    free(vd->detail);
    free(vd->tests);
    free(vd->vis);
}

/* vsm_rt (vsm with `trace: {between: [lo, hi]}`) beside vsm on the
 * primitives: each PFL pixel whose vsm visibility lies in the band is
 * traced, one ray each, and equals the truth (verdict, and visibility 0 or
 * 1); every other pixel is vsm's; so its wrong pixels are at most vsm's,
 * and it traces some pixels but not all. */
static void packages_traced(void **st)
{
    (void)st;
    gl_close();
    struct fixture fx;
    assert_true(fixture_open(&fx, "scenes/primitives.yaml", 2));
    struct sl_view v;
    assert_true(fixture_view(&fx, 0, 256, 192, &v));
    struct sl_light_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.size = 1024;
    memcpy(fr.dir, fx.scene.light_dir, sizeof fr.dir);
    sl_light_fit(&fx.scene, &v, &fr.box);
    fr.texel_world = fmaxf(fr.box.hi[0] - fr.box.lo[0], fr.box.hi[1] - fr.box.lo[1]) / (float)fr.size;
    fr.depth_range = fr.box.hi[2] - fr.box.lo[2];
    struct sl_packages set = {0};
    struct sl_diag d;
    enum sl_err e = sl_packages_load(&set, NULL, 0, NULL, NULL, &d);
    diag_print(e, &d);
    assert_int_equal(e, SL_OK);
    const struct sl_method *plain = sl_packages_find(&set, "vsm"), *hybrid = sl_packages_find(&set, "vsm_rt");
    assert_true(plain && hybrid);
    const struct sl_technique *t = sl_package_of(hybrid);
    assert_int_equal(t->trace, 1);
    assert_int_equal(sl_package_of(plain)->trace, 0);
    assert_int_equal(plain->exact, 0);
    assert_int_equal(hybrid->exact, SL_EXACT_PROVED);
    struct sl_verdicts a, b;
    struct sl_cost ca, cb;
    method_run(&fx, &v, &fr, plain, &a, &ca);
    method_run(&fx, &v, &fr, hybrid, &b, &cb);
    const size_t n = (size_t)v.w * (size_t)v.h;
    size_t pfl = 0, band = 0, wrong_a = 0, wrong_b = 0, off = 0;
    for (size_t i = 0; i < n; i++) {
        if (v.cls[i] != SL_C_PFL)
            continue;
        pfl++;
        const int t_lit = v.truth[i] == SL_T_LIT;
        wrong_a += (a.v[i] == SL_V_LIT) != t_lit;
        wrong_b += (b.v[i] == SL_V_LIT) != t_lit;
        if (a.vis[i] >= (float)t->trace_lo && a.vis[i] <= (float)t->trace_hi) {
            band++;
            off += b.how[i] != SL_HOW_TRACED || (b.v[i] == SL_V_LIT) != t_lit || b.vis[i] != (t_lit ? 1.0f : 0.0f);
        } else {
            off += b.how[i] != a.how[i] || b.v[i] != a.v[i] || b.vis[i] != a.vis[i];
        }
    }
    printf("  %zu PFL pixels: vsm wrong %zu (%.2f %%), vsm_rt wrong %zu (%.2f %%), band [%g, %g] %zu pixels, "
           "%llu rays (%.1f %% of the PFL pixels), trace %.1f ms\n",
           pfl, wrong_a, 100.0 * wrong_a / pfl, wrong_b, 100.0 * wrong_b / pfl, t->trace_lo, t->trace_hi, band,
           (unsigned long long)cb.rays, 100.0 * cb.rays / pfl, cb.ms_trace);
    assert_int_equal(off, 0);
    assert_int_equal(ca.rays, 0);
    assert_true(cb.rays > 0 && cb.rays < pfl);
    assert_int_equal(cb.rays, band);
    assert_true(cb.ms_trace > 0.0 && cb.ms_method >= cb.ms_trace);
    assert_true(wrong_b <= wrong_a);
    assert_true(wrong_a > 0 && wrong_b < wrong_a);   /* the band holds some of vsm's wrong pixels */
    verdicts_free(&a);
    verdicts_free(&b);
    sl_packages_release_gl(&set);
    sl_packages_free(&set);
    sl_light_box_free(&fr.box);
    sl_frame_free(&fr);
    sl_view_free(&v);
    fixture_close(&fx);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(packages, load),
        SL_CASE(packages, vsm_chebyshev),
        SL_CASE(packages, esm_exp),
        SL_CASE(packages, evsm_bound),
        SL_CASE(packages, msm_hamburger),
        SL_CASE(packages, pcss_penumbra),
        SL_CASE(packages, pcss_perspective),
        SL_CASE(packages, perspective_depth),
        SL_CASE(packages, reach),
        SL_CASE(packages, rendered),
        SL_CASE(packages, traced),
        SL_CASE(packages, doc_example),
        SL_CASE(packages, pixel),
        SL_CASE(packages, pcf_off_axis),
    };
    return sl_run_group(argc, argv, "packages", tests, sl_test_setup, group_teardown);
}
