/*
 * table.c — see table.h.
 *
 * Invariants: every format walks the cells in one order, computed once:
 * groups of (scene, viewpoint, viewport, label) in order of first appearance,
 * map sizes ascending inside a group (two cells of one group with the same map
 * size are refused: a table cannot show both). Regions keep the cell's own
 * order (figures.c: contours ascending, whole image last). A percentage that
 * is NaN has no base and is printed as the count alone (CSV: empty).
 * Nothing here prints to stdout/stderr or reads files; it writes to `out`.
 */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */
#include "table.h"
#include "emit.h"
#include <ctype.h>
#include <math.h>
#include "pivot.h"
#include <stdlib.h>
#include <string.h>
#include "util.h"

int sl_table_format_parse(const char *name)
{
    static const struct { const char *name; enum sl_table_format fmt; } formats[] = {
        {"md", SL_TABLE_MD},
        {"csv", SL_TABLE_CSV},
        {"latex", SL_TABLE_LATEX},
        {"json", SL_TABLE_JSON},
        {NULL, SL_TABLE_MD},
    };
    for (int i = 0; name && formats[i].name; i++)
        if (strcmp(name, formats[i].name) == 0)
            return (int)formats[i].fmt;
    return -1;
}

/* ---- order ---- */

static int same_table(const struct sl_cell_record *a, const struct sl_cell_record *b)
{
    return a->vw == b->vw && a->vh == b->vh && strcmp(a->scene, b->scene) == 0 &&
           strcmp(a->viewpoint, b->viewpoint) == 0 && strcmp(a->label, b->label) == 0;
}

/* The cells of one table, by index into the caller's array. */
struct group {
    const int *idx;
    int        n;
};

struct layout {
    int          *order;    /* all cell indices, table by table */
    struct group *groups;
    int           ngroups;
};

static void layout_free(struct layout *l)
{
    free(l->order);
    free(l->groups);
}

static enum sl_err layout_build(const struct sl_cell_record *cells, int ncells, struct layout *l,
                                struct sl_diag *d)
{
    memset(l, 0, sizeof *l);
    int *gid = sl_calloc((size_t)ncells, sizeof *gid);
    l->order = sl_calloc((size_t)ncells, sizeof *l->order);
    l->groups = sl_calloc((size_t)ncells, sizeof *l->groups);
    if (!gid || !l->order || !l->groups) {
        free(gid);
        layout_free(l);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "table layout of %d cells", ncells);
    }
    for (int i = 0; i < ncells; i++) {
        gid[i] = -1;
        for (int j = 0; j < i && gid[i] < 0; j++)
            if (same_table(&cells[i], &cells[j]))
                gid[i] = gid[j];
        if (gid[i] < 0)
            gid[i] = l->ngroups++;
    }
    int pos = 0;
    enum sl_err e = SL_OK;
    for (int g = 0; g < l->ngroups && !e; g++) {
        int start = pos;
        for (int i = 0; i < ncells; i++)
            if (gid[i] == g) {
                /* insertion keeps equal map sizes in input order; they are refused below */
                int k = pos++;
                while (k > start && cells[l->order[k - 1]].map_size > cells[i].map_size) {
                    l->order[k] = l->order[k - 1];
                    k--;
                }
                l->order[k] = i;
            }
        l->groups[g].idx = l->order + start;
        l->groups[g].n = pos - start;
        for (int k = start + 1; k < pos && !e; k++) {
            const struct sl_cell_record *a = &cells[l->order[k - 1]], *b = &cells[l->order[k]];
            if (a->map_size == b->map_size) {
                char key[96];
                snprintf(key, sizeof key, "%s/%s/%dx%d/%s", b->scene, b->viewpoint, b->vw, b->vh, b->label);
                e = sl_fail(d, SL_E_USAGE, NULL, 0, key, "two cells with map size %d in one table",
                            b->map_size);
            }
        }
    }
    for (int i = 0; i < ncells && !e; i++)
        if (cells[i].fig.nregions < 0 || cells[i].fig.nregions > SL_MAX_REGIONS)
            e = sl_fail(d, SL_E_USAGE, NULL, 0, cells[i].label, "cell with %d regions (at most %d)",
                        cells[i].fig.nregions, SL_MAX_REGIONS);
    free(gid);
    if (e)
        layout_free(l);
    return e;
}

