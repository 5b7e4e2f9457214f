/*
 * adjacency.c — edge and vertex adjacency of a scene's triangles.
 *
 * Invariants and costs:
 * - Edges: every half-edge (3t+k) gets the key (min vertex, max vertex);
 *   the keys are sorted (LSD radix sort on 64 bits with the half-edge id as
 *   the tie order, O(n)), so each undirected edge is one run of equal keys.
 *   A run of 1 is open, of 2 a manifold pair, of 3+ non-manifold; the
 *   counters advance once per run, never once per side.
 * - Vertex neighbours: a vertex -> triangles CSR is filled in triangle order,
 *   so each vertex's list is ascending; a triangle's neighbours are the
 *   3-way merge of its corners' lists with duplicates and itself removed.
 *   That is linear in the output, which is itself sum(valence^2) — the
 *   least any method can write.
 * - On error nothing is left allocated and *a is zeroed.
 */
#include "adjacency.h"
#include <stdlib.h>
#include <string.h>
#include "util.h"

struct half { uint64_t key; uint32_t he; uint32_t pad; };

/* Stable LSD radix sort by key, 16 bits a pass; input order (the half-edge
 * id) is the tie order, so runs list their triangles ascending. */
static int sort_halves(struct half **pa, size_t n)
{
    struct half *a = *pa, *b = malloc((n ? n : 1) * sizeof *b);
    size_t *cnt = malloc(65536 * sizeof *cnt);
    if (!b || !cnt) {
        free(b);
        free(cnt);
        return 0;
    }
    uint64_t all_or = 0;
    for (size_t i = 0; i < n; i++)
        all_or |= a[i].key;
    for (int shift = 0; shift < 64; shift += 16) {
        if (((all_or >> shift) & 0xffffu) == 0)
            continue;   /* every key has zeros here: the pass would not move anything */
        memset(cnt, 0, 65536 * sizeof *cnt);
        for (size_t i = 0; i < n; i++)
            cnt[(a[i].key >> shift) & 0xffffu]++;
        size_t sum = 0;
        for (size_t i = 0; i < 65536; i++) {
            size_t c = cnt[i];
            cnt[i] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; i++)
            b[cnt[(a[i].key >> shift) & 0xffffu]++] = a[i];
        struct half *t = a;
        a = b;
        b = t;
    }
    free(b);
    free(cnt);
    *pa = a;
    return 1;
}

static uint32_t third_vertex(const uint32_t *tri, uint32_t v0, uint32_t v1)
{
    for (int k = 0; k < 3; k++)
        if (tri[k] != v0 && tri[k] != v1)
            return tri[k];
    return SL_ADJ_NONE;
}

static enum sl_err build_edges(const struct sl_scene *s, struct sl_adjacency *a, struct sl_diag *d)
{
    size_t nh = 3 * (size_t)s->nt;
    struct half *h = malloc((nh ? nh : 1) * sizeof *h);
    if (!h)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "adjacency of %u triangles", s->nt);
    for (size_t i = 0; i < nh; i++) {
        uint32_t t = (uint32_t)(i / 3), k = (uint32_t)(i % 3);
        uint32_t v0 = s->idx[3 * (size_t)t + k], v1 = s->idx[3 * (size_t)t + (k + 1) % 3];
        uint32_t lo = v0 < v1 ? v0 : v1, hi = v0 < v1 ? v1 : v0;
        h[i].key = (uint64_t)lo << 32 | hi;
        h[i].he = (uint32_t)i;
        h[i].pad = 0;
    }
    if (!sort_halves(&h, nh)) {
        free(h);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "adjacency sort of %u triangles", s->nt);
    }
    for (size_t i = 0; i < nh;) {
        size_t j = i + 1;
        while (j < nh && h[j].key == h[i].key)
            j++;
        size_t run = j - i;
        if (run == 1) {
            a->edge[h[i].he] = SL_ADJ_NONE;
            a->opposite[h[i].he] = SL_ADJ_NONE;
            a->open_edges++;
        } else if (run == 2) {
            uint32_t e0 = h[i].he, e1 = h[i + 1].he;
            uint32_t t0 = e0 / 3, t1 = e1 / 3;
            uint32_t v0 = (uint32_t)(h[i].key >> 32), v1 = (uint32_t)h[i].key;
            if (t0 == t1) {
                /* one triangle using an edge twice has repeated vertices;
                 * scenes hold none, but it is no neighbour of itself */
                a->edge[e0] = a->edge[e1] = SL_ADJ_NONE;
                a->opposite[e0] = a->opposite[e1] = SL_ADJ_NONE;
                a->open_edges++;
            } else {
                a->edge[e0] = t1;
                a->edge[e1] = t0;
                a->opposite[e0] = third_vertex(s->idx + 3 * (size_t)t1, v0, v1);
                a->opposite[e1] = third_vertex(s->idx + 3 * (size_t)t0, v0, v1);
            }
        } else {
            for (size_t r = i; r < j; r++) {
                a->edge[h[r].he] = SL_ADJ_MULTI;
                a->opposite[h[r].he] = SL_ADJ_NONE;
            }
            a->nonmanifold_edges++;
        }
        i = j;
    }
    free(h);
    return SL_OK;
}

