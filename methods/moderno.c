/*
 * moderno.c — Moderno 2011, "Shadow Mapping and Ray-Tracing": how far the
 * shadow map's own information (depths and the ids of the triangles it
 * stores) confirms or corrects a pixel with a handful of ray-triangle tests.
 *
 * All read the front-face-culled depth + id layer of normal shadow mapping
 * (the thesis's map; coherence by default) and start from its verdict
 * (kept in verdicts.base, so the figures count corrected / turned bad /
 * maintained against NSM):
 * - coherence (texels 4 or 9): the pixel's depth test against the 2x2 texels
 *   of its bilinear footprint or the 3x3 around its texel; all agree: a hint
 *   (may be wrong); otherwise undecided. Its self_shadow (default
 *   front_faces, the thesis's) may name any of nsm's policies, read from
 *   the map of the nearest surfaces as nsm reads it.
 * - texel: a ray against the triangle stored in the texel: a hit shadows the
 *   pixel (confirms NSM's shadow, or corrects its light: Figure 19).
 * - neighbours (texels 4 or 9): the same against the triangles of the texel
 *   and its 3 neighbours toward the pixel's quadrant, or all 8 neighbours.
 * - adjacency (level 1 or 2): the stored triangle and its edge-adjacent (1)
 *   or vertex-adjacent (2) triangles.
 * - chain (finish trace or lit): coherence(4) -> neighbours(9) ->
 *   adjacency(2) for pixels the map shadows -> the rest traced with Embree,
 *   or left lit.
 * Standalone, a method that finds no intersection leaves the pixel lit
 * (sections 4.5-4.7); in the chain it stays undecided.
 *
 * A "hit" is a sure one (sl_shadow_ray_tri_sure's +1, asked as
 * sl_shadow_ray_tri_hit: the same answer in a cheaper order): the ray
 * crosses the triangle inside by a margin and beyond twice the truth's
 * tnear, so Embree meets it too: a confirmation or a correction is never
 * wrong (the driver checks it, SL_EXACT_PROVED). Rays that graze a
 * triangle's edge count as no hit, the side that can only leave a pixel
 * undecided.
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include "adjacency.h"
#include "method.h"
#include "raytri.h"
#include "truth.h"
#include "util.h"

enum kind { K_COHERENCE, K_TEXEL, K_NEIGHBOURS, K_ADJACENCY };

static unsigned needs_map(const struct sl_method_params *p) { (void)p; return SL_NEED(SL_LAYER_DEPTH_ID_BACK); }
static unsigned needs_adj(const struct sl_method_params *p) { (void)p; return SL_NEED(SL_LAYER_DEPTH_ID_BACK) | SL_NEED_ADJACENCY; }

/* texels: 4 (2x2) or 9 (3x3), declared as the range 4..9 and checked here */
static const struct sl_param texels_params[] = {
    SL_PARAM_INT_DECL("texels", 4, 4, 9, "texels", "texels tested: 4 (2x2) or 9 (3x3)"),
};
/* coherence alone takes the self-shadow policy too (issue 48: which policy
 * reproduces the thesis's wrong hints); the chain keeps the thesis's map */
static const struct sl_param coherence_params[] = {
    SL_PARAM_INT_DECL("texels", 4, 4, 9, "texels", "texels tested: 4 (2x2) or 9 (3x3)"),
    SL_SELF_SHADOW_DECL,
    SL_DEPTH_BIAS_DECLS,
};
static const struct sl_param level_params[] = {
    SL_PARAM_INT_DECL("level", 2, 1, 2, "", "1: the stored triangle's edge neighbours; 2: and its vertex neighbours"),
};
static const struct sl_param chain_params[] = {
    SL_PARAM_CHOICE_DECL("finish", 0, "what the chain does with the pixels its steps leave: trace them or leave them lit",
                         "trace", "lit"),
};

static enum sl_err conf_texels(struct sl_method_params *p, struct sl_diag *d)
{
    int texels = (int)sl_method_param(p, "texels");
    if (texels != 4 && texels != 9)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "texels", "texels must be 4 or 9");
    return SL_OK;
}

static enum sl_err conf_coherence(struct sl_method_params *p, struct sl_diag *d)
{
    enum sl_err e = conf_texels(p, d);
    return e ? e : sl_self_shadow_configure(p, d);
}

static int coherence_policy(const struct sl_method_params *p)
{
    return (int)sl_method_param(p, "self_shadow");
}