/* 1 if every cell of the group has the provenance of the first. */
static int same_provenance(const struct sl_cell_record *cells, const struct group *g)
{
    const struct sl_cell_record *a = &cells[g->idx[0]];
    for (int k = 1; k < g->n; k++) {
        const struct sl_cell_record *b = &cells[g->idx[k]];
        if (strcmp(a->git_sha, b->git_sha) || strcmp(a->config_hash, b->config_hash) ||
            strcmp(a->machine, b->machine) || strcmp(a->method, b->method))
            return 0;
    }
    return 1;
}

/* ---- Markdown ---- */

static const char md_note[] =
    "Percentages: PFL, PnFL, light, shadow, uncertain, wrong of the region's pixels; "
    "correct/incorrect of the method's light or shadow pixels; wrong caught of all wrong pixels of "
    "the image. Background pixels enter no region; PnFL pixels count as shadow.\n\n";

/* A cell's columns and rows: hard cells have a column per region and the
 * figures of figures.h; soft cells (an area light) one column, the whole
 * image, and the figures of softfig.h. A hard method's cell under an area
 * light has both: it is written as its soft table and then, through a copy
 * with has_soft cleared (its "point twin"), as its hard table. */
static int point_twin(const struct sl_cell_record *c) { return !c->has_soft && c->soft.n[SL_SFIG_soft_pixels] > 0; }
static int dual(const struct sl_cell_record *c) { return c->has_soft && c->fig.nregions > 0; }
static int cell_cols(const struct sl_cell_record *c) { return c->has_soft ? 1 : c->fig.nregions; }
static int cell_rows(const struct sl_cell_record *c) { return c->has_soft ? SL_SFIG_COUNT : SL_FIG_COUNT; }
static int col_thickness(const struct sl_cell_record *c, int col) { return c->has_soft ? 0 : c->fig.r[col].thickness; }
static const char *row_name(const struct sl_cell_record *c, int k)
{
    return c->has_soft ? sl_soft_figure_name((enum sl_soft_figure)k) : sl_figure_name((enum sl_figure)k);
}
static const char *row_of(const struct sl_cell_record *c, int k)
{
    return c->has_soft ? sl_soft_figure_of((enum sl_soft_figure)k) : sl_figure_of((enum sl_figure)k);
}
static void cell_value(const struct sl_cell_record *c, int col, int k, uint64_t *n, double *pct)
{
    *n = c->has_soft ? c->soft.n[k] : c->fig.r[col].n[k];
    *pct = c->has_soft ? c->soft.pct[k] : c->fig.r[col].pct[k];
}
/* "count (pct%)", or for a soft mean "pct (of visibility)" */
static void value_text(const struct sl_cell_record *c, int k, uint64_t n, double pct, int tex, char *out, size_t sz)
{
    const char *pc = tex ? "\\%" : "%";
    if (isnan(pct))
        snprintf(out, sz, "%llu", (unsigned long long)n);
    else if (c->has_soft && !strcmp(row_of(c, k), "visibility"))
        snprintf(out, sz, "%.3f%s", pct, pc);
    else
        snprintf(out, sz, "%llu (%.2f%s)", (unsigned long long)n, pct, pc);
}

/* Whether figure row fi of a table is shown (table.h: struct sl_table_rows). */
static int row_shown(const struct sl_cell_record *cells, const struct group *g, int fi,
                     const struct sl_table_rows *rows)
{
    const struct sl_cell_record *c0 = &cells[g->idx[0]];
    if (!rows)
        return 1;
    if (rows->picked)
        return c0->has_soft ? rows->pick_soft[fi] : rows->pick_hard[fi];
    if (!rows->produced || c0->has_soft || fi <= SL_FIG_wrong_caught)
        return 1;
    for (int k = 0; k < g->n; k++) {
        const struct sl_cell_record *c = &cells[g->idx[k]];
        for (int r = 0; r < cell_cols(c); r++) {
            uint64_t n;
            double pct;
            cell_value(c, r, fi, &n, &pct);
            if (n)
                return 1;
        }
    }
    return 0;
}

static int rows_shown(const struct sl_cell_record *cells, const struct group *g, const struct sl_table_rows *rows)
{
    int n = 0;
    for (int fi = 0; fi < cell_rows(&cells[g->idx[0]]); fi++)
        n += row_shown(cells, g, fi, rows);
    return n;
}

/* The view's pixel counts under a hard light: PFL, PnFL, background and the
 * truth of the PFL ones. Under a spot light the PnFL pixels outside its cone
 * are named apart (view.h: a part of n_pnfl), never scored as errors. */
