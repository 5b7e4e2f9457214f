/*
 * gen.c — procedural meshes. Invariants: closed solids are watertight
 * (shared seam vertices, poles welded), faces wind counter-clockwise seen from
 * outside, and no generator emits a zero-area triangle (pole caps use one
 * vertex per pole, not a ring of coincident ones).
 */
#include "gen.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SL_PI 3.14159265358979323846

static int grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    uint32_t c = *cap ? *cap : 256;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

uint32_t sl_mesh_vertex(struct sl_mesh *m, float x, float y, float z)
{
    if (!grow((void **)&m->pos, &m->cap_v, m->nv + 1, 3 * sizeof(float))) {
        m->oom = 1;
        return 0;
    }
    float *p = m->pos + 3 * (size_t)m->nv;
    p[0] = x; p[1] = y; p[2] = z;
    return m->nv++;
}

void sl_mesh_tri(struct sl_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    if (!grow((void **)&m->idx, &m->cap_t, m->nt + 1, 3 * sizeof(uint32_t))) {
        m->oom = 1;
        return;
    }
    uint32_t *t = m->idx + 3 * (size_t)m->nt;
    t[0] = a; t[1] = b; t[2] = c;
    m->nt++;
}

void sl_mesh_free(struct sl_mesh *m)
{
    free(m->pos);
    free(m->idx);
    memset(m, 0, sizeof *m);
}

/* Horizontal grid facing +y. */
void sl_gen_plane(struct sl_mesh *m, float cx, float y, float cz, float size, int grid)
{
    uint32_t base = m->nv;
    float h = 0.5f * size;
    for (int j = 0; j <= grid; j++)
        for (int i = 0; i <= grid; i++)
            sl_mesh_vertex(m, cx - h + size * (float)i / (float)grid, y,
                           cz - h + size * (float)j / (float)grid);
    for (int j = 0; j < grid; j++)
        for (int i = 0; i < grid; i++) {
            uint32_t a = base + (uint32_t)(j * (grid + 1) + i);
            uint32_t b = a + 1, c = a + (uint32_t)(grid + 1), e = c + 1;
            /* (x right, z toward viewer): a-c-b is counter-clockwise from +y */
            sl_mesh_tri(m, a, c, b);
            sl_mesh_tri(m, b, c, e);
        }
}

/* UV sphere: stacks-1 rings, one vertex per pole; 2*slices*(stacks-1) triangles. */
void sl_gen_sphere(struct sl_mesh *m, float cx, float cy, float cz, float r, int slices, int stacks)
{
    uint32_t top = sl_mesh_vertex(m, cx, cy + r, cz);
    uint32_t ring0 = m->nv;
    for (int j = 1; j < stacks; j++) {
        double th = SL_PI * j / stacks;
        for (int i = 0; i < slices; i++) {
            double ph = 2.0 * SL_PI * i / slices;
            sl_mesh_vertex(m, cx + (float)(r * sin(th) * cos(ph)), cy + (float)(r * cos(th)),
                           cz - (float)(r * sin(th) * sin(ph)));
        }
    }
    uint32_t bot = sl_mesh_vertex(m, cx, cy - r, cz);
    uint32_t S = (uint32_t)slices;
    for (uint32_t i = 0; i < S; i++)
        sl_mesh_tri(m, top, ring0 + i, ring0 + (i + 1) % S);
    for (int j = 0; j < stacks - 2; j++) {
        uint32_t a0 = ring0 + (uint32_t)j * S, b0 = a0 + S;
        for (uint32_t i = 0; i < S; i++) {
            uint32_t i1 = (i + 1) % S;
            sl_mesh_tri(m, a0 + i, b0 + i, b0 + i1);
            sl_mesh_tri(m, a0 + i, b0 + i1, a0 + i1);
        }
    }
    uint32_t last = ring0 + (uint32_t)(stacks - 2) * S;
    for (uint32_t i = 0; i < S; i++)
        sl_mesh_tri(m, last + i, bot, last + (i + 1) % S);
}

/* Torus lying flat (axis +y): 2*nu*nv triangles. */
void sl_gen_torus(struct sl_mesh *m, float cx, float cy, float cz, float R, float r, int nu, int nv)
{
    uint32_t base = m->nv;
    for (int i = 0; i < nu; i++) {
        double u = 2.0 * SL_PI * i / nu;
        for (int j = 0; j < nv; j++) {
            double v = 2.0 * SL_PI * j / nv;
            double rr = R + r * cos(v);
            sl_mesh_vertex(m, cx + (float)(rr * cos(u)), cy + (float)(r * sin(v)),
                           cz - (float)(rr * sin(u)));
        }
    }
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            uint32_t a = base + (uint32_t)(i * nv + j);
            uint32_t b = base + (uint32_t)(((i + 1) % nu) * nv + j);
            uint32_t c = base + (uint32_t)(((i + 1) % nu) * nv + (j + 1) % nv);
            uint32_t e = base + (uint32_t)(i * nv + (j + 1) % nv);
            sl_mesh_tri(m, a, b, c);
            sl_mesh_tri(m, a, c, e);
        }
}