/* Merge the three ascending lists of t's corners into out (NULL: count
 * only), skipping t and duplicates; returns the count. */
static uint32_t merge_corners(const uint32_t *voff, const uint32_t *vt, const uint32_t *tri,
                              uint32_t t, uint32_t *out)
{
    const uint32_t *p[3], *e[3];
    for (int k = 0; k < 3; k++) {
        p[k] = vt + voff[tri[k]];
        e[k] = vt + voff[tri[k] + 1];
    }
    uint32_t n = 0, last = SL_ADJ_NONE;
    for (;;) {
        uint32_t best = SL_ADJ_NONE;
        for (int k = 0; k < 3; k++)
            if (p[k] < e[k] && *p[k] < best)
                best = *p[k];
        if (best == SL_ADJ_NONE)
            break;
        for (int k = 0; k < 3; k++)
            while (p[k] < e[k] && *p[k] == best)
                p[k]++;
        if (best != t && best != last) {
            if (out)
                out[n] = best;
            n++;
        }
        last = best;
    }
    return n;
}

static enum sl_err build_vertex(const struct sl_scene *s, struct sl_adjacency *a, struct sl_diag *d)
{
    uint32_t *voff = calloc((size_t)s->nv + 2, sizeof *voff);
    uint32_t *vt = malloc((3 * (size_t)s->nt + 1) * sizeof *vt);
    if (!voff || !vt) {
        free(voff);
        free(vt);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "vertex adjacency of %u vertices", s->nv);
    }
    /* counting sort of (vertex, triangle) by vertex, triangle order kept;
     * a triangle listed twice under one vertex (repeated index) is merged
     * away like any duplicate */
    for (size_t i = 0; i < 3 * (size_t)s->nt; i++)
        voff[s->idx[i] + 2]++;
    for (size_t v = 0; v < s->nv; v++)
        voff[v + 2] += voff[v + 1];
    for (size_t i = 0; i < 3 * (size_t)s->nt; i++)
        vt[voff[s->idx[i] + 1]++] = (uint32_t)(i / 3);
    /* now voff[v] .. voff[v+1] is vertex v's list */

    enum sl_err e = SL_OK;
    uint64_t total = 0;
    a->vtx_off[0] = 0;
    for (uint32_t t = 0; t < s->nt; t++) {
        total += merge_corners(voff, vt, s->idx + 3 * (size_t)t, t, NULL);
        if (total > 0xfffffff0u) {
            e = sl_fail(d, SL_E_SCENE, NULL, 0, NULL,
                        "vertex adjacency exceeds 2^32 entries (a vertex of huge valence)");
            break;
        }
        a->vtx_off[t + 1] = (uint32_t)total;
    }
    if (!e) {
        a->vtx_tris = malloc((total ? total : 1) * sizeof *a->vtx_tris);
        if (!a->vtx_tris)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "vertex adjacency of %llu entries",
                        (unsigned long long)total);
    }
    for (uint32_t t = 0; !e && t < s->nt; t++)
        merge_corners(voff, vt, s->idx + 3 * (size_t)t, t, a->vtx_tris + a->vtx_off[t]);
    free(voff);
    free(vt);
    return e;
}

void sl_adjacency_free(struct sl_adjacency *a)
{
    if (!a)
        return;
    free(a->edge);
    free(a->opposite);
    free(a->vtx_off);
    free(a->vtx_tris);
    memset(a, 0, sizeof *a);
}

enum sl_err sl_adjacency_build(const struct sl_scene *s, struct sl_adjacency *a, struct sl_diag *d)
{
    if (!a)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "sl_adjacency_build: NULL output");
    memset(a, 0, sizeof *a);
    if (!s || (s->nt && (!s->idx || !s->nv)))
        return sl_fail(d, SL_E_SCENE, NULL, 0, NULL, "adjacency of an empty or missing scene");
    if (s->nt > 0x55555555u)
        return sl_fail(d, SL_E_SCENE, NULL, 0, NULL, "too many triangles for adjacency: %u", s->nt);
    for (size_t i = 0; i < 3 * (size_t)s->nt; i++)
        if (s->idx[i] >= s->nv)
            return sl_fail(d, SL_E_SCENE, NULL, 0, NULL, "triangle %zu indexes a missing vertex",
                           i / 3);
    size_t n3 = 3 * (size_t)s->nt;
    a->nt = s->nt;
    a->edge = malloc((n3 ? n3 : 1) * sizeof *a->edge);
    a->opposite = malloc((n3 ? n3 : 1) * sizeof *a->opposite);
    a->vtx_off = malloc(((size_t)s->nt + 1) * sizeof *a->vtx_off);
    enum sl_err e = SL_OK;
    if (!a->edge || !a->opposite || !a->vtx_off)
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "adjacency of %u triangles", s->nt);
    if (!e)
        e = build_edges(s, a, d);
    if (!e)
        e = build_vertex(s, a, d);
    if (e)
        sl_adjacency_free(a);
    return e;
}
