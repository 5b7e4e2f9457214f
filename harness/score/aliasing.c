/*
 * aliasing.c — see aliasing.h. Invariant: every footprint is computed in
 * double from the inverse of the float matrices the renderer used, so m is
 * the same on every thread count (each pixel's is computed alone).
 */
#include "aliasing.h"
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include "contour.h"

static const char *const afig_name[] = {
#define F(name, text, of) #name,
    SL_ALIAS_FIGURES(F)
#undef F
};
static const char *const afig_text[] = {
#define F(name, text, of) text,
    SL_ALIAS_FIGURES(F)
#undef F
};
static const char *const afig_of[] = {
#define F(name, text, of) of,
    SL_ALIAS_FIGURES(F)
#undef F
};

const char *sl_alias_figure_name(enum sl_alias_figure f) { return afig_name[f]; }
const char *sl_alias_figure_text(enum sl_alias_figure f) { return afig_text[f]; }
const char *sl_alias_figure_of(enum sl_alias_figure f) { return afig_of[f]; }

int sl_alias_figure_parse(const char *name)
{
    for (int k = 0; k < SL_AFIG_COUNT; k++)
        if (strcmp(afig_name[k], name) == 0)
            return k;
    return -1;
}

/* A view-projection in double, with its inverse, over a window of w x h. */
struct beam {
    double vp[16], inv[16];   /* column-major, as cglm */
    int    w, h;
    int    ok;                /* the matrix is invertible */
    int    parallel;          /* every beam runs along dir (orthographic, or a directional
                               * light's warped frame); else they meet at eye */
    double dir[3], eye[3];
};

/* Gauss-Jordan with partial pivoting; returns 0 if singular. */
static int invert4(const double m[16], double out[16])
{
    double a[4][8];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            a[r][c] = m[c * 4 + r];
            a[r][c + 4] = r == c;
        }
    for (int c = 0; c < 4; c++) {
        int piv = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(a[r][c]) > fabs(a[piv][c]))
                piv = r;
        if (!(fabs(a[piv][c]) > 0.0))
            return 0;
        if (piv != c)
            for (int k = 0; k < 8; k++) {
                double t = a[c][k];
                a[c][k] = a[piv][k];
                a[piv][k] = t;
            }
        double s = 1.0 / a[c][c];
        for (int k = 0; k < 8; k++)
            a[c][k] *= s;
        for (int r = 0; r < 4; r++)
            if (r != c && a[r][c] != 0.0) {
                double f = a[r][c];
                for (int k = 0; k < 8; k++)
                    a[r][k] -= f * a[c][k];
            }
    }
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            out[c * 4 + r] = a[r][c + 4];
    return 1;
}

static void beam_init(struct beam *b, const mat4 vp, int w, int h)
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            b->vp[c * 4 + r] = vp[c][r];
    b->w = w;
    b->h = h;
    b->ok = invert4(b->vp, b->inv);
    /* the centre of projection: inv (0, 0, 1, 0), the point whose X, Y and W
     * vanish; at infinity (w = 0 up to rounding) the beams are parallel */
    const double *c = b->inv + 8;
    double scale = fabs(c[0]) + fabs(c[1]) + fabs(c[2]);
    b->parallel = !(fabs(c[3]) > 1e-12 * scale);
    for (int k = 0; k < 3; k++) {
        b->dir[k] = c[k];
        b->eye[k] = b->parallel ? 0.0 : c[k] / c[3];
    }
}

/* Where the edge beam through the point q (on the beam, at the surface
 * point's window depth) meets the plane (p, n): the beam runs through q and
 * the centre of projection (b->eye, or along b->dir for parallel beams);
 * 0 if it runs parallel to the plane or meets it behind the eye. */