/* Capped cylinder standing on y0, axis +y: 4n triangles. */
void sl_gen_cylinder(struct sl_mesh *m, float cx, float y0, float cz, float r, float h, int n)
{
    uint32_t bc = sl_mesh_vertex(m, cx, y0, cz);
    uint32_t tc = sl_mesh_vertex(m, cx, y0 + h, cz);
    uint32_t base = m->nv;
    for (int i = 0; i < n; i++) {
        double ph = 2.0 * SL_PI * i / n;
        float x = cx + (float)(r * cos(ph)), z = cz - (float)(r * sin(ph));
        sl_mesh_vertex(m, x, y0, z);
        sl_mesh_vertex(m, x, y0 + h, z);
    }
    uint32_t N = (uint32_t)n;
    for (uint32_t i = 0; i < N; i++) {
        uint32_t b0 = base + 2 * i, t0 = b0 + 1;
        uint32_t b1 = base + 2 * ((i + 1) % N), t1 = b1 + 1;
        sl_mesh_tri(m, b0, b1, t1);
        sl_mesh_tri(m, b0, t1, t0);
        sl_mesh_tri(m, tc, t0, t1);
        sl_mesh_tri(m, bc, b1, b0);
    }
}

/* Square pyramid on y0: 4 sides + 2 base triangles. */
void sl_gen_pyramid(struct sl_mesh *m, float cx, float y0, float cz, float base, float h)
{
    float s = 0.5f * base;
    uint32_t a = sl_mesh_vertex(m, cx - s, y0, cz + s);
    uint32_t b = sl_mesh_vertex(m, cx + s, y0, cz + s);
    uint32_t c = sl_mesh_vertex(m, cx + s, y0, cz - s);
    uint32_t e = sl_mesh_vertex(m, cx - s, y0, cz - s);
    uint32_t t = sl_mesh_vertex(m, cx, y0 + h, cz);
    sl_mesh_tri(m, a, b, t);
    sl_mesh_tri(m, b, c, t);
    sl_mesh_tri(m, c, e, t);
    sl_mesh_tri(m, e, a, t);
    sl_mesh_tri(m, a, e, c);
    sl_mesh_tri(m, a, c, b);
}

void sl_gen_box(struct sl_mesh *m, const float lo[3], const float hi[3])
{
    uint32_t v[8];
    for (int i = 0; i < 8; i++)
        v[i] = sl_mesh_vertex(m, (i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1],
                              (i & 4) ? hi[2] : lo[2]);
    /* faces as (a,b,c,d) counter-clockwise from outside */
    static const int f[6][4] = {
        {0, 4, 6, 2}, {1, 3, 7, 5},   /* -x, +x */
        {0, 1, 5, 4}, {2, 6, 7, 3},   /* -y, +y */
        {0, 2, 3, 1}, {4, 5, 7, 6},   /* -z, +z */
    };
    for (int i = 0; i < 6; i++) {
        sl_mesh_tri(m, v[f[i][0]], v[f[i][1]], v[f[i][2]]);
        sl_mesh_tri(m, v[f[i][0]], v[f[i][2]], v[f[i][3]]);
    }
}

/* ------------------------------------------------------------------------
 * Scene props for Moderno 2011's "Bench", "Trees" and "Flowers" scenes.
 * Units are metres (a ~100-unit scene is a small park). Random placement
 * comes from gen_rng (PCG32), never rand(): the same seed gives the same
 * bytes on one machine; a different seed a different mesh.
 * ------------------------------------------------------------------------ */

struct gen_rng { uint64_t s; };

static uint32_t gen_rng_u32(struct gen_rng *r)
{
    uint64_t old = r->s;
    r->s = old * 6364136223846793005ull + 1442695040888963407ull;
    uint32_t x = (uint32_t)(((old >> 18) ^ old) >> 27), rot = (uint32_t)(old >> 59);
    return (x >> rot) | (x << ((32u - rot) & 31u));
}

static void gen_rng_seed(struct gen_rng *r, uint32_t seed, uint32_t stream)
{
    /* splitmix64 of (seed, stream), so nearby seeds start far apart */
    uint64_t z = ((uint64_t)stream << 32 | seed) + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    r->s = z ^ (z >> 31);
    gen_rng_u32(r);
}

