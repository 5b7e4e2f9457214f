/*
 * cell.c — see cell.h.
 *
 * Invariant: every figure and every check reads only the inputs it is
 * handed, so a cell's numbers depend on the view, the frame and the
 * verdicts alone, never on which cells ran before it.
 */
#include "cell.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "aliasing.h"
#include "contour.h"
#include "image.h"
#include "overlay.h"
#include "sheetsink.h"
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
            int bad = sl_exact_violated(m->exact, vd->v[i], how, v->truth[i]);
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
                    if ((f->have & SL_NEED(l)) && f->layer[l].id)   /* BGSM2 keeps no ids */
                        o->layer_tri[l] = f->layer[l].id[sl_layer_at(&f->layer[l], k, i)] & ~SL_FULL;
            }
            cell->violations++;
        }
}

/* The sheet's title and crop (overlay.h: the scene's bounding box, or its
 * shadows' and errors', when that fills less than half the frame). */
static void sheet_frame(const struct sl_cell_inputs *in, const struct sl_cell *cell, const uint8_t *band,
                        const uint8_t *err, struct sl_image_sheet *sh)
{
    const struct sl_view *v = in->view;
    snprintf(sh->title, sizeof sh->title, "%s/%s  %s  map %d  %dx%d", cell->scene, cell->viewpoint,
             in->label ? in->label : in->method->name, in->frame ? in->frame->size : 0, v->w, v->h);
    struct sl_ov_box b;
    if (sl_overlay_crop(v, band, err, 16, &b)) {
        sh->view[0] = b.x;
        sh->view[1] = b.y;
        sh->view[2] = b.w;
        sh->view[3] = b.h;
    }
}

/* Where a sheet is drawn: with the run's sink (in->sheets), one of its slots,
 * handed back once drawn (the overlay writer's worker: ovwriter.h), so the cell pays for
 * drawing, not for composing and compressing the PNG; without one, the
 * cell's own scratch (rgb, and err: w * h), written here. */
static enum sl_err sheet_buffers(const struct sl_cell_inputs *in, uint8_t *err, void **slot, uint8_t **rgb_out,
                                 uint8_t **keep_out, struct sl_diag *d)
{
    *slot = NULL;
    *rgb_out = in->rgb;
    *keep_out = err;
    if (!in->sheets)
        return SL_OK;
    unsigned char *rgb, *keep;
    enum sl_err e = in->sheets->acquire(in->sheets->ctx, in->view->w, in->view->h, slot, &rgb, &keep, d);
    if (!e) {
        *rgb_out = rgb;
        *keep_out = keep;
    }
    return e;
}

static enum sl_err sheet_write(const struct sl_cell_inputs *in, void *slot, const struct sl_image_sheet *sh,
                               struct sl_diag *d)
{
    return slot ? in->sheets->submit(in->sheets->ctx, slot, in->overlay_path, sh, d)
                : sl_image_write_sheet(in->overlay_path, sh, d);
}

/* A hard-light cell's overlay sheet: the frame at 1:1 (cropped to the scene
 * when small), the three windows with most wrong pixels zoomed beside it (the
 * uncertain ones when none is wrong), a legend with each class's count.
 * scratch: w * h (the error mask, when the cell writes the sheet itself). */