static int beam_hit(const struct beam *b, const double q[3], const double p[3], const double n[3], double hit[3])
{
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = b->parallel ? b->dir[k] : q[k] - b->eye[k];
    double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (!(fabs(dn) > 1e-300))
        return 0;
    double t = ((p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] + (p[2] - q[2]) * n[2]) / dn;
    if (!b->parallel && !(1.0 + t > 0.0))
        return 0;   /* hit = eye + (1 + t)(q - eye): behind the eye */
    for (int k = 0; k < 3; k++)
        hit[k] = q[k] + t * d[k];
    return isfinite(hit[0]) && isfinite(hit[1]) && isfinite(hit[2]);
}

/* The spans at p: the window point of p moved by half a pixel (texel) in x
 * or y at p's own clip depth is, in homogeneous world coordinates,
 * (p, 1) +- (w_p / w) inv[:, 0] (or / h, inv[:, 1]); its edge beam joins it
 * to the centre of projection inv[:, 2] (the point with X = Y = W = 0). */
static int beam_spans(const struct beam *b, const float pf[3], const float nf[3], double a[3], double bb[3])
{
    if (!b->ok)
        return 0;
    double p[3] = {pf[0], pf[1], pf[2]}, n[3] = {nf[0], nf[1], nf[2]};
    const double *m = b->vp;
    double wp = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    if (!(fabs(wp) > 0.0))
        return 0;
    double hit[4][3];
    for (int e = 0; e < 4; e++) {
        const double *col = b->inv + (e < 2 ? 0 : 4);
        double s = (e % 2 ? -1.0 : 1.0) * wp / (e < 2 ? b->w : b->h);
        double r = 1.0 / (1.0 + s * col[3]), q[3];
        for (int k = 0; k < 3; k++)
            q[k] = (p[k] + s * col[k]) * r;
        if (!beam_hit(b, q, p, n, hit[e]))
            return 0;
    }
    for (int k = 0; k < 3; k++) {
        a[k] = hit[0][k] - hit[1][k];
        bb[k] = hit[2][k] - hit[3][k];
    }
    return 1;
}

int sl_alias_spans(const mat4 vp, int w, int h, const float p[3], const float nrm[3], double a[3], double b[3])
{
    struct beam bm;
    beam_init(&bm, vp, w, h);
    return beam_spans(&bm, p, nrm, a, b);
}

/* m from the two pairs of spans in the plane with unit normal n. */
static double m_of_spans(int cam_ok, const double ac[3], const double bc[3], int lit_ok, const double al[3],
                         const double bl[3], const float nf[3])
{
    if (!cam_ok && !lit_ok)
        return NAN;
    if (!lit_ok)
        return INFINITY;
    if (!cam_ok)
        return 0.0;
    /* an orthonormal basis of the plane */
    double n[3] = {nf[0], nf[1], nf[2]}, t[3] = {0, 0, 0}, e1[3], e2[3];
    int ax = fabs(n[0]) <= fabs(n[1]) && fabs(n[0]) <= fabs(n[2]) ? 0 : fabs(n[1]) <= fabs(n[2]) ? 1 : 2;
    t[ax] = 1.0;
    e1[0] = n[1] * t[2] - n[2] * t[1];
    e1[1] = n[2] * t[0] - n[0] * t[2];
    e1[2] = n[0] * t[1] - n[1] * t[0];
    double l = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; k++)
        e1[k] /= l;
    e2[0] = n[1] * e1[2] - n[2] * e1[1];
    e2[1] = n[2] * e1[0] - n[0] * e1[2];
    e2[2] = n[0] * e1[1] - n[1] * e1[0];
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
    double C[2][2] = {{DOT(ac, e1), DOT(bc, e1)}, {DOT(ac, e2), DOT(bc, e2)}};
    double L[2][2] = {{DOT(al, e1), DOT(bl, e1)}, {DOT(al, e2), DOT(bl, e2)}};
