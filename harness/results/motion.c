/*
 * motion.c — see motion.h.
 * Invariant: a row's sums are over cells of exactly its key; a frame's
 * flicker counts only when that frame was compared (flicker_compared > 0).
 */
#include "motion.h"
#include "emit.h"
#include "pivot.h"
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int sl_motion_frame_of(const char *viewpoint, char *path, size_t n)
{
    const char *dot = strrchr(viewpoint, '.');
    if (!dot || dot == viewpoint || strlen(dot + 1) != 3)
        return -1;
    for (int k = 1; k <= 3; k++)
        if (!isdigit((unsigned char)dot[k]))
            return -1;
    if (path)
        snprintf(path, n, "%.*s", (int)(dot - viewpoint), viewpoint);
    return atoi(dot + 1);
}

static int same_key(const struct sl_motion_row *r, const struct sl_cell_record *c, const char *path)
{
    return strcmp(r->scene, c->scene) == 0 && strcmp(r->path, path) == 0 && strcmp(r->label, c->label) == 0 &&
           r->vw == c->vw && r->vh == c->vh && r->map_size == c->map_size;
}

static int row_cmp(const void *pa, const void *pb)
{
    const struct sl_motion_row *a = pa, *b = pb;
    int k = strcmp(a->scene, b->scene);
    if (!k) k = strcmp(a->path, b->path);
    if (!k) k = (a->vw * 100000 + a->vh) - (b->vw * 100000 + b->vh);
    if (!k) k = a->map_size - b->map_size;
    /* labels keep their first appearance (worst_frame is borrowed below) */
    return k;
}

enum sl_err sl_motion_rows(const struct sl_cell_record *cells, int ncells, struct sl_motion_row **rows,
                           int *nrows, struct sl_diag *d)
{
    *rows = NULL;
    *nrows = 0;
    struct sl_motion_row *out = NULL;
    int n = 0, cap = 0;
    for (int i = 0; i < ncells; i++) {
        const struct sl_cell_record *c = &cells[i];
        char path[64];
        int frame = sl_motion_frame_of(c->viewpoint, path, sizeof path);
        if (frame < 0)
            continue;
        int r = 0;
        while (r < n && !same_key(&out[r], c, path))
            r++;
        if (r == n) {
            if (n == cap) {
                struct sl_motion_row *g = realloc(out, (size_t)(cap ? 2 * cap : 16) * sizeof *g);
                if (!g) {
                    free(out);
                    return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "motion rows");
                }
                out = g;
                cap = cap ? 2 * cap : 16;
            }
            memset(&out[n], 0, sizeof out[n]);
            snprintf(out[n].scene, sizeof out[n].scene, "%s", c->scene);
            snprintf(out[n].path, sizeof out[n].path, "%s", path);
            snprintf(out[n].label, sizeof out[n].label, "%s", c->label);
            out[n].vw = c->vw;
            out[n].vh = c->vh;
            out[n].map_size = c->map_size;
            out[n].worst_frame = out[n].worst_flicker_frame = -1;
            n++;
        }
        struct sl_motion_row *w = &out[r];
        uint64_t wrong = c->fig.wrong_image;
        w->frames++;
        w->mean_wrong += (double)wrong;
        if (w->worst_frame < 0 || wrong > w->worst_wrong) {
            w->worst_wrong = wrong;
            w->worst_frame = frame;
        }
        if (c->flicker_compared > 0) {
            w->pairs++;
            w->flicker += c->flicker;
            w->compared += c->flicker_compared;
            w->contour_px += c->fig.nregions > 0 ? c->fig.r[0].n[SL_FIG_pixels] : 0;
            if (w->worst_flicker_frame < 0 || c->flicker > w->worst_flicker) {
                w->worst_flicker = c->flicker;
                w->worst_flicker_frame = frame;
            }
        }
    }
    for (int r = 0; r < n; r++) {
        out[r].mean_wrong /= out[r].frames;
        out[r].mean_flicker = out[r].pairs ? (double)out[r].flicker / out[r].pairs : NAN;
        out[r].per_1000 = out[r].contour_px ? 1000.0 * (double)out[r].flicker / (double)out[r].contour_px : NAN;
    }
    /* stable: insertion sort keeps the labels' order within a key */
    for (int i = 1; i < n; i++)
        for (int k = i; k > 0 && row_cmp(&out[k - 1], &out[k]) > 0; k--) {
            struct sl_motion_row t = out[k];
            out[k] = out[k - 1];
            out[k - 1] = t;
        }
    *rows = out;
    *nrows = n;
    return SL_OK;
}