static enum sl_err write_overlay(const struct sl_cell_inputs *in, const struct sl_verdicts *vd, const uint8_t *band,
                                 const struct sl_cell *cell, uint8_t *scratch, struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    int W = v->w, H = v->h, th = in->overlay_contour;
    void *slot;
    uint8_t *rgb, *err;
    enum sl_err e = sheet_buffers(in, scratch, &slot, &rgb, &err, d);
    if (e)
        return e;
    uint64_t count[SL_OV_CLASSES];
    sl_overlay_build_shaded(in->overlay_shade, v, in->light_dir, in->light_pos, vd, band, th, rgb, err, count);
    struct sl_image_sheet sh;
    memset(&sh, 0, sizeof sh);
    sh.w = W;
    sh.h = H;
    sh.rgb = rgb;
    sh.keep = err;
    sheet_frame(in, cell, band, err, &sh);
    uint64_t wrong = count[SL_OV_LIT_WRONG] + count[SL_OV_SHADOW_WRONG] + count[SL_OV_WRONG_OUTSIDE];
    size_t npx = (size_t)W * (size_t)H;
    if (wrong > 0 && count[SL_OV_UNCERTAIN] > 0) {
        /* the insets go where the wrong pixels are: leave the uncertain
         * ones out of the mask while choosing (put back below) */
        for (size_t i = 0; i < npx; i++)
            err[i] = err[i] && vd->v[i] != SL_V_UNCERTAIN ? 255 : 0;
    }
    /* windows of 1/16 the frame's shorter side (64 px at 1024), zoomed to
     * fill about a third of the view's height each, 4x (a pixel plainly a
     * square) to 8x */
    int s = (W < H ? W : H) / 16, vh = sh.view[2] ? sh.view[3] : H;
    s = s < 8 ? 8 : s > 128 ? 128 : s;
    struct sl_ov_box box[3];
    uint64_t inbox[3];
    int n = wrong || count[SL_OV_UNCERTAIN] ? sl_overlay_insets(W, H, err, s, 3, box, inbox) : 0;
    if (n < 0) {
        if (slot)
            in->sheets->release(in->sheets->ctx, slot);
        return sl_fail(d, SL_E_NOMEM, in->overlay_path, 0, NULL, "inset search");
    }
    if (wrong > 0 && count[SL_OV_UNCERTAIN] > 0)
        for (size_t i = 0; i < npx; i++)
            err[i] = err[i] || vd->v[i] == SL_V_UNCERTAIN ? 255 : 0;
    int z = vh / 3 / s;
    sh.zoom = z < 4 ? 4 : z > 8 ? 8 : z;
    sh.ninsets = n;
    for (int k = 0; k < n; k++) {
        sh.inset[k][0] = box[k].x;
        sh.inset[k][1] = box[k].y;
        sh.inset[k][2] = box[k].w;
        sh.inset[k][3] = box[k].h;
        snprintf(sh.inset_caption[k], sizeof sh.inset_caption[k], "%d: %llu %s in %dx%d, x%d", k + 1,
                 (unsigned long long)inbox[k], wrong ? "wrong" : "uncertain", box[k].w, box[k].h, sh.zoom);
    }
    char c[12];
    if (th > 0)
        snprintf(c, sizeof c, "%d-px", th);   /* "2-px" */
    static const char *const what[SL_OV_CLASSES] = {
        [SL_OV_LIT_WRONG] = "said lit, shadowed", [SL_OV_SHADOW_WRONG] = "said shadowed, lit",
        [SL_OV_WRONG_OUTSIDE] = "wrong, outside the contour", [SL_OV_UNCERTAIN] = "uncertain",
        [SL_OV_CONTOUR] = "contour (right pixels)",
        [SL_OV_OUTSIDE_CONE] = "outside the spot's cone (hatched)",
    };
    for (int k = 0; k < SL_OV_CLASSES; k++) {
        if ((th == 0 && (k == SL_OV_WRONG_OUTSIDE || k == SL_OV_CONTOUR)) || (k == SL_OV_OUTSIDE_CONE && !count[k]))
            continue;   /* contour 0: the whole image, nothing outside it; no spot's cone in view */
        memcpy(sh.legend_rgb[sh.nlegend], sl_overlay_colour[k], 3);
        if (k == SL_OV_CONTOUR)
            snprintf(sh.legend_text[sh.nlegend], sizeof sh.legend_text[0], "%s contour, faint", c);
        else
            snprintf(sh.legend_text[sh.nlegend], sizeof sh.legend_text[0], "%s%s%s%s: %llu", what[k],
                     k < SL_OV_WRONG_OUTSIDE && th > 0 ? ", in the " : "",
                     k < SL_OV_WRONG_OUTSIDE && th > 0 ? c : "", k < SL_OV_WRONG_OUTSIDE && th > 0 ? " contour" : "",
                     (unsigned long long)count[k]);
        sh.nlegend++;
    }
    if (sh.nlegend < SL_SHEET_MAX_LEGEND) {
        static const uint8_t box_white[3] = {255, 255, 255};
        memcpy(sh.legend_rgb[sh.nlegend], box_white, 3);
        snprintf(sh.legend_text[sh.nlegend++], sizeof sh.legend_text[0], "white boxes: the insets' windows");
    }
    return sheet_write(in, slot, &sh, d);
}