/* front_faces reads the thesis's culled map; the other policies the map
 * of the nearest surfaces, as nsm does under them */
static unsigned needs_coherence(const struct sl_method_params *p)
{
    return coherence_policy(p) == SL_SELF_FRONT_FACES ? SL_NEED(SL_LAYER_DEPTH_ID_BACK)
                                                      : SL_NEED(SL_LAYER_DEPTH_ID);
}

struct ctx {
    const struct sl_method_args *a;
    const struct sl_depth_layer *L;
    const struct sl_frame_look *look;   /* the driver's lookups in L for this view, or NULL */
    int S;
};

static struct ctx ctx_of(const struct sl_method_args *a)
{
    const struct sl_light_frame *f = a->frame;
    const struct sl_view *v = a->view;
    return (struct ctx){.a = a, .L = &f->layer[SL_LAYER_DEPTH_ID_BACK], .S = f->size,
                        .look = sl_frame_look_of(f, SL_LAYER_DEPTH_ID_BACK, v->serial, (size_t)v->w * v->h)};
}

/* A decided pixel's lookup in the map: texel coordinates u, w, window
 * depth z, texel k and NSM's verdict there. Taken from the lookups the
 * driver made once for the view (sl_frame_look: every method here makes
 * the same ones) or, without them, made here by the same inline code. */
struct pix {
    float u, w, z;
    uint32_t k;
    uint8_t nsm;
};

static inline void pix_at(const struct ctx *c, long i, struct pix *q)
{
    if (c->look) {
        const struct sl_pix_look l = c->look->px[i];
        q->u = l.u, q->w = l.v, q->z = l.z;
        q->k = l.k & ~SL_LOOK_SHADOW;
        q->nsm = (l.k & SL_LOOK_SHADOW) ? SL_V_SHADOW : SL_V_LIT;
        return;
    }
    const struct sl_light_frame *f = c->a->frame;
    sl_frame_project(f, c->a->view->pos + 3 * i, &q->u, &q->w, &q->z);
    q->k = sl_frame_texel(f, q->u, q->w);
    q->nsm = q->z <= c->L->depth[q->k] ? SL_V_LIT : SL_V_SHADOW;
}

/* The triangle (+ 1) the map stores at pixel i's texel k. */
static inline uint32_t stored_at(const struct ctx *c, long i, uint32_t k)
{
    return c->look ? c->look->id[i] : c->L->id[k];
}

/* What the lookups cost, charged to each method that reads them (as the
 * work each would otherwise do itself). */
static double look_ms(const struct ctx *c, int pcf)
{
    return c->look ? c->look->ms + (pcf && c->look->pcf ? c->look->ms_pcf : 0.0) : 0.0;
}

/* A pixel's shadow ray: its origin, direction toward the light, end and
 * start (sl_rt_tnear), computed on the first test that needs them: most
 * pixels test no triangle (their texels store nothing, or their own
 * triangle), and the direction was a call per pixel for every method. */
struct sray {
    const struct sl_light_frame *f;
    const float *p;
    float toward[3], tmax, tnear;
    int ready;
};

static void sray_of(const struct ctx *c, const float p[3], struct sray *r)
{
    r->f = c->a->frame;
    r->p = p;
    r->ready = 0;
}

static const struct sray *sray_get(struct sray *r)
{
    if (!r->ready) {
        sl_frame_toward(r->f, r->p, r->toward, &r->tmax);
        r->tnear = sl_rt_tnear(r->p);
        r->ready = 1;
    }
    return r;
}

/* 1 all lit, 2 all shadowed, 0 not coherent; *shadowed = how many say shadow:
 * the percentage-closer count of the view's lookups where the driver made
 * them (SL_LOOK_PCF), else counted here by the same inline code. */
static int coherence(const struct ctx *c, long i, float u, float v, float z, int texels, uint64_t *lookups,
                     int *shadowed)
{
    const int n = texels == 4 ? 4 : 9;
    const int lit = c->look && c->look->pcf ? (texels == 4 ? c->look->pcf[i] & 15 : c->look->pcf[i] >> 4)
                                            : sl_frame_pcf_lit(c->L->depth, c->S, u, v, z, texels);
    *lookups += (uint64_t)n;
    *shadowed = n - lit;
    return lit == n ? 1 : lit == 0 ? 2 : 0;
}