static void view_counts(FILE *f, const struct sl_cell_record *c0, int tex)
{
    uint64_t out = c0->n_outside_cone <= c0->n_pnfl ? c0->n_outside_cone : c0->n_pnfl;
    uint64_t img = c0->n_pfl + c0->n_pnfl + c0->n_background;
    fprintf(f, "PFL %llu, PnFL %llu", (unsigned long long)c0->n_pfl, (unsigned long long)(c0->n_pnfl - out));
    if (out)
        fprintf(f, " facing away, outside the spot's cone %llu (%.2f%s of the image; unlit by definition, "
                   "counted as PnFL in the figures, never as errors)",
                (unsigned long long)out, img ? 100.0 * (double)out / (double)img : 0.0, tex ? "\\%" : "%");
    fprintf(f, ", background %llu; truth%s: %llu PFL lit, %llu PFL shadowed.", (unsigned long long)c0->n_background,
            point_twin(c0) && !c0->frac ? " of the area light's centre" : "", (unsigned long long)c0->n_truth_lit,
            (unsigned long long)c0->n_truth_shadow);
}

/* " (spot light, 70°)" after the scene's name, when the cell knows its light */
static void light_words(FILE *f, const struct sl_cell_record *c0, int tex)
{
    if (!c0->light[0])
        return;
    fputs(" (", f);
    if (tex)
        sl_tex_text(f, c0->light);
    else
        fputs(c0->light, f);
    fputc(')', f);
}

/* The intro of a soft table: the light the truth was computed for, and
 * under a hard light (frac: a fractional visibility against its 0/1 truth)
 * the tolerance its classes take (softfig.h, SL_SOFT_HARD_TOL); tex: "%"
 * escaped by the caller's text writer, so the same words either way. */
static void soft_intro(FILE *f, const struct sl_cell_record *c0)
{
    if (!c0->frac) {
        fputs("Area light: the visible fraction of the light against the area truth "
              "(means in % of full visibility).", f);
        return;
    }
    const char *l = c0->light[0] ? c0->light : "hard light";
    fprintf(f, "%c%s: the visibility against the light's 0/1 truth over the PFL pixels (means in %% of full "
               "visibility); a pixel is lit within \xCE\xB5 = %.2f of 1 and umbra within \xCE\xB5 of 0, so a class "
               "is right when |v \xE2\x88\x92 truth| \xE2\x89\xA4 %.2f and no truth pixel is penumbra.",
            toupper((unsigned char)l[0]), l + 1, (double)SL_SOFT_HARD_TOL, (double)SL_SOFT_HARD_TOL);
}

/* Under every table that has one: its cells' values not finite */
static void nonfinite_note(FILE *fn, const struct sl_cell_record *c)
{
    if (c->nonfinite)
        fprintf(fn, "NON-FINITE: %d\xC2\xB2: %llu value(s) not finite (NaN, \xC2\xB1inf) or out of range; "
                    "their pixels are left out of the figures (a package's verdict there: uncertain).\n\n",
                c->map_size, (unsigned long long)c->nonfinite);
}

static void md_provenance(FILE *f, const struct sl_cell_record *c)
{
    fprintf(f, "method `%s`; contours from `%s` (contour_from); git `%s`, config `%s`, machine `%s`", c->method,
            c->contour_from, c->git_sha, c->config_hash, c->machine);
}

/* One table in the model: its heading names the view and the label, the
 * view's counts above it, a column per map size and region, a row per figure
 * shown; under it which rows are shown and the provenance (once when every
 * map size shares it). Returns 0 when no row is shown (nothing to write), -1
 * out of memory. */