/* The EXR's mesh layer: code k + 1 for a pixel on the scene's k-th named
 * mesh (scene.h: its triangle ranges, in the scene file's order), 255 for
 * the 255th and later, 0 on background. Returns the header's legend
 * ("0 background, 1 ground, 2 box, ...", malloc'ed), NULL out of memory. */
static char *mesh_codes(const struct sl_scene *s, const struct sl_view *v, uint8_t *code)
{
    const size_t npx = (size_t)v->w * (size_t)v->h;
    const int nr = s ? s->nranges : 0;
    for (size_t i = 0; i < npx; i++) {
        const uint32_t t = v->tri ? v->tri[i] : 0;
        const int r = t && nr ? sl_scene_mesh_of(s, t - 1) : -1;
        code[i] = (uint8_t)(r < 0 ? 0 : r < 254 ? r + 1 : 255);
    }
    size_t cap = 64 + (size_t)nr * (SL_MESH_NAME + 8), k = 0;
    char *legend = malloc(cap);
    if (!legend)
        return NULL;
    k += (size_t)snprintf(legend, cap, "0 background");
    for (int j = 0; j < nr && j < 254; j++)
        k += (size_t)snprintf(legend + k, cap - k, ", %d %s", j + 1, s->ranges[j].name);
    if (nr > 254)
        snprintf(legend + k, cap - k, ", 255 the 255th mesh and later");
    return legend;
}

/* The EXR layers, each code named in the header (shadowlab:<layer>).
 * errcls: w * h scratch; acode: 2 * w * h. */
static enum sl_err write_exr(const struct sl_cell_inputs *in, const struct sl_verdicts *vd, const uint8_t *band,
                             const struct sl_cell *cell, uint8_t *errcls, const float *am, uint8_t *acode,
                             struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    size_t npx = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < npx; i++) {
        uint8_t t = v->truth[i], x = vd->v[i];
        errcls[i] = x == SL_V_LIT && t != SL_T_LIT && t != SL_T_BACKGROUND ? 1
                    : x == SL_V_SHADOW && t == SL_T_LIT                    ? 2
                    : x == SL_V_UNCERTAIN                                  ? 3
                                                                           : 0;
    }
    char how[400] = "", title[200], cf[160];
    int k = 0;
    static const char *const hows[] = {
#define SL_HOW_TEXT(id, text) text,
        SL_HOWS(SL_HOW_TEXT)
#undef SL_HOW_TEXT
    };
    for (size_t j = 0; j < sizeof hows / sizeof hows[0]; j++)
        k += snprintf(how + k, sizeof how - (size_t)k, "%s%zu %s", j ? ", " : "", j, hows[j]);
    snprintf(title, sizeof title, "%s/%s %s map %d %dx%d", cell->scene, cell->viewpoint,
             in->label ? in->label : in->method->name, in->frame ? in->frame->size : 0, v->w, v->h);
    snprintf(cf, sizeof cf, "k >= 1: inside the 2k-px contour (and every thicker one) of the verdicts it is "
             "scored on; 0 outside all");
    const struct sl_image_attr attrs[] = {
        {"shadowlab:truth", "0 background, 1 PnFL (faces away from the light, or outside a spot light's cone), "
                            "2 lit, 3 shadowed"},
        {"shadowlab:verdict", "0 background, 1 lit, 2 shadowed, 3 uncertain (left for a ray tracer)"},
        {"shadowlab:error", "0 right or background, 1 said lit but not lit in truth, 2 said shadowed but lit, "
                            "3 uncertain"},
        {"shadowlab:contour", cf},
        {"shadowlab:how", how},
        {"shadowlab:aliasing", "aliasing error m (seed 004 eq. 61, aliasing.h) in 1/8 octaves: 0 not a PFL pixel "
                               "or m undefined, else m = 2^((code - 128) / 8) rounded, clamped to 1..255; "
                               "m = 1, 2, 4, 8 are codes 128, 136, 144, 152"},
        {"shadowlab:channels", "each layer twice: half (the code as a number) and uint32 code.<layer>"},
        {"shadowlab:cell", title},
    };
    for (size_t i = 0; i < npx; i++)
        acode[i] = am ? sl_alias_code(am[i]) : 0;
    /* the mesh each pixel lies on: which object holds the errors */
    uint8_t *mcode = acode + npx;
    char *meshes = mesh_codes(in->scene, v, mcode);
    if (!meshes)
        return sl_fail(d, SL_E_NOMEM, in->exr_path, 0, NULL, "EXR mesh names");
    const struct sl_image_attr all[] = {
        attrs[0], attrs[1], attrs[2], attrs[3], attrs[4], attrs[5],
        {"shadowlab:mesh", meshes},
        attrs[6], attrs[7],
    };
    static const char *const names[] = {"truth", "verdict", "error", "contour", "how", "aliasing", "mesh"};
    const unsigned char *layers[] = {v->truth, vd->v, errcls, band, vd->how, acode, mcode};
    enum sl_err e = sl_image_write_layers(in->exr_path, v->w, v->h, 7, names, layers,
                                          (int)(sizeof all / sizeof all[0]), all, d);
    free(meshes);
    return e;
}

