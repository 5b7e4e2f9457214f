/*
 * summary.c — see summary.h. Invariant: every value printed is one cell's
 * percentage (best, worst, average case) or the plain mean of those the
 * average runs over; ties keep the first cell in the caller's order.
 */
#include "summary.h"
#include "emit.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "tex.h"
#include "util.h"

struct pick { const struct sl_cell_record *cell; int region; double v; };

static int wanted(const struct sl_summary_opts *o, int thickness)
{
    return o->region < 0 ? thickness != 0 : thickness == o->region;
}

/* One label's summary of one figure (cells[idx[0..n)]). */
struct sum {
    int         maps[64], nmaps;
    struct pick best[64], worst[64], avgcase;
    double      avg;
    long        count;
};

static void summarise(const struct sl_cell_record *cells, const int *idx, int n, const struct sl_summary_opts *o,
                      struct sum *s)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < n; i++) {
        int m = cells[idx[i]].map_size, k = 0;
        while (k < s->nmaps && s->maps[k] != m)
            k++;
        if (k == s->nmaps && s->nmaps < 64)
            s->maps[s->nmaps++] = m;
    }
    for (int a = 1; a < s->nmaps; a++)
        for (int b = a; b > 0 && s->maps[b - 1] > s->maps[b]; b--) {
            int t = s->maps[b]; s->maps[b] = s->maps[b - 1]; s->maps[b - 1] = t;
        }
    double sum = 0.0;
    s->avgcase = (struct pick){NULL, 0, NAN};
    for (int k = 0; k < s->nmaps; k++)
        s->best[k] = s->worst[k] = (struct pick){NULL, 0, NAN};
    for (int i = 0; i < n; i++) {
        const struct sl_cell_record *c = &cells[idx[i]];
        int k = 0;
        while (k < s->nmaps && s->maps[k] != c->map_size)
            k++;
        if (k == s->nmaps)
            continue;   /* past 64 map sizes */
        for (int r = 0; r < c->fig.nregions; r++) {
            int t = c->fig.r[r].thickness;
            double v = c->fig.r[r].pct[o->figure];
            if (o->avg_scene && !strcmp(c->scene, o->avg_scene) && o->avg_viewpoint &&
                !strcmp(c->viewpoint, o->avg_viewpoint) && t == o->avg_region &&
                (!o->avg_map || o->avg_map == c->map_size) && !s->avgcase.cell)
                s->avgcase = (struct pick){c, t, v};
            if (!wanted(o, t) || isnan(v))
                continue;
            sum += v;
            s->count++;
            int better = o->lower_is_better ? v < s->best[k].v : v > s->best[k].v;
            int worse = o->lower_is_better ? v > s->worst[k].v : v < s->worst[k].v;
            if (!s->best[k].cell || better)
                s->best[k] = (struct pick){c, t, v};
            if (!s->worst[k].cell || worse)
                s->worst[k] = (struct pick){c, t, v};
        }
    }
    s->avg = s->count ? sum / (double)s->count : NAN;
}

/* The data table (CSV): a line for the average, each map size's best and
 * worst, the average case. */
static void data_head(struct sl_tab *t)
{
    static const char *const heads[] = {"figure", "label", "kind", "map_size", "scene", "viewpoint", "region",
                                        "percent"};
    sl_tab_init(t, "summary", 8, 7, "summary");
    for (int k = 0; k < 8; k++)
        sl_tab_head(t, k, "%s", heads[k]);
}

static void data_table(struct sl_tab *t, const char *name, const char *label, const struct sum *s)
{
    char rn[16];
    data_head(t);
    sl_tab_row(t, 0);
    sl_tab_cell(t, 0, "%s", name);
    sl_tab_cell(t, 1, "%s", label);
    sl_tab_cell(t, 2, "average");
    sl_tab_cell(t, 7, "%.4f", s->avg);
    for (int k = 0; k <= s->nmaps; k++) {
        const struct pick *p[2] = {&s->best[k], &s->worst[k]};
        for (int w = 0; w < (k < s->nmaps ? 2 : 1); w++) {
            const struct pick *q = k < s->nmaps ? p[w] : &s->avgcase;
            if (!q->cell)
                continue;
            sl_region_name(q->region, rn, sizeof rn);
            sl_tab_row(t, 0);
            sl_tab_cell(t, 0, "%s", name);
            sl_tab_cell(t, 1, "%s", label);
            sl_tab_cell(t, 2, "%s", k == s->nmaps ? "average case" : w ? "worst" : "best");
            sl_tab_cell(t, 3, "%d", k < s->nmaps ? s->maps[k] : q->cell->map_size);
            sl_tab_cell(t, 4, "%s", q->cell->scene);
            sl_tab_cell(t, 5, "%s", q->cell->viewpoint);
            sl_tab_cell(t, 6, "%s", rn);
            sl_tab_cell(t, 7, "%.4f", q->v);
        }
    }
}

/* The reading table: a column for the average, each map size's best and
 * worst and the average case; a row for each thing that says where. */