/* uniform in [a, b) */
static double gen_rng_range(struct gen_rng *r, double a, double b)
{
    return a + (b - a) * ((double)(gen_rng_u32(r) >> 8) * (1.0 / 16777216.0));
}

static uint32_t vtx_d(struct sl_mesh *m, const double p[3])
{
    return sl_mesh_vertex(m, (float)p[0], (float)p[1], (float)p[2]);
}

/* Triangle wound so that its normal (of the float positions) has a positive
 * component along `toward`: the generators below say which way a face
 * looks and let this pick the winding. */
static void tri_facing(struct sl_mesh *m, uint32_t a, uint32_t b, uint32_t c, const double toward[3])
{
    if (m->oom)
        return;
    const float *pa = m->pos + 3 * (size_t)a, *pb = m->pos + 3 * (size_t)b, *pc = m->pos + 3 * (size_t)c;
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)pb[k] - pa[k];
        e2[k] = (double)pc[k] - pa[k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * toward[0] + n[1] * toward[1] + n[2] * toward[2] >= 0.0)
        sl_mesh_tri(m, a, b, c);
    else
        sl_mesh_tri(m, a, c, b);
}

/* Planar convex quad a-b-c-d (in order around it) as two triangles facing
 * `toward`. */
static void quad_facing(struct sl_mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d,
                        const double toward[3])
{
    tri_facing(m, a, b, c, toward);
    tri_facing(m, a, c, d, toward);
}

/* Box with centre c, right-handed unit axes ax[0..2] and half extents he:
 * 12 triangles, the same corner order and faces as sl_gen_box. */
static void gen_obox(struct sl_mesh *m, const double c[3], const double ax[3][3], const double he[3])
{
    uint32_t v[8];
    for (int i = 0; i < 8; i++) {
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = c[k] + ((i & 1) ? he[0] : -he[0]) * ax[0][k] + ((i & 2) ? he[1] : -he[1]) * ax[1][k] +
                   ((i & 4) ? he[2] : -he[2]) * ax[2][k];
        v[i] = vtx_d(m, p);
    }
    static const int f[6][4] = {
        {0, 4, 6, 2}, {1, 3, 7, 5},
        {0, 1, 5, 4}, {2, 6, 7, 3},
        {0, 2, 3, 1}, {4, 5, 7, 6},
    };
    for (int i = 0; i < 6; i++) {
        sl_mesh_tri(m, v[f[i][0]], v[f[i][1]], v[f[i][2]]);
        sl_mesh_tri(m, v[f[i][0]], v[f[i][2]], v[f[i][3]]);
    }
}

static void gen_abox(struct sl_mesh *m, double x0, double y0, double z0, double x1, double y1, double z1)
{
    const float lo[3] = {(float)x0, (float)y0, (float)z0}, hi[3] = {(float)x1, (float)y1, (float)z1};
    sl_gen_box(m, lo, hi);
}

/* Closed cone standing on y0, apex at y0 + h: n side triangles and n base
 * triangles (one centre vertex, no zero-area fan), 2n in all. */
void sl_gen_cone(struct sl_mesh *m, float cx, float y0, float cz, float r, float h, int n)
{
    uint32_t bc = sl_mesh_vertex(m, cx, y0, cz);
    uint32_t apex = sl_mesh_vertex(m, cx, y0 + h, cz);
    uint32_t base = m->nv;
    for (int i = 0; i < n; i++) {
        double ph = 2.0 * SL_PI * i / n;
        sl_mesh_vertex(m, cx + (float)(r * cos(ph)), y0, cz - (float)(r * sin(ph)));
    }
    uint32_t N = (uint32_t)n;
    for (uint32_t i = 0; i < N; i++) {
        uint32_t b0 = base + i, b1 = base + (i + 1) % N;
        sl_mesh_tri(m, b0, b1, apex);
        sl_mesh_tri(m, bc, b1, b0);
    }
}

#define SL_TREE_TRUNK_SIDES 16
#define SL_TREE_LEAVES      960

/*
 * Tree of total height `height`: a trunk (closed cylinder, 16 sides, radius
 * 0.035 height, 0.62 height tall) and a crown of 960 single leaf triangles
 * scattered through an ellipsoid (radii 0.30/0.28/0.30 height, centred at
 * 0.66 height) with random orientations. Leaves are open, one triangle each,
 * and meant to be rendered two-sided; their winding is random. Each leaf is
 * near-equilateral with a circumradius of 0.05..0.08 height (edges of
 * 0.7..1.1 units for an 8-unit tree: many texels of a shadow map over a
 * 100-unit scene).
 * Triangles: 4 * 16 + 960 = 1024.
 */