/* The visibility the cell was scored on, as `shadowlab grade` reads it
 * back (doc/grade.md): V the visibility (a method's own, has_vis; else its
 * verdict: 1 lit, 0 shadowed, NaN uncertain), 0 on PnFL pixels as every
 * method's is; on background V NaN and A 0 (A 1 elsewhere); Z the linear
 * depth of the view (eye-space distance along the view axis, NaN on
 * background), so the same file registers itself (grade --depth). */
static enum sl_err write_visibility(const struct sl_cell_inputs *in, const struct sl_verdicts *vd,
                                    const struct sl_cell *cell, struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    size_t npx = (size_t)v->w * (size_t)v->h;
    float *buf = malloc(3 * npx * sizeof *buf);
    if (!buf)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "visibility %dx%d", v->w, v->h);
    float *vis = buf, *alpha = buf + npx, *z = buf + 2 * npx;
    const mat4 *V = &v->view;
    for (size_t i = 0; i < npx; i++) {
        if (v->tri[i] == 0) {
            vis[i] = z[i] = NAN;
            alpha[i] = 0.0f;
            continue;
        }
        alpha[i] = 1.0f;
        const float *p = v->pos + 3 * i;
        z[i] = -((*V)[0][2] * p[0] + (*V)[1][2] * p[1] + (*V)[2][2] * p[2] + (*V)[3][2]);
        if (vd->has_vis || in->soft_truth)
            vis[i] = vd->vis[i];
        else
            vis[i] = vd->v[i] == SL_V_LIT ? 1.0f : vd->v[i] == SL_V_SHADOW ? 0.0f : NAN;
    }
    char title[200];
    snprintf(title, sizeof title, "%s/%s %s map %d %dx%d", cell->scene, cell->viewpoint,
             in->label ? in->label : in->method->name, in->frame ? in->frame->size : 0, v->w, v->h);
    const struct sl_image_attr attrs[] = {
        {"shadowlab:V", "visibility as scored: 1 lit, 0 shadowed, fractions as the method gave them; "
                        "0 facing away; NaN background or uncertain"},
        {"shadowlab:A", "1 a surface, 0 background"},
        {"shadowlab:Z", "linear depth: eye-space distance along the view axis, world units; NaN background"},
        {"shadowlab:rows", "bottom-up in the view (OpenGL); written top-down as every image file"},
        {"shadowlab:cell", title},
    };
    static const char *const names[] = {"V", "A", "Z"};
    const float *chans[] = {vis, alpha, z};
    enum sl_err e = sl_image_write_floats(in->visibility_path, v->w, v->h, 3, names, chans,
                                          (int)(sizeof attrs / sizeof attrs[0]), attrs, d);
    free(buf);
    return e;
}

/* The soft overlay of a visibility against a truth over the pixels tri
 * marks: the error heat map (sl_overlay_soft), framed and keyed. */