static int sure_hit(const struct ctx *c, struct sray *r, uint32_t tri_plus1, uint32_t own, uint64_t *tests)
{
    if (!tri_plus1 || tri_plus1 == own)
        return 0;
    const struct sl_scene *s = c->a->scene;
    const uint32_t *ix = s->idx + 3 * (size_t)(tri_plus1 - 1);
    const struct sray *g = sray_get(r);
    (*tests)++;
    return sl_shadow_ray_tri_hit(g->p, g->toward, g->tmax, g->tnear, s->pos + 3 * ix[0], s->pos + 3 * ix[1],
                                 s->pos + 3 * ix[2]);
}

/* Triangles of the texel and its neighbours: 4 toward the pixel's quadrant or 9. */
static int neighbours_hit(const struct ctx *c, struct sray *p, float u, float v, int texels, uint32_t own,
                          uint64_t *lookups, uint64_t *tests)
{
    int tx = (int)floorf(u), ty = (int)floorf(v);
    int x0 = tx - 1, y0 = ty - 1, n = 3;
    if (texels == 4) {
        x0 = (u - (float)tx < 0.5f) ? tx - 1 : tx;
        y0 = (v - (float)ty < 0.5f) ? ty - 1 : ty;
        n = 2;
    }
    const int inside = x0 >= 0 && y0 >= 0 && x0 + n <= c->S && y0 + n <= c->S;
    if (inside) {
        /* Most pixels' texels all hold nothing or the pixel's own triangle,
         * which sure_hit never tests: then the walk below would look each
         * up and test none. One pass over them, without branches, says so. */
        const uint32_t *row = c->L->id + (size_t)y0 * (size_t)c->S + (size_t)x0;
        int any = 0;
        for (int j = 0; j < n; j++, row += c->S)
            for (int i = 0; i < n; i++)
                any |= row[i] != 0 && row[i] != own;
        if (!any) {
            *lookups += (uint64_t)(n * n);
            return 0;
        }
    }
    uint32_t seen[9];
    int nseen = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int x = x0 + i, y = y0 + j;
            if (!inside && (x < 0 || y < 0 || x >= c->S || y >= c->S))
                continue;
            (*lookups)++;
            uint32_t id = c->L->id[(size_t)y * (size_t)c->S + (size_t)x];
            /* sure_hit tests neither an empty texel nor the pixel's own
             * triangle: passing them over before the dedupe leaves the same
             * tests in the same order, and most texels hold one of them */
            if (!id || id == own)
                continue;
            int dup = 0;
            for (int k = 0; k < nseen; k++)
                dup |= seen[k] == id;
            if (dup)
                continue;
            seen[nseen++] = id;
            if (sure_hit(c, p, id, own, tests))
                return 1;
        }
    return 0;
}

static int adjacency_hit(const struct ctx *c, struct sray *p, uint32_t stored, int level, uint32_t own,
                         uint64_t *tests)
{
    if (!stored)
        return 0;
    if (sure_hit(c, p, stored, own, tests))
        return 1;
    const struct sl_adjacency *adj = c->a->adj;
    uint32_t t = stored - 1;
    if (level == 1) {
        for (int k = 0; k < 3; k++) {
            uint32_t nb = adj->edge[3 * (size_t)t + (size_t)k];
            if (nb != SL_ADJ_NONE && nb != SL_ADJ_MULTI && sure_hit(c, p, nb + 1, own, tests))
                return 1;
        }
        return 0;
    }
    for (uint32_t k = adj->vtx_off[t]; k < adj->vtx_off[t + 1]; k++)
        if (sure_hit(c, p, adj->vtx_tris[k] + 1, own, tests))
            return 1;
    return 0;
}

static enum sl_err run_kind(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *cost,
                            enum kind kind, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_light_frame *f = a->frame;
    if (!(f->have & SL_NEED(SL_LAYER_DEPTH_ID_BACK)))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "moderno: the shadow map was not rendered");
    if (kind == K_ADJACENCY && !a->adj)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "moderno: no adjacency");
    const struct ctx c = ctx_of(a);
    const long n = (long)v->w * v->h;
    const int texels = kind == K_COHERENCE || kind == K_NEIGHBOURS ? (int)sl_method_param(a->params, "texels") : 0;
    const int level = kind == K_ADJACENCY ? (int)sl_method_param(a->params, "level") : 0;
    out->has_base = 1;
    out->has_detail = kind == K_COHERENCE;
    uint64_t lookups = 0, tests = 0;
    double t0 = sl_now();