void sl_gen_tree(struct sl_mesh *m, float cx, float y0, float cz, float height, uint32_t seed)
{
    double H = height;
    sl_gen_cylinder(m, cx, y0, cz, (float)(0.035 * H), (float)(0.62 * H), SL_TREE_TRUNK_SIDES);
    struct gen_rng r;
    gen_rng_seed(&r, seed, 1);
    const double ctr[3] = {cx, y0 + 0.66 * H, cz}, rad[3] = {0.30 * H, 0.28 * H, 0.30 * H};
    for (int l = 0; l < SL_TREE_LEAVES; l++) {
        double p[3], n[3], len2;
        do {
            for (int k = 0; k < 3; k++)
                p[k] = gen_rng_range(&r, -1.0, 1.0);
        } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1.0);
        do {
            for (int k = 0; k < 3; k++)
                n[k] = gen_rng_range(&r, -1.0, 1.0);
            len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        } while (len2 > 1.0 || len2 < 0.01);
        double ln = sqrt(len2);
        for (int k = 0; k < 3; k++) {
            p[k] = ctr[k] + p[k] * rad[k];
            n[k] /= ln;
        }
        /* u: any unit vector across n; v = n x u */
        double h[3] = {0, 0, 0};
        h[fabs(n[0]) < 0.6 ? 0 : 1] = 1.0;
        double u[3] = {n[1] * h[2] - n[2] * h[1], n[2] * h[0] - n[0] * h[2], n[0] * h[1] - n[1] * h[0]};
        double lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int k = 0; k < 3; k++)
            u[k] /= lu;
        double v[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
        double s = H * gen_rng_range(&r, 0.05, 0.08), th0 = gen_rng_range(&r, 0.0, 2.0 * SL_PI);
        uint32_t vi[3];
        for (int c = 0; c < 3; c++) {
            /* corners 120 degrees apart, +-0.3 rad: never thinner than ~85 degrees apart */
            double th = th0 + c * (2.0 * SL_PI / 3.0) + gen_rng_range(&r, -0.3, 0.3);
            double q[3];
            for (int k = 0; k < 3; k++)
                q[k] = p[k] + s * (cos(th) * u[k] + sin(th) * v[k]);
            vi[c] = vtx_d(m, q);
        }
        sl_mesh_tri(m, vi[0], vi[1], vi[2]);
    }
}

#define SL_FLOWER_PETALS     8

/*
 * The flowers' thin parts (petals, leaves, the blossom's cone) are closed
 * thin solids, so the mesh is drawn one-sided and the shadow pass's
 * front-face culling works on it as on any closed solid: the faces toward
 * the light are culled and the map keeps the ones behind them, deeper by
 * the part's thickness, so a lit face is not shadowed by itself where the
 * part is thicker than the depth the map's texel spreads over it. Open
 * surfaces drawn two-sided (these flowers before) keep the lit face at its
 * own depth and shadow themselves at every map size; scaled 16.3 in the
 * Bench scenes that was NSM's acne on the petals (scenes/CALIBRATION.md).
 *
 * A petal or a leaf is a flat diamond made a tetrahedron (thin_tetra):
 * the diagonal across it raised T/2 along its normal, the one along it
 * (base to tip) lowered T/2; the two faces on the upper diagonal are its
 * top, the two on the lower its underside, back to back, T apart where
 * the diagonals cross and meeting at the outline, which is the diamond's.
 * 4 triangles, as the open diamond's 2 drawn from both sides. Why these:
 * - two parallel diamonds T apart (4 triangles too) leave the outline
 *   open: a shadow ray that enters the top face near the rim leaves
 *   through the gap, not the face the map keeps, and the map misses a band
 *   2.25 T wide at the far edge of every petal's shadow under the Bench
 *   light. Measured on flowers/against 512x512 (T = 2 mm): 3,400-4,300
 *   pixels said lit and shadowed at every map size from 512^2 to 4096^2,
 *   against 1,600 falling to 230 with the tetrahedra. Closing the diamond
 *   with side walls takes 12 triangles a petal;
 * - folded along the diagonal across, not along the midrib: the faces
 *   tilt T over half the length, not half the width, and fewer turn from
 *   the light (bench/against, pixels facing away at 1024x1024, T = 2 mm:
 *   3.40% folded across, 3.45% along the midrib; 3.32% with the open
 *   flowers, the band's top 3.38%).
 * The blossom's cone is a closed double cone (its twin points down, T
 * below the rim).
 *
 * Why T = 1.5 mm. A lit face is shadowed by the face behind it where that
 * face, sampled at a texel's centre up to half a texel away, comes nearer
 * the light than the pixel; it stays behind while the part is thicker than
 * (|n_x| w_x + |n_y| w_y) / 2, n the face's unit normal in the light's
 * frame and w_x, w_y the texel's sides in world units (the depth slope
 * times half a texel, measured along the normal). Over the 22,400 petal,
 * leaf and cone triangles of the Bench scenes' flowers (scaled 16.3), in
 * the tight frames sl_light_fit gives the studies' views, that asks for at
 * most (median, about 3/4 of it), in scene units:
 *   flowers/against 512x512 (Morais Tables 5 and 8): maps 512^2 0.030
 *     (0.022), 1024^2 0.015, 2048^2 0.0075, 4096^2 0.0038;
 *   flowers/side and /with 512x512 and 1024x1024: 512^2 0.038,
 *     1024^2 0.019; the Flowers views at 1920x1080: 512^2 0.053,
 *     1024^2 0.026;
 *   bench/with 768x768 (the aliasing study): 1024^2 0.045 (0.032),
 *     2048^2 0.023.
 * 1.5 mm is 0.0245 units after the scale: the median petal's need at
 * Morais's coarsest map on flowers/against, 1.6 times the most its 1024^2
 * map asks and 3 to 6 times its finer maps', so NSM's errors on the petals
 * are near their rims and fall with map size (flowers/against, shadow
 * incorrect, maps 512^2 to 4096^2: 4,237 / 2,550 / 1,415 / 704). Thicker
 * is cleaner at 512^2 (2 mm: 3,532 / 2,047 / 1,100 / 528) but tilts the
 * faces further from the light: bench/against's pixels facing away rise
 * to 3.38% at 1.75 mm and 3.40% at 2 mm, out of the band that holds them
 * to the thesis's 2.38% (scenes/CALIBRATION.md); 1.5 mm gives 3.36%.
 */