static enum sl_err soft_overlay(const struct sl_cell_inputs *in, const uint32_t *tri, const float *vis,
                                const float *truth, const char *const key_text[3], struct sl_cell *cell,
                                struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    double t0 = sl_now();
    void *slot;
    uint8_t *rgb, *unused;
    enum sl_err e = sheet_buffers(in, in->state, &slot, &rgb, &unused, d);
    if (e)
        return e;
    sl_overlay_soft(v->w, v->h, tri, vis, truth, rgb);
    struct sl_image_sheet sh;
    memset(&sh, 0, sizeof sh);
    sh.w = v->w;
    sh.h = v->h;
    sh.rgb = rgb;
    sheet_frame(in, cell, NULL, NULL, &sh);
    static const uint8_t key_rgb[3][3] = {{213, 94, 0}, {0, 114, 178}, {220, 220, 220}};
    for (int k = 0; k < 3; k++) {
        memcpy(sh.legend_rgb[k], key_rgb[k], 3);
        snprintf(sh.legend_text[k], sizeof sh.legend_text[k], "%s", key_text[k]);
    }
    sh.nlegend = 3;
    e = sheet_write(in, slot, &sh, d);
    cell->ms.overlay = 1e3 * (sl_now() - t0);
    return e;
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
    sl_soft_figures_compute(W, H, v->tri, vd->vis, in->soft_truth, in->soft_se, 0.0, &cell->soft);
    cell->has_soft = 1;
    for (size_t i = 0; i < npx; i++)
        cell->nonfinite += v->tri[i] && !(vd->vis[i] >= 0.0f && vd->vis[i] <= 1.0f);
    cell->ms.figures += 1e3 * (sl_now() - t0);
    if (!in->overlay_path)
        return SL_OK;
    static const char *const key[3] = {
        "too dark (off the area truth by > 0.05)",
        "too light (off by > 0.05)",
        "grey: the visible fraction",
    };
    return soft_overlay(in, v->tri, vd->vis, in->soft_truth, key, cell, d);
}

/* A hard light's cell whose method wrote a fractional visibility: its soft
 * figures against the 0/1 truth over the PFL pixels (has_soft beside the
 * hard figures, as a hard method under an area light has both), its classes
 * within SL_SOFT_HARD_TOL (softfig.h: exact classes call a filtered
 * visibility penumbra wherever it is). */
