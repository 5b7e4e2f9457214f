/*
 * layouts.c — Moderno's and Curtis's thesis tables and the cost section of one
 * study (Morais's are morais.c's).
 *
 * Which thesis's sections a study gets is decided by the methods its cells
 * ran, from their own metadata (sl_method.family/beside, stored per cell;
 * family_ids below; report/README.md):
 * - Moderno 2011 (own: coherence, texel, neighbours, adjacency, chain; nsm
 *   tabulated beside them): the thesis measures everything inside contours
 *   of 2/4/6 px and the whole image, and against NSM; its tables are the
 *   summaries over the study (Tables 5-15: average, best and worst per map
 *   size, average case), and per view the errors caught per contour (Tables
 *   17/18), the hints (Table 19) and the changes against NSM (Table 23);
 *   with it come the fidelity section (scene primitives) and the chain's
 *   steps (a chain label). The aliasing section (seed 004) is no thesis's:
 *   any study with aliasing figures gets it.
 * - Morais 2015 (own: bgsm, sgsm, sgsm_adj, csm, csm_adj; nsm, hertel, hertel_exact and
 *   raytrace beside them): its tables are morais.c's.
 * - Curtis 2009 (own: soft_mc, point_map, hard_point) names the soft-shadow
 *   table of the cells under an area light (a study with area-light cells
 *   and none of Curtis's methods gets the same table, unnamed).
 * A study that ran only methods of no row (its own methods, technique
 * packages, nsm variants) gets no thesis section: the summary, the plots,
 * the fractional errors (when it has frac cells), the costs, the overlays
 * and the figure tables, which every study gets.
 * Values are printed as the seeds print them: "count (percent%)" with the
 * percentage of figures.h's base, or "count of base (percent%)".
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "provenance.h"
#include "report_int.h"
#include "util.h"

/* The theses whose sections the report can draw, by the name a method's
 * family (method.h: sl_method.family, stored as cells.family/beside) gives
 * them. The report keeps no list of methods: a method says where it comes
 * from, and a study gets a thesis's sections when a method of that family
 * ran (own); a method that names the thesis in `beside` is a baseline its
 * tables list beside the thesis's own methods, bringing no section by
 * itself (a study of NSM biases is nobody's thesis). A method of neither
 * (the researcher's own, a technique package) gets the sections every
 * study gets (summary, plots, figure tables, overlays, costs). */
static const char *const family_ids[SL_REPORT_NFAMILIES] = {"moderno-2011", "morais-2015", "curtis-2009"};

const char *sl_report_family_id(enum sl_report_family f)
{
    return f >= 0 && f < SL_REPORT_NFAMILIES ? family_ids[f] : "";
}

int sl_report_family_of(const char *family, const char *beside, enum sl_report_family f)
{
    const char *id = sl_report_family_id(f);
    size_t n = strlen(id);
    if (!n)
        return 0;
    if (family && strcmp(family, id) == 0)
        return 2;
    for (const char *p = beside ? beside : ""; *p;) {   /* space-separated words */
        while (*p == ' ')
            p++;
        size_t w = strcspn(p, " ");
        if (w == n && strncmp(p, id, n) == 0)
            return 1;
        p += w;
    }
    return 0;
}

int sl_report_label_in(const struct sl_report_study *s, int l, enum sl_report_family f)
{
    return sl_report_family_of(s->family[l], s->beside[l], f);
}

int sl_report_is_moderno(const struct sl_report_study *s, int l) { return sl_report_label_in(s, l, SL_REPORT_MODERNO) > 0; }
int sl_report_is_morais(const struct sl_report_study *s, int l) { return sl_report_label_in(s, l, SL_REPORT_MORAIS) > 0; }

/* ---- study keys ---- */

void sl_report_region_name(int t, char *buf, size_t n)
{
    if (t == 0)
        snprintf(buf, n, "image");
    else
        snprintf(buf, n, "%d px", t);
}

int sl_report_region(const struct sl_cell_record *c, int thickness)
{
    for (int r = 0; r < c->fig.nregions && r < SL_MAX_REGIONS; r++)
        if (c->fig.r[r].thickness == thickness)
            return r;
    return -1;
}

static int same_view(const struct sl_report_view *v, const struct sl_cell_record *c)
{
    return v->vw == c->vw && v->vh == c->vh && strcmp(v->scene, c->scene) == 0 &&
           strcmp(v->viewpoint, c->viewpoint) == 0;
}