#undef DOT
    double det = C[0][0] * C[1][1] - C[0][1] * C[1][0];
    if (!(fabs(det) > 0.0))
        return INFINITY;   /* the pixel's footprint is degenerate: edge-on */
    double Ci[2][2] = {{C[1][1] / det, -C[0][1] / det}, {-C[1][0] / det, C[0][0] / det}};
    double T[2][2];
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < 2; c++)
            T[r][c] = Ci[r][0] * L[0][c] + Ci[r][1] * L[1][c];
    double s = T[0][0] * T[0][0] + T[0][1] * T[0][1] + T[1][0] * T[1][0] + T[1][1] * T[1][1];
    double dt = T[0][0] * T[1][1] - T[0][1] * T[1][0];
    double disc = s * s - 4.0 * dt * dt;
    return sqrt(0.5 * (s + sqrt(disc > 0.0 ? disc : 0.0)));
}

static float m_pixel(const struct beam *cam, const struct beam *lit, const float p[3], const float nrm[3])
{
    double ac[3], bc[3], al[3], bl[3];
    int okc = beam_spans(cam, p, nrm, ac, bc), okl = beam_spans(lit, p, nrm, al, bl);
    return (float)m_of_spans(okc, ac, bc, okl, al, bl, nrm);
}

double sl_alias_m(const mat4 cam_vp, int cw, int ch, const mat4 light_vp, int size, const float p[3],
                  const float nrm[3])
{
    struct beam c, l;
    beam_init(&c, cam_vp, cw, ch);
    beam_init(&l, light_vp, size, size);
    double ac[3], bc[3], al[3], bl[3];
    int okc = beam_spans(&c, p, nrm, ac, bc), okl = beam_spans(&l, p, nrm, al, bl);
    return m_of_spans(okc, ac, bc, okl, al, bl, nrm);
}

/* The same m for SL_ALIAS_LANES pixels at once, in GCC's generic vectors:
 * every lane does the scalar code's operations in the scalar code's order
 * (IEEE division and square root are exact-rounded per lane, and this file
 * is built with -ffp-contract=off, CMakeLists.txt), so each pixel's m is
 * bit for bit the scalar one (aliasing::image_lanes_match). The early
 * returns become lane masks: a failed lane computes on and is discarded.
 * Per pixel m is some twenty dependent divisions and square roots; in
 * lanes they overlap (m was 13% of the Morais study's CPU). */
#define SL_ALIAS_LANES 8
typedef double vd_t __attribute__((vector_size(8 * SL_ALIAS_LANES)));
typedef int64_t vl_t __attribute__((vector_size(8 * SL_ALIAS_LANES)));

#define VSEL(m, a, b) ((vd_t)(((vl_t)(a) & (m)) | ((vl_t)(b) & ~(m))))
#define VABS(x) ((vd_t)((vl_t)(x) & INT64_MAX))
/* isfinite: NAN compares false */
#define VFINITE(x) (VABS(x) <= DBL_MAX)

static inline __attribute__((always_inline)) vl_t vbeam_hit(const struct beam *b, const vd_t q[3], const vd_t p[3],
                                                          const vd_t n[3], vd_t hit[3])
{
    vd_t d[3];
    for (int k = 0; k < 3; k++)
        d[k] = b->parallel ? (vd_t){0} + b->dir[k] : q[k] - b->eye[k];
    vd_t dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    vl_t ok = VABS(dn) > 1e-300;
    vd_t t = ((p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] + (p[2] - q[2]) * n[2]) / dn;
    if (!b->parallel)
        ok &= 1.0 + t > 0.0;
    for (int k = 0; k < 3; k++) {
        hit[k] = q[k] + t * d[k];
        ok &= VFINITE(hit[k]);
    }
    return ok;
}

