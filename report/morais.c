/*
 * morais.c — Morais 2015's tables (seed 000) as Morais counts them, with his
 * printed numbers beside ours, and Hertel 2009's classification (seed 002).
 *
 * Morais counts the pixels facing the light (PFL) and leaves the others
 * (PnFL) out: his light and shadow are shares of PFL, correct/incorrect
 * shares of the method's light or shadow, and the conservative methods'
 * uncertain pixels, split by the ray's answer (the truth's), shares of the
 * final light or shadow (Tables 19-24).
 * figures.h counts PnFL as shadow; sl_morais_counts takes them back out.
 *
 * His tables are about three views, his cases: Side-Trees (best), Against-
 * Flowers (worst), Against-Bench (average); per case the truth (Tables
 * 4-6), one table per method (NSM 7-9, BGSM 10-12, SGSM 13-15, SGSM with
 * adjacency 16-18, CSMa 19-21, CSMA 22-24; rows viewport x pixel type,
 * columns map sizes), the map rendering times (25/27/29) and the ray step
 * (26/28/30). Each of ours has the thesis's row under it where the thesis
 * prints one (report/theses/morais-2015.csv and morais-2015-times.csv, read
 * by theses.c): a reader compares on the page. Times come from another
 * machine (his GPU and OptiX Prime, ours llvmpipe and Embree): both are
 * printed, no ratio. Hertel's hybrid (hertel, as published, and
 * hertel_exact) gets a table per case: rays traced as a share of PFL, wrong
 * pixels, violations and the ray step, and Hertel's Table 2 (his share of
 * view samples traced) once.
 * Views that are none of his cases get the same rows per view, with every
 * Morais label and no thesis rows, and their times per label.
 * Cells are matched by the method they ran, not their label (the first
 * label of a method is taken), so a config's labels may differ from the
 * thesis's names.
 */
#include <string.h>
#include "report_int.h"

static const char *const row_names[SL_MR_COUNT] = {
#define SL_MR_NAME(id, text) text,
    SL_MORAIS_ROWS(SL_MR_NAME)
#undef SL_MR_NAME
};

const char *sl_morais_row_name(enum sl_morais_row r) { return r < SL_MR_COUNT ? row_names[r] : "?"; }

int sl_morais_counts(const struct sl_cell_record *c, struct sl_morais_counts *out)
{
    memset(out, 0, sizeof *out);
    int r = sl_report_region(c, 0);
    if (r < 0)
        return 0;
    const uint64_t *n = c->fig.r[r].n;
    uint64_t pnfl = n[SL_FIG_pnfl];
    uint64_t *o = out->n, *b = out->base;
    o[SL_MR_pfl] = n[SL_FIG_pfl];
    o[SL_MR_pnfl] = pnfl;
    b[SL_MR_pfl] = b[SL_MR_pnfl] = n[SL_FIG_pixels];
    o[SL_MR_truth_light] = c->n_truth_lit;
    o[SL_MR_truth_shadow] = c->n_truth_shadow;
    b[SL_MR_truth_light] = b[SL_MR_truth_shadow] = c->n_truth_lit + c->n_truth_shadow;
    /* PnFL: always shadow, always right (figures.h) */
    o[SL_MR_light] = n[SL_FIG_light];
    o[SL_MR_shadow] = n[SL_FIG_shadow] >= pnfl ? n[SL_FIG_shadow] - pnfl : 0;
    b[SL_MR_light] = b[SL_MR_shadow] = n[SL_FIG_pfl];
    o[SL_MR_light_correct] = n[SL_FIG_light_correct];
    o[SL_MR_light_incorrect] = n[SL_FIG_light_incorrect];
    b[SL_MR_light_correct] = b[SL_MR_light_incorrect] = o[SL_MR_light];
    o[SL_MR_shadow_correct] = n[SL_FIG_shadow_correct] >= pnfl ? n[SL_FIG_shadow_correct] - pnfl : 0;
    o[SL_MR_shadow_incorrect] = n[SL_FIG_shadow_incorrect];
    b[SL_MR_shadow_correct] = b[SL_MR_shadow_incorrect] = o[SL_MR_shadow];
    /* the traced pixels are the maps' uncertain ones, PFL only (sl_method_trace_left) */
    o[SL_MR_shadow_uncertain] = n[SL_FIG_traced_shadow];
    o[SL_MR_light_uncertain] =
        n[SL_FIG_traced] >= n[SL_FIG_traced_shadow] ? n[SL_FIG_traced] - n[SL_FIG_traced_shadow] : 0;
    /* of the final image's light and shadow, as the thesis's numbers are (morais-2015.csv) */
    b[SL_MR_light_uncertain] = o[SL_MR_light];
    b[SL_MR_shadow_uncertain] = o[SL_MR_shadow];
    return 1;
}

/* ---- the thesis's cases and tables ---- */