enum sl_err sl_report_study_keys(struct sl_report_study *s, struct sl_diag *d)
{
    s->nviews = s->nscenes = s->nlabels = s->nmaps = s->nregions = 0;
    int has_image = 0, moderno_own = 0, morais_own = 0, curtis_own = 0, hard = 0;
    s->curtis = s->area = s->frac = 0;
    for (int i = 0; i < s->n; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        int k;
        s->area |= c->has_soft && !c->frac;   /* frac: a hard light's fractional errors, never an area light's */
        s->frac |= c->has_soft && c->frac;
        hard |= !c->has_soft || c->fig.nregions > 0;   /* a hard method under an area light has both */
        for (k = 0; k < s->nviews && !same_view(&s->views[k], c); k++)
            ;
        if (k == s->nviews) {
            if (k == (int)(sizeof s->views / sizeof s->views[0]))
                return sl_fail(d, SL_E_USAGE, NULL, 0, s->name, "more than %d views in one study", k);
            struct sl_report_view *v = &s->views[s->nviews++];
            snprintf(v->scene, sizeof v->scene, "%s", c->scene);
            snprintf(v->viewpoint, sizeof v->viewpoint, "%s", c->viewpoint);
            v->vw = c->vw;
            v->vh = c->vh;
            snprintf(v->light, sizeof v->light, "%s", c->light);
            v->n_outside_cone = c->n_outside_cone;
            v->n_image = (uint64_t)c->vw * (uint64_t)c->vh;
        }
        for (k = 0; k < s->nscenes && strcmp(s->scenes[k], c->scene) != 0; k++)
            ;
        if (k == s->nscenes) {
            if (k == SL_REPORT_MAXKEYS)
                return sl_fail(d, SL_E_USAGE, NULL, 0, s->name, "more than %d scenes in one study", k);
            snprintf(s->scenes[s->nscenes++], sizeof s->scenes[0], "%s", c->scene);
        }
        for (k = 0; k < s->nlabels && strcmp(s->labels[k], c->label) != 0; k++)
            ;
        if (k == s->nlabels) {
            if (k == SL_REPORT_MAXKEYS)
                return sl_fail(d, SL_E_USAGE, NULL, 0, s->name, "more than %d method labels in one study", k);
            snprintf(s->labels[k], sizeof s->labels[0], "%s", c->label);
            snprintf(s->methods[k], sizeof s->methods[0], "%s", c->method);
            snprintf(s->family[k], sizeof s->family[0], "%s", c->family);
            snprintf(s->beside[k], sizeof s->beside[0], "%s", c->beside);
            s->nlabels++;
            moderno_own |= sl_report_label_in(s, k, SL_REPORT_MODERNO) == 2;
            morais_own |= sl_report_label_in(s, k, SL_REPORT_MORAIS) == 2;
            curtis_own |= sl_report_label_in(s, k, SL_REPORT_CURTIS) == 2;
        }
        for (k = 0; k < s->nmaps && s->maps[k] != c->map_size; k++)
            ;
        if (k == s->nmaps) {
            if (k == SL_REPORT_MAXKEYS)
                return sl_fail(d, SL_E_USAGE, NULL, 0, s->name, "more than %d map sizes in one study", k);
            int j = s->nmaps++;
            while (j > 0 && s->maps[j - 1] > c->map_size) {
                s->maps[j] = s->maps[j - 1];
                j--;
            }
            s->maps[j] = c->map_size;
        }
        for (int r = 0; r < c->fig.nregions && r < SL_MAX_REGIONS; r++) {
            int t = c->fig.r[r].thickness;
            if (t == 0) {
                has_image = 1;
                continue;
            }
            for (k = 0; k < s->nregions && s->regions[k] != t; k++)
                ;
            if (k == s->nregions && s->nregions < SL_MAX_REGIONS - 1) {
                int j = s->nregions++;
                while (j > 0 && s->regions[j - 1] > t) {
                    s->regions[j] = s->regions[j - 1];
                    j--;
                }
                s->regions[j] = t;
            }
        }
    }
    if (has_image)
        s->regions[s->nregions++] = 0;
    s->morais = hard && morais_own;
    s->moderno = hard && moderno_own;
    s->curtis = s->area && curtis_own;
    return SL_OK;
}

const struct sl_cell_record *sl_report_study_cell(const struct sl_report_study *s, const struct sl_report_view *v,
                                                 const char *label, int map_size)
{
    for (int i = 0; i < s->n; i++) {
        const struct sl_cell_record *c = &s->cells[i];
        if (c->map_size == map_size && same_view(v, c) && strcmp(c->label, label) == 0)
            return c;
    }
    return NULL;
}

/* A label's name for people: its cells' display name (`display:`, else
 * its method's own), else the label itself (issue 47: a table names a
 * method one way, the way the run's LaTeX does). */
const char *sl_report_display(const struct sl_report_study *s, const char *label)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->cells[i].label, label) && s->cells[i].display[0])
            return s->cells[i].display;
    return label;
}

/* ---- value formats ---- */

static void fmt_of(char *buf, size_t n, uint64_t v, uint64_t base)
{
    if (base == 0)
        snprintf(buf, n, "%llu of 0", (unsigned long long)v);
    else
        snprintf(buf, n, "%llu of %llu (%.2f%%)", (unsigned long long)v, (unsigned long long)base,
                 100.0 * (double)v / (double)base);
}

void sl_report_fmt_ms(char *buf, size_t n, double ms)
{
    if (!(ms > 0.0))
        snprintf(buf, n, "–");
    else if (ms < 10.0)
        snprintf(buf, n, "%.2f", ms);
    else if (ms < 1000.0)
        snprintf(buf, n, "%.1f", ms);
    else
        snprintf(buf, n, "%.0f", ms);
}

