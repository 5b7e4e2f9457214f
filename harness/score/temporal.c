/*
 * temporal.c — see temporal.h.
 * Invariants: a snapshot's verdict slots belong to its frame only (they are
 * marked empty when the snapshot is refilled); flicker never compares two
 * pixels on different triangles or with different truths.
 */
#include "temporal.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "method.h"
#include "util.h"

/* What the pixel shows: an undecided pixel is left for a shadow ray
 * (method.h), whose answer is the truth's. */
static uint8_t resolved(uint8_t v, uint8_t truth)
{
    if (v != SL_V_UNCERTAIN)
        return v;
    return truth == SL_T_LIT ? SL_V_LIT : truth == SL_T_BACKGROUND ? SL_V_NONE : SL_V_SHADOW;
}

void sl_temporal_match(const struct sl_temporal_frame *a, const struct sl_temporal_frame *b, int same_camera,
                       uint32_t *match)
{
    const size_t np = (size_t)a->w * (size_t)a->h;
    for (size_t p = 0; p < np; p++) {
        match[p] = 0;
        if (!a->tri[p])
            continue;
        size_t q = p;
        if (!same_camera) {
            vec4 w, h;
            sl_point4(a->pos + 3 * p, w);
            glm_mat4_mulv((vec4 *)b->vp, w, h);
            if (!(h[3] > 0.0f))
                continue;   /* behind the later camera */
            double x = ((double)h[0] / h[3] * 0.5 + 0.5) * b->w, y = ((double)h[1] / h[3] * 0.5 + 0.5) * b->h;
            if (!(x >= 0.0 && y >= 0.0 && x < (double)b->w && y < (double)b->h))
                continue;
            q = (size_t)floor(y) * (size_t)b->w + (size_t)floor(x);
        } else if (a->w != b->w || a->h != b->h) {
            continue;
        }
        if (b->tri[q] == a->tri[p] && b->truth[q] == a->truth[p])
            match[p] = (uint32_t)q + 1u;
    }
}

uint64_t sl_temporal_count(const struct sl_temporal_frame *a, const uint8_t *va, const struct sl_temporal_frame *b,
                           const uint8_t *vb, const uint32_t *match, uint64_t *compared)
{
    uint64_t n = 0, c = 0;
    const size_t np = (size_t)a->w * (size_t)a->h;
    for (size_t p = 0; p < np; p++) {
        if (!match[p])
            continue;
        const size_t q = match[p] - 1u;
        c++;
        n += resolved(va[p], a->truth[p]) != resolved(vb[q], b->truth[q]);
    }
    if (compared)
        *compared = c;
    return n;
}

uint64_t sl_temporal_flicker(const struct sl_temporal_frame *a, const uint8_t *va,
                             const struct sl_temporal_frame *b, const uint8_t *vb, int same_camera,
                             uint64_t *compared)
{
    uint32_t *match = sl_calloc((size_t)a->w * (size_t)a->h, sizeof *match);
    if (!match) {
        if (compared)
            *compared = 0;
        return 0;
    }
    sl_temporal_match(a, b, same_camera, match);
    uint64_t n = sl_temporal_count(a, va, b, vb, match, compared);
    free(match);
    return n;
}

static void snapshot_free(struct sl_temporal *t, int s)
{
    free(t->pos[s]);
    free(t->tri[s]);
    free(t->truth[s]);
    if (s == 0) {
        free(t->match);
        t->match = NULL;
        t->have_match = 0;
    }
    t->pos[s] = NULL;
    t->tri[s] = NULL;
    t->truth[s] = NULL;
    for (int k = 0; k < SL_TEMPORAL_SLOTS; k++) {
        free(t->v[s][k]);
        t->v[s][k] = NULL;
        t->has_v[s][k] = 0;
    }
    t->have[s] = 0;
}

void sl_temporal_free(struct sl_temporal *t)
{
    if (!t)
        return;
    snapshot_free(t, 0);
    snapshot_free(t, 1);
    memset(t, 0, sizeof *t);
}

static void frame_of(const struct sl_temporal *t, int s, struct sl_temporal_frame *f)
{
    f->w = t->w;
    f->h = t->h;
    f->pos = t->pos[s];
    f->tri = t->tri[s];
    f->truth = t->truth[s];
    glm_mat4_copy((vec4 *)t->cam[s], f->vp);
}