static const struct mcase {
    const char *scene, *viewpoint, *name;
    int truth_table, time_table;   /* Tables 4-6; 25, 27, 29 (and the next: the ray step) */
} cases[] = {
    {"trees", "side", "Side-Trees (best case)", 4, 25},
    {"flowers", "against", "Against-Flowers (worst case)", 5, 27},
    {"bench", "against", "Against-Bench (average case)", 6, 29},
};
#define NCASES ((int)(sizeof cases / sizeof cases[0]))

/* table = first + case index (7 best, 8 worst, 9 average) */
static const struct mmethod {
    const char *method, *name;
    int first, csm;
} mmethods[] = {
    {"nsm", "NSM", 7, 0},          {"bgsm", "BGSM", 10, 0},    {"sgsm", "SGSM", 13, 0},
    {"sgsm_adj", "SGSM with adjacency", 16, 0}, {"csm", "CSMa (CSM without adjacency)", 19, 1},
    {"csm_adj", "CSMA (CSM with adjacency)", 22, 1},
};
#define NMMETHODS ((int)(sizeof mmethods / sizeof mmethods[0]))

static int case_of(const char *scene, const char *viewpoint)
{
    for (int k = 0; k < NCASES; k++)
        if (!strcmp(cases[k].scene, scene) && !strcmp(cases[k].viewpoint, viewpoint))
            return k;
    return -1;
}

/* the first label that ran method m, -1 if none */
static int label_of(const struct sl_report_study *s, const char *m)
{
    for (int l = 0; l < s->nlabels; l++)
        if (!strcmp(s->methods[l], m))
            return l;
    return -1;
}

/* The thesis's rows (theses.h): sl_report_morais reads them before any
 * table is filled, so these lookups find them in memory (and nothing when
 * they could not be read). */
static const struct sl_morais_datum *thesis_find(int table, int vw, int vh, int map, enum sl_morais_row row)
{
    const struct sl_morais_datum *rows;
    int n;
    if (sl_theses_morais(&rows, &n, NULL))
        return NULL;
    for (const struct sl_morais_datum *t = rows; t->scene; t++)
        if (t->table == table && t->vw == vw && t->vh == vh && t->map_size == map && t->row == row)
            return t;
    return NULL;
}

static const struct sl_morais_time *thesis_time(int table, int vw, int vh, int map, const char *method)
{
    const struct sl_morais_time *rows;
    int n;
    if (sl_theses_morais_times(&rows, &n, NULL))
        return NULL;
    for (const struct sl_morais_time *t = rows; t->scene; t++)
        if (t->table == table && t->vw == vw && t->vh == vh && t->map_size == map && !strcmp(t->method, method))
            return t;
    return NULL;
}

static void fmt_count(char *buf, size_t n, uint64_t v, uint64_t base)
{
    if (base == 0)
        snprintf(buf, n, "%llu", (unsigned long long)v);
    else
        snprintf(buf, n, "%llu (%.2f%%)", (unsigned long long)v, 100.0 * (double)v / (double)base);
}

/* The thesis's notes met while filling a table, "*" after the value and the
 * note under the table (as much of them as the note holds). */
struct notes { char text[700]; size_t len; int n, dropped; };

static void note_add(struct notes *nt, int table, int vw, int vh, int map, const char *note)
{
    char one[300];
    int k = map ? snprintf(one, sizeof one, "%sTable %d, %d×%d, %d²: %s", nt->n ? "; " : "", table, vw, vh, map, note)
                : snprintf(one, sizeof one, "%sTable %d, %d×%d: %s", nt->n ? "; " : "", table, vw, vh, note);
    if (k > 0 && strstr(nt->text, one + (nt->n ? 2 : 0)))
        return;   /* one note for the rows it covers */
    if (k > 0 && nt->len + (size_t)k < sizeof nt->text) {
        memcpy(nt->text + nt->len, one, (size_t)k + 1);
        nt->len += (size_t)k;
        nt->n++;
    } else {
        nt->dropped++;
    }
}

static void thesis_value(char *buf, size_t n, const struct sl_morais_datum *t, struct notes *nt)
{
    snprintf(buf, n, "%llu (%.2f%%)%s", (unsigned long long)t->n, t->pct, t->note ? "*" : "");
    if (t->note)
        note_add(nt, t->table, t->vw, t->vh, t->map_size, t->note);
}

static void notes_append(struct sl_tab *t, const struct notes *nt)
{
    if (nt->n)
        sl_tab_note_cat(t, " * The thesis's value as printed, read so: %s%s.", nt->text,
                        nt->dropped ? "; more in report/theses/" : "");
}

/* the study's views of a case, in their order (viewports) */
static int case_views(const struct sl_report_study *s, int k, const struct sl_report_view **v, int max)
{
    int n = 0;
    for (int i = 0; i < s->nviews && n < max; i++)
        if (!strcmp(s->views[i].scene, cases[k].scene) && !strcmp(s->views[i].viewpoint, cases[k].viewpoint))
            v[n++] = &s->views[i];
    return n;
}