static void fmt_count(char *buf, size_t n, double v)
{
    if (v >= 1e9)
        snprintf(buf, n, "%.2fG", v / 1e9);
    else if (v >= 1e6)
        snprintf(buf, n, "%.2fM", v / 1e6);
    else if (v >= 1e4)
        snprintf(buf, n, "%.1fk", v / 1e3);
    else
        snprintf(buf, n, "%.0f", v);
}


/* 1 if a cell of the label has figure f > 0 in some region */
static int label_has(const struct sl_report_study *s, int l, enum sl_figure f)
{
    for (int i = 0; i < s->n; i++)
        if (strcmp(s->cells[i].label, s->labels[l]) == 0)
            for (int r = 0; r < s->cells[i].fig.nregions && r < SL_MAX_REGIONS; r++)
                if (s->cells[i].fig.r[r].n[f] > 0)
                    return 1;
    return 0;
}

void sl_report_view_title(const struct sl_report_view *v, char *buf, size_t n)
{
    snprintf(buf, n, v->light[0] ? "%s (%s) / %s / %d×%d" : "%s%s / %s / %d×%d", v->scene, v->light, v->viewpoint,
             v->vw, v->vh);
}

void sl_report_view_id(const struct sl_report_study *s, const struct sl_report_view *v, const char *what, char *buf,
                       size_t n)
{
    snprintf(buf, n, "%s-%s-%s-%s-%dx%d", s->slug, what, v->scene, v->viewpoint, v->vw, v->vh);
}

/* ---- Moderno 2011: summaries (Tables 5-15) ---- */

struct pick { const struct sl_cell_record *cell; int region; double v; };

static void pick_text(const struct pick *p, char *buf, size_t n)
{
    if (!p->cell) {
        snprintf(buf, n, "–");
        return;
    }
    char rn[16];
    sl_report_region_name(p->region, rn, sizeof rn);
    snprintf(buf, n, "%.2f (%s/%s, %s)", p->v, p->cell->scene, p->cell->viewpoint, rn);
}

/* Each row names a thesis table only where it holds that table's quantity
 * over that table's pixels (the contour of NSM's image under contour_from
 * nsm; PnFL counted as Moderno counts them: shadow, hinted, confirmed);
 * `method` limits it to the approach the table is about (NULL: every
 * Moderno method). In the thesis's order (Tables 5, 6, 7-8, 12, 13); the
 * "wrong" row is also the first row of Tables 9-11 and 14-15. Not here:
 * Tables 9-11's rows 2-3 (light corrected, shadow confirmed, % of NSM's
 * light / shadow and of its correct ones), which no stored percentage has
 * as its base, and Tables 14-15's rows 2-3: in the thesis they repeat
 * Table 7's rows 4-5 digit for digit (0.55/0.12 and the same five cases'
 * values under other scenes' names), a copy error, so no quantity is
 * known for them. */
static const struct {
    enum sl_figure fig;
    int lower_is_better, always;
    const char *method;
    const char *title;
} moderno_summaries[] = {
    {SL_FIG_wrong_caught, 0, 1, NULL, "Errors caught inside the contour, % of the image's wrong pixels (Moderno 2011 Table 5)"},
    {SL_FIG_wrong, 1, 1, NULL, "Wrong pixels, % of the contour's pixels (Moderno 2011 Tables 6, 9-11, 14-15)"},
    {SL_FIG_light_incorrect, 1, 0, "nsm", "Errors in light, % of NSM's lit pixels (Moderno 2011 Table 6, row 2)"},
    {SL_FIG_shadow_incorrect, 1, 0, "nsm", "Errors in shadow, % of NSM's shadowed pixels with PnFL (Moderno 2011 Table 6, row 3)"},
    {SL_FIG_hinted_moderno, 0, 0, "coherence", "Confirmations by texel coherence (hints, PnFL hinted), % of the contour's pixels (Moderno 2011 Tables 7-8, row 1)"},
    {SL_FIG_hinted_light, 0, 0, "coherence", "Confirmations in light, % of NSM's lit pixels (Moderno 2011 Tables 7-8, row 2)"},
    {SL_FIG_hinted_shadow_moderno, 0, 0, "coherence", "Confirmations in shadow, % of NSM's shadowed pixels with PnFL (Moderno 2011 Tables 7-8, row 3)"},
    {SL_FIG_hinted_light_wrong, 1, 0, "coherence", "Wrong confirmations in light, % of NSM's lit pixels (Moderno 2011 Tables 7-8, row 4)"},
    {SL_FIG_hinted_shadow_wrong_moderno, 1, 0, "coherence", "Wrong confirmations in shadow, % of NSM's shadowed pixels with PnFL (Moderno 2011 Tables 7-8, row 5)"},
    {SL_FIG_conf_step2_moderno, 0, 0, "chain", "Confirmations after the neighbour-texel step (hints + confirmations + corrections, PnFL with them), % of the contour's pixels (Moderno 2011 Table 12, row 1)"},
    {SL_FIG_conf_light_moderno, 0, 0, "chain", "Confirmations/corrections in light after the neighbour-texel step, % of NSM's lit pixels (Moderno 2011 Table 12, row 2)"},
    {SL_FIG_conf_shadow_step2_moderno, 0, 0, "chain", "Confirmations in shadow after the neighbour-texel step, % of NSM's shadowed pixels with PnFL (Moderno 2011 Table 12, row 3)"},
    {SL_FIG_conf_moderno, 0, 0, "chain", "Confirmations after the adjacent-geometry step (hints + confirmations + corrections, PnFL with them), % of the contour's pixels (Moderno 2011 Table 13, row 1)"},
    {SL_FIG_conf_shadow_moderno, 0, 0, "chain", "Confirmations in shadow after the adjacent-geometry step, % of NSM's shadowed pixels with PnFL (Moderno 2011 Table 13, row 2)"},
    {SL_FIG_confirmed, 0, 0, NULL, "Shadow confirmed by a ray-triangle hit alone, % of the contour's pixels (no thesis table: its Tables 12-13 add hints and corrections, above)"},
    {SL_FIG_corrected, 0, 0, NULL, "Lit turned shadowed by a ray-triangle hit, % of the contour's pixels (no thesis table)"},
};