static inline __attribute__((always_inline)) vl_t vbeam_spans(const struct beam *b, const vd_t p[3], const vd_t n[3],
                                                            vd_t a[3], vd_t bb[3])
{
    if (!b->ok) {
        for (int k = 0; k < 3; k++)
            a[k] = bb[k] = (vd_t){0};
        return (vl_t){0};
    }
    const double *m = b->vp;
    vd_t wp = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    vl_t ok = VABS(wp) > 0.0;
    vd_t hit[4][3];
    /* Two divisions fewer than the scalar code, the same bits: an odd
     * edge's s is (-wp) / w, which IEEE division makes exactly -(wp / w);
     * and where the column's w term is 0 (an orthographic frame: a
     * directional light's), r is 1 / (1 + s 0) = 1 exactly for a finite s,
     * and a non-finite s fails the edge either way (its hit is not finite),
     * so q is p + s col as it stands. Eight of some thirty divisions a
     * pixel (aliasing::image_lanes_match checks the bits). */
    vd_t sx = wp / (double)b->w, sy = wp / (double)b->h;
    for (int e = 0; e < 4; e++) {
        const double *col = b->inv + (e < 2 ? 0 : 4);
        vd_t s = e == 0 ? sx : e == 1 ? -sx : e == 2 ? sy : -sy, q[3];
        if (col[3] == 0.0) {
            for (int k = 0; k < 3; k++)
                q[k] = p[k] + s * col[k];
        } else {
            vd_t r = 1.0 / (1.0 + s * col[3]);
            for (int k = 0; k < 3; k++)
                q[k] = (p[k] + s * col[k]) * r;
        }
        ok &= vbeam_hit(b, q, p, n, hit[e]);
    }
    for (int k = 0; k < 3; k++) {
        a[k] = hit[0][k] - hit[1][k];
        bb[k] = hit[2][k] - hit[3][k];
    }
    return ok;
}

static inline __attribute__((always_inline)) vd_t vsqrt(vd_t x)
{
    vd_t r;
    for (int l = 0; l < SL_ALIAS_LANES; l++)
        r[l] = sqrt(x[l]);
    return r;
}

/* m_of_spans, lane by lane */
static inline __attribute__((always_inline)) vd_t vm_of_spans(vl_t cam_ok, const vd_t ac[3], const vd_t bc[3],
                                                            vl_t lit_ok, const vd_t al[3], const vd_t bl[3],
                                                            const vd_t n[3])
{
    vd_t a0 = VABS(n[0]), a1 = VABS(n[1]), a2 = VABS(n[2]);
    vl_t x0 = (a0 <= a1) & (a0 <= a2), x1 = ~x0 & (a1 <= a2), x2 = ~x0 & ~x1;
    vd_t one = (vd_t){0} + 1.0, zero = (vd_t){0};
    vd_t t[3] = {VSEL(x0, one, zero), VSEL(x1, one, zero), VSEL(x2, one, zero)}, e1[3], e2[3];
    e1[0] = n[1] * t[2] - n[2] * t[1];
    e1[1] = n[2] * t[0] - n[0] * t[2];
    e1[2] = n[0] * t[1] - n[1] * t[0];
    vd_t l = vsqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; k++)
        e1[k] /= l;
    e2[0] = n[1] * e1[2] - n[2] * e1[1];
    e2[1] = n[2] * e1[0] - n[0] * e1[2];
    e2[2] = n[0] * e1[1] - n[1] * e1[0];
#define DOT(u, v) ((u)[0] * (v)[0] + (u)[1] * (v)[1] + (u)[2] * (v)[2])
    vd_t C00 = DOT(ac, e1), C01 = DOT(bc, e1), C10 = DOT(ac, e2), C11 = DOT(bc, e2);
    vd_t L00 = DOT(al, e1), L01 = DOT(bl, e1), L10 = DOT(al, e2), L11 = DOT(bl, e2);
#undef DOT
    vd_t det = C00 * C11 - C01 * C10;
    vl_t flat = ~(VABS(det) > 0.0);
    vd_t I00 = C11 / det, I01 = -C01 / det, I10 = -C10 / det, I11 = C00 / det;
    vd_t T00 = I00 * L00 + I01 * L10, T01 = I00 * L01 + I01 * L11;
    vd_t T10 = I10 * L00 + I11 * L10, T11 = I10 * L01 + I11 * L11;
    vd_t s = T00 * T00 + T01 * T01 + T10 * T10 + T11 * T11;
    vd_t dt = T00 * T11 - T01 * T10;
    vd_t disc = s * s - 4.0 * dt * dt;
    vd_t m = vsqrt(0.5 * (s + vsqrt(VSEL(disc > 0.0, disc, zero))));
    vd_t inf = zero + INFINITY;
    m = VSEL(flat, inf, m);
    m = VSEL(cam_ok, m, zero);                  /* !cam_ok: 0 */
    m = VSEL(lit_ok, m, inf);                   /* !lit_ok: infinite */
    return VSEL(cam_ok | lit_ok, m, zero + NAN);
}