static const struct sl_cell_record *any_cell(const struct sl_report_study *s, const struct sl_report_view *v)
{
    for (int l = 0; l < s->nlabels; l++)
        for (int m = 0; m < s->nmaps; m++) {
            const struct sl_cell_record *c = sl_report_study_cell(s, v, s->labels[l], s->maps[m]);
            if (c && sl_report_region(c, 0) >= 0)
                return c;
        }
    return NULL;
}

/* A column of a table whose rows of ours have the thesis's under them: our
 * counts there (has: a cell was counted) and where the thesis's value stands
 * (its viewport and map size, 0 in a table without maps). */
struct mcol {
    struct sl_morais_counts mc;
    int has, vw, vh, map;
};

static void mcol_set(struct mcol *m, const struct sl_cell_record *c, const struct sl_report_view *v, int map)
{
    m->has = c && sl_morais_counts(c, &m->mc);
    m->vw = v->vw;
    m->vh = v->vh;
    m->map = map;
}

/* The values of pixel type r from column `col` on, the source named in the
 * column before: ours (thesis 0) from the columns' counts, or the thesis's
 * Table `table` (thesis 1), set back, its notes gathered in nt. Returns
 * whether a value of ours was written. */
static int source_row(struct sl_tab *t, int thesis, int col, enum sl_morais_row r, const struct mcol *c,
                      int n, int table, struct notes *nt)
{
    sl_tab_cell(t, col - 1, thesis ? "thesis" : "ours");
    if (thesis)
        sl_tab_muted(t);
    int any = 0;
    for (int j = 0; j < n; j++) {
        char buf[64];
        if (!thesis) {
            if (!c[j].has)
                continue;
            fmt_count(buf, sizeof buf, c[j].mc.n[r], c[j].mc.base[r]);
            any = 1;
        } else {
            const struct sl_morais_datum *th = thesis_find(table, c[j].vw, c[j].vh, c[j].map, r);
            if (!th)
                continue;
            thesis_value(buf, sizeof buf, th, nt);
        }
        sl_tab_cell(t, col + j, "%s", buf);
    }
    return any;
}

/* Tables 4-6: the truth of a case per viewport */
static enum sl_err case_truth(struct sl_report_doc *doc, const struct sl_report_study *s, int k,
                              const struct sl_report_view **v, int nv, struct sl_diag *d)
{
    char id[160];
    snprintf(id, sizeof id, "%s-table%d-%s-%s", s->slug, cases[k].truth_table, cases[k].scene, cases[k].viewpoint);
    struct sl_tab t;
    char cite[40];
    sl_tab_init(&t, id, 2 + nv, 2, "%s: the truth's pixels (Morais 2015 %s)", cases[k].name,
                sl_thesis_cite(SL_THESIS_MORAIS, cases[k].truth_table, cite, sizeof cite));
    sl_tab_head(&t, 0, "pixel type");
    sl_tab_head(&t, 1, "source");
    for (int i = 0; i < nv; i++)
        sl_tab_head(&t, 2 + i, "%d×%d", v[i]->vw, v[i]->vh);
    struct mcol col[SL_REPORT_MAXCOLS];   /* nv <= 8 (case_views) */
    for (int i = 0; i < nv; i++)
        mcol_set(&col[i], any_cell(s, v[i]), v[i], 0);
    struct notes nt = {{0}, 0, 0, 0};
    int any = 0;
    for (int r = SL_MR_pfl; r <= SL_MR_truth_shadow; r++)
        for (int src = 0; src < 2; src++) {
            sl_tab_row(&t, src == 0);
            if (src == 0)
                sl_tab_cell(&t, 0, "%s", row_names[r]);
            any |= source_row(&t, src, 2, (enum sl_morais_row)r, col, nv, cases[k].truth_table, &nt);
        }
    sl_tab_notef(&t, "PFL and PnFL: %% of the view's pixels (background excluded: the thesis's "
             "views have none); light and shadow: %% of PFL, by the truth (ours: Embree, his: OptiX Prime).");
    notes_append(&t, &nt);
    enum sl_err e = any ? sl_report_doc_table(doc, &t, d) : SL_OK;
    sl_tab_free(&t);
    return e;
}