static int summary_wants(const struct sl_report_study *s, int l, int which)
{
    const char *m = moderno_summaries[which].method;
    return sl_report_is_moderno(s, l) && (!m || strcmp(s->methods[l], m) == 0) &&
           (moderno_summaries[which].always || label_has(s, l, moderno_summaries[which].fig));
}

static enum sl_err moderno_summary(struct sl_report_doc *doc, const struct sl_report_study *s, int which,
                                   struct sl_diag *d)
{
    enum sl_figure f = moderno_summaries[which].fig;
    int lower = moderno_summaries[which].lower_is_better;
    int nmaps = s->nmaps > 10 ? 10 : s->nmaps;
    /* contours only, as the thesis; a study without contours summarises the image */
    int contours = s->nregions > 0 && s->regions[0] != 0;
    /* the thesis's average case: Bench, "with" viewpoint, 2 px contour */
    int has_avgcase = 0;
    for (int i = 0; i < s->n && !has_avgcase; i++)
        has_avgcase = !strcmp(s->cells[i].scene, "bench") && !strcmp(s->cells[i].viewpoint, "with") &&
                      sl_report_region(&s->cells[i], 2) >= 0;
    int nrows = 0;
    for (int l = 0; l < s->nlabels; l++)
        nrows += summary_wants(s, l, which);
    if (nrows == 0)
        return SL_OK;
    struct sl_tab t;
    char id[160];
    snprintf(id, sizeof id, "%s-summary-%s", s->slug, sl_figure_name(f));
    sl_tab_init(&t, id, 2 + 2 * nmaps + has_avgcase, 1, "%s", moderno_summaries[which].title);
    sl_tab_group(&t, 2, "%s", "");
    for (int k = 0; k < nmaps; k++)
        sl_tab_group(&t, 2, "%d²", s->maps[k]);
    if (has_avgcase)
        sl_tab_group(&t, 1, "%s", "");
    sl_tab_head(&t, 0, "method");
    sl_tab_head(&t, 1, "average");
    for (int k = 0; k < nmaps; k++) {
        sl_tab_head(&t, 2 + 2 * k, "best");
        sl_tab_head(&t, 3 + 2 * k, "worst");
    }
    if (has_avgcase)
        sl_tab_head(&t, 2 + 2 * nmaps, "average case (bench/with, 2 px)");
    for (int l = 0; l < s->nlabels; l++) {
        if (!summary_wants(s, l, which))
            continue;
        struct pick best[10], worst[10], avgcase = {NULL, 0, NAN};
        memset(best, 0, sizeof best);
        memset(worst, 0, sizeof worst);
        double sum = 0.0;
        long count = 0;
        for (int i = 0; i < s->n; i++) {
            const struct sl_cell_record *c = &s->cells[i];
            if (strcmp(c->label, s->labels[l]) != 0)
                continue;
            int k = 0;
            while (k < nmaps && s->maps[k] != c->map_size)
                k++;
            for (int r = 0; r < c->fig.nregions && r < SL_MAX_REGIONS; r++) {
                int th = c->fig.r[r].thickness;
                double v = c->fig.r[r].pct[f];
                if (!strcmp(c->scene, "bench") && !strcmp(c->viewpoint, "with") && th == 2 && !avgcase.cell &&
                    !isnan(v))
                    avgcase = (struct pick){c, th, v};
                if ((contours ? th == 0 : th != 0) || isnan(v))
                    continue;
                sum += v;
                count++;
                if (k == nmaps)
                    continue;
                if (!best[k].cell || (lower ? v < best[k].v : v > best[k].v))
                    best[k] = (struct pick){c, th, v};
                if (!worst[k].cell || (lower ? v > worst[k].v : v < worst[k].v))
                    worst[k] = (struct pick){c, th, v};
            }
        }
        char buf[160];
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
        if (count)
            sl_tab_cell(&t, 1, "%.2f", sum / (double)count);
        else
            sl_tab_cell(&t, 1, "–");
        for (int k = 0; k < nmaps; k++) {
            pick_text(&best[k], buf, sizeof buf);
            sl_tab_cell(&t, 2 + 2 * k, "%s", buf);
            pick_text(&worst[k], buf, sizeof buf);
            sl_tab_cell(&t, 3 + 2 * k, "%s", buf);
        }
        if (has_avgcase) {
            pick_text(&avgcase, buf, sizeof buf);
            sl_tab_cell(&t, 2 + 2 * nmaps, "%s", buf);
        }
    }
    sl_tab_notef(&t,
             "Average over every (cell, %s) value of the label; best and worst name the cell's scene/viewpoint "
             "and %s. %s.", contours ? "contour" : "region", contours ? "contour" : "region",
             lower ? "Lower is better" : "Higher is better");
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    return e;
}