static int same_camera(const struct sl_viewpoint *a, const struct sl_viewpoint *b)
{
    return memcmp(a->pos, b->pos, sizeof a->pos) == 0 && memcmp(a->dir, b->dir, sizeof a->dir) == 0 &&
           memcmp(a->up, b->up, sizeof a->up) == 0 && a->fov_deg == b->fov_deg && a->znear == b->znear &&
           a->zfar == b->zfar;
}

enum sl_err sl_temporal_view(struct sl_temporal *t, int scene, int viewport, const struct sl_viewpoint *vp,
                             const struct sl_view *v, struct sl_diag *d)
{
    const double t0 = sl_now();
    const int prev = t->cur;
    const int follows = vp->path >= 0 && t->have[prev] && t->scene[prev] == scene && t->viewport[prev] == viewport &&
                        t->vp[prev].path == vp->path && t->vp[prev].frame + 1 == vp->frame &&
                        t->w == v->w && t->h == v->h;
    if (!follows)
        t->have[prev] = 0;
    if (vp->path < 0) {
        t->have[1 - prev] = 0;
        return SL_OK;
    }
    if (t->w != v->w || t->h != v->h) {
        snapshot_free(t, 0);
        snapshot_free(t, 1);
        t->w = v->w;
        t->h = v->h;
    }
    const int s = 1 - prev;
    const size_t np = (size_t)v->w * (size_t)v->h;
    if (!t->pos[s]) {
        t->pos[s] = sl_calloc(np, 3 * sizeof(float));
        t->tri[s] = sl_calloc(np, sizeof(uint32_t));
        t->truth[s] = sl_calloc(np, 1);
        if (!t->pos[s] || !t->tri[s] || !t->truth[s]) {
            snapshot_free(t, s);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "frame snapshot %dx%d", v->w, v->h);
        }
    }
    memcpy(t->pos[s], v->pos, np * 3 * sizeof(float));
    memcpy(t->tri[s], v->tri, np * sizeof(uint32_t));
    memcpy(t->truth[s], v->truth, np);
    glm_mat4_mul((vec4 *)v->proj, (vec4 *)v->view, t->cam[s]);
    memset(t->has_v[s], 0, sizeof t->has_v[s]);
    t->vp[s] = *vp;
    t->scene[s] = scene;
    t->viewport[s] = viewport;
    t->have[s] = 1;
    t->cur = s;
    /* where the previous frame's pixels land in this one, once for every
     * (map, label) of the view */
    t->have_match = 0;
    t->ms_match = 0.0;
    if (t->have[prev]) {
        if (!t->match && !(t->match = sl_calloc(np, sizeof *t->match)))
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "frame match %dx%d", v->w, v->h);
        struct sl_temporal_frame a, b;
        frame_of(t, prev, &a);
        frame_of(t, s, &b);
        sl_temporal_match(&a, &b, same_camera(&t->vp[prev], &t->vp[s]), t->match);
        t->have_match = 1;
    }
    t->ms_match = 1e3 * (sl_now() - t0);   /* the frame's copies and the match */
    return SL_OK;
}

enum sl_err sl_temporal_cell(struct sl_temporal *t, int map, int label, const uint8_t *verdicts, int *measured,
                             uint64_t *flicker, uint64_t *compared, double *ms, struct sl_diag *d)
{
    const double t0 = sl_now();
    if (ms)
        *ms = 0.0;
    *measured = 0;
    *flicker = *compared = 0;
    const int s = t->cur, p = 1 - s, slot = map * 32 + label;
    if (!t->have[s] || slot < 0 || slot >= SL_TEMPORAL_SLOTS)
        return SL_OK;
    const size_t np = (size_t)t->w * (size_t)t->h;
    if (!t->v[s][slot] && !(t->v[s][slot] = sl_calloc(np, 1)))
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "frame verdicts %dx%d", t->w, t->h);
    memcpy(t->v[s][slot], verdicts, np);
    t->has_v[s][slot] = 1;
    if (!t->have[p] || !t->has_v[p][slot] || !t->have_match)
        return SL_OK;
    struct sl_temporal_frame a, b;
    frame_of(t, p, &a);
    frame_of(t, s, &b);
    *flicker = sl_temporal_count(&a, t->v[p][slot], &b, verdicts, t->match, compared);
    *measured = 1;
    if (ms)
        *ms = 1e3 * (sl_now() - t0) + t->ms_match;
    return SL_OK;
}