static int md_model(struct sl_tab *t, const struct sl_cell_record *cells, const struct group *g,
                    const struct sl_table_rows *rows)
{
    const struct sl_cell_record *c0 = &cells[g->idx[0]];
    int shown = rows_shown(cells, g, rows), ncols = 0;
    if (shown == 0)
        return 0;
    for (int k = 0; k < g->n; k++)
        ncols += cell_cols(&cells[g->idx[k]]);
    char *light = NULL, *intro = NULL, *note = NULL;
    size_t nl = 0, ni = 0, nn = 0;
    FILE *fl = open_memstream(&light, &nl), *fi = open_memstream(&intro, &ni), *fn = open_memstream(&note, &nn);
    if (fl)
        light_words(fl, c0, 0);
    if (fi && c0->has_soft)
        soft_intro(fi, c0);
    else if (fi)
        view_counts(fi, c0, 0);
    for (int k = 0; fn && k < g->n; k++)
        nonfinite_note(fn, &cells[g->idx[k]]);
    if (fn && shown < cell_rows(c0))
        fprintf(fn, "(%d of %d figures shown: %s; table.md and `shadowlab table --figures all` have every row.)\n\n",
                shown, cell_rows(c0),
                rows->picked ? "those picked with --figures" : "the rest are 0 in every column, not produced by "
                "this method");
    if (fn && same_provenance(cells, g))
        md_provenance(fn, c0);
    else
        for (int k = 0; fn && k < g->n; k++) {
            const struct sl_cell_record *c = &cells[g->idx[k]];
            fprintf(fn, "%s- %d\xC2\xB2: ", k ? "\n" : "", c->map_size);
            md_provenance(fn, c);
        }
    int bad = !fl || fclose(fl) != 0;
    bad |= !fi || fclose(fi) != 0;
    bad |= !fn || fclose(fn) != 0;
    char id[160];
    snprintf(id, sizeof id, "%s-%s-%dx%d-%s", c0->scene, c0->viewpoint, c0->vw, c0->vh, c0->label);
    sl_tab_init(t, id, 1 + ncols, 1, "%s%s / %s / %dx%d / %s", c0->scene, light ? light : "", c0->viewpoint, c0->vw,
                c0->vh, c0->label);
    t->level = 2;
    t->plain = 1;
    t->oom |= bad;
    if (!bad) {
        sl_tab_intro(t, intro);
        sl_tab_notef(t, "%s", note);
    }
    free(light);
    free(intro);
    free(note);
    sl_tab_head(t, 0, "figure");
    for (int k = 0, col = 1; k < g->n; k++) {
        const struct sl_cell_record *c = &cells[g->idx[k]];
        for (int r = 0; r < cell_cols(c); r++, col++) {
            char rn[16];
            sl_region_name(col_thickness(c, r), rn, sizeof rn);
            sl_tab_head(t, col, "%d\xC2\xB2 %s", c->map_size, rn);
        }
    }
    for (int fi2 = 0; fi2 < cell_rows(c0); fi2++) {
        if (!row_shown(cells, g, fi2, rows))
            continue;
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", row_name(c0, fi2));
        for (int k = 0, col = 1; k < g->n; k++) {
            const struct sl_cell_record *c = &cells[g->idx[k]];
            for (int r = 0; r < cell_cols(c); r++, col++) {
                uint64_t n;
                double pct;
                char v[64];
                cell_value(c, r, fi2, &n, &pct);
                value_text(c, fi2, n, pct, 0, v, sizeof v);
                sl_tab_cell(t, col, "%s", v);
            }
        }
    }
    return t->oom ? -1 : 1;
}

static int md_table(FILE *f, const struct sl_cell_record *cells, const struct group *g,
                    const struct sl_table_rows *rows)
{
    struct sl_tab t;
    int k = md_model(&t, cells, g, rows);
    if (k > 0)
        k = sl_emit_md(f, &t, NULL) < 0 ? -1 : 1;
    if (k != 0)
        sl_tab_free(&t);
    return k;
}

/* ---- CSV ---- */


/* The long form: a line per (cell, region, figure), the aliasing figures
 * (by error m) of a hard cell's region after its figures, then the image's
 * background pixels and a spot light's pixels outside its cone. */
static const char *const csv_heads[] = {"scene", "viewpoint", "viewport", "map_size", "method", "label", "region",
                                        "figure", "count", "percent", "percent_of", "git_sha", "config_hash",
                                        "machine"};

/* a line of cell c: its key, then region, figure, count, percent (NaN:
 * empty), percent_of, then its provenance */