/* ---- Moderno 2011: per view ---- */

/* Rows label x map x region for the labels `want` accepts; fill(t, cell, region index, col0). */
typedef void (*row_fill)(struct sl_tab *t, const struct sl_cell_record *c, int r);

static int view_rows(struct sl_tab *t, const struct sl_report_study *s, const struct sl_report_view *v,
                     int (*want)(const struct sl_report_study *, int), row_fill fill)
{
    int rows = 0;
    for (int l = 0; l < s->nlabels; l++) {
        if (!want(s, l))
            continue;
        int first_of_label = 1;
        for (int k = 0; k < s->nmaps; k++) {
            const struct sl_cell_record *c = sl_report_study_cell(s, v, s->labels[l], s->maps[k]);
            if (!c)
                continue;
            for (int r = 0; r < c->fig.nregions && r < SL_MAX_REGIONS; r++) {
                char rn[16];
                sl_report_region_name(c->fig.r[r].thickness, rn, sizeof rn);
                sl_tab_row(t, first_of_label);
                if (first_of_label)
                    sl_tab_cell(t, 0, "%s", sl_report_display(s, s->labels[l]));
                if (r == 0)
                    sl_tab_cell(t, 1, "%d²", c->map_size);
                sl_tab_cell(t, 2, "%s", rn);
                fill(t, c, r);
                first_of_label = 0;
                rows++;
            }
        }
    }
    return rows;
}

static int want_moderno(const struct sl_report_study *s, int l)
{
    return sl_report_is_moderno(s, l);
}

static int want_vs_nsm(const struct sl_report_study *s, int l)
{
    if (!sl_report_is_moderno(s, l))
        return 0;
    return label_has(s, l, SL_FIG_fixed_ls) || label_has(s, l, SL_FIG_fixed_sl) ||
           label_has(s, l, SL_FIG_broken_ls) || label_has(s, l, SL_FIG_broken_sl) ||
           label_has(s, l, SL_FIG_kept_right) || label_has(s, l, SL_FIG_kept_wrong);
}

static int want_hints(const struct sl_report_study *s, int l)
{
    return sl_report_is_moderno(s, l) && label_has(s, l, SL_FIG_hinted);
}

static void fill_errors(struct sl_tab *t, const struct sl_cell_record *c, int r)
{
    const struct sl_region_figures *g = &c->fig.r[r];
    char buf[96];
    fmt_of(buf, sizeof buf, g->n[SL_FIG_wrong_caught], c->fig.wrong_image);
    sl_tab_cell(t, 3, "%s", buf);
    fmt_of(buf, sizeof buf, g->n[SL_FIG_light_incorrect], g->n[SL_FIG_light]);
    sl_tab_cell(t, 4, "%s", buf);
    fmt_of(buf, sizeof buf, g->n[SL_FIG_shadow_incorrect], g->n[SL_FIG_shadow]);
    sl_tab_cell(t, 5, "%s", buf);
    fmt_of(buf, sizeof buf, g->n[SL_FIG_wrong], g->n[SL_FIG_pixels]);
    sl_tab_cell(t, 6, "%s", buf);
}

static void fill_vs_nsm(struct sl_tab *t, const struct sl_cell_record *c, int r)
{
    static const enum sl_figure cols[] = {SL_FIG_fixed_ls, SL_FIG_fixed_sl, SL_FIG_broken_ls, SL_FIG_broken_sl,
                                          SL_FIG_kept_ll_right, SL_FIG_kept_ss_right_moderno,
                                          SL_FIG_kept_ll_wrong, SL_FIG_kept_ss_wrong};
    for (int k = 0; k < 8; k++)
        sl_tab_cell(t, 3 + k, "%llu", (unsigned long long)c->fig.r[r].n[cols[k]]);
}

static void fill_hints(struct sl_tab *t, const struct sl_cell_record *c, int r)
{
    const uint64_t *n = c->fig.r[r].n;
    char buf[96];
    /* Moderno's count: PnFL are NSM shadow and hinted */
    uint64_t base[2] = {n[SL_FIG_nsm_light], n[SL_FIG_nsm_shadow_moderno]};
    uint64_t hinted[2] = {n[SL_FIG_hinted_light], n[SL_FIG_hinted_shadow_moderno]};
    uint64_t wrong[2] = {n[SL_FIG_hinted_light_wrong], n[SL_FIG_hinted_shadow_wrong_moderno]};
    for (int k = 0; k < 2; k++) {
        fmt_of(buf, sizeof buf, hinted[k], base[k]);
        sl_tab_cell(t, 3 + 3 * k, "%s", buf);
        fmt_of(buf, sizeof buf, wrong[k], base[k]);
        sl_tab_cell(t, 4 + 3 * k, "%s", buf);
        fmt_of(buf, sizeof buf, base[k] > hinted[k] ? base[k] - hinted[k] : 0, base[k]);
        sl_tab_cell(t, 5 + 3 * k, "%s", buf);
    }
}