#define SL_FLOWER_THICKNESS  0.0015

/* Ring of 3 stem vertices around the point a, angle offset ph, radius rs. */
static uint32_t stem_ring(struct sl_mesh *m, const double a[3], double ph, double rs)
{
    uint32_t first = m->nv;
    for (int k = 0; k < 3; k++) {
        double an = ph + k * (2.0 * SL_PI / 3.0);
        double p[3] = {a[0] + rs * cos(an), a[1], a[2] - rs * sin(an)};
        vtx_d(m, p);
    }
    return first;
}

/* Tetrahedron over the flat diamond q[0..3] (in order around it; a
 * parallelogram, q0 + q2 = q1 + q3): the diagonal q0-q2 moved T/2 along
 * the diamond's normal on the side of `up`, q1-q3 moved T/2 the other way;
 * 4 triangles (the faces without q3, q2, q1, q0 in turn), each wound away
 * from the vertex it does not hold. */
static void thin_tetra(struct sl_mesh *m, const double *const q[4], const double up[3], double T)
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = q[1][k] - q[0][k];
        e2[k] = q[2][k] - q[0][k];
    }
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (n[0] * up[0] + n[1] * up[1] + n[2] * up[2] < 0.0)
        ln = -ln;
    double p[4][3], c[3] = {0, 0, 0};
    uint32_t v[4];
    for (int i = 0; i < 4; i++) {
        double s = (i & 1) ? -0.5 * T : 0.5 * T;
        for (int k = 0; k < 3; k++) {
            p[i][k] = q[i][k] + s * n[k] / ln;
            c[k] += 0.25 * p[i][k];
        }
        v[i] = vtx_d(m, p[i]);
    }
    for (int skip = 3; skip >= 0; skip--) {
        uint32_t f[3];
        double out[3];
        for (int i = 0, j = 0; i < 4; i++)
            if (i != skip)
                f[j++] = v[i];
        for (int k = 0; k < 3; k++)
            out[k] = c[k] - p[skip][k];
        tri_facing(m, f[0], f[1], f[2], out);
    }
}

/*
 * Bed of `count` flowers planted at y0 in the width (x) by depth (z)
 * rectangle centred at (cx, cz), positions uniform (a margin of 10 cm keeps
 * every flower inside when the bed is wider and deeper than 0.4). Metres;
 * the Bench scenes scale the bed 16.3 times (scenes/bench.yaml). Each
 * flower is 12 closed solids:
 * - stem: a closed triangular prism of radius 4-6 mm, 0.22-0.38 tall (from
 *   1 cm below y0), leaning up to 4 cm: 6 sides and 2 end caps, 8
 *   triangles (the stem is straight: one segment is its whole surface);
 * - two stem leaves, 4-5.5 cm diamonds, each a tetrahedron: 8 triangles;
 * - blossom: a low double cone (radius 1.2 cm, 4 mm up, 1.5 mm down), 16
 *   triangles, and 8 petals from its rim, diamonds 3-4.5 cm long and
 *   1.4-2.2 cm wide tilted up, each a tetrahedron: 32 triangles.
 * Thin parts are SL_FLOWER_THICKNESS thick (above, with why), every face
 * wound outward: the mesh is meant to be drawn one-sided. The seed draws
 * what it drew for the open flowers (same places, sizes and turns).
 * Triangles: 64 * count, as before (the Bench scene stays at 54,200).
 */