#pragma omp parallel for num_threads(a->threads) schedule(dynamic, 4096) reduction(+ : lookups, tests)
    for (long i = 0; i < n; i++) {
        if (sl_verdict_fixed(v, (size_t)i, out)) {
            out->base[i] = out->v[i];
            continue;
        }
        const float *p = v->pos + 3 * i;
        struct pix q;
        pix_at(&c, i, &q);
        const float u = q.u, w = q.w, z = q.z;
        lookups++;
        const uint64_t tests_before = tests;
        const uint8_t nsm = q.nsm;
        out->base[i] = nsm;
        const uint32_t own = v->tri[i];
        int hit = 0, coh = 0, shadowed = 0;
        struct sray ray;
        switch (kind) {
        case K_COHERENCE:
            coh = coherence(&c, i, u, w, z, texels, &lookups, &shadowed);
            out->v[i] = coh == 1 ? SL_V_LIT : coh == 2 ? SL_V_SHADOW : SL_V_UNCERTAIN;
            out->how[i] = coh ? SL_HOW_HINT : SL_HOW_NONE;
            out->detail[i] = (uint8_t)shadowed;
            continue;
        case K_TEXEL:
            sray_of(&c, p, &ray);
            hit = sure_hit(&c, &ray, stored_at(&c, i, q.k), own, &tests);
            break;
        case K_NEIGHBOURS:
            sray_of(&c, p, &ray);
            hit = neighbours_hit(&c, &ray, u, w, texels, own, &lookups, &tests);
            break;
        case K_ADJACENCY:
            sray_of(&c, p, &ray);
            hit = adjacency_hit(&c, &ray, stored_at(&c, i, q.k), level, own, &tests);
            break;
        }
        out->tests[i] = (uint8_t)(tests - tests_before > 255 ? 255 : tests - tests_before);
        if (hit) {
            out->v[i] = SL_V_SHADOW;
            out->how[i] = nsm == SL_V_SHADOW ? SL_HOW_CONFIRM : SL_HOW_CORRECT;
        } else {
            out->v[i] = SL_V_LIT;           /* standalone: no intersection, lit */
            out->how[i] = SL_HOW_FALLBACK;
        }
    }
    cost->ms_method += 1e3 * (sl_now() - t0) + look_ms(&c, kind == K_COHERENCE);
    cost->lookups += lookups;
    cost->tri_tests += tests;
    return SL_OK;
}

static uint8_t clamp255(uint64_t x) { return (uint8_t)(x > 255 ? 255 : x); }

/* The chain, one timed pass per step over the pixels the steps before left
 * undecided (stage[i]: 1 after coherence, 2 after neighbours, 3 after
 * adjacency): so that each step's time and rays come out apart. */
static enum sl_err run_chain_steps(const struct sl_method_args *a, struct sl_verdicts *out,
                                   struct sl_cost *cost, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_light_frame *f = a->frame;
    if (!(f->have & SL_NEED(SL_LAYER_DEPTH_ID_BACK)) || !a->adj)
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "chain: no shadow map or no adjacency");
    const struct ctx c = ctx_of(a);
    const long n = (long)v->w * v->h;
    uint8_t *stage = sl_calloc((size_t)n, 1);
    if (!stage)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "chain stages");
    out->has_base = 1;
    uint64_t lookups = 0, tests = 0;
    for (int step = 0; step < 3; step++) {
        double t0 = sl_now();
#pragma omp parallel for num_threads(a->threads) schedule(dynamic, 4096) reduction(+ : lookups, tests)
        for (long i = 0; i < n; i++) {
            if (step == 0 && sl_verdict_fixed(v, (size_t)i, out)) {
                out->base[i] = out->v[i];
                continue;
            }
            if (step > 0 && stage[i] != step)
                continue;
            const float *p = v->pos + 3 * i;
            struct pix q;
            pix_at(&c, i, &q);
            const float u = q.u, w = q.w, z = q.z;
            const uint64_t before = tests;
            if (step == 0) {                    /* NSM, then coherence over 4 texels */
                lookups++;
                out->base[i] = q.nsm;
                int shadowed, coh = coherence(&c, i, u, w, z, 4, &lookups, &shadowed);
                if (coh) {
                    out->v[i] = coh == 1 ? SL_V_LIT : SL_V_SHADOW;
                    out->how[i] = SL_HOW_HINT;
                } else {
                    stage[i] = 1;
                }
                continue;
            }
            struct sray ray;
            sray_of(&c, p, &ray);
            if (step == 1 && neighbours_hit(&c, &ray, u, w, 9, v->tri[i], &lookups, &tests)) {
                out->v[i] = SL_V_SHADOW;
                out->how[i] = out->base[i] == SL_V_SHADOW ? SL_HOW_CONFIRM : SL_HOW_CORRECT;
            } else if (step == 2 && out->base[i] == SL_V_SHADOW &&
                       adjacency_hit(&c, &ray, stored_at(&c, i, q.k), 2, v->tri[i], &tests)) {
                out->v[i] = SL_V_SHADOW;        /* the map shadowed it: a confirmation */
                out->how[i] = SL_HOW_CONFIRM_ADJ;
            } else {
                stage[i] = (uint8_t)(step + 1);
            }
            out->tests[i] = clamp255(out->tests[i] + tests - before);
        }
        cost->ms_step[step] = 1e3 * (sl_now() - t0) + (step == 0 ? look_ms(&c, 1) : 0.0);
        cost->ms_method += cost->ms_step[step];
    }
    cost->lookups += lookups;
    cost->tri_tests += tests;
    /* what is left: traced, or left lit */
    double t0 = sl_now();
    enum sl_err e = SL_OK;
    for (long i = 0; i < n; i++)
        if (stage[i] == 3) {
            out->v[i] = SL_V_LIT;
            out->how[i] = SL_HOW_FALLBACK;
        }
    if (sl_method_param(a->params, "finish") == 0) {   /* trace */
        for (long i = 0; i < n; i++)
            stage[i] = stage[i] == 3;
        double ms_method = cost->ms_method;
        e = sl_method_trace_left(a, stage, NULL, out, cost, d);
        cost->ms_method = ms_method;        /* added below with the step */
    }
    cost->ms_step[3] = 1e3 * (sl_now() - t0);
    cost->ms_method += cost->ms_step[3];
    free(stage);
    return e;
}