/* Which contour the study's cells were scored on (config contour_from). */
static const char *contour_note(const struct sl_report_study *s)
{
    int own = 0, nsm = 0;
    for (int i = 0; i < s->n; i++) {
        own += strcmp(s->cells[i].contour_from, "own") == 0;
        nsm += strcmp(s->cells[i].contour_from, "own") != 0;
    }
    if (own && nsm)
        return "Contours: mixed (some cells contour_from nsm, some own) - not comparable.";
    return own ? "Contours from each method's own result image (contour_from: own), not the thesis's."
               : "Contours from NSM's image (front faces culled), one per view and map shared by every method "
                 "(contour_from: nsm, the thesis's).";
}

static void key_heads(struct sl_tab *t)
{
    sl_tab_head(t, 0, "method");
    sl_tab_head(t, 1, "map");
    sl_tab_head(t, 2, "region");
}

static enum sl_err moderno_view(struct sl_report_doc *doc, const struct sl_report_study *s,
                                const struct sl_report_view *v, struct sl_diag *d)
{
    char vt[160], id[160];
    sl_report_view_title(v, vt, sizeof vt);
    enum sl_err e = SL_OK;
    struct sl_tab t;

    sl_report_view_id(s, v, "errors", id, sizeof id);
    sl_tab_init(&t, id, 7, 3, "%s: wrong pixels by contour (Moderno 2011 Tables 17/18)", vt);
    key_heads(&t);
    sl_tab_head(&t, 3, "caught (of the image's wrong)");
    sl_tab_head(&t, 4, "wrongly lit (of light)");
    sl_tab_head(&t, 5, "wrongly shadowed (of shadow)");
    sl_tab_head(&t, 6, "wrong (of pixels)");
    sl_tab_notef(&t, "PnFL pixels count as shadow. %s", contour_note(s));
    if (view_rows(&t, s, v, want_moderno, fill_errors))
        e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);

    if (!e) {
        sl_report_view_id(s, v, "hints", id, sizeof id);
        sl_tab_init(&t, id, 9, 3, "%s: texel coherence hints of NSM's light and shadow (Moderno 2011 Table 19)", vt);
        key_heads(&t);
        sl_tab_group(&t, 3, "%s", "");
        sl_tab_group(&t, 3, "NSM light");
        sl_tab_group(&t, 3, "NSM shadow");
        for (int k = 0; k < 2; k++) {
            sl_tab_head(&t, 3 + 3 * k, "hinted");
            sl_tab_head(&t, 4 + 3 * k, "wrongly hinted");
            sl_tab_head(&t, 5 + 3 * k, "undecided");
        }
        sl_tab_notef(&t, "Percentages of NSM's pixels in light (in shadow, PnFL with them: hinted, "
                 "as Moderno counts them) in the region. %s", contour_note(s));
        if (view_rows(&t, s, v, want_hints, fill_hints))
            e = sl_report_doc_table(doc, &t, d);
        sl_tab_free(&t);
    }

    if (!e) {
        sl_report_view_id(s, v, "vs-nsm", id, sizeof id);
        sl_tab_init(&t, id, 11, 3, "%s: pixel changes against NSM (Moderno 2011 Table 23)", vt);
        key_heads(&t);
        sl_tab_group(&t, 3, "%s", "");
        sl_tab_group(&t, 2, "corrected");
        sl_tab_group(&t, 2, "turned bad");
        sl_tab_group(&t, 2, "maintained correct");
        sl_tab_head(&t, 3, "L→S");
        sl_tab_head(&t, 4, "S→L");
        sl_tab_head(&t, 5, "L→S");
        sl_tab_head(&t, 6, "S→L");
        sl_tab_group(&t, 2, "maintained incorrect");
        sl_tab_head(&t, 7, "L→L");
        sl_tab_head(&t, 8, "S→S");
        sl_tab_head(&t, 9, "L→L");
        sl_tab_head(&t, 10, "S→S");
        sl_tab_notef(&t,
                 "L→S: NSM put it in light, the method in shadow. Maintained: the same verdict as NSM. PnFL pixels "
                 "are maintained correct S→S, as Moderno counts them; with no pixel left undecided the classes add "
                 "up to the region's pixels. %s", contour_note(s));
        if (view_rows(&t, s, v, want_vs_nsm, fill_vs_nsm))
            e = sl_report_doc_table(doc, &t, d);
        sl_tab_free(&t);
    }
    return e;
}

enum sl_err sl_report_moderno(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    for (size_t w = 0; w < sizeof moderno_summaries / sizeof moderno_summaries[0] && !e; w++)
        e = moderno_summary(doc, s, (int)w, d);
    for (int v = 0; v < s->nviews && !e; v++)
        e = moderno_view(doc, s, &s->views[v], d);
    return e;
}