static void csv_line(struct sl_tab *t, const struct sl_cell_record *c, const char *region, const char *figure,
                     uint64_t n, double pct, const char *of)
{
    sl_tab_row(t, 0);
    sl_tab_cell(t, 0, "%s", c->scene);
    sl_tab_cell(t, 1, "%s", c->viewpoint);
    sl_tab_cell(t, 2, "%dx%d", c->vw, c->vh);
    sl_tab_cell(t, 3, "%d", c->map_size);
    sl_tab_cell(t, 4, "%s", c->method);
    sl_tab_cell(t, 5, "%s", c->label);
    sl_tab_cell(t, 6, "%s", region);
    sl_tab_cell(t, 7, "%s", figure);
    sl_tab_cell(t, 8, "%llu", (unsigned long long)n);
    if (!isnan(pct))
        sl_tab_cell(t, 9, "%.4f", pct);
    sl_tab_cell(t, 10, "%s", of);
    sl_tab_cell(t, 11, "%s", c->git_sha);
    sl_tab_cell(t, 12, "%s", c->config_hash);
    sl_tab_cell(t, 13, "%s", c->machine);
}

static void csv_model(struct sl_tab *t, const struct sl_cell_record *c, int background)
{
    sl_tab_init(t, "figures", 14, 8, "figures");
    for (int k = 0; k < 14; k++)
        sl_tab_head(t, k, "%s", csv_heads[k]);
    for (int r = 0; c && r < cell_cols(c); r++) {
        char rn[16];
        sl_region_name(col_thickness(c, r), rn, sizeof rn);
        for (int k = 0; k < cell_rows(c); k++) {
            uint64_t n;
            double pct;
            cell_value(c, r, k, &n, &pct);
            csv_line(t, c, rn, row_name(c, k), n, pct, row_of(c, k));
        }
        /* a hard cell's aliasing figures (by error m), stored per region like its
         * figures: the file holds every figure the store holds for the cell */
        for (int k = 0; !c->has_soft && c->has_alias && r < c->alias.nregions && k < SL_AFIG_COUNT; k++) {
            char an[16];
            sl_region_name(c->alias.thickness[r], an, sizeof an);
            csv_line(t, c, an, sl_alias_figure_name((enum sl_alias_figure)k), c->alias.n[r][k], c->alias.pct[r][k],
                     sl_alias_figure_of((enum sl_alias_figure)k));
        }
    }
    if (!c || !background)
        return;
    csv_line(t, c, "image", "background", c->fig.background, NAN, "");
    /* a spot light's pixels outside its cone (view.h): part of PnFL, named apart */
    if (c->n_outside_cone)
        csv_line(t, c, "image", "outside_cone", c->n_outside_cone, NAN, "");
}

/* cell c's lines (NULL: the header alone); -1 out of memory */
static int csv_cell(FILE *f, const struct sl_cell_record *c, int background)
{
    struct sl_tab t;
    const struct sl_emit_opts o = {.first = !c};
    csv_model(&t, c, background);
    int k = sl_emit_csv(f, &t, &o);
    sl_tab_free(&t);
    return k;
}

/* ---- LaTeX ---- */


/* \label keys: letters, digits and '-' only, appended to buf */
static void tex_key(char *buf, size_t n, const char *s)
{
    size_t k = strlen(buf);
    for (; *s && k + 1 < n; s++) {
        char ch = *s;
        int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9');
        buf[k++] = ok ? ch : '-';
    }
    buf[k] = '\0';
}

/* One float per map size (a cell), so a table has 1 + its regions columns:
 * split by map size because two map sizes side by side were 60-294 pt wider
 * than an A4 article's \textwidth. Nothing is scaled: what is still wider
 * than the line (long figure names beside four or five regions:
 * "1028918 (99.84%)" is 70 pt) has its cells stacked, the count above its
 * percentage, when the rows then still fit a page (LATEX_LINES); else it is
 * split by regions into several floats, each with the figure names. */
#define LATEX_COLSEP 8.0   /* 2 \tabcolsep of 4 pt */
#define LATEX_LINES  44    /* \footnotesize lines a float may hold */

/* Estimated width (pt, \footnotesize) of region column r of cell c over the
 * rows shown, its heading included; stacked, a cell's longer line. */
static double latex_col_pt(const struct sl_cell_record *cells, const struct group *g, const struct sl_cell_record *c,
                           int r, const struct sl_table_rows *rows, int stack)
{
    char rn[16];
    sl_region_name(col_thickness(c, r), rn, sizeof rn);
    double w = sl_tex_text_pt(rn);
    for (int fi = 0; fi < cell_rows(&cells[g->idx[0]]); fi++) {
        if (!row_shown(cells, g, fi, rows))
            continue;
        uint64_t n;
        double pct;
        char v[64];
        cell_value(c, r, fi, &n, &pct);
        value_text(c, fi, n, pct, 0, v, sizeof v);
        char *cut = stack ? strstr(v, " (") : NULL;
        double x;
        if (cut) {
            *cut = '\0';
            double a = sl_tex_text_pt(v), b = sl_tex_text_pt(cut + 1);
            x = a > b ? a : b;
        } else
            x = sl_tex_text_pt(v);
        w = x > w ? x : w;
    }
    return w * SL_TEX_FOOTNOTE * SL_TEX_SLACK + LATEX_COLSEP;
}