/* Tables 7-24: one method on one case, rows viewport x pixel type x source, columns map sizes */
static enum sl_err case_method(struct sl_report_doc *doc, const struct sl_report_study *s, int k, int mi,
                               const struct sl_report_view **v, int nv, struct sl_diag *d)
{
    const struct mmethod *mm = &mmethods[mi];
    int l = label_of(s, mm->method);
    if (l < 0)
        return SL_OK;
    int table = mm->first + k;
    int nmaps = s->nmaps > SL_REPORT_MAXCOLS - 3 ? SL_REPORT_MAXCOLS - 3 : s->nmaps;
    static const enum sl_morais_row plain[6] = {SL_MR_light, SL_MR_shadow, SL_MR_light_correct,
                                                SL_MR_light_incorrect, SL_MR_shadow_correct, SL_MR_shadow_incorrect};
    static const enum sl_morais_row csm[6] = {SL_MR_light_uncertain, SL_MR_shadow_uncertain, SL_MR_light_correct,
                                              SL_MR_light_incorrect, SL_MR_shadow_correct, SL_MR_shadow_incorrect};
    const enum sl_morais_row *rows = mm->csm ? csm : plain;
    char id[160];
    snprintf(id, sizeof id, "%s-table%d-%s-%s", s->slug, table, cases[k].scene, cases[k].viewpoint);
    struct sl_tab t;
    char cite[40];
    sl_tab_init(&t, id, 3 + nmaps, 3, "%s: %s (label %s), Morais 2015 %s", cases[k].name, mm->name,
                s->labels[l], sl_thesis_cite(SL_THESIS_MORAIS, table, cite, sizeof cite));
    sl_tab_group(&t, 3, "%s", "");
    sl_tab_group(&t, nmaps, "shadow map size");
    sl_tab_head(&t, 0, "viewport");
    sl_tab_head(&t, 1, "pixel type");
    sl_tab_head(&t, 2, "source");
    for (int m = 0; m < nmaps; m++)
        sl_tab_head(&t, 3 + m, "%d²", s->maps[m]);
    struct notes nt = {{0}, 0, 0, 0};
    int any = 0;
    for (int i = 0; i < nv; i++) {
        struct mcol col[SL_REPORT_MAXCOLS];
        for (int m = 0; m < nmaps; m++)
            mcol_set(&col[m], sl_report_study_cell(s, v[i], s->labels[l], s->maps[m]), v[i], s->maps[m]);
        for (int q = 0; q < 6; q++)
            for (int src = 0; src < 2; src++) {
                sl_tab_row(&t, q == 0 && src == 0);
                if (q == 0 && src == 0)
                    sl_tab_cell(&t, 0, "%d×%d", v[i]->vw, v[i]->vh);
                if (src == 0)
                    sl_tab_cell(&t, 1, "%s", row_names[rows[q]]);
                any |= source_row(&t, src, 3, rows[q], col, nmaps, table, &nt);
            }
    }
    sl_tab_notef(&t, "%s", mm->csm
             ? "Pixels facing the light only (PnFL left out). Uncertain: the pixels the two maps leave undecided "
               "and a ray decides, split by its answer (the truth's), % of the final image's light or shadow "
               "(the thesis's base); correct/incorrect: % of the final light or shadow."
             : "Pixels facing the light only (PnFL left out): light and shadow % of PFL, correct/incorrect % of "
               "the method's light or shadow.");
    notes_append(&t, &nt);
    enum sl_err e = any ? sl_report_doc_table(doc, &t, d) : SL_OK;
    sl_tab_free(&t);
    return e;
}

