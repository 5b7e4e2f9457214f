/*
 * external.c — method `external` (external.h): an image rendered by another
 * program, registered against the view, then read as verdicts and a
 * visibility.
 *
 * Registration is a comparison under a few transforms of the image: as it
 * stands, rows flipped, columns flipped, and shifted one pixel each way.
 * The image is refused when, as it stands, more than the tolerance of its
 * pixels disagree with the view, or when one of the other transforms would
 * halve the disagreement (an image off by one pixel disagrees only along
 * silhouettes, a small share, which the tolerance alone would let pass).
 * The cause named is the transform that explains it; when none does, the
 * foreground's share (another field of view) or where the disagreeing
 * pixels lie (along silhouettes only: jitter or a half-pixel offset) says
 * what is likely.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "external.h"
#include "method.h"

float sl_external_view_depth(const struct sl_view *v, size_t i)
{
    if (v->tri[i] == 0)
        return NAN;
    const float *p = v->pos + 3 * i;
    /* eye-space z of the position (cglm: column-major, view[col][row]) */
    float z = v->view[0][2] * p[0] + v->view[1][2] * p[1] + v->view[2][2] * p[2] + v->view[3][2];
    return -z;
}

/* The transforms tried, the first the image as it stands. */
struct xform {
    int flip_x, flip_y, dx, dy;
    const char *cause;
};
static const struct xform xforms[] = {
    {0, 0, 0, 0, NULL},
    {0, 1, 0, 0, "y flipped: its rows are upside down (a GL read-back saved bottom row first, or a "
                 "Vulkan / D3D viewport with y up); flip the rows"},
    {1, 0, 0, 0, "x flipped: its columns run right to left; mirror it"},
    {0, 0, 1, 0, "off by one pixel: the image is shifted one pixel right of the view (pixel centres at "
                 "integer coordinates, or a viewport offset)"},
    {0, 0, -1, 0, "off by one pixel: the image is shifted one pixel left of the view (pixel centres at "
                  "integer coordinates, or a viewport offset)"},
    {0, 0, 0, 1, "off by one pixel: the image is shifted one pixel up from the view (pixel centres at "
                 "integer coordinates, or a viewport offset)"},
    {0, 0, 0, -1, "off by one pixel: the image is shifted one pixel down from the view (pixel centres at "
                  "integer coordinates, or a viewport offset)"},
};
#define NXFORMS ((int)(sizeof xforms / sizeof xforms[0]))

/* The image's pixel that transform t puts at the view's (x, y); -1 outside. */
static long source_of(const struct xform *t, int w, int h, int x, int y)
{
    int sx = (t->flip_x ? w - 1 - x : x) + t->dx, sy = (t->flip_y ? h - 1 - y : y) + t->dy;
    if (sx < 0 || sy < 0 || sx >= w || sy >= h)
        return -1;
    return (long)sy * w + sx;
}

/* Whether the image's pixel s disagrees with the view's pixel i, and by how
 * much (score: 1 for a background disagreement, the relative depth error
 * capped at 1 otherwise; 0 agree). */
static double disagree(const struct sl_external *e, const struct sl_view *v, size_t i, long s, int *bad)
{
    int vbg = v->tri[i] == 0;
    if (e->depth) {
        float z = e->depth[s];
        int ibg = !isfinite(z) || z <= 0.0f;
        if (ibg != vbg) {
            *bad = 1;
            return 1.0;
        }
        if (vbg) {
            *bad = 0;
            return 0.0;
        }
        double zv = sl_external_view_depth(v, i), rel = fabs((double)z - zv) / zv;
        *bad = rel > e->depth_tolerance;
        return rel < 1.0 ? rel : 1.0;
    }
    *bad = (e->bg[s] != 0) != vbg;
    return *bad;
}

/* Whether view pixel (x, y) lies on a silhouette: a 4-neighbour of another
 * triangle set (background vs not), or, with depth, a depth step. */
static int on_silhouette(const struct sl_view *v, int x, int y)
{
    size_t i = (size_t)y * (size_t)v->w + (size_t)x;
    int bg = v->tri[i] == 0;
    static const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int k = 0; k < 4; k++) {
        int nx = x + nb[k][0], ny = y + nb[k][1];
        if (nx < 0 || ny < 0 || nx >= v->w || ny >= v->h)
            continue;
        size_t j = (size_t)ny * (size_t)v->w + (size_t)nx;
        if ((v->tri[j] == 0) != bg)
            return 1;
        if (!bg && v->tri[j] != 0) {
            float a = sl_external_view_depth(v, i), b = sl_external_view_depth(v, j);
            if (fabsf(a - b) > 0.02f * a)
                return 1;
        }
    }
    return 0;
}