/* The LaTeX tables of one group (scene, path, viewport, map size), rows
 * [i, e): two paged tables (floats of a page of rows each) that each fit a
 * plain article's \\columnwidth at \\small (the eight columns side by side
 * ran 222 pt too wide): the wrong pixels per frame (wrong, what = 0), then
 * the flicker (what = 1). Numbers as sl_tab_number writes them; a frame or
 * a count as it is. */
static void tex_table(struct sl_tab *t, const struct sl_motion_row *rows, int i, int e, int what)
{
    static const char *const heads[2][7] = {{"label", "frames", "mean", "worst", "frame"},
                                            {"label", "pairs", "flicker", "per pair", "worst", "frame",
                                             "per 1,000"}};
    static const char *const whats[2] = {
        "the whole image's wrong pixels per frame (mean, worst and the frame of the worst)",
        "flicker, pixels whose verdict changes between consecutive frames while their truth does not: in all, "
        "per compared pair, at worst (and its frame), and per 1,000 pixels of the thinnest contour; -- where no "
        "pair was compared"};
    const struct sl_motion_row *g = &rows[i];
    int ncols = what ? 7 : 5;
    sl_tab_init(t, "motion", ncols, 1, "%s, path %s, %d\xC3\x97%d, map %d\xC2\xB2: %s", g->scene, g->path, g->vw,
                g->vh, g->map_size, whats[what]);
    t->paged = 1;
    t->nolabel = 1;
    for (int k = 0; k < ncols; k++)
        sl_tab_head(t, k, "%s", heads[what][k]);
    for (int k = i; k < e; k++) {
        const struct sl_motion_row *r = &rows[k];
        char v[64];
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", r->label);
        if (!what) {
            sl_tab_cell(t, 1, "%d", r->frames);
            sl_tab_number(v, sizeof v, r->mean_wrong, 1);
            sl_tab_cell(t, 2, "%s", v);
            sl_tab_number(v, sizeof v, (double)r->worst_wrong, 0);
            sl_tab_cell(t, 3, "%s", v);
            sl_tab_cell(t, 4, "%d", r->worst_frame);
            continue;
        }
        sl_tab_cell(t, 1, "%d", r->pairs);
        sl_tab_number(v, sizeof v, r->pairs ? (double)r->flicker : NAN, 0);
        sl_tab_cell(t, 2, "%s", v);
        sl_tab_number(v, sizeof v, r->mean_flicker, 1);
        sl_tab_cell(t, 3, "%s", v);
        sl_tab_number(v, sizeof v, r->pairs ? (double)r->worst_flicker : NAN, 0);
        sl_tab_cell(t, 4, "%s", v);
        if (r->pairs)
            sl_tab_cell(t, 5, "%d", r->worst_flicker_frame);
        else
            sl_tab_cell(t, 5, "\xE2\x80\x93");
        sl_tab_number(v, sizeof v, r->per_1000, 2);
        sl_tab_cell(t, 6, "%s", v);
    }
}

/* "v" with fmt, or "n/a" where not defined */
static void num_text(char *out, size_t n, double v, const char *fmt)
{
    if (isnan(v))
        snprintf(out, n, "n/a");
    else
        snprintf(out, n, fmt, v);
}

