/*
 * cell.c — see cell.h.
 *
 * Invariant: every figure and every check reads only the inputs it is
 * handed, so a cell's numbers depend on the view, the frame and the
 * verdicts alone, never on which cells ran before it.
 */
#include "cell.h"
#include <math.h>
#include <string.h>
#include "contour.h"
#include "image.h"
#include "overlay.h"
#include "softfig.h"
#include "util.h"

/* Every PFL pixel against the guarantee the method declares. */
static void check_exact(const struct sl_cell_inputs *in, const struct sl_verdicts *vd, struct sl_cell *cell)
{
    const struct sl_view *v = in->view;
    const struct sl_light_frame *f = in->frame;
    const struct sl_method *m = in->method;
    for (int y = 0; y < v->h; y++)
        for (int xx = 0; xx < v->w; xx++) {
            size_t i = (size_t)y * (size_t)v->w + (size_t)xx;
            if (v->cls[i] != SL_C_PFL)
                continue;
            uint8_t how = vd->how[i];
            int proved = how == SL_HOW_CONFIRM || how == SL_HOW_CONFIRM_ADJ || how == SL_HOW_CORRECT ||
                         how == SL_HOW_TRACED;
            int right = (vd->v[i] == SL_V_LIT) == (v->truth[i] == SL_T_LIT);
            int bad = ((m->exact & SL_EXACT_LIT) && vd->v[i] == SL_V_LIT && v->truth[i] != SL_T_LIT) ||
                      ((m->exact & SL_EXACT_SHADOW) && vd->v[i] == SL_V_SHADOW && v->truth[i] != SL_T_SHADOW) ||
                      ((m->exact & SL_EXACT_PROVED) && proved && !right);
            if (!bad)
                continue;
            if (cell->violations < SL_MAX_VIOLATIONS) {
                struct sl_violation *o = &cell->violation[cell->violations];
                memset(o, 0, sizeof *o);
                o->x = xx;
                o->y = y;
                o->truth = v->truth[i];
                o->verdict = vd->v[i];
                o->how = vd->how[i];
                o->own_tri = v->tri[i];
                float u, w, z;
                sl_frame_project(f, v->pos + 3 * i, &u, &w, &z);
                uint32_t k = sl_frame_texel(f, u, w);
                o->tx = (int)(k % (uint32_t)f->size);
                o->ty = (int)(k / (uint32_t)f->size);
                for (int l = 0; l < SL_LAYER_COUNT; l++)
                    if (f->have & SL_NEED(l))
                        o->layer_tri[l] = f->layer[l].id[k] & ~SL_FULL;
            }
            cell->violations++;
        }
}

/* An area light's cell: the soft figures of the visible fraction vd->vis
 * against the area truth, and the error heat map as its overlay. */
static enum sl_err soft_score(const struct sl_cell_inputs *in, const struct sl_verdicts *vd, struct sl_cell *cell,
                              struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    int W = v->w, H = v->h;
    size_t npx = (size_t)W * (size_t)H;
    double t0 = sl_now();
    sl_soft_figures_compute(W, H, v->tri, vd->vis, in->soft_truth, in->soft_se, &cell->soft);
    cell->has_soft = 1;
    for (size_t i = 0; i < npx; i++)
        cell->nonfinite += v->tri[i] && !(vd->vis[i] >= 0.0f && vd->vis[i] <= 1.0f);
    cell->ms.figures += 1e3 * (sl_now() - t0);
    if (!in->overlay_path)
        return SL_OK;
    t0 = sl_now();
    sl_overlay_soft(W, H, v->tri, vd->vis, in->soft_truth, in->rgb);
    enum sl_err e = sl_image_write_rgb8(in->overlay_path, W, H, in->rgb, d);
    cell->ms.overlay = 1e3 * (sl_now() - t0);
    return e;
}

/* Texel coherence's patterns (Moderno 2011 Tables 20/22): per region, PFL
 * pixels by how many of the tested texels say shadow, and how many of those
 * are shadowed in truth. */
static void count_patterns(const struct sl_view *v, const struct sl_verdicts *vd, const uint8_t *band,
                           struct sl_cell *cell)
{
    size_t npx = (size_t)v->w * (size_t)v->h;
    cell->has_patterns = 1;
    for (size_t i = 0; i < npx; i++) {
        if (v->cls[i] != SL_C_PFL)
            continue;
        uint8_t k = vd->detail[i] < 10 ? vd->detail[i] : 9;
        for (int r = 0; r < cell->fig.nregions; r++)
            if (sl_in_contour(band[i], cell->fig.r[r].thickness)) {
                cell->pattern[r][k][0]++;
                cell->pattern[r][k][1] += v->truth[i] == SL_T_SHADOW;
            }
    }
}

enum sl_err sl_cell_score(const struct sl_cell_inputs *in, struct sl_verdicts *vd, struct sl_cell *cell,
                          struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    int W = v->w, H = v->h;
    size_t npx = (size_t)W * (size_t)H;
    if (in->method->lights & SL_LIGHTS_AREA) {
        memset(&cell->fig, 0, sizeof cell->fig);
        cell->fig.background = v->n_background;
        return soft_score(in, vd, cell, d);
    }
    double t0 = sl_now();
    const uint8_t *band = in->shared_band;
    if (band) {
        cell->ms.contours = in->shared_band_ms;
    } else {
        for (size_t i = 0; i < npx; i++)
            in->state[i] = vd->v[i];   /* 0 background, else the verdict */
        /* regions are the increasing contours, then 0 (whole image) */
        int maxt = in->regions[in->nregions - 2];
        sl_contour_bands(W, H, in->state, maxt / 2 - 1, in->band);
        band = in->band;
        cell->ms.contours = 1e3 * (sl_now() - t0);
    }
    t0 = sl_now();
    sl_figures_compute(v, vd, band, in->regions, in->nregions, &cell->fig);
    cell->ms.figures = 1e3 * (sl_now() - t0);
    if (in->method->exact)
        check_exact(in, vd, cell);
    if (vd->has_detail)
        count_patterns(v, vd, band, cell);
    enum sl_err e = SL_OK;
    const char *overlay = in->overlay_path;
    if (in->soft_truth) {
        /* a hard method under an area light: its verdicts as a visible
         * fraction, scored against the area truth. A pixel it leaves
         * uncertain counts as half lit: the method says neither, and 0.5 is
         * the guess whose worst error is smallest. */
        for (size_t i = 0; i < npx; i++)
            vd->vis[i] = vd->v[i] == SL_V_LIT ? 1.0f : vd->v[i] == SL_V_UNCERTAIN ? 0.5f : 0.0f;
        e = soft_score(in, vd, cell, d);
        overlay = NULL;   /* the overlay is the soft one: the error against the area truth */
    }
    if (overlay && !e) {
        t0 = sl_now();
        sl_overlay_build(v, in->light_dir, vd, band, in->overlay_contour, in->rgb);
        e = sl_image_write_rgb8(overlay, W, H, in->rgb, d);
        cell->ms.overlay = 1e3 * (sl_now() - t0);
    }
    if (in->exr_path && !e) {
        /* the per-pixel layers behind the figures, for anyone who wants to
         * recount: truth (enum sl_truth), verdict (enum sl_verdict), how
         * (enum sl_how) and contour band (k: inside the 2k-px contour) */
        static const char *const names[] = {"truth", "verdict", "how", "contour"};
        const unsigned char *layers[] = {v->truth, vd->v, vd->how, band};
        e = sl_image_write_layers(in->exr_path, W, H, 4, names, layers, d);
    }
    return e;
}