/* Tables 25-30: stage 0 the shadow-map rendering, 1 the ray step; ours beside the thesis's */
static enum sl_err case_times(struct sl_report_doc *doc, const struct sl_report_study *s, int k, int stage,
                              const struct sl_report_view **v, int nv, struct sl_diag *d)
{
    static const char *const meth[2][3] = {{"nsm", "csm", "csm_adj"}, {"raytrace", "csm", "csm_adj"}};
    static const char *const head[2][3] = {{"NSM", "CSMa", "CSMA"}, {"full trace", "CSMa", "CSMA"}};
    int table = cases[k].time_table + stage;
    int l[3], nl = 0;
    for (int j = 0; j < 3; j++)
        nl += (l[j] = label_of(s, meth[stage][j])) >= 0;
    if (nl == 0)
        return SL_OK;
    char id[160];
    snprintf(id, sizeof id, "%s-table%d-%s-%s", s->slug, table, cases[k].scene, cases[k].viewpoint);
    struct sl_tab t;
    char cite[40];
    sl_tab_init(&t, id, 8, 2, "%s: %s, ms (Morais 2015 %s)", cases[k].name,
                stage ? "the ray-tracing step" : "the shadow-map rendering",
                sl_thesis_cite(SL_THESIS_MORAIS_TIMES, table, cite, sizeof cite));
    sl_tab_group(&t, 2, "%s", "");
    for (int j = 0; j < 3; j++)
        sl_tab_group(&t, 2, "%s", head[stage][j]);
    sl_tab_head(&t, 0, "viewport");
    sl_tab_head(&t, 1, "map");
    for (int j = 0; j < 3; j++) {
        sl_tab_head(&t, 2 + 2 * j, "ours");
        sl_tab_head(&t, 3 + 2 * j, "thesis");
    }
    int runs = 0, once = 0;
    struct notes nt = {{0}, 0, 0, 0};
    for (int i = 0; i < nv; i++)
        for (int m = 0; m < s->nmaps; m++) {
            sl_tab_row(&t, m == 0);
            if (m == 0)
                sl_tab_cell(&t, 0, "%d×%d", v[i]->vw, v[i]->vh);
            sl_tab_cell(&t, 1, "%d²", s->maps[m]);
            for (int j = 0; j < 3; j++) {
                char buf[48];
                const struct sl_cell_record *c = l[j] >= 0 ? sl_report_study_cell(s, v[i], s->labels[l[j]], s->maps[m])
                                                           : NULL;
                sl_report_fmt_ms(buf, sizeof buf, c ? (stage ? c->ms_ray_step : c->ms_map_render) : 0.0);
                int one = c && c->runs == 1 && strcmp(buf, "–") != 0;
                sl_tab_cell(&t, 2 + 2 * j, "%s%s", buf, one ? SL_REPORT_ONCE : "");
                once |= one;
                if (c && c->runs > runs)
                    runs = c->runs;
                const struct sl_morais_time *th = thesis_time(table, v[i]->vw, v[i]->vh, s->maps[m], meth[stage][j]);
                if (th) {
                    sl_tab_cell(&t, 3 + 2 * j, "%.2f%s", th->ms, th->note ? "*" : "");
                    if (th->note)
                        note_add(&nt, table, th->vw, th->vh, th->map_size, th->note);
                }
            }
        }
    sl_tab_notef(&t, "ours: medians over %d timed repetition(s) per cell on this machine (llvmpipe "
             "and Embree on CPU cores); thesis: his GPU and OptiX Prime. Different machines: read each column's trend, "
             "not the ratio. %s", runs,
             stage ? "Ours: the rays' time alone (ms_ray_step); the full trace (raytrace; his OptiX Prime) traces "
                     "every PFL pixel."
                   : "Ours: the render of the layers the method reads (ms_map_render).");
    notes_append(&t, &nt);
    if (once)
        sl_report_tab_once(&t);
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    return e;
}

/* Hertel 2009's hybrid on a case: hertel (as published) and hertel_exact */
static enum sl_err case_hertel(struct sl_report_doc *doc, const struct sl_report_study *s, int k,
                               const struct sl_report_view **v, int nv, struct sl_diag *d)
{
    static const char *const meth[2] = {"hertel", "hertel_exact"};
    int l[2] = {label_of(s, meth[0]), label_of(s, meth[1])};
    if (l[0] < 0 && l[1] < 0)
        return SL_OK;
    char id[160];
    snprintf(id, sizeof id, "%s-hertel-%s-%s", s->slug, cases[k].scene, cases[k].viewpoint);
    struct sl_tab t;
    int rt = label_of(s, "raytrace");
    sl_tab_init(&t, id, 12, 2, "%s: Hertel 2009's classification, as published (hertel) and exact "
                       "(hertel_exact)", cases[k].name);
    sl_tab_group(&t, 2, "%s", "");
    for (int j = 0; j < 2; j++)
        sl_tab_group(&t, 5, "%s", l[j] >= 0 ? s->labels[l[j]] : meth[j]);
    sl_tab_head(&t, 0, "viewport");
    sl_tab_head(&t, 1, "map");
    for (int j = 0; j < 2; j++) {
        sl_tab_head(&t, 2 + 5 * j, "traced (of PFL)");
        sl_tab_head(&t, 3 + 5 * j, "wrong");
        sl_tab_head(&t, 4 + 5 * j, "violations");
        sl_tab_head(&t, 5 + 5 * j, "ray step ms");
        sl_tab_head(&t, 6 + 5 * j, "of full trace");
    }
    int once = 0;
    for (int i = 0; i < nv; i++)
        for (int m = 0; m < s->nmaps; m++) {
            sl_tab_row(&t, m == 0);
            if (m == 0)
                sl_tab_cell(&t, 0, "%d×%d", v[i]->vw, v[i]->vh);
            sl_tab_cell(&t, 1, "%d²", s->maps[m]);
            for (int j = 0; j < 2; j++) {
                const struct sl_cell_record *c = l[j] >= 0 ? sl_report_study_cell(s, v[i], s->labels[l[j]], s->maps[m])
                                                           : NULL;
                int r = c ? sl_report_region(c, 0) : -1;
                if (r < 0)
                    continue;
                const uint64_t *n = c->fig.r[r].n;
                char buf[64];
                fmt_count(buf, sizeof buf, n[SL_FIG_traced], n[SL_FIG_pfl]);
                sl_tab_cell(&t, 2 + 5 * j, "%s", buf);
                fmt_count(buf, sizeof buf, n[SL_FIG_wrong], n[SL_FIG_pfl]);
                sl_tab_cell(&t, 3 + 5 * j, "%s", buf);
                sl_tab_cell(&t, 4 + 5 * j, "%llu", (unsigned long long)c->violations);
                sl_report_fmt_ms(buf, sizeof buf, c->ms_ray_step);
                int one = c->runs == 1 && strcmp(buf, "–") != 0;
                sl_tab_cell(&t, 5 + 5 * j, "%s%s", buf, one ? SL_REPORT_ONCE : "");
                once |= one;
                /* the same machine's full trace of the view: a ratio that carries (his RT insec / RT class) */
                const struct sl_cell_record *full = rt >= 0 ? sl_report_study_cell(s, v[i], s->labels[rt], s->maps[m])
                                                            : NULL;
                if (full && full->ms_ray_step > 0.0 && c->ms_ray_step > 0.0)
                    sl_tab_cell(&t, 6 + 5 * j, "%.0f%%", 100.0 * c->ms_ray_step / full->ms_ray_step);
            }
        }
    /* Hertel's Table 2 (report/theses/hertel-2009.csv): the share of the
     * rays he traced and of their time, over his scenes */
    double lo = 100.0, hi = 0.0, tlo = 100.0, thi = 0.0;
    const struct sl_hertel_row *h;
    int nh = 0;
    if (sl_theses_hertel(&h, &nh, NULL))
        nh = 0;
    for (int i = 0; i < nh; i++) {
        double share = 100.0 * (double)h[i].rays / (double)h[i].insec;
        double time = 100.0 * h[i].rt_insec / h[i].rt_class;
        lo = share < lo ? share : lo;
        hi = share > hi ? share : hi;
        tlo = time < tlo ? time : tlo;
        thi = time > thi ? time : thi;
    }
    sl_tab_notef(&t, "traced: pixels decided by a shadow ray, %% of PFL (Hertel's \"uncertain\" "
             "view samples); wrong: %% of PFL; violations: pixels breaking the method's exactness guarantee "
             "(hertel promises none, so its errors show as wrong pixels); of full trace: the ray step against "
             "the raytrace label's on the same view and machine (noisy: one median of a few repetitions each).");
    if (nh)
        sl_tab_note_cat(&t, " Hertel's Table 2 traces %.1f-%.1f%% of the rays a full trace casts and takes "
                        "%.0f-%.0f%% of its time (RT insec / RT class), on his scenes (the table \"Hertel 2009 "
                        "Table 2\").", lo, hi, tlo, thi);
    if (once)
        sl_report_tab_once(&t);
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    return e;
}