void sl_gen_flowers(struct sl_mesh *m, float cx, float y0, float cz, float width, float depth,
                    int count, uint32_t seed)
{
    static const double up[3] = {0.0, 1.0, 0.0}, down[3] = {0.0, -1.0, 0.0};
    const double T = SL_FLOWER_THICKNESS;
    struct gen_rng r;
    gen_rng_seed(&r, seed, 2);
    /* reach from the stem base: lean 4 cm + blossom 1.2 + petal 4.5 cm */
    double mx = width > 0.4f ? 0.1 : 0.25 * width, mz = depth > 0.4f ? 0.1 : 0.25 * depth;
    for (int f = 0; f < count; f++) {
        double b[3] = {cx + gen_rng_range(&r, -0.5, 0.5) * (width - 2.0 * mx), y0 - 0.01,
                       cz + gen_rng_range(&r, -0.5, 0.5) * (depth - 2.0 * mz)};
        double hs = gen_rng_range(&r, 0.22, 0.38), rs = gen_rng_range(&r, 0.004, 0.006);
        double lean[2] = {gen_rng_range(&r, -0.04, 0.04), gen_rng_range(&r, -0.04, 0.04)};
        double ph = gen_rng_range(&r, 0.0, 2.0 * SL_PI);
        double top[3] = {b[0] + lean[0], b[1] + hs, b[2] + lean[1]};

        /* stem: sides wound like sl_gen_cylinder's, caps facing out */
        uint32_t r0 = stem_ring(m, b, ph, rs), r1 = stem_ring(m, top, ph, rs);
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t b0 = r0 + k, b1 = r0 + (k + 1) % 3, t0 = r1 + k, t1 = r1 + (k + 1) % 3;
            sl_mesh_tri(m, b0, b1, t1);
            sl_mesh_tri(m, b0, t1, t0);
        }
        tri_facing(m, r0, r0 + 1, r0 + 2, down);
        tri_facing(m, r1, r1 + 1, r1 + 2, up);

        /* two leaves on opposite sides, at 35% and 60% of the stem */
        double la = gen_rng_range(&r, 0.0, 2.0 * SL_PI);
        for (int l = 0; l < 2; l++) {
            double tl = l ? 0.60 : 0.35, dir[2] = {cos(la + l * SL_PI), -sin(la + l * SL_PI)};
            double L = gen_rng_range(&r, 0.04, 0.055), W = gen_rng_range(&r, 0.012, 0.018);
            double q[3], s1[3], s2[3], tip[3];
            for (int k = 0; k < 3; k++)
                q[k] = b[k] + tl * (top[k] - b[k]);
            tip[0] = q[0] + L * dir[0];
            tip[1] = q[1] + 0.35 * L;
            tip[2] = q[2] + L * dir[1];
            /* the sides halfway up the tip's rise: a flat diamond */
            s1[0] = q[0] + 0.5 * L * dir[0] + 0.5 * W * dir[1];
            s1[1] = q[1] + 0.175 * L;
            s1[2] = q[2] + 0.5 * L * dir[1] - 0.5 * W * dir[0];
            s2[0] = q[0] + 0.5 * L * dir[0] - 0.5 * W * dir[1];
            s2[1] = q[1] + 0.175 * L;
            s2[2] = q[2] + 0.5 * L * dir[1] + 0.5 * W * dir[0];
            const double *dia[4] = {s1, tip, s2, q};
            thin_tetra(m, dia, up, T);
        }

        /* blossom: the double cone, then petals from its rim */
        double rc = 0.012, ph0 = gen_rng_range(&r, 0.0, 2.0 * SL_PI);
        double cpt[3] = {top[0], top[1] + 0.004, top[2]}, cpb[3] = {top[0], top[1] - T, top[2]};
        uint32_t vc = vtx_d(m, cpt), vb = vtx_d(m, cpb), rim = m->nv;
        for (int i = 0; i < SL_FLOWER_PETALS; i++) {
            double an = ph0 + i * (2.0 * SL_PI / SL_FLOWER_PETALS);
            double p[3] = {top[0] + rc * cos(an), top[1], top[2] - rc * sin(an)};
            vtx_d(m, p);
        }
        for (uint32_t i = 0; i < SL_FLOWER_PETALS; i++) {
            uint32_t a = rim + i, c = rim + (i + 1) % SL_FLOWER_PETALS;
            tri_facing(m, vc, a, c, up);
            tri_facing(m, vb, c, a, down);
        }
        for (int i = 0; i < SL_FLOWER_PETALS; i++) {
            double an = ph0 + i * (2.0 * SL_PI / SL_FLOWER_PETALS);
            double d[2] = {cos(an), -sin(an)}, pp[2] = {-d[1], d[0]};
            double L = gen_rng_range(&r, 0.03, 0.045), W = gen_rng_range(&r, 0.014, 0.022);
            double lift = gen_rng_range(&r, 0.1, 0.5);   /* tip rises lift * L */
            double o[3] = {top[0] + rc * cos(an), top[1], top[2] - rc * sin(an)}, s1[3], s2[3], tip[3];
            tip[0] = o[0] + L * d[0];
            tip[1] = o[1] + lift * L;
            tip[2] = o[2] + L * d[1];
            for (int sgn = 0; sgn < 2; sgn++) {
                double *s = sgn ? s2 : s1, w = sgn ? -0.5 * W : 0.5 * W;
                s[0] = o[0] + 0.5 * L * d[0] + w * pp[0];
                s[1] = o[1] + 0.5 * lift * L;
                s[2] = o[2] + 0.5 * L * d[1] + w * pp[1];
            }
            const double *dia[4] = {s1, tip, s2, o};
            thin_tetra(m, dia, up, T);
        }
    }
}

