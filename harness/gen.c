/*
 * gen.c — procedural meshes. Invariants: closed solids are watertight
 * (shared seam vertices, poles welded), faces wind counter-clockwise seen from
 * outside, and no generator emits a zero-area triangle (pole caps use one
 * vertex per pole, not a ring of coincident ones).
 */
#include "scene.h"
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