/* m of the SL_ALIAS_LANES pixels from i (all inside the image) under one
 * light beam; NAN where not PFL. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
static void alias_lanes(const struct sl_view *v, const struct beam *cam, const struct beam *lit, long i, float *m)
{
    vd_t p[3], n[3];
    for (int l = 0; l < SL_ALIAS_LANES; l++)
        for (int k = 0; k < 3; k++) {
            p[k][l] = v->pos[3 * (i + l) + k];
            n[k][l] = v->nrm[3 * (i + l) + k];
        }
    vd_t ac[3], bc[3], al[3], bl[3];
    vl_t okc = vbeam_spans(cam, p, n, ac, bc), okl = vbeam_spans(lit, p, n, al, bl);
    vd_t r = vm_of_spans(okc, ac, bc, okl, al, bl, n);
    for (int l = 0; l < SL_ALIAS_LANES; l++)
        m[i + l] = v->cls[i + l] == SL_C_PFL ? (float)r[l] : NAN;
}

#define SL_ALIAS_MAX_FRAMES 16

void sl_alias_image(const struct sl_view *v, const struct sl_light_frame *f, const struct sl_verdicts *vd,
                    int threads, float *m)
{
    mat4 cvp;
    glm_mat4_mul((vec4 *)v->proj, (vec4 *)v->view, cvp);
    struct beam cam, lit[SL_ALIAS_MAX_FRAMES];
    beam_init(&cam, cvp, v->w, v->h);
    int nf = vd && vd->nframes > 0 ? vd->nframes : 1;
    if (nf > SL_ALIAS_MAX_FRAMES)
        nf = SL_ALIAS_MAX_FRAMES;
    for (int k = 0; k < nf; k++) {
        const struct sl_light_frame *fk = vd && vd->nframes > 0 ? &vd->frames[k] : f;
        beam_init(&lit[k], (vec4 *)fk->box.vp, fk->size, fk->size);
        lit[k].ok &= fk->size > 0;
    }
    const long n = (long)v->w * v->h;
    const uint8_t *slice = vd && vd->nframes > 0 ? vd->slice : NULL;
    if (!slice) {
        /* one light frame for every pixel: in lanes, the tail alone */
        const long nb = n / SL_ALIAS_LANES;
#pragma omp parallel for num_threads(threads > 0 ? threads : omp_get_max_threads()) schedule(static)
        for (long b = 0; b < nb; b++)
            alias_lanes(v, &cam, &lit[0], b * SL_ALIAS_LANES, m);
        for (long i = nb * SL_ALIAS_LANES; i < n; i++) {
            if (v->cls[i] != SL_C_PFL) {
                m[i] = NAN;
                continue;
            }
            m[i] = m_pixel(&cam, &lit[0], v->pos + 3 * i, v->nrm + 3 * i);
        }
        return;
    }
#pragma omp parallel for num_threads(threads > 0 ? threads : omp_get_max_threads()) schedule(static)
    for (long i = 0; i < n; i++) {
        int s = slice ? slice[i] : 0;
        if (v->cls[i] != SL_C_PFL || s >= nf) {
            m[i] = NAN;
            continue;
        }
        m[i] = m_pixel(&cam, &lit[s], v->pos + 3 * i, v->nrm + 3 * i);
    }
}