/*
 * Park bench `length` long (x), centred at (cx, cz), standing on y0, seat
 * front toward +z; metres (seat 0.42-0.455 high, back to ~0.85). Every part
 * is a closed box, and parts overlap rather than touch, so no two boxes share
 * a corner and welding never joins them:
 *   5 seat slats, 2 seat rails, 4 legs, 2 back posts and 3 back slats
 *   (leaning back 12 degrees), 2 arm supports, 2 arm rests = 20 boxes.
 * The seed moves slats by a few millimetres (a weathered bench).
 * Triangles: 20 * 12 = 240. Meant for length >= 0.8.
 */
void sl_gen_bench(struct sl_mesh *m, float cx, float y0, float cz, float length, uint32_t seed)
{
    struct gen_rng r;
    gen_rng_seed(&r, seed, 3);
    double X = cx, Y = y0, Z = cz, hx = 0.5 * length, xs = hx - 0.18;
    for (int i = 0; i < 5; i++) {                    /* seat slats */
        double zc = Z + 0.1875 - 0.085 * i + gen_rng_range(&r, -0.004, 0.004);
        double hz = 0.0325 + gen_rng_range(&r, -0.002, 0.002), dy = gen_rng_range(&r, -0.003, 0.003);
        gen_abox(m, X - hx, Y + 0.42 + dy, zc - hz, X + hx, Y + 0.455 + dy, zc + hz);
    }
    for (int s = -1; s <= 1; s += 2) {               /* seat rails and legs */
        double x = X + s * xs;
        gen_abox(m, x - 0.025, Y + 0.37, Z - 0.22, x + 0.025, Y + 0.425, Z + 0.24);
        gen_abox(m, x - 0.03, Y, Z + 0.16, x + 0.03, Y + 0.39, Z + 0.22);
        gen_abox(m, x - 0.03, Y, Z - 0.20, x + 0.03, Y + 0.39, Z - 0.14);
    }
    const double al = 12.0 * SL_PI / 180.0;
    const double ax[3][3] = {{1, 0, 0}, {0, cos(al), -sin(al)}, {0, sin(al), cos(al)}};
    for (int s = -1; s <= 1; s += 2) {               /* back posts */
        double c[3] = {X + s * xs, Y + 0.36 + 0.26 * ax[1][1], Z - 0.17 + 0.26 * ax[1][2]};
        const double he[3] = {0.025, 0.26, 0.025};
        gen_obox(m, c, ax, he);
    }
    for (int i = 0; i < 3; i++) {                    /* back slats, 3 mm into the posts */
        double along = 0.22 + 0.1 * i + gen_rng_range(&r, -0.004, 0.004);
        double off = 0.025 + 0.0125 - 0.003;
        double c[3];
        for (int k = 0; k < 3; k++)
            c[k] = (k == 0 ? X : k == 1 ? Y + 0.36 : Z - 0.17) + along * ax[1][k] + off * ax[2][k];
        const double he[3] = {hx - 0.02, 0.04, 0.0125};
        gen_obox(m, c, ax, he);
    }
    for (int s = -1; s <= 1; s += 2) {               /* arm supports and rests */
        double x = X + s * (hx - 0.04);
        gen_abox(m, x - 0.02, Y + 0.40, Z + 0.15, x + 0.02, Y + 0.64, Z + 0.19);
        gen_abox(m, x - 0.03, Y + 0.62, Z - 0.16, x + 0.03, Y + 0.66, Z + 0.22);
    }
}