/* Coherence under a self-shadow policy other than the thesis's culled map
 * (none, constant, slope, triangle_id): the map of the nearest surfaces,
 * NSM's verdict and each footprint texel's test made as nsm makes them
 * under that policy (the same offset; under triangle_id a texel storing
 * the pixel's own triangle says lit), over the texels sl_frame_pcf_lit
 * reads. Under front_faces run_kind's path is taken (the driver's shared
 * lookups). */
static enum sl_err run_coherence_policy(const struct sl_method_args *a, struct sl_verdicts *out,
                                        struct sl_cost *cost, struct sl_diag *d)
{
    const struct sl_view *v = a->view;
    const struct sl_light_frame *f = a->frame;
    if (!(f->have & SL_NEED(SL_LAYER_DEPTH_ID)))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, NULL, "coherence: the nearest-surface map was not rendered");
    const float *depth = f->layer[SL_LAYER_DEPTH_ID].depth;
    const uint32_t *id = f->layer[SL_LAYER_DEPTH_ID].id;
    const int S = f->size;
    const int texels = (int)sl_method_param(a->params, "texels");
    const int n1 = texels == 4 ? 2 : 3;
    struct sl_self_test t;
    sl_self_test_of(a, &t);
    const int tid = t.policy == SL_SELF_TRIANGLE_ID;
    const long n = (long)v->w * v->h;
    out->has_base = 1;
    out->has_detail = 1;
    uint64_t lookups = 0;
    double t0 = sl_now();