const float *sl_alias_cached(struct sl_alias_cache *c, const struct sl_view *v, const struct sl_light_frame *f,
                             int threads)
{
    size_t n = (size_t)v->w * (size_t)v->h;
    if (c->m && c->serial == v->serial && c->size == f->size && !memcmp(c->vp, f->box.vp, sizeof c->vp))
        return c->m;
    if (c->cap < n) {
        free(c->m);
        c->cap = 0;
        c->serial = 0;
        if (!(c->m = malloc(n * sizeof *c->m)))
            return NULL;
        c->cap = n;
    }
    sl_alias_image(v, f, NULL, threads, c->m);
    c->gen++;
    c->serial = v->serial;
    c->size = f->size;
    memcpy(c->vp, f->box.vp, sizeof c->vp);
    return c->m;
}

void sl_alias_cache_free(struct sl_alias_cache *c)
{
    free(c->m);
    free(c->band);
    memset(c, 0, sizeof *c);
}

/* A float's bits as a key whose unsigned order is the floats' order (NAN
 * excluded; -0 sorts before +0, which compare equal and give one value). */
static inline uint32_t fkey(float x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return u & 0x80000000u ? ~u : u | 0x80000000u;
}

static inline float fval(uint32_t k)
{
    uint32_t u = k & 0x80000000u ? k & 0x7fffffffu : ~k;
    float x;
    memcpy(&x, &u, sizeof x);
    return x;
}

/* The k-th smallest of the n values x (0-based, k < n, none NAN): a radix
 * select in two passes of 16-bit histograms, linear time whatever the
 * values (a sort was a fifth of the Morais study's CPU time). hist: 65536
 * counters of scratch. */
static float kth(const float *x, size_t n, size_t k, uint64_t *hist)
{
    memset(hist, 0, 65536 * sizeof *hist);
    for (size_t i = 0; i < n; i++)
        hist[fkey(x[i]) >> 16]++;
    uint32_t hi = 0;
    while (k >= hist[hi])
        k -= hist[hi++];
    memset(hist, 0, 65536 * sizeof *hist);
    for (size_t i = 0; i < n; i++) {
        uint32_t q = fkey(x[i]);
        if (q >> 16 == hi)
            hist[q & 0xffffu]++;
    }
    uint32_t lo = 0;
    while (k >= hist[lo])
        k -= hist[lo++];
    return fval(hi << 16 | lo);
}

/* The median of the first n values; 0 when n = 0. Even n: the mean of the
 * two middle values. NULL hist (no scratch): 0. */
static double median(const float *x, size_t n, uint64_t *hist)
{
    if (n == 0 || !hist)
        return 0.0;
    return n % 2 ? (double)kth(x, n, n / 2, hist)
                 : 0.5 * ((double)kth(x, n, n / 2 - 1, hist) + (double)kth(x, n, n / 2, hist));
}

static uint64_t milli(double m)
{
    if (!(m >= 0.0))
        return 0;
    double r = floor(m * 1000.0 + 0.5);
    return r >= 9e15 ? (uint64_t)9e15 : (uint64_t)r;   /* an infinite median stays a storable count */
}

/* The figures of the PFL pixels, whatever the verdicts: per region the
 * count of PFL pixels, those by band of m, those without m, and the median
 * m. hist: 65536 counters; all: w*h floats of scratch (NULL: no median). */
static void pfl_side(const struct sl_view *v, const float *m, const uint8_t *band, const int *thickness,
                     int nregions, uint64_t n[][SL_AFIG_COUNT], uint64_t *pfl, float *all, uint64_t *hist)
{
    size_t npx = (size_t)v->w * (size_t)v->h;
    for (int r = 0; r < nregions; r++) {
        uint64_t *c = n[r];
        size_t na = 0;
        pfl[r] = 0;
        for (size_t i = 0; i < npx; i++) {
            if (v->cls[i] != SL_C_PFL || !sl_in_contour(band[i], thickness[r]))
                continue;
            pfl[r]++;
            if (isnan(m[i])) {
                c[SL_AFIG_m_none]++;
                continue;
            }
            c[SL_AFIG_px_m_le1 + sl_alias_band(m[i])]++;
            if (all)
                all[na++] = m[i];
        }
        /* without scratch memory no median is claimed (0) */
        c[SL_AFIG_m_median_milli] = all ? milli(median(all, na, hist)) : 0;
    }
}