/* ---- costs ---- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* median of v[0..n) (sorted in place); NAN when n is 0 */
static double median(double *v, int n)
{
    if (n == 0)
        return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void fmt_range(char *buf, size_t n, double med, double lo, double hi)
{
    char a[32], b[32], c[32];
    sl_report_fmt_ms(a, sizeof a, med);
    if (!(med > 0.0)) {
        snprintf(buf, n, "–");
        return;
    }
    sl_report_fmt_ms(b, sizeof b, lo);
    sl_report_fmt_ms(c, sizeof c, hi);
    snprintf(buf, n, "%s [%s–%s]", a, b, c);
}

enum sl_err sl_report_costs(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d)
{
    double *meth = sl_calloc((size_t)s->n + 1, sizeof *meth);
    double *map = sl_calloc((size_t)s->n + 1, sizeof *map);
    if (!meth || !map) {
        free(meth);
        free(map);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, s->name, "cost table");
    }
    char id[160];
    snprintf(id, sizeof id, "%s-costs", s->slug);
    struct sl_tab t;
    sl_tab_init(&t, id, 11, 2, "%s: cost per method and map size", s->name);
    static const char *const heads[] = {"method", "map", "cells", "step ms: median [min–max]",
                                        "layers ms: median [min–max]", "rays", "rays / pixel",
                                        "ray-tri tests", "lookups", "GS prims", "fragments"};
    for (int k = 0; k < 11; k++)
        sl_tab_head(&t, k, "%s", heads[k]);
    int runs = 0, once = 0;
    for (int l = 0; l < s->nlabels; l++)
        for (int m = 0; m < s->nmaps; m++) {
            int n = 0, nmap = 0, cells = 0, one = 0;
            double lo = INFINITY, hi = 0.0, mlo = INFINITY, mhi = 0.0;
            double rays = 0.0, px = 0.0, tests = 0.0, lookups = 0.0, gs = 0.0, frags = 0.0;
            for (int i = 0; i < s->n; i++) {
                const struct sl_cell_record *c = &s->cells[i];
                if (c->map_size != s->maps[m] || strcmp(c->label, s->labels[l]) != 0)
                    continue;
                const struct sl_cell_record *k = c;
                if (k->ms_method > 0.0) {
                    meth[n++] = k->ms_method;
                    lo = fmin(lo, k->ms_method_min > 0.0 ? k->ms_method_min : k->ms_method);
                    hi = fmax(hi, fmax(k->ms_method_max, k->ms_method));
                }
                if (k->ms_map_render > 0.0) {
                    map[nmap++] = k->ms_map_render;
                    mlo = fmin(mlo, k->ms_map_render_min > 0.0 ? k->ms_map_render_min : k->ms_map_render);
                    mhi = fmax(mhi, fmax(k->ms_map_render_max, k->ms_map_render));
                }
                int r = sl_report_region(c, 0);
                px += r >= 0 ? (double)c->fig.r[r].n[SL_FIG_pixels] : (double)c->n_pfl + (double)c->n_pnfl;
                rays += (double)k->rays;
                tests += (double)k->tri_tests;
                lookups += (double)k->lookups;
                gs += (double)k->gs_prims;
                frags += (double)k->fragments;
                if (k->runs > runs)
                    runs = k->runs;
                one |= k->runs == 1;
                cells++;
            }
            if (cells == 0)
                continue;
            char buf[96];
            sl_tab_row(&t, m == 0);
            if (m == 0)
                sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
            sl_tab_cell(&t, 1, "%d²", s->maps[m]);
            sl_tab_cell(&t, 2, "%d", cells);
            /* a cell timed once makes its row's times one measurement each */
            fmt_range(buf, sizeof buf, median(meth, n), lo, hi);
            sl_tab_cell(&t, 3, "%s%s", buf, one && n ? SL_REPORT_ONCE : "");
            fmt_range(buf, sizeof buf, median(map, nmap), mlo, mhi);
            sl_tab_cell(&t, 4, "%s%s", buf, one && nmap ? SL_REPORT_ONCE : "");
            once |= one && (n || nmap);
            fmt_count(buf, sizeof buf, rays / cells);
            sl_tab_cell(&t, 5, "%s", buf);
            sl_tab_cell(&t, 6, "%.3f", px > 0.0 ? rays / px : 0.0);
            fmt_count(buf, sizeof buf, tests / cells);
            sl_tab_cell(&t, 7, "%s", buf);
            fmt_count(buf, sizeof buf, lookups / cells);
            sl_tab_cell(&t, 8, "%s", buf);
            fmt_count(buf, sizeof buf, gs / cells);
            sl_tab_cell(&t, 9, "%s", buf);
            fmt_count(buf, sizeof buf, frags / cells);
            sl_tab_cell(&t, 10, "%s", buf);
        }
    free(meth);
    free(map);
    /* the renderer the times are of: the cells' (the store's runs), once */
    char gl[400];
    const char *ren = s->n > 0 ? s->cells[0].gl_renderer : "";
    for (int i = 1; i < s->n; i++)
        if (strcmp(s->cells[i].gl_renderer, ren))
            ren = "several GL renderers (see the runs table)";
    sl_gl_times_note(ren, gl, sizeof gl);
    sl_tab_notef(&t,
             "Times: the median over the cells (scenes, viewpoints, viewports) of each cell's median over %d "
             "timed repetition(s), in brackets the lowest and highest single repetition. Counters: mean per cell "
             "(rays / pixel: over all non-background pixels). GS prims and fragments are GL query counts of the "
             "layers the method reads. step ms: the method's per-pixel step (lookup and rays); layers "
             "ms: the shadow-map render of the driver's layers it reads (a package's own map pass, zpart's "
             "slices: in its stages, ms_cost). %s", runs, gl);
    if (once)
        sl_report_tab_once(&t);
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    if (!e)
        sl_report_doc_para(doc,
                           "Where the renderer above is llvmpipe these times come from a CPU-only machine: "
                           "OpenGL runs on CPU threads and the rays on Embree, so rasterisation is slow and rays "
                           "are cheap compared with a GPU. The "
                           "machine-independent counters (shadow rays, ray-triangle tests, map lookups, "
                           "geometry-shader primitives, fragments) let a reader carry the comparison to a GPU, "
                           "where the balance between raster and ray cost differs: weigh each counter with that "
                           "GPU's cost per ray, per test and per fragment.");
    return e;
}