/* the region columns cut into runs that fit beside the names; returns the runs */
static int latex_cuts(const struct sl_cell_record *cells, const struct group *g, const struct sl_cell_record *c,
                      const struct sl_table_rows *rows, int stack, double name_pt, int *cut)
{
    int parts = 0;
    cut[0] = 0;
    double w = name_pt;
    for (int r = 0; r < cell_cols(c); r++) {
        double x = latex_col_pt(cells, g, c, r, rows, stack);
        if (r > cut[parts] && w + x > SL_TEX_BUDGET) {
            cut[++parts] = r;
            w = name_pt;
        }
        w += x;
    }
    cut[++parts] = cell_cols(c);
    return parts;
}

/* The model of float p of parts (region columns [r0, r1)) of cell c: one
 * float as laid out here (the emitter's fixed layout), its caption's
 * counts (the intro) and its label on the first part only, the
 * provenance under the last. */
static void latex_model(struct sl_tab *t, const struct sl_cell_record *cells, const struct group *g,
                        const struct sl_cell_record *c, int shown, const struct sl_table_rows *rows, int stack, int p,
                        int parts, int r0, int r1)
{
    const struct sl_cell_record *c0 = &cells[g->idx[0]];
    char id[256] = "", num[48], part[96] = "";
    tex_key(id, sizeof id, c0->scene);
    tex_key(id, sizeof id, "-");
    tex_key(id, sizeof id, c0->viewpoint);
    snprintf(num, sizeof num, "-%dx%d-", c0->vw, c0->vh);
    tex_key(id, sizeof id, num);
    tex_key(id, sizeof id, c0->label);
    snprintf(num, sizeof num, "-%d%s", c->map_size, point_twin(c0) ? "-point" : "");
    tex_key(id, sizeof id, num);
    if (parts > 1) {
        char a[16], b[16];
        sl_region_name(col_thickness(c, r0), a, sizeof a);
        sl_region_name(col_thickness(c, r1 - 1), b, sizeof b);
        snprintf(part, sizeof part, " (part %d of %d: %s%s%s)", p + 1, parts, a, r1 - r0 > 1 ? "\xE2\x80\x93" : "",
                 r1 - r0 > 1 ? b : "");
    }
    /* " ∕ " (U+2215): a separator, not a path's '/', which LaTeX may break after */
    sl_tab_init(t, id, 1 + r1 - r0, 1, "%s%s%s%s \xE2\x88\x95 %s \xE2\x88\x95 %d\xC3\x97%d \xE2\x88\x95 %s \xE2\x88\x95 %d\xC2\xB2 map%s", c0->scene,
                c0->light[0] ? " (" : "", c0->light, c0->light[0] ? ")" : "", c0->viewpoint, c0->vw, c0->vh,
                c0->label, c->map_size, part);
    t->fixed = 1;
    t->squares = 1;
    t->stack = stack;
    t->code = 1;
    t->nolabel = p > 0;
    if (p == 0) {
        char *intro = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&intro, &len);
        if (m) {
            if (c0->has_soft)
                soft_intro(m, c0);
            else
                view_counts(m, c0, 0);
            /* "-\u200C-": two hyphens LaTeX does not join into a dash */
            if (shown < cell_rows(c0))
                fprintf(m, " %d of %d figures shown (%s).", shown, cell_rows(c0),
                        rows->picked ? "chosen with -\xE2\x80\x8C-figures"
                                     : "the others are 0: not produced by this method");
            fclose(m);
        }
        if (!m || !intro)
            t->oom = 1;
        sl_tab_intro(t, intro);
        free(intro);
    }
    sl_tab_head(t, 0, "figure");
    for (int r = r0; r < r1; r++) {
        char rn[16];
        sl_region_name(col_thickness(c, r), rn, sizeof rn);
        sl_tab_head(t, 1 + r - r0, "%s", rn);
    }
    for (int fi = 0; fi < cell_rows(c0); fi++) {
        if (!row_shown(cells, g, fi, rows))
            continue;
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", row_name(c0, fi));
        for (int r = r0; r < r1; r++) {
            uint64_t n;
            double pct;
            char v[64];
            cell_value(c, r, fi, &n, &pct);
            value_text(c, fi, n, pct, 0, v, sizeof v);
            sl_tab_cell(t, 1 + r - r0, "%s", v);
        }
    }
    if (p == parts - 1) {
        /* the NON-FINITE words of table.md, as a sentence before the provenance */
        if (c->nonfinite)
            sl_tab_notef(t, "NON-FINITE: %llu value(s) not finite (NaN, \xC2\xB1inf) or out of range; their pixels "
                            "are left out of the figures (a package's verdict there: uncertain). ",
                         (unsigned long long)c->nonfinite);
        sl_tab_note_cat(t, "method `%s`; contours from `%s` (contour_from); git `%s`, config `%s`, machine %s",
                        c->method, c->contour_from, c->git_sha, c->config_hash, c->machine);
    }
}