static enum sl_err hertel_thesis(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d)
{
    const struct sl_hertel_row *h;   /* report/theses/hertel-2009.csv: as printed */
    int nh;
    enum sl_err er = sl_theses_hertel(&h, &nh, d);
    if (er)
        return er;
    char id[160];
    snprintf(id, sizeof id, "%s-hertel-table2", s->slug);
    struct sl_tab t;
    char cite[40];
    sl_tab_init(&t, id, 8, 1, "Hertel 2009 %s: his scenes, ms on his GPU and the rays traced",
                sl_thesis_cite(SL_THESIS_HERTEL, 2, cite, sizeof cite));
    static const char *const head[] = {"scene (triangles)", "RT class ms", "RT insec ms", "RT opt ms",
                                       "RT insec / class", "# rays", "# insec. rays", "rays / insec. rays"};
    for (int k = 0; k < 8; k++)
        sl_tab_head(&t, k, "%s", head[k]);
    for (int i = 0; i < nh; i++) {
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "%s (%d)", h[i].scene, h[i].tris);
        sl_tab_cell(&t, 1, "%.0f", h[i].rt_class);
        sl_tab_cell(&t, 2, "%.0f", h[i].rt_insec);
        sl_tab_cell(&t, 3, "%.0f", h[i].rt_opt);
        sl_tab_cell(&t, 4, "%.0f%%", 100.0 * h[i].rt_insec / h[i].rt_class);
        sl_tab_cell(&t, 5, "%llu", (unsigned long long)h[i].rays);
        sl_tab_cell(&t, 6, "%llu", (unsigned long long)h[i].insec);
        sl_tab_cell(&t, 7, "%.1f%%", 100.0 * (double)h[i].rays / (double)h[i].insec);
    }
    sl_tab_notef(&t, "As printed (1280×1024, a 1K² map; RT class: every ray, insec: the uncertain "
             "only, opt: with the ray cut at the stored depth). The caption calls the last two columns the rays "
             "without and with the classification, but \"# rays\" is the smaller in every row; the last column "
             "reads it as the traced share. Compare with \"traced (of PFL)\" above: a share of view samples, on "
             "other scenes.");
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    return e;
}

/* ---- every other view: the same rows, every Morais label, no thesis ---- */