/* ---- Curtis 2009: soft shadows ---- */

/* Per view, a row per soft label and map size: how close the visible
 * fraction is to the area truth, and what it cost. Curtis reports images
 * and frame times; this table puts his quality question (how far from the
 * reference, and where: lit, umbra, penumbra) beside the cost in numbers. */
enum sl_err sl_report_curtis(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    for (int v = 0; v < s->nviews && !e; v++) {
        const struct sl_report_view *vw = &s->views[v];
        char id[160];
        sl_report_view_id(s, vw, "soft", id, sizeof id);
        char title[200];
        sl_report_view_title(vw, title, sizeof title);
        struct sl_tab t;
        sl_tab_init(&t, id, 11, 2, "%s: the visible fraction of the light against the area truth%s", title,
                           s->curtis ? " (Curtis 2009)" : "");
        static const char *const head[] = {"label", "map", "MAE", "RMSE", "bias", "within 0.05", "within 0.1",
                                           "class right", "penumbra right", "rays / pixel", "step ms"};
        for (int k = 0; k < 11; k++)
            sl_tab_head(&t, k, "%s", head[k]);
        int any = 0, once = 0;
        double stderr_mean = NAN;
        for (int l = 0; l < s->nlabels; l++)
            for (int m = 0; m < s->nmaps; m++) {
                const struct sl_cell_record *c = sl_report_study_cell(s, vw, s->labels[l], s->maps[m]);
                if (!c || !c->has_soft || c->frac)   /* frac: a hard light's, fractional.c */
                    continue;
                const struct sl_soft_figures *f = &c->soft;
                sl_tab_row(&t, m == 0);
                if (m == 0 || !any)
                    sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
                any = 1;
                sl_tab_cell(&t, 1, "%d²", c->map_size);
                sl_tab_cell(&t, 2, "%.2f", f->pct[SL_SFIG_soft_mae]);
                sl_tab_cell(&t, 3, "%.2f", f->pct[SL_SFIG_soft_rmse]);
                sl_tab_cell(&t, 4, "%+.2f", f->pct[SL_SFIG_soft_bias]);
                sl_tab_cell(&t, 5, "%.2f%%", f->pct[SL_SFIG_soft_within_005]);
                sl_tab_cell(&t, 6, "%.2f%%", f->pct[SL_SFIG_soft_within_010]);
                sl_tab_cell(&t, 7, "%.2f%%", f->pct[SL_SFIG_soft_class_right]);
                if (isnan(f->pct[SL_SFIG_soft_penumbra_right]))
                    sl_tab_cell(&t, 8, "–");
                else
                    sl_tab_cell(&t, 8, "%.2f%%", f->pct[SL_SFIG_soft_penumbra_right]);
                uint64_t px = f->n[SL_SFIG_soft_pixels];
                sl_tab_cell(&t, 9, "%.2f", px ? (double)c->rays / (double)px : 0.0);
                char buf[32];
                sl_report_fmt_ms(buf, sizeof buf, c->ms_method);
                int one = c->runs == 1 && strcmp(buf, "–") != 0;
                sl_tab_cell(&t, 10, "%s%s", buf, one ? SL_REPORT_ONCE : "");
                once |= one;
                stderr_mean = f->pct[SL_SFIG_soft_truth_stderr];
            }
        sl_tab_notef(&t, "Errors in %% of full visibility (MAE, RMSE; bias > 0: too light); "
                 "within: share of pixels; class: lit / umbra / penumbra as the truth classes them; the "
                 "truth's own mean standard error here: %.3f.", stderr_mean);
        if (once)
            sl_report_tab_once(&t);
        if (any)
            e = sl_report_doc_table(doc, &t, d);
        sl_tab_free(&t);
    }
    return e;
}