enum sl_err sl_external_register(const struct sl_external *e, const struct sl_view *v,
                                 struct sl_external_report *r, struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    const char *what = e->depth ? (e->depth_file ? e->depth_file : "depth") : e->image;
    if (e->w != v->w || e->h != v->h)
        return sl_fail(d, SL_E_USAGE, what, 0, NULL, "%d x %d pixels where the viewport is %d x %d", e->w, e->h,
                       v->w, v->h);
    r->pixels = (uint64_t)v->w * (uint64_t)v->h;
    if (!e->depth) {
        /* backgrounds compared where neither has one prove nothing: a
         * flipped image would agree as well as the right one */
        uint64_t any = 0;
        for (size_t i = 0; i < r->pixels && !any && e->has_bg; i++)
            any = e->bg[i] || v->tri[i] == 0;
        if (!any)
            return SL_OK;   /* unchecked: the caller warns */
    }
    r->checked = 1;
    r->by_depth = e->depth != NULL;
    double score[NXFORMS];
    uint64_t bad[NXFORMS], on_edge = 0, img_fg = 0, view_fg = 0;
    for (int t = 0; t < NXFORMS; t++) {
        double sc = 0.0;
        uint64_t nb = 0, compared = 0;
        for (int y = 0; y < v->h; y++)
            for (int x = 0; x < v->w; x++) {
                size_t i = (size_t)y * (size_t)v->w + (size_t)x;
                long s = source_of(&xforms[t], v->w, v->h, x, y);
                if (s < 0)
                    continue;   /* a shift compares the pixels both cover */
                int b = 1;
                sc += disagree(e, v, i, s, &b);
                nb += (uint64_t)b;
                compared++;
                if (t == 0 && b)
                    on_edge += (uint64_t)on_silhouette(v, x, y);
                if (t == 0) {
                    view_fg += v->tri[i] != 0;
                    img_fg += e->depth ? isfinite(e->depth[s]) && e->depth[s] > 0.0f : !e->bg[s];
                }
            }
        score[t] = compared ? sc / (double)compared : 1.0;
        bad[t] = nb;
    }
    r->misregistered = bad[0];
    r->share = (double)bad[0] / (double)r->pixels;
    int best = 0;
    for (int t = 1; t < NXFORMS; t++)
        if (score[t] < score[best])
            best = t;
    /* a transform explains the disagreement when it halves it; a handful of
     * pixels is noise, never a shift */
    int explained = best != 0 && bad[0] >= 8 && score[best] < 0.5 * score[0];
    if (!explained && r->share <= e->tolerance)
        return SL_OK;
    if (explained)
        snprintf(r->cause, sizeof r->cause, "%s", xforms[best].cause);
    else if (fabs((double)img_fg - (double)view_fg) > 0.02 * (double)r->pixels)
        snprintf(r->cause, sizeof r->cause,
                 "another field of view, camera or viewport: the image covers %.1f %% of its pixels, the view "
                 "%.1f %%",
                 100.0 * (double)img_fg / (double)r->pixels, 100.0 * (double)view_fg / (double)r->pixels);
    else if (on_edge >= bad[0] * 9 / 10)
        snprintf(r->cause, sizeof r->cause,
                 "sub-pixel offset: %.0f %% of them lie on silhouettes (jitter left on, or pixel centres not "
                 "at half-integers)",
                 100.0 * (double)on_edge / (double)bad[0]);
    else
        snprintf(r->cause, sizeof r->cause, "another camera, viewpoint or scene%s",
                 e->depth ? ", or another depth convention (linear, window, reversed-Z, near, far)" : "");
    return sl_fail(d, SL_E_USAGE, what, 0, NULL,
                   "not registered with the view: %.2f %% of the pixels (%llu of %llu) disagree by %s "
                   "(tolerance %.2f %%); likely cause: %s",
                   100.0 * r->share, (unsigned long long)bad[0], (unsigned long long)r->pixels,
                   e->depth ? "depth" : "background", 100.0 * e->tolerance, r->cause);
}

static unsigned external_needs(const struct sl_method_params *p)
{
    (void)p;
    return 0;   /* the image is the whole of it: no layer */
}

static enum sl_err external_run(const struct sl_method_args *a, struct sl_verdicts *out, struct sl_cost *c,
                                struct sl_diag *d)
{
    const struct sl_external *e = a->params->external;
    const struct sl_view *v = a->view;
    if (!e)
        return sl_fail(d, SL_E_METHOD, NULL, 0, "method",
                       "method external grades an image handed to it by `shadowlab grade`; a config cannot run it");
    if (!out->vis)
        return sl_fail(d, SL_E_METHOD, NULL, 0, NULL, "external: no visibility buffer to write");
    struct sl_external_report local, *r = e->report ? e->report : &local;
    enum sl_err err = sl_external_register(e, v, r, d);
    if (err)
        return err;
    size_t npx = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < npx; i++) {
        out->vis[i] = 0.0f;
        if (sl_verdict_fixed(v, i, out))
            continue;
        float x = e->vis[i];
        out->vis[i] = x;
        if (!isfinite(x)) {
            out->v[i] = SL_V_UNCERTAIN;
            out->how[i] = SL_HOW_MAP;
            out->vis[i] = NAN;
            out->nonfinite++;
            continue;
        }
        out->v[i] = x >= e->threshold ? SL_V_LIT : SL_V_SHADOW;
        out->how[i] = SL_HOW_MAP;
    }
    out->has_vis = 1;
    (void)c;   /* no lookups, no rays: the engine's cost is its own */
    return SL_OK;
}

const struct sl_method sl_method_external = {
    .name = "external",
    .summary = "a visibility image rendered by another program, graded by `shadowlab grade`",
    .family = "external",
    .display = "External",
    .needs = external_needs,
    .run = external_run,
};