/* The wrong pixels' figures: per region their count, by band of m, and
 * their median m. One pass gathers the wrong PFL pixels (a few in a
 * hundred), the regions then count over those alone. hist NULL: no medians. */
static void wrong_side(const struct sl_view *v, const struct sl_verdicts *vd, const float *m, const uint8_t *band,
                       const int *thickness, int nregions, uint64_t n[][SL_AFIG_COUNT], uint64_t *wrong,
                       uint64_t *hist)
{
    size_t npx = (size_t)v->w * (size_t)v->h;
    size_t nw = 0;
    /* & and |, not && and ||: no branches, so the counting pass vectorises
     * (it ran at ~1.4 ms a cell, 2% of the Moderno study) */
#define SL_WRONG_PFL(i)                                                                                          \
    ((v->cls[i] == SL_C_PFL) & (((vd->v[i] == SL_V_LIT) & (v->truth[i] == SL_T_SHADOW)) |                      \
                                ((vd->v[i] == SL_V_SHADOW) & (v->truth[i] == SL_T_LIT))))
    for (size_t i = 0; i < npx; i++)
        nw += SL_WRONG_PFL(i);
    /* the gathered pixels' m and bands, sized to them (a frame's worth of
     * scratch held at a 4096^2 group's peak was 8 MB at 1920x1080) */
    float *bad = hist ? malloc((nw + 1) * sizeof *bad) : NULL;
    uint8_t *wband = bad ? malloc(nw + 1) : NULL;
    if (!wband) {
        free(bad);
        bad = NULL;
        /* no scratch: count region by region over every pixel, no medians */
        for (int r = 0; r < nregions; r++) {
            wrong[r] = 0;
            for (size_t i = 0; i < npx; i++) {
                if (!SL_WRONG_PFL(i) || !sl_in_contour(band[i], thickness[r]))
                    continue;
                wrong[r]++;
                if (!isnan(m[i]))
                    n[r][SL_AFIG_wrong_m_le1 + sl_alias_band(m[i])]++;
            }
            n[r][SL_AFIG_wrong_m_median_milli] = 0;
        }
        return;
    }
    /* the gathering in runs of 64 pixels, each first tested whole by the
     * same branch-free test (it vectorises): the wrong pixels lie along
     * the shadows' edges, so most runs have none and cost no branch per
     * pixel (a branch per pixel was 2.4 ms a cell, 4% of the Moderno
     * study's samples) */
    nw = 0;
    for (size_t i0 = 0; i0 < npx; i0 += 64) {
        size_t e = npx - i0 < 64 ? npx - i0 : 64;
        unsigned any = 0;
        for (size_t i = i0; i < i0 + e; i++)
            any |= SL_WRONG_PFL(i);
        if (!any)
            continue;
        for (size_t i = i0; i < i0 + e; i++)
            if (SL_WRONG_PFL(i)) {
                bad[nw] = m[i];
                wband[nw++] = band[i];
            }
    }
#undef SL_WRONG_PFL
    float *sel = malloc((nw + 1) * sizeof *sel);   /* a region's m (NULL: no median) */
    for (int r = 0; r < nregions; r++) {
        uint64_t *c = n[r];
        size_t nb = 0;
        wrong[r] = 0;
        for (size_t j = 0; j < nw; j++) {
            if (!sl_in_contour(wband[j], thickness[r]))
                continue;
            wrong[r]++;
            if (isnan(bad[j]))
                continue;
            c[SL_AFIG_wrong_m_le1 + sl_alias_band(bad[j])]++;
            if (sel)
                sel[nb++] = bad[j];
        }
        c[SL_AFIG_wrong_m_median_milli] = sel ? milli(median(sel, nb, hist)) : 0;
    }
    free(sel);
    free(bad);
    free(wband);
}

/* The PFL side from the cache when it was counted on this m (the cache's
 * own), these bands and these regions; else counted and kept. */