static enum sl_err fractional_score(const struct sl_cell_inputs *in, const struct sl_verdicts *vd,
                                    struct sl_cell *cell, struct sl_diag *d)
{
    const struct sl_view *v = in->view;
    size_t npx = (size_t)v->w * (size_t)v->h;
    double t0 = sl_now();
    float *t = malloc(npx * sizeof *t);
    uint32_t *pfl = malloc(npx * sizeof *pfl);
    if (!t || !pfl) {
        free(t);
        free(pfl);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "fractional figures %dx%d", v->w, v->h);
    }
    for (size_t i = 0; i < npx; i++) {
        pfl[i] = v->cls[i] == SL_C_PFL;
        t[i] = v->truth[i] == SL_T_LIT ? 1.0f : 0.0f;
        cell->nonfinite += pfl[i] && !(vd->vis[i] >= 0.0f && vd->vis[i] <= 1.0f);
    }
    sl_soft_figures_compute(v->w, v->h, pfl, vd->vis, t, NULL, SL_SOFT_HARD_TOL, &cell->soft);
    cell->has_soft = 1;
    cell->has_frac = 1;
    cell->ms.figures += 1e3 * (sl_now() - t0);
    enum sl_err e = SL_OK;
    if (in->overlay_path) {
        /* the overlay shows what the hard verdict hides: where the
         * visibility leaks light into the shadow and where it darkens the
         * light (the hard errors are among them, off by >= the threshold) */
        static const char *const key[3] = {
            "too dark: over-darkening (lit in truth, visibility < 0.95)",
            "too light: light leaking (shadowed in truth, visibility > 0.05)",
            "grey: the visibility (PFL pixels)",
        };
        e = soft_overlay(in, pfl, vd->vis, t, key, cell, d);
    }
    free(t);
    free(pfl);
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
    cell->nonfinite += vd->nonfinite;
    if (in->method->lights & SL_LIGHTS_AREA) {
        memset(&cell->fig, 0, sizeof cell->fig);
        cell->fig.background = v->n_background;
        return soft_score(in, vd, cell, d);
    }
    double t0 = sl_now();
    const uint8_t *band = in->shared_band;
    /* contours, figures and the exactness count in one pass; the
     * violations' details (where, which texel, which triangles) are looked
     * up pixel by pixel only when there are any, which an exact method
     * never has */
    uint64_t bad;
    if (band) {
        cell->ms.contours = in->shared_band_ms;
        bad = sl_figures_fused(v, vd, band, in->regions, in->nregions, in->method->exact, in->threads, &cell->fig);
        cell->ms.figures = 1e3 * (sl_now() - t0);
    } else {
        /* the states are the verdicts themselves (0 background); regions
         * are the increasing contours, then 0 (whole image). One pass
         * draws the bands and counts: its time is the figures', and the
         * contours' is 0 (costs.csv keeps both columns) */
        int maxt = in->regions[in->nregions - 2];
        bad = sl_score_fused(v, vd, vd->v, maxt / 2 - 1, in->band, in->regions, in->nregions, in->method->exact, in->threads,
                             &cell->fig);
        band = in->band;
        cell->ms.contours = 0.0;
        cell->ms.figures = 1e3 * (sl_now() - t0);
    }
    if (in->method->exact && bad)
        check_exact(in, vd, cell);
    if (vd->has_detail)
        count_patterns(v, vd, band, cell);
    /* the aliasing error m of every PFL pixel under the frame that served it.
     * One frame for every pixel (no per-pixel frames): m is the view's under
     * that frame, the same for every cell sharing both (the cache; the first
     * such cell's figures time pays for it). Per-pixel frames (zpart's
     * slices, a cube's faces) are the method's own: computed here. */
    int own_m = in->aliasing && in->frame && vd->nframes > 0;
    int cached_m = in->aliasing && !own_m && in->frame && in->frame->size > 0;
    float *am = own_m || (cached_m && !in->alias_cache) ? malloc(npx * sizeof *am) : NULL;
    cell->texels = 0;
    for (int k = 0; k < vd->nframes; k++)
        cell->texels += (uint64_t)vd->frames[k].size * (uint64_t)vd->frames[k].size;
    if (vd->nframes == 0 && in->frame && in->params &&
        (in->method->needs(in->params) & ((1u << SL_LAYER_COUNT) - 1u)))
        cell->texels = (uint64_t)in->frame->size * (uint64_t)in->frame->size;
    const float *m = am;
    t0 = sl_now();
    if (am)
        sl_alias_image(v, in->frame, vd, in->threads, am);
    else if (cached_m && !(m = sl_alias_cached(in->alias_cache, v, in->frame, in->threads)))
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "aliasing error m %dx%d", v->w, v->h);
    if (m) {
        sl_alias_figures_cached(in->alias_cache, v, vd, m, band, in->regions, in->nregions, &cell->alias);
        cell->has_alias = 1;
        cell->ms.figures += 1e3 * (sl_now() - t0);
    }
    enum sl_err e = SL_OK;
    const char *overlay = in->overlay_path;
    if (in->soft_truth) {
        /* a hard method under an area light: its verdicts as a visible
         * fraction, scored against the area truth. A pixel it leaves
         * uncertain counts as half lit: the method says neither, and 0.5 is
         * the guess whose worst error is smallest. A method that wrote a
         * fractional visibility of its own (has_vis: a technique package)
         * is scored on that. */
        if (!vd->has_vis)
            for (size_t i = 0; i < npx; i++)
                vd->vis[i] = vd->v[i] == SL_V_LIT ? 1.0f : vd->v[i] == SL_V_UNCERTAIN ? 0.5f : 0.0f;
        e = soft_score(in, vd, cell, d);
        overlay = NULL;   /* the overlay is the soft one: the error against the area truth */
    } else if (vd->has_vis) {
        /* a fractional visibility under a hard light: the errors its hard
         * verdict hides, as the soft figures against the 0/1 truth over
         * the PFL pixels (mean |v - truth|, signed bias, within 0.05 and
         * 0.1). With a 0/1 truth the bias splits them: light leaking (the
         * visibility summed where the truth is shadowed) is (mae + bias) / 2
         * of the PFL pixels, over-darkening (1 - v where lit) (mae - bias) / 2. */
        e = fractional_score(in, vd, cell, d);
        overlay = NULL;   /* the overlay is the fractional one */
    }
    /* the scratch state is free once the bands are drawn: the overlay's
     * error mask, then the EXR's error classes */
    if (overlay && !e) {
        t0 = sl_now();
        e = write_overlay(in, vd, band, cell, in->state, d);
        cell->ms.overlay = 1e3 * (sl_now() - t0);
    }
    if (in->exr_path && !e) {
        /* the per-pixel layers behind the figures, for anyone who wants to
         * recount: truth (enum sl_truth), verdict (enum sl_verdict), the
         * error class, the contour band (k: inside the 2k-px contour) and
         * how (enum sl_how), each code named in the header */
        e = write_exr(in, vd, band, cell, in->state, m, in->rgb, d);
    }
    if (in->visibility_path && !e)
        e = write_visibility(in, vd, cell, d);
    free(am);
    return e;
}