#pragma omp parallel for num_threads(a->threads) schedule(dynamic, 4096) reduction(+ : lookups)
    for (long i = 0; i < n; i++) {
        if (sl_verdict_fixed(v, (size_t)i, out)) {
            out->base[i] = out->v[i];
            continue;
        }
        const float *p = v->pos + 3 * i;
        float u, w, z;
        sl_frame_project(f, p, &u, &w, &z);
        const uint32_t k = sl_frame_texel(f, u, w), own = v->tri[i];
        const float zo = z - sl_self_offset(&t, f, p, v->nrm + 3 * i, z);
        out->base[i] = (tid && id[k] == own) || zo <= depth[k] ? SL_V_LIT : SL_V_SHADOW;
        /* the footprint's depth tests at the offset depth are
         * sl_frame_pcf_lit's; triangle_id also lights a texel that stores
         * the pixel's own triangle, so it walks the same texels itself */
        int lit;
        if (!tid)
            lit = sl_frame_pcf_lit(depth, S, u, w, zo, texels);
        else {
            const int x0 = texels == 4 ? (int)floorf(u - 0.5f) : (int)floorf(u) - 1;
            const int y0 = texels == 4 ? (int)floorf(w - 0.5f) : (int)floorf(w) - 1;
            lit = 0;
            for (int jj = 0; jj < n1; jj++)
                for (int ii = 0; ii < n1; ii++) {
                    const int tx = x0 + ii < 0 ? 0 : x0 + ii >= S ? S - 1 : x0 + ii;
                    const int ty = y0 + jj < 0 ? 0 : y0 + jj >= S ? S - 1 : y0 + jj;
                    const size_t kk = (size_t)ty * (size_t)S + (size_t)tx;
                    lit += id[kk] == own || zo <= depth[kk];
                }
        }
        lookups += 1 + (uint64_t)(n1 * n1);
        const int coh = lit == n1 * n1 ? 1 : lit == 0 ? 2 : 0;
        out->v[i] = coh == 1 ? SL_V_LIT : coh == 2 ? SL_V_SHADOW : SL_V_UNCERTAIN;
        out->how[i] = coh ? SL_HOW_HINT : SL_HOW_NONE;
        out->detail[i] = (uint8_t)(n1 * n1 - lit);
    }
    cost->ms_method += 1e3 * (sl_now() - t0);
    cost->lookups += lookups;
    return SL_OK;
}

static enum sl_err run_coherence(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d)
{
    return coherence_policy(a->params) == SL_SELF_FRONT_FACES ? run_kind(a, o, c, K_COHERENCE, d)
                                                               : run_coherence_policy(a, o, c, d);
}
static enum sl_err run_texel(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_kind(a, o, c, K_TEXEL, d); }
static enum sl_err run_neighbours(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_kind(a, o, c, K_NEIGHBOURS, d); }
static enum sl_err run_adjacency(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_kind(a, o, c, K_ADJACENCY, d); }
static enum sl_err run_chain(const struct sl_method_args *a, struct sl_verdicts *o, struct sl_cost *c, struct sl_diag *d) { return run_chain_steps(a, o, c, d); }

const struct sl_method sl_method_coherence = {
    .cite = "moderno2011",
    .name = "coherence", .display = "Texel coherence", .family = "moderno-2011", .summary = "texel coherence, 4 or 9 texels (Moderno 2011): hints, may be wrong",
    SL_METHOD_PARAMS(coherence_params), .needs = needs_coherence, .configure = conf_coherence, .run = run_coherence,
    .fast = {.looks = SL_NEED(SL_LAYER_DEPTH_ID_BACK), .look_parts = SL_LOOK_PCF},
};
const struct sl_method sl_method_texel = {
    .cite = "moderno2011",
    .name = "texel", .display = "Single texel", .family = "moderno-2011", .summary = "a ray against the texel's stored triangle (Moderno 2011)",
    .exact = SL_EXACT_PROVED, .needs = needs_map, .run = run_texel,
    .fast = {.looks = SL_NEED(SL_LAYER_DEPTH_ID_BACK)},
};
const struct sl_method sl_method_neighbours = {
    .cite = "moderno2011",
    .name = "neighbours", .display = "Neighbour texels", .family = "moderno-2011", .summary = "rays against the triangles of 4 or 9 texels (Moderno 2011)",
    .exact = SL_EXACT_PROVED, SL_METHOD_PARAMS(texels_params), .needs = needs_map, .configure = conf_texels,
    .run = run_neighbours, .fast = {.looks = SL_NEED(SL_LAYER_DEPTH_ID_BACK)},
};
const struct sl_method sl_method_adjacency = {
    .cite = "moderno2011",
    .name = "adjacency", .display = "Adjacent geometry", .family = "moderno-2011", .summary = "rays against the stored triangle and its edge (1) or vertex (2) neighbours",
    .exact = SL_EXACT_PROVED, SL_METHOD_PARAMS(level_params), .needs = needs_adj,
    .run = run_adjacency, .fast = {.looks = SL_NEED(SL_LAYER_DEPTH_ID_BACK)},
};
const struct sl_method sl_method_chain = {
    .cite = "moderno2011",
    .name = "chain", .display = "Moderno chain", .family = "moderno-2011", .summary = "coherence(4) -> neighbours(9) -> adjacency(2) -> traced or lit (Moderno 2011)",
    .exact = SL_EXACT_PROVED, SL_METHOD_PARAMS(chain_params), .needs = needs_adj,
    .run = run_chain, .fast = {.looks = SL_NEED(SL_LAYER_DEPTH_ID_BACK), .look_parts = SL_LOOK_PCF},
};