/* Writes the floats of one table; returns how many. */
static int latex_table(FILE *f, const struct sl_cell_record *cells, const struct group *g,
                       const struct sl_table_rows *rows)
{
    const struct sl_cell_record *c0 = &cells[g->idx[0]];
    int shown = rows_shown(cells, g, rows), floats = 0;
    if (shown == 0)
        return 0;
    double name_pt = sl_tex_text_pt("figure");
    for (int fi = 0; fi < cell_rows(c0); fi++)
        if (row_shown(cells, g, fi, rows) && sl_tex_text_pt(row_name(c0, fi)) > name_pt)
            name_pt = sl_tex_text_pt(row_name(c0, fi));
    name_pt = name_pt * SL_TEX_FOOTNOTE * SL_TEX_SLACK + LATEX_COLSEP;
    for (int k = 0; k < g->n; k++) {
        const struct sl_cell_record *c = &cells[g->idx[k]];
        int cut[SL_MAX_REGIONS + 2], stack = 0;
        int parts = latex_cuts(cells, g, c, rows, 0, name_pt, cut);
        if (parts > 1 && 2 * shown <= LATEX_LINES && latex_cuts(cells, g, c, rows, 1, name_pt, cut) == 1)
            stack = 1, parts = 1;
        else
            parts = latex_cuts(cells, g, c, rows, 0, name_pt, cut);
        for (int p = 0; p < parts && floats >= 0; p++, floats++) {
            struct sl_tab t;
            const struct sl_emit_opts o = {.blank = 1};
            latex_model(&t, cells, g, c, shown, rows, stack, p, parts, cut[p], cut[p + 1]);
            if (sl_emit_tex(f, &t, &o) < 0)
                floats = -2;   /* -1 after the loop's ++ */
            sl_tab_free(&t);
        }
    }
    return floats;
}

/* ---- entry ---- */

enum sl_err sl_table_figures_parse(const char *list, struct sl_table_rows *rows, struct sl_diag *d)
{
    memset(rows, 0, sizeof *rows);
    if (!list || strcmp(list, "all") == 0)
        return SL_OK;
    rows->picked = 1;
    const char *p = list;
    while (*p) {
        size_t len = strcspn(p, ",");
        int found = 0;
        for (int k = 0; k < SL_FIG_COUNT; k++)
            if (strlen(sl_figure_name((enum sl_figure)k)) == len &&
                strncmp(sl_figure_name((enum sl_figure)k), p, len) == 0)
                rows->pick_hard[k] = 1, found = 1;
        for (int k = 0; k < SL_SFIG_COUNT; k++)
            if (strlen(sl_soft_figure_name((enum sl_soft_figure)k)) == len &&
                strncmp(sl_soft_figure_name((enum sl_soft_figure)k), p, len) == 0)
                rows->pick_soft[k] = 1, found = 1;
        if (!found)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "--figures",
                           "unknown figure '%.*s' (the names of figures.h and softfig.h, e.g. wrong, "
                           "light_incorrect, uncertain, soft_mae, leaking, over_dark; or all)", (int)len, p);
        p += len;
        if (*p == ',')
            p++;
    }
    return SL_OK;
}

enum sl_err sl_table_write(FILE *out, enum sl_table_format fmt, const char *title,
                           const struct sl_cell_record *cells, int ncells, struct sl_diag *d)
{
    /* LaTeX leaves out the rows a method does not produce; the others keep everything */
    struct sl_table_rows rows = {.produced = fmt == SL_TABLE_LATEX};
    return sl_table_write_rows(out, fmt, title, cells, ncells, &rows, d);
}