static void pfl_side_cached(struct sl_alias_cache *k, const struct sl_view *v, const float *m,
                            const uint8_t *band, const int *thickness, int nregions, uint64_t n[][SL_AFIG_COUNT],
                            uint64_t *pfl, uint64_t *hist)
{
    size_t npx = (size_t)v->w * (size_t)v->h;
    int fits = k && m == k->m && k->pfl_gen == k->gen && k->nregions == nregions && k->band &&
               !memcmp(k->thickness, thickness, (size_t)nregions * sizeof *thickness) &&
               !memcmp(k->band, band, npx);
    if (!fits) {
        float *all = hist ? malloc(npx * sizeof *all) : NULL;   /* no scratch: no medians (0) */
        pfl_side(v, m, band, thickness, nregions, n, pfl, all, hist);
        free(all);
        if (!k || m != k->m || !all || !hist)
            return;
        if (k->band_cap < npx) {
            free(k->band);
            k->band_cap = 0;
            if (!(k->band = malloc(npx)))
                return;
            k->band_cap = npx;
        }
        memcpy(k->band, band, npx);
        memcpy(k->thickness, thickness, (size_t)nregions * sizeof *thickness);
        memcpy(k->pfl_n, n, (size_t)nregions * sizeof *n);
        memcpy(k->pfl, pfl, (size_t)nregions * sizeof *pfl);
        k->nregions = nregions;
        k->pfl_gen = k->gen;
        return;
    }
    memcpy(n, k->pfl_n, (size_t)nregions * sizeof *n);
    memcpy(pfl, k->pfl, (size_t)nregions * sizeof *pfl);
}

void sl_alias_figures_compute(const struct sl_view *v, const struct sl_verdicts *vd, const float *m,
                              const uint8_t *band, const int *thickness, int nregions,
                              struct sl_alias_figures *out)
{
    sl_alias_figures_cached(NULL, v, vd, m, band, thickness, nregions, out);
}

void sl_alias_figures_cached(struct sl_alias_cache *k, const struct sl_view *v, const struct sl_verdicts *vd,
                             const float *m, const uint8_t *band, const int *thickness, int nregions,
                             struct sl_alias_figures *out)
{
    memset(out, 0, sizeof *out);
    if (nregions > SL_MAX_REGIONS)
        nregions = SL_MAX_REGIONS;
    out->nregions = nregions;
    memcpy(out->thickness, thickness, (size_t)nregions * sizeof *thickness);
    uint64_t *hist = malloc(65536 * sizeof *hist), pfl[SL_MAX_REGIONS], wrong[SL_MAX_REGIONS];
    uint64_t (*n)[SL_AFIG_COUNT] = out->n;
    pfl_side_cached(k, v, m, band, thickness, nregions, n, pfl, hist);
    wrong_side(v, vd, m, band, thickness, nregions, n, wrong, hist);
    for (int r = 0; r < nregions; r++)
        for (int f = 0; f < SL_AFIG_COUNT; f++) {
            double base = !strcmp(afig_of[f], "pfl") ? (double)pfl[r] : !strcmp(afig_of[f], "wrong") ? (double)wrong[r]
                                                                                                     : 0.0;
            out->pct[r][f] = base > 0.0 ? 100.0 * (double)n[r][f] / base : NAN;
        }
    free(hist);
}

int sl_alias_figures_put(struct sl_alias_figures *a, int thickness, const char *figure, uint64_t count, double pct)
{
    int k = sl_alias_figure_parse(figure), j = 0;
    if (k < 0)
        return 0;
    while (j < a->nregions && a->thickness[j] != thickness)
        j++;
    if (j == SL_MAX_REGIONS)
        return 1;   /* more regions than a cell holds: the store refuses such a cell before */
    if (j == a->nregions) {
        a->nregions++;
        a->thickness[j] = thickness;
        for (int q = 0; q < SL_AFIG_COUNT; q++)
            a->pct[j][q] = NAN;
    }
    a->n[j][k] = count;
    a->pct[j][k] = pct;
    return 1;
}