/* The data table (CSV): a line per row, every sum and count as it is, an
 * undefined mean empty. */
static void data_table(struct sl_tab *t, const struct sl_motion_row *rows, int n)
{
    static const char *const heads[] = {"scene", "path", "viewport", "map_size", "label", "frames", "pairs",
                                        "mean_wrong", "worst_wrong", "worst_frame", "flicker", "mean_flicker",
                                        "worst_flicker", "worst_flicker_frame", "compared", "contour_px",
                                        "flicker_per_1000_contour"};
    sl_tab_init(t, "motion", 17, 5, "motion");
    for (int k = 0; k < 17; k++)
        sl_tab_head(t, k, "%s", heads[k]);
    for (int i = 0; i < n; i++) {
        const struct sl_motion_row *r = &rows[i];
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", r->scene);
        sl_tab_cell(t, 1, "%s", r->path);
        sl_tab_cell(t, 2, "%dx%d", r->vw, r->vh);
        sl_tab_cell(t, 3, "%d", r->map_size);
        sl_tab_cell(t, 4, "%s", r->label);
        sl_tab_cell(t, 5, "%d", r->frames);
        sl_tab_cell(t, 6, "%d", r->pairs);
        sl_tab_cell(t, 7, "%.2f", r->mean_wrong);
        sl_tab_cell(t, 8, "%llu", (unsigned long long)r->worst_wrong);
        sl_tab_cell(t, 9, "%d", r->worst_frame);
        sl_tab_cell(t, 10, "%llu", (unsigned long long)r->flicker);
        if (!isnan(r->mean_flicker))
            sl_tab_cell(t, 11, "%.2f", r->mean_flicker);
        sl_tab_cell(t, 12, "%llu", (unsigned long long)r->worst_flicker);
        sl_tab_cell(t, 13, "%d", r->worst_flicker_frame);
        sl_tab_cell(t, 14, "%llu", (unsigned long long)r->compared);
        sl_tab_cell(t, 15, "%llu", (unsigned long long)r->contour_px);
        if (!isnan(r->per_1000))
            sl_tab_cell(t, 16, "%.3f", r->per_1000);
    }
}

/* The reading table of one group (scene, path, viewport, map size): rows
 * [i, e), a label each. */
static void group_table(struct sl_tab *t, const struct sl_motion_row *rows, int i, int e)
{
    static const char *const heads[] = {"label", "frames", "mean wrong", "worst wrong (frame)", "flicker",
                                        "mean per pair", "worst (frame)", "per 1,000 contour px"};
    const struct sl_motion_row *g = &rows[i];
    char id[160];
    snprintf(id, sizeof id, "motion-%s-%s-%dx%d-%d", g->scene, g->path, g->vw, g->vh, g->map_size);
    sl_tab_init(t, id, 8, 1, "%s, path %s, %dx%d, map %d\xC2\xB2", g->scene, g->path, g->vw, g->vh, g->map_size);
    t->level = 3;
    t->plain = 1;
    for (int k = 0; k < 8; k++)
        sl_tab_head(t, k, "%s", heads[k]);
    for (int k = i; k < e; k++) {
        const struct sl_motion_row *r = &rows[k];
        char v[48];
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", r->label);
        sl_tab_cell(t, 1, "%d", r->frames);
        sl_tab_cell(t, 2, "%.1f", r->mean_wrong);
        sl_tab_cell(t, 3, "%llu (%d)", (unsigned long long)r->worst_wrong, r->worst_frame);
        if (r->pairs)
            sl_tab_cell(t, 4, "%llu", (unsigned long long)r->flicker);
        else   /* no compared pair: fewer than two comparable frames */
            sl_tab_cell(t, 4, "not defined");
        num_text(v, sizeof v, r->mean_flicker, "%.1f");
        sl_tab_cell(t, 5, "%s", v);
        if (r->pairs)
            sl_tab_cell(t, 6, "%llu (%d)", (unsigned long long)r->worst_flicker, r->worst_flicker_frame);
        else
            sl_tab_cell(t, 6, "n/a");
        num_text(v, sizeof v, r->per_1000, "%.2f");
        sl_tab_cell(t, 7, "%s", v);
    }
}