static enum sl_err other_view(struct sl_report_doc *doc, const struct sl_report_study *s,
                              const struct sl_report_view *v, struct sl_diag *d)
{
    static const enum sl_morais_row rows[] = {SL_MR_light, SL_MR_shadow, SL_MR_light_correct, SL_MR_light_incorrect,
                                              SL_MR_shadow_correct, SL_MR_shadow_incorrect, SL_MR_light_uncertain,
                                              SL_MR_shadow_uncertain};
    int nmaps = s->nmaps > SL_REPORT_MAXCOLS - 2 ? SL_REPORT_MAXCOLS - 2 : s->nmaps;
    char vt[160], id[160], buf[64];
    sl_report_view_title(v, vt, sizeof vt);
    sl_report_view_id(s, v, "morais", id, sizeof id);
    struct sl_tab t;
    sl_tab_init(&t, id, 2 + nmaps, 2, "%s: pixels per method and map size (as in Morais 2015 Tables 7-24; not "
                       "one of his cases)", vt);
    sl_tab_group(&t, 2, "%s", "");
    sl_tab_group(&t, nmaps, "shadow map size");
    sl_tab_head(&t, 0, "method");
    sl_tab_head(&t, 1, "pixel type");
    for (int k = 0; k < nmaps; k++)
        sl_tab_head(&t, 2 + k, "%d²", s->maps[k]);
    int any = 0;
    for (int l = 0; l < s->nlabels; l++) {
        if (!sl_report_is_morais(s, l))
            continue;
        struct sl_morais_counts mc[SL_REPORT_MAXCOLS];
        int has = 0, traced = 0;
        for (int k = 0; k < nmaps; k++) {
            const struct sl_cell_record *c = sl_report_study_cell(s, v, s->labels[l], s->maps[k]);
            int ok = c && sl_morais_counts(c, &mc[k]);
            if (!ok)
                mc[k].base[SL_MR_pfl] = UINT64_MAX;   /* no cell */
            has |= ok;
            traced |= ok && (mc[k].n[SL_MR_light_uncertain] || mc[k].n[SL_MR_shadow_uncertain]);
        }
        if (!has)
            continue;
        int first = 1;
        for (size_t q = 0; q < sizeof rows / sizeof rows[0]; q++) {
            if (!traced && (rows[q] == SL_MR_light_uncertain || rows[q] == SL_MR_shadow_uncertain))
                continue;
            sl_tab_row(&t, first);
            if (first)
                sl_tab_cell(&t, 0, "%s", sl_report_display(s, s->labels[l]));
            first = 0;
            sl_tab_cell(&t, 1, "%s", row_names[rows[q]]);
            for (int k = 0; k < nmaps; k++) {
                if (mc[k].base[SL_MR_pfl] == UINT64_MAX)
                    continue;
                fmt_count(buf, sizeof buf, mc[k].n[rows[q]], mc[k].base[rows[q]]);
                sl_tab_cell(&t, 2 + k, "%s", buf);
            }
        }
        any = 1;
    }
    sl_tab_notef(&t, "Pixels facing the light only (PnFL left out), as Morais counts them: light "
             "and shadow %% of PFL, correct/incorrect %% of the method's light or shadow, uncertain (traced) %% "
             "of the final light or shadow.");
    enum sl_err e = any ? sl_report_doc_table(doc, &t, d) : SL_OK;
    sl_tab_free(&t);
    return e;
}

/* rows viewport x map size, a column per Morais label; `stage` 0 map render, 1 ray step */
static enum sl_err other_times(struct sl_report_doc *doc, const struct sl_report_study *s, const char *scene,
                               const char *viewpoint, int stage, struct sl_diag *d)
{
    int cols[SL_REPORT_MAXCOLS], ncols = 0;
    for (int l = 0; l < s->nlabels && ncols < SL_REPORT_MAXCOLS - 2; l++)
        if (sl_report_is_morais(s, l))
            cols[ncols++] = l;
    if (ncols == 0)
        return SL_OK;
    char id[160];
    snprintf(id, sizeof id, "%s-%s-%s-%s", s->slug, stage ? "raystep" : "maprender", scene, viewpoint);
    struct sl_tab t;
    sl_tab_init(&t, id, 2 + ncols, 2, "%s / %s: %s, ms (as in Morais 2015 Tables 25-30)", scene, viewpoint,
                       stage ? "the ray-tracing step" : "shadow-map rendering of the layers the method reads");
    sl_tab_group(&t, 2, "%s", "");
    sl_tab_group(&t, ncols, "execution time (ms, median)");
    sl_tab_head(&t, 0, "viewport");
    sl_tab_head(&t, 1, "map");
    for (int k = 0; k < ncols; k++)
        sl_tab_head(&t, 2 + k, "%s", s->labels[cols[k]]);
    int runs = 0, once = 0;
    for (int v = 0; v < s->nviews; v++) {
        const struct sl_report_view *vw = &s->views[v];
        if (strcmp(vw->scene, scene) || strcmp(vw->viewpoint, viewpoint))
            continue;
        for (int m = 0; m < s->nmaps; m++) {
            sl_tab_row(&t, m == 0);
            if (m == 0)
                sl_tab_cell(&t, 0, "%d×%d", vw->vw, vw->vh);
            sl_tab_cell(&t, 1, "%d²", s->maps[m]);
            for (int k = 0; k < ncols; k++) {
                const struct sl_cell_record *c = sl_report_study_cell(s, vw, s->labels[cols[k]], s->maps[m]);
                char buf[32];
                sl_report_fmt_ms(buf, sizeof buf, c ? (stage ? c->ms_ray_step : c->ms_map_render) : 0.0);
                int one = c && c->runs == 1 && strcmp(buf, "–") != 0;
                sl_tab_cell(&t, 2 + k, "%s%s", buf, one ? SL_REPORT_ONCE : "");
                once |= one;
                if (c && c->runs > runs)
                    runs = c->runs;
            }
        }
    }
    sl_tab_notef(&t, "Medians over %d timed repetition(s) per cell on this machine (CPU: llvmpipe "
             "and Embree); – where the method has no such stage or no time was stored.", runs);
    if (once)
        sl_report_tab_once(&t);
    enum sl_err e = sl_report_doc_table(doc, &t, d);
    sl_tab_free(&t);
    return e;
}