/*
 * Street lamp `height` tall standing at (cx, y0, cz), all closed solids that
 * overlap instead of touching:
 *   base  cylinder r 0.04 h, 0.06 h tall, 16 sides          64
 *   pole  cylinder r 0.012 h from 0.03 h to 0.93 h, 16 sides 64
 *   head  box 0.10 h wide, 0.88 h .. 0.96 h                  12
 *   roof  cone r 0.08 h, from 0.955 h, 0.05 h tall, 16 sides 32
 * Triangles: 172.
 */
void sl_gen_lamp(struct sl_mesh *m, float cx, float y0, float cz, float height)
{
    double H = height;
    sl_gen_cylinder(m, cx, y0, cz, (float)(0.04 * H), (float)(0.06 * H), 16);
    sl_gen_cylinder(m, cx, y0 + (float)(0.03 * H), cz, (float)(0.012 * H), (float)(0.90 * H), 16);
    gen_abox(m, cx - 0.05 * H, y0 + 0.88 * H, cz - 0.05 * H, cx + 0.05 * H, y0 + 0.96 * H, cz + 0.05 * H);
    sl_gen_cone(m, cx, y0 + (float)(0.955 * H), cz, (float)(0.08 * H), (float)(0.05 * H), 16);
}

/*
 * Open-top planter w (x) by d (z) by h, on y0, as ONE closed watertight
 * solid: outer walls and bottom, a rim of wall thickness t = 0.08 min(w, d),
 * inner walls, and the inner floor at soil level y0 + 0.8 h (the planter is
 * filled with soil, whose surface that floor is). One solid rather than five
 * wall boxes: boxes meeting at corners would either overlap with coplanar
 * faces (z-fighting in every shadow map) or share corners, which welding
 * turns into edges of four triangles.
 * 16 vertices; triangles: 2 (bottom) + 8 (outer) + 8 (rim) + 8 (inner)
 * + 2 (soil) = 28. Returns the soil height, where flowers are planted
 * (sl_gen_flowers over the (w - 2t) by (d - 2t) bed).
 */
float sl_gen_flower_box(struct sl_mesh *m, float cx, float y0, float cz, float w, float d, float h)
{
    double t = 0.08 * (w < d ? w : d), ys = y0 + 0.8 * h, yt = (double)y0 + h;
    double ox[2] = {cx - 0.5 * w, cx + 0.5 * w}, oz[2] = {cz - 0.5 * d, cz + 0.5 * d};
    double ix[2] = {ox[0] + t, ox[1] - t}, iz[2] = {oz[0] + t, oz[1] - t};
    /* corners in order around the rectangle: (x0,z0) (x1,z0) (x1,z1) (x0,z1) */
    static const int cxi[4] = {0, 1, 1, 0}, czi[4] = {0, 0, 1, 1};
    uint32_t ob[4], ot[4], it[4], ib[4];
    for (int i = 0; i < 4; i++) {
        double p[3] = {ox[cxi[i]], y0, oz[czi[i]]};
        ob[i] = vtx_d(m, p);
        p[1] = yt;
        ot[i] = vtx_d(m, p);
        double q[3] = {ix[cxi[i]], yt, iz[czi[i]]};
        it[i] = vtx_d(m, q);
        q[1] = ys;
        ib[i] = vtx_d(m, q);
    }
    static const double down[3] = {0, -1, 0}, up[3] = {0, 1, 0};
    /* outward normals of the sides, side i runs from corner i to i+1 */
    static const double side_n[4][3] = {{0, 0, -1}, {1, 0, 0}, {0, 0, 1}, {-1, 0, 0}};
    quad_facing(m, ob[0], ob[1], ob[2], ob[3], down);
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) % 4;
        const double in_n[3] = {-side_n[i][0], -side_n[i][1], -side_n[i][2]};
        quad_facing(m, ob[i], ob[j], ot[j], ot[i], side_n[i]);   /* outer wall */
        quad_facing(m, ot[i], ot[j], it[j], it[i], up);          /* rim */
        quad_facing(m, it[i], it[j], ib[j], ib[i], in_n);        /* inner wall, faces the soil */
    }
    quad_facing(m, ib[0], ib[1], ib[2], ib[3], up);
    return (float)ys;
}