enum sl_err sl_table_write_rows(FILE *out, enum sl_table_format fmt, const char *title,
                                const struct sl_cell_record *cells, int ncells, const struct sl_table_rows *rows,
                                struct sl_diag *d)
{
    if (!out || ncells < 0 || (ncells > 0 && !cells))
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_table_write: bad arguments");
    if (fmt == SL_TABLE_LATEX_SUMMARY)
        return sl_pivot_tex_summary(out, title, cells, ncells, d);
    if (fmt == SL_TABLE_LATEX_DETAIL)
        return sl_pivot_tex_detail(out, title, cells, ncells, d);
    if (fmt == SL_TABLE_JSON)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--format", "json is a pivot's format (--rows, --cols, --figure)");
    if (fmt != SL_TABLE_MD && fmt != SL_TABLE_CSV && fmt != SL_TABLE_LATEX)
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "unknown table format %d (md, csv, latex)", (int)fmt);
    struct layout l;
    enum sl_err e = layout_build(cells, ncells, &l, d);
    if (e)
        return e;
    /* the point twins of cells that have both kinds of figures */
    struct sl_cell_record *twin = NULL;
    for (int i = 0; i < ncells && !twin; i++)
        if (dual(&cells[i])) {
            twin = malloc((size_t)ncells * sizeof *twin);
            if (!twin) {
                layout_free(&l);
                return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "tables");
            }
            memcpy(twin, cells, (size_t)ncells * sizeof *twin);
            for (int j = 0; j < ncells; j++)
                twin[j].has_soft = twin[j].has_soft && !dual(&cells[j]);
        }
    int oom = 0;
    switch (fmt) {
    case SL_TABLE_MD:
        if (title)
            fprintf(out, "# %s\n\n", title);
        fputs(md_note, out);
        for (int g = 0; g < l.ngroups && !oom; g++) {
            oom |= md_table(out, cells, &l.groups[g], rows) < 0;
            if (dual(&cells[l.groups[g].idx[0]]))
                oom |= md_table(out, twin, &l.groups[g], rows) < 0;
        }
        break;
    case SL_TABLE_CSV:
        oom |= csv_cell(out, NULL, 0) < 0;
        for (int i = 0; i < ncells && !oom; i++) {
            oom |= csv_cell(out, &cells[l.order[i]], 1) < 0;
            if (dual(&cells[l.order[i]]))
                oom |= csv_cell(out, &twin[l.order[i]], 0) < 0;
        }
        break;
    case SL_TABLE_LATEX:
        /* no heading: the file is \\input into the reader's own document; the
         * source is a comment (one line: a title holds no line break here) */
        sl_emit_tex_comment(out, "shadowlab tables; needs \\usepackage{booktabs}; wider tables are split, never scaled",
                            !title);
        if (title) {
            char *from = malloc(strlen(title) + 8);
            if (from) {
                snprintf(from, strlen(title) + 8, "from: %s", title);
                for (char *t = from; *t; t++)
                    *t = *t == '\n' || *t == '\r' ? ' ' : *t;
                sl_emit_tex_comment(out, from, 1);
            }
            oom |= !from;
            free(from);
        }
        /* LaTeX holds at most 18 floats it has not placed: a page break
         * every few lets a long file of floats alone compile */
        for (int g = 0, floats = 0; g < l.ngroups && !oom; g++) {
            int k = latex_table(out, cells, &l.groups[g], rows);
            if (k >= 0 && dual(&cells[l.groups[g].idx[0]])) {
                int k2 = latex_table(out, twin, &l.groups[g], rows);
                k = k2 < 0 ? -1 : k + k2;
            }
            oom |= k < 0;
            floats += k;
            if (floats >= 8 && g + 1 < l.ngroups) {
                sl_emit_tex_clearpage(out);
                floats = 0;
            }
        }
        break;
    case SL_TABLE_JSON:
    case SL_TABLE_LATEX_SUMMARY:
    case SL_TABLE_LATEX_DETAIL: break;   /* answered above */
    }
    free(twin);
    layout_free(&l);
    if (oom)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "tables");
    if (ferror(out) || fflush(out) != 0)
        return sl_fail(d, SL_E_IO, NULL, 0, NULL, "writing the tables failed");
    return SL_OK;
}