static void read_table(struct sl_tab *t, const char *name, const char *of, const char *label, const struct sum *s)
{
    char rn[16], id[160];
    int cols = 2 * s->nmaps + (s->avgcase.cell ? 1 : 0);
    snprintf(id, sizeof id, "summary-%s-%s", name, label);
    sl_tab_init(t, id, 2 + cols, 1, "Summary of %s (%% of %s), label %s", name, of, label);
    t->level = 2;
    t->plain = 1;
    sl_tab_head(t, 1, "average");
    for (int k = 0; k < s->nmaps; k++) {
        sl_tab_head(t, 2 + 2 * k, "%d\xC2\xB2 best", s->maps[k]);
        sl_tab_head(t, 3 + 2 * k, "%d\xC2\xB2 worst", s->maps[k]);
    }
    if (s->avgcase.cell)
        sl_tab_head(t, 2 + cols - 1, "average case");
    const char *rows[] = {"scene", "viewpoint", "contour", "map", "value"};
    for (int row = 0; row < 5; row++) {
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", rows[row]);
        if (row == 4)
            sl_tab_cell(t, 1, "%.2f", s->avg);
        for (int col = 0; col < cols; col++) {
            const struct pick *p = col < 2 * s->nmaps ? (col % 2 ? &s->worst[col / 2] : &s->best[col / 2])
                                                      : &s->avgcase;
            if (!p->cell)
                continue;
            sl_region_name(p->region, rn, sizeof rn);
            switch (row) {
            case 0:   /* with its light, as every heading names it: "lamp (spot light, 70°)" */
                if (p->cell->light[0])
                    sl_tab_cell(t, 2 + col, "%s (%s)", p->cell->scene, p->cell->light);
                else
                    sl_tab_cell(t, 2 + col, "%s", p->cell->scene);
                break;
            case 1: sl_tab_cell(t, 2 + col, "%s", p->cell->viewpoint); break;
            case 2: sl_tab_cell(t, 2 + col, "%s", rn); break;
            case 3: sl_tab_cell(t, 2 + col, "%d\xC2\xB2", p->cell->map_size); break;
            case 4: sl_tab_cell(t, 2 + col, "%.2f", p->v); break;
            }
        }
    }
    sl_tab_notef(t, "Average over %ld (cell, region) values.", s->count);
}

/* LaTeX: a booktabs float per label, transposed against the Markdown (a row
 * per value: the average, each map size's best and worst, the average
 * case; where it was as columns) so that it is narrow; the scene (with its
 * light) wrapped in a \parbox when the estimate is wider than the line.
 * Never scaled. */
#define TEX_COLSEP 8.0   /* 2 \tabcolsep of 4 pt */

static const struct pick *tex_pick(const struct sum *s, int k)
{
    return k < 2 * s->nmaps ? (k % 2 ? &s->worst[k / 2] : &s->best[k / 2]) : &s->avgcase;
}