enum sl_err sl_report_morais(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d)
{
    /* the thesis's numbers, read on first use: a missing or damaged file
     * stops the report here rather than print tables without them */
    const struct sl_morais_datum *rows;
    const struct sl_morais_time *times;
    int nrows, ntimes;
    enum sl_err e = sl_theses_morais(&rows, &nrows, d);
    if (!e)
        e = sl_theses_morais_times(&times, &ntimes, d);
    if (e)
        return e;
    int hertel = label_of(s, "hertel") >= 0 || label_of(s, "hertel_exact") >= 0, hertel_cases = 0;
    int ncases = 0;
    for (int k = 0; k < NCASES; k++) {
        const struct sl_report_view *v[8];
        ncases += case_views(s, k, v, 8) > 0;
    }
    if (ncases)
        sl_report_doc_para(doc, "Counted as Morais counts them: pixels facing the light (PFL) only, PnFL left "
                           "out. Under each of our rows (\"ours\") the thesis's printed row (\"thesis\") for "
                           "the same case, viewport and map size, where he prints one; * marks a printed value "
                           "that is a typo or a copy error of the thesis, explained under its table. His scenes "
                           "are rebuilt from his Tables 1-3 (camera and light), not his geometry: the shares "
                           "differ where the scenes do.");
    for (int k = 0; k < NCASES && !e; k++) {
        const struct sl_report_view *v[8];
        int nv = case_views(s, k, v, 8);
        if (nv == 0)
            continue;
        sl_report_doc_heading(doc, 4, NULL, "%s: %s, Morais 2015 Tables %d, %d, %d, %d, %d, %d, %d, %d and %d",
                              s->name, cases[k].name, cases[k].truth_table, 7 + k, 10 + k, 13 + k, 16 + k, 19 + k,
                              22 + k, cases[k].time_table, cases[k].time_table + 1);
        e = case_truth(doc, s, k, v, nv, d);
        for (int mi = 0; mi < NMMETHODS && !e; mi++)
            e = case_method(doc, s, k, mi, v, nv, d);
        for (int stage = 0; stage < 2 && !e; stage++)
            e = case_times(doc, s, k, stage, v, nv, d);
        if (!e && hertel) {
            e = case_hertel(doc, s, k, v, nv, d);
            hertel_cases++;
        }
    }
    if (!e && hertel_cases)
        e = hertel_thesis(doc, s, d);
    /* every other view: rows per view, times per (scene, viewpoint) in order of first appearance */
    int others = 0;
    for (int v = 0; v < s->nviews && !e; v++)
        if (case_of(s->views[v].scene, s->views[v].viewpoint) < 0) {
            if (!others++)
                sl_report_doc_heading(doc, 4, NULL, "%s: views outside Morais 2015's three cases", s->name);
            e = other_view(doc, s, &s->views[v], d);
        }
    for (int v = 0; v < s->nviews && !e; v++) {
        if (case_of(s->views[v].scene, s->views[v].viewpoint) >= 0)
            continue;
        int seen = 0;
        for (int u = 0; u < v && !seen; u++)
            seen = !strcmp(s->views[u].scene, s->views[v].scene) &&
                   !strcmp(s->views[u].viewpoint, s->views[v].viewpoint);
        if (seen)
            continue;
        e = other_times(doc, s, s->views[v].scene, s->views[v].viewpoint, 0, d);
        if (!e)
            e = other_times(doc, s, s->views[v].scene, s->views[v].viewpoint, 1, d);
    }
    return e;
}