enum sl_err sl_motion_write(FILE *f, enum sl_table_format fmt, const struct sl_motion_row *rows, int n,
                            struct sl_diag *d)
{
    struct sl_tab t;
    int bad = 0;
    /* LaTeX: two paged tables per group; a \clearpage after every eighth
     * float (LaTeX holds at most 18 it has not placed) */
    int floats = 0;
    if (fmt == SL_TABLE_LATEX && n == 0)
        sl_emit_tex_comment(f, "shadowlab motion tables; needs \\usepackage{booktabs}", 1);
    for (int i = 0, e; fmt == SL_TABLE_LATEX && i < n && !bad; i = e) {
        e = i + 1;
        while (e < n && row_cmp(&rows[i], &rows[e]) == 0)
            e++;
        for (int what = 0; what < 2 && !bad; what++) {
            tex_table(&t, rows, i, e, what);
            const struct sl_emit_opts o = {.first = i == 0 && what == 0,
                                           .comment = "shadowlab motion tables; needs \\usepackage{booktabs}",
                                           .clear = floats >= 6, .blank = 1};
            int k = sl_emit_tex(f, &t, &o);
            bad = k < 0;
            floats = o.clear ? k : floats + k;
            sl_tab_free(&t);
        }
    }
    if (fmt == SL_TABLE_CSV) {
        data_table(&t, rows, n);
        bad = sl_emit_csv(f, &t, NULL) < 0;
        sl_tab_free(&t);
    }
    /* Markdown: a table per group */
    for (int i = 0, e; fmt == SL_TABLE_MD && i < n && !bad; i = e) {
        e = i + 1;
        while (e < n && row_cmp(&rows[i], &rows[e]) == 0)
            e++;
        group_table(&t, rows, i, e);
        const struct sl_emit_opts o = {.first = i == 0, .gap = i > 0};
        bad = sl_emit_md(f, &t, &o) < 0;
        sl_tab_free(&t);
    }
    return bad ? sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "motion tables") : SL_OK;
}

int sl_motion_series(FILE *f, const struct sl_cell_record *cells, int ncells, const struct sl_motion_row *row,
                     char (*labels)[48], int nlabels)
{
    int maxf = -1;
    for (int i = 0; i < ncells; i++) {
        char path[64];
        int fr = sl_motion_frame_of(cells[i].viewpoint, path, sizeof path);
        if (fr > maxf && strcmp(path, row->path) == 0 && strcmp(cells[i].scene, row->scene) == 0)
            maxf = fr;
    }
    int written = 0;
    for (int fr = 0; fr <= maxf; fr++) {
        fprintf(f, "%d", fr);
        for (int l = 0; l < nlabels; l++) {
            const struct sl_cell_record *hit = NULL;
            for (int i = 0; i < ncells && !hit; i++) {
                char path[64];
                if (sl_motion_frame_of(cells[i].viewpoint, path, sizeof path) == fr &&
                    strcmp(path, row->path) == 0 && strcmp(cells[i].scene, row->scene) == 0 &&
                    strcmp(cells[i].label, labels[l]) == 0 && cells[i].vw == row->vw && cells[i].vh == row->vh &&
                    cells[i].map_size == row->map_size)
                    hit = &cells[i];
            }
            if (!hit)
                fputs(" - -", f);
            else if (hit->flicker_compared)
                fprintf(f, " %llu %llu", (unsigned long long)hit->fig.wrong_image, (unsigned long long)hit->flicker);
            else
                fprintf(f, " %llu NaN", (unsigned long long)hit->fig.wrong_image);
        }
        fputc('\n', f);
        written++;
    }
    return written;
}