static void write_tex(struct sl_tab *t, const char *name, const char *of, const char *label, const struct sum *s)
{
    char scene[200], rn[16], num[48];
    const double f = SL_TEX_FOOTNOTE * SL_TEX_SLACK;
    double scene_pt = sl_tex_text_pt("scene"), first_pt = sl_tex_text_pt("average case"), vp_pt = 0;
    for (int k = 0; k <= 2 * s->nmaps; k++) {
        const struct pick *p = tex_pick(s, k);
        if (!p->cell)
            continue;
        snprintf(scene, sizeof scene, p->cell->light[0] ? "%s (%s)" : "%s", p->cell->scene, p->cell->light);
        double x = sl_tex_text_pt(scene), y = sl_tex_text_pt(p->cell->viewpoint);
        scene_pt = x > scene_pt ? x : scene_pt;
        vp_pt = y > vp_pt ? y : vp_pt;
        snprintf(num, sizeof num, "%d\xC2\xB2 worst", s->maps[k / 2 < s->nmaps ? k / 2 : 0]);
        x = sl_tex_text_pt(num);
        first_pt = x > first_pt ? x : first_pt;
    }
    vp_pt = vp_pt > sl_tex_text_pt("viewpoint") ? vp_pt : sl_tex_text_pt("viewpoint");
    double rest = (first_pt + vp_pt + sl_tex_text_pt("contour") + sl_tex_text_pt("16384x") +
                   sl_tex_text_pt("100.00")) * f + 6 * TEX_COLSEP;
    double box = rest + scene_pt * f > SL_TEX_BUDGET ? SL_TEX_BUDGET - rest : 0;
    if (box > 0 && box < 60)
        box = 60;
    /* its label: the figure's name in lower case letters and digits, the
     * label's in letters and digits, anything else '-' */
    char id[160];
    size_t k = (size_t)snprintf(id, sizeof id, "summary-");
    for (const char *c = name; *c && k + 2 < sizeof id; c++)
        id[k++] = (*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') ? *c : '-';
    id[k++] = '-';
    for (const char *c = label; *c && k + 1 < sizeof id; c++)
        id[k++] = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ? *c : '-';
    id[k] = '\0';
    sl_tab_init(t, id, 6, 5,
                "Summary of %s (%% of %s), label %s: average over %ld (cell, region) values; each map size's best "
                "and worst cell.",
                name, of, label, s->count);
    t->fixed = 1;
    t->squares = 1;
    t->parbox[1] = box > 0 ? box - TEX_COLSEP : 0;
    static const char *const heads[] = {"", "scene", "viewpoint", "contour", "map", "%"};
    for (int c = 0; c < 6; c++)
        sl_tab_head(t, c, "%s", heads[c]);
    sl_tab_row(t, 0);
    sl_tab_cell(t, 0, "average");
    sl_tab_number(num, sizeof num, s->avg, 2);
    sl_tab_cell(t, 5, "%s", num);
    for (int j = 0; j <= 2 * s->nmaps; j++) {
        const struct pick *p = tex_pick(s, j);
        if (!p->cell)
            continue;
        sl_tab_row(t, 0);
        if (j < 2 * s->nmaps)
            sl_tab_cell(t, 0, "%d\xC2\xB2 %s", s->maps[j / 2], j % 2 ? "worst" : "best");
        else
            sl_tab_cell(t, 0, "average case");
        snprintf(scene, sizeof scene, p->cell->light[0] ? "%s (%s)" : "%s", p->cell->scene, p->cell->light);
        sl_tab_cell(t, 1, "%s", scene);
        sl_tab_cell(t, 2, "%s", p->cell->viewpoint);
        sl_region_name(p->region, rn, sizeof rn);
        sl_tab_cell(t, 3, "%s", rn);
        sl_tab_cell(t, 4, "%d\xC2\xB2", p->cell->map_size);
        sl_tab_number(num, sizeof num, p->v, 2);
        sl_tab_cell(t, 5, "%s", num);
    }
}

enum sl_err sl_summary_write(FILE *out, enum sl_table_format fmt, const struct sl_cell_record *cells, int n,
                             const struct sl_summary_opts *o, struct sl_diag *d)
{
    if (o->figure < 0 || o->figure >= SL_FIG_COUNT)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--summary", "unknown figure");
    if (!sl_figure_of((enum sl_figure)o->figure)[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--summary", "'%s' is a count, not a percentage",
                       sl_figure_name((enum sl_figure)o->figure));
    if (fmt != SL_TABLE_CSV && fmt != SL_TABLE_MD && fmt != SL_TABLE_LATEX)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--format", "summaries come as md, csv or latex");
    const char *name = sl_figure_name((enum sl_figure)o->figure), *of = sl_figure_of((enum sl_figure)o->figure);
    int *idx = malloc((size_t)(n > 0 ? n : 1) * sizeof *idx);
    unsigned char *done = calloc((size_t)(n > 0 ? n : 1), 1);
    struct sum *s = malloc(sizeof *s);
    if (!idx || !done || !s) {
        free(idx), free(done), free(s);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "summary");
    }
    enum sl_err e = SL_OK;
    if (fmt == SL_TABLE_CSV && !o->continued) {
        /* the header, whether or not a label has a value */
        struct sl_tab t;
        const struct sl_emit_opts head = {.first = 1};
        data_head(&t);
        if (sl_emit_csv(out, &t, &head) < 0)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "summary table");
        sl_tab_free(&t);
    }
    if (fmt == SL_TABLE_LATEX && !o->continued)
        sl_emit_tex_comment(out, "shadowlab table --summary; needs \\usepackage{booktabs}", 0);
    /* a summary per label, in the cells' order */
    int any = 0, floats = 0;
    for (int i = 0; i < n && !e; i++) {
        if (done[i])
            continue;
        int m = 0;
        for (int j = i; j < n; j++)
            if (!done[j] && !strcmp(cells[j].label, cells[i].label))
                idx[m++] = j, done[j] = 1;
        summarise(cells, idx, m, o, s);
        if (!s->count)
            continue;   /* this label has no value there: said below if none has */
        if (fmt == SL_TABLE_CSV || fmt == SL_TABLE_MD) {
            struct sl_tab t;
            const struct sl_emit_opts eo = {.first = fmt == SL_TABLE_MD && !o->continued && !any};
            if (fmt == SL_TABLE_CSV)
                data_table(&t, name, cells[i].label, s);
            else
                read_table(&t, name, of, cells[i].label, s);
            if ((fmt == SL_TABLE_CSV ? sl_emit_csv : sl_emit_md)(out, &t, &eo) < 0)
                e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "summary table");
            sl_tab_free(&t);
            any = 1;
        } else {
            any = 1;
            /* LaTeX holds at most 18 floats it has not placed */
            struct sl_tab t;
            const struct sl_emit_opts eo = {.clear = (floats > 0 || o->continued) && floats % 8 == 0, .blank = 1};
            write_tex(&t, name, of, cells[i].label, s);
            if (sl_emit_tex(out, &t, &eo) < 0)
                e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "summary table");
            sl_tab_free(&t);
            floats++;
        }
    }
    if (!any)
        e = sl_fail(d, SL_E_USAGE, NULL, 0, "--summary", "no cell has a value for '%s' in that region", name);
    free(idx);
    free(done);
    free(s);
    return e;
}
