/* morais::* — Morais 2015's tables (report/morais.c) on his base, and his
 * transcribed numbers (report/theses/morais-2015.csv and
 * morais-2015-times.csv, as report/theses.c loads them):
 * - transcription: every printed percentage is its count's share of the
 *   row's base, and the counts add up as the thesis's own sums, except the
 *   values a note explains (the thesis's typos and copy errors); spot values
 *   read off seed 000;
 * - counts: a cell's stored figures (PnFL counted as shadow) taken back to
 *   Morais's base: light + shadow (+ undecided) = PFL, PnFL out, the traced
 *   pixels split by the truth add up to the traced count;
 * - section: a report of cells holding Table 8's and Table 23's counts
 *   prints our row as the thesis prints it, with the thesis's row under it,
 *   and Hertel's table when hertel ran. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "report_int.h"

/* The loaded rows (theses.h), which must load. */
static const struct sl_morais_datum *thesis(void)
{
    const struct sl_morais_datum *rows;
    int n;
    struct sl_diag d;
    enum sl_err e = sl_theses_morais(&rows, &n, &d);
    if (e)
        fail_msg("%s:%d: %s: %s", d.file, d.line, d.key, d.msg);
    return rows;
}

static const struct sl_morais_datum *find(int table, int vw, int map, enum sl_morais_row row)
{
    for (const struct sl_morais_datum *t = thesis(); t->scene; t++)
        if (t->table == table && t->vw == vw && t->map_size == map && t->row == row)
            return t;
    return NULL;
}

/* the row whose count is this row's base in the thesis (a sum of two rows, b1 + b2) */
static void base_rows(const struct sl_morais_datum *t, enum sl_morais_row *b1, enum sl_morais_row *b2, int *table)
{
    *table = t->table;
    switch (t->row) {
    case SL_MR_light: case SL_MR_shadow:           *b1 = SL_MR_light; *b2 = SL_MR_shadow; break;
    case SL_MR_light_correct: case SL_MR_light_incorrect:
    case SL_MR_light_uncertain:                     *b1 = SL_MR_light_correct; *b2 = SL_MR_light_incorrect; break;
    case SL_MR_shadow_correct: case SL_MR_shadow_incorrect:
    case SL_MR_shadow_uncertain:                    *b1 = SL_MR_shadow_correct; *b2 = SL_MR_shadow_incorrect; break;
    case SL_MR_pfl: case SL_MR_pnfl:                *b1 = SL_MR_pfl; *b2 = SL_MR_pnfl; break;
    default:                                        *b1 = SL_MR_truth_light; *b2 = SL_MR_truth_shadow; break;
    }
}

static void morais_transcription(void **st)
{
    (void)st;
    int n = 0, checked = 0, noted = 0;
    int per_table[31] = {0};
    for (const struct sl_morais_datum *t = thesis(); t->scene; t++, n++) {
        assert_true(t->table >= 4 && t->table <= 24);
        per_table[t->table]++;
        noted += t->note != NULL;
        enum sl_morais_row b1, b2;
        int table;
        base_rows(t, &b1, &b2, &table);
        const struct sl_morais_datum *x = find(table, t->vw, t->map_size, b1), *y = find(table, t->vw, t->map_size, b2);
        assert_non_null(x);
        assert_non_null(y);
        if (t->note || x->note || y->note)
            continue;
        double want = 100.0 * (double)t->n / (double)(x->n + y->n);
        if (fabs(t->pct - want) > 0.005 + 1e-9)
            fail_msg("Table %d, %dx%d, map %d, %s: printed %.2f%%, %llu is %.4f%%", t->table, t->vw, t->vh,
                     t->map_size, sl_morais_row_name(t->row), t->pct, (unsigned long long)t->n, want);
        checked++;
    }
    /* Tables 4-6: 4 rows x 3 viewports; 7-24: 6 rows x 3 viewports x 4 maps */
    for (int k = 4; k <= 6; k++)
        assert_int_equal(per_table[k], 12);
    for (int k = 7; k <= 24; k++)
        assert_int_equal(per_table[k], 72);
    assert_int_equal(n, 3 * 12 + 18 * 72);
    assert_true(checked > n - 2 * noted - 10);   /* a note skips its row and the rows it is the base of */
    /* the thesis's own sums: each table's light + shadow are the case's PFL (Tables 4-6) */
    for (const struct sl_morais_datum *t = thesis(); t->scene; t++) {
        if (t->table < 7 || t->table > 18 || t->row != SL_MR_light)
            continue;
        const struct sl_morais_datum *s = find(t->table, t->vw, t->map_size, SL_MR_shadow);
        const struct sl_morais_datum *pfl = find(4 + (t->table - 7) % 3, t->vw, 0, SL_MR_pfl);
        assert_non_null(s);
        assert_non_null(pfl);
        assert_int_equal(t->n + s->n, pfl->n);
        assert_int_equal(t->n, find(t->table, t->vw, t->map_size, SL_MR_light_correct)->n +
                                   find(t->table, t->vw, t->map_size, SL_MR_light_incorrect)->n);
    }
    for (int k = 4; k <= 6; k++)
        for (int v = 0; v < 3; v++) {
            static const int vw[3] = {512, 1024, 1920}, vh[3] = {512, 1024, 1080};
            const struct sl_morais_datum *pfl = find(k, vw[v], 0, SL_MR_pfl), *pnfl = find(k, vw[v], 0, SL_MR_pnfl);
            assert_int_equal(pfl->n + pnfl->n, (uint64_t)vw[v] * (uint64_t)vh[v]);
            assert_int_equal(find(k, vw[v], 0, SL_MR_truth_light)->n + find(k, vw[v], 0, SL_MR_truth_shadow)->n,
                             pfl->n);
        }
    /* spot values, read off seed 000 */
    assert_int_equal(find(8, 512, 512, SL_MR_light)->n, 131133);    /* + 115853 = 246986 = PFL */
    assert_int_equal(find(8, 512, 512, SL_MR_shadow)->n, 115853);
    assert_int_equal(find(5, 512, 0, SL_MR_pfl)->n, 246986);
    assert_int_equal(find(22, 1920, 4096, SL_MR_shadow_uncertain)->n, 12477);
    assert_int_equal(find(12, 1024, 2048, SL_MR_shadow_incorrect)->n, 12993);
    assert_int_equal(find(19, 512, 2048, SL_MR_light_correct)->n, 168949);   /* printed 1168949 */
    assert_non_null(find(19, 512, 2048, SL_MR_light_correct)->note);
    /* Tables 25-30: 3 viewports x 4 maps x 3 columns each */
    int times[31] = {0}, nt = 0, ntimes;
    const struct sl_morais_time *tt;
    struct sl_diag d;
    if (sl_theses_morais_times(&tt, &ntimes, &d))
        fail_msg("%s:%d: %s: %s", d.file, d.line, d.key, d.msg);
    for (const struct sl_morais_time *t = tt; t->scene; t++, nt++) {
        assert_true(t->table >= 25 && t->table <= 30);
        assert_int_equal(t->stage, (t->table - 25) % 2);
        assert_true(t->ms > 0.0);
        times[t->table]++;
    }
    for (int k = 25; k <= 30; k++)
        assert_int_equal(times[k], 36);
    assert_int_equal(nt, 216);
    assert_int_equal(ntimes, 216);
}

/* ---- cells ---- */

/* A whole-image cell of `scene/vp` at 512x512 whose figures hold Morais's
 * PFL counts (light, shadow and correct/incorrect of PFL) with pnfl PnFL
 * pixels added to shadow as figures.h counts them, and `traced` of them
 * decided by rays, traced_shadow shadowed in truth. */
static struct sl_cell_record cell(const char *scene, const char *vp, const char *method, int map, uint64_t pnfl,
                                  uint64_t lc, uint64_t li, uint64_t sc, uint64_t si, uint64_t traced,
                                  uint64_t traced_shadow)
{
    struct sl_cell_record c;
    memset(&c, 0, sizeof c);
    snprintf(c.study, sizeof c.study, "mor");
    snprintf(c.scene, sizeof c.scene, "%s", scene);
    snprintf(c.viewpoint, sizeof c.viewpoint, "%s", vp);
    snprintf(c.label, sizeof c.label, "%s", method);
    sl_test_cell_method(&c, method);
    snprintf(c.contour_from, sizeof c.contour_from, "nsm");
    c.vw = c.vh = 512;
    c.map_size = map;
    c.run_id = 1;
    uint64_t pfl = lc + li + sc + si;
    c.n_pfl = pfl;
    c.n_pnfl = pnfl;
    c.n_background = 262144 - pfl - pnfl;
    c.n_truth_lit = lc + si;
    c.n_truth_shadow = sc + li;
    c.fig.background = c.n_background;
    c.fig.nregions = 1;
    struct sl_region_figures *g = &c.fig.r[0];
    g->thickness = 0;
    g->n[SL_FIG_pixels] = pfl + pnfl;
    g->n[SL_FIG_pfl] = pfl;
    g->n[SL_FIG_pnfl] = pnfl;
    g->n[SL_FIG_light] = lc + li;
    g->n[SL_FIG_shadow] = sc + si + pnfl;
    g->n[SL_FIG_light_correct] = lc;
    g->n[SL_FIG_light_incorrect] = li;
    g->n[SL_FIG_shadow_correct] = sc + pnfl;
    g->n[SL_FIG_shadow_incorrect] = si;
    g->n[SL_FIG_wrong] = li + si;
    g->n[SL_FIG_wrong_caught] = li + si;
    g->n[SL_FIG_traced] = traced;
    g->n[SL_FIG_traced_shadow] = traced_shadow;
    c.fig.wrong_image = li + si;
    for (int k = 0; k < SL_FIG_COUNT; k++)
        g->pct[k] = NAN;
    c.runs = 3;
    c.ms_map_render = 2.5;
    c.ms_ray_step = traced ? 7.25 : 0.0;
    c.ms_method = 9.0;
    c.rays = traced;
    snprintf(c.git_sha, sizeof c.git_sha, "abc1234");
    snprintf(c.config_hash, sizeof c.config_hash, "0123456789abcdef");
    snprintf(c.machine, sizeof c.machine, "host/cpu/isa");
    return c;
}

static void morais_counts(void **st)
{
    (void)st;
    /* Table 8, 512x512, map 512 (Against-Flowers, NSM): 15158 PnFL */
    struct sl_cell_record c = cell("flowers", "against", "nsm", 512, 15158, 128612, 2521, 113575, 2278, 0, 0);
    struct sl_morais_counts m;
    assert_int_equal(sl_morais_counts(&c, &m), 1);
    assert_int_equal(m.n[SL_MR_light], 131133);
    assert_int_equal(m.n[SL_MR_shadow], 115853);            /* PnFL left out */
    assert_int_equal(m.n[SL_MR_light] + m.n[SL_MR_shadow], m.n[SL_MR_pfl]);
    assert_int_equal(m.base[SL_MR_light], 246986);           /* of PFL */
    assert_int_equal(m.base[SL_MR_shadow], 246986);
    assert_int_equal(m.n[SL_MR_shadow_correct], 113575);
    assert_int_equal(m.base[SL_MR_shadow_correct], 115853);   /* of the method's shadow */
    assert_int_equal(m.base[SL_MR_light_incorrect], 131133);
    assert_int_equal(m.n[SL_MR_pnfl], 15158);
    assert_int_equal(m.base[SL_MR_pnfl], 262144);
    assert_int_equal(m.n[SL_MR_truth_light], 130890);          /* Table 5 */
    /* a conservative cell: 1000 traced, 400 shadowed in truth; the split adds up to the traced count */
    c = cell("flowers", "against", "csm_adj", 512, 15158, 130890, 0, 116096, 0, 1000, 400);
    assert_int_equal(sl_morais_counts(&c, &m), 1);
    assert_int_equal(m.n[SL_MR_light_uncertain], 600);
    assert_int_equal(m.n[SL_MR_shadow_uncertain], 400);
    assert_int_equal(m.n[SL_MR_light_uncertain] + m.n[SL_MR_shadow_uncertain], c.fig.r[0].n[SL_FIG_traced]);
    assert_int_equal(m.base[SL_MR_light_uncertain], 130890);   /* the final light */
    assert_int_equal(m.base[SL_MR_shadow_uncertain], 116096);
    /* undecided pixels (not traced) stay out of light and shadow: light + shadow + undecided = PFL */
    c.fig.r[0].n[SL_FIG_uncertain] = 96;
    c.fig.r[0].n[SL_FIG_light] -= 96;
    c.fig.r[0].n[SL_FIG_light_correct] -= 96;
    assert_int_equal(sl_morais_counts(&c, &m), 1);
    assert_int_equal(m.n[SL_MR_light] + m.n[SL_MR_shadow] + c.fig.r[0].n[SL_FIG_uncertain], m.n[SL_MR_pfl]);
    /* no whole-image region: nothing */
    c.fig.r[0].thickness = 2;
    assert_int_equal(sl_morais_counts(&c, &m), 0);
}

static void morais_section(void **st)
{
    (void)st;
    struct sl_cell_record c[9];
    int n = 0;
    /* Table 8 (NSM) and Table 23 (CSMA), 512x512, maps 512 and 1024, from the thesis's counts */
    c[n++] = cell("flowers", "against", "nsm", 512, 15158, 128612, 2521, 113575, 2278, 0, 0);
    c[n++] = cell("flowers", "against", "nsm", 1024, 15158, 129437, 1947, 114149, 1453, 0, 0);
    c[n++] = cell("flowers", "against", "csm_adj", 512, 15158, 130890, 0, 116096, 0, 15491 + 19726, 19726);
    c[n++] = cell("flowers", "against", "csm_adj", 1024, 15158, 130889, 5, 116091, 1, 14668 + 13767, 13767);
    c[n++] = cell("flowers", "against", "hertel", 512, 15158, 130890, 0, 116096, 0, 5000, 2000);
    c[n] = cell("flowers", "against", "raytrace", 512, 15158, 130890, 0, 116096, 0, 246986, 116096);
    c[n++].ms_ray_step = 29.0;   /* hertel's 7.25 is 25% of it */
    /* a view that is none of his cases */
    c[n++] = cell("flowers", "side", "nsm", 512, 100, 1000, 10, 500, 20, 0, 0);
    c[n++] = cell("flowers", "side", "csm_adj", 512, 100, 1010, 0, 520, 0, 300, 100);
    struct sl_store_run run;
    memset(&run, 0, sizeof run);
    run.run_id = 1;
    snprintf(run.study, sizeof run.study, "mor");
    snprintf(run.config_hash, sizeof run.config_hash, "0123456789abcdef");
    run.ncells = n;
    struct sl_report_input in = {c, n, &run, 1, "test cells", sl_test_dir, NULL};
    char out[300];
    snprintf(out, sizeof out, "%s/out", sl_test_dir);
    sl_test_report(&in, out);
    char path[400];
    snprintf(path, sizeof path, "%s/tex/mor-table8-flowers-against.tex", out);
    char *tex = sl_test_slurp(path);
    assert_non_null(tex);
    free(tex);
    snprintf(path, sizeof path, "%s/report.md", out);
    char *md = sl_test_slurp(path);
    assert_non_null(md);
    /* the thesis's table cited with the page it prints it on (its List of Tables) */
    assert_non_null(strstr(md, "Against-Flowers (worst case): NSM (label nsm), Morais 2015 Table 8, p. 51"));
    /* ours on his base, then his row beside it: the same numbers */
    const char *ours = strstr(md, "| 512×512 | Pixels in Light | ours | 131133 (53.09%) | 131384 (53.19%) |");
    if (!ours) {
        const char *t8 = strstr(md, "Morais 2015 Table 8");
        fprintf(stderr, "%.1500s\n", t8 ? t8 : md);
    }
    assert_non_null(ours);
    assert_non_null(strstr(ours, "| thesis | 131133 (53.09%) | 131384 (53.19%) |"));
    assert_true(strstr(ours, "| thesis | 131133 (53.09%)") - ours < 200);   /* the next row */
    assert_non_null(strstr(md, "| Pixels in Shadow | ours | 115853 (46.91%) | 115602 (46.81%) |"));
    assert_non_null(strstr(md, "| Shadow – Incorrect | ours | 2278 (1.97%) | 1453 (1.26%) |"));
    /* Table 23: uncertain split by the truth, of the final light and shadow */
    assert_non_null(strstr(md, "| Light – Uncertain | ours | 15491 (11.84%) | 14668 (11.21%) |"));
    assert_non_null(strstr(md, "| thesis | 15491 (11.84%) | 14668 (11.21%) |"));
    assert_non_null(strstr(md, "| Shadow – Uncertain | ours | 19726 (16.99%) | 13767 (11.86%) |"));
    /* Table 5: the truth; Table 27/28: times beside the thesis's */
    assert_non_null(strstr(md, "| PFL | ours | 246986 (94.22%) |"));   /* background 0 here: of 262144 */
    assert_non_null(strstr(md, "| thesis | 246986 (94.21%)\\* |"));     /* his rounding, noted */
    assert_non_null(strstr(md, "(Morais 2015 Table 27, p. 89)"));
    assert_non_null(strstr(md, "the truth's pixels (Morais 2015 Table 5, p. 47)"));
    assert_non_null(strstr(md, "| 512×512 | 512² | 2.50 | 1.73 | – | 2.41 | 2.50 | 6.60 |"));
    /* Hertel: traced share of PFL, and his Table 2 */
    assert_non_null(strstr(md, "| 512×512 | 512² | 5000 (2.02%) | 0 (0.00%) | 0 | 7.25 | 25% |"));
    assert_non_null(strstr(md, "and takes 67-86% of its time"));   /* 641/956, 2670/3115 */
    assert_non_null(strstr(md, "Hertel 2009 Table 2: "));   /* no page: the paper prints none */
    assert_non_null(strstr(md, "Hertel's Table 2 traces 20.5-58.0% of the rays"));   /* 198576/967655, 32079/55294 */
    /* the other view: our rows, no thesis */
    assert_non_null(strstr(md, "flowers / side / 512×512: pixels per method and map size (as in Morais 2015 Tables 7-24; not one of his cases)"));
    free(md);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(morais, transcription),
        SL_CASE(morais, counts),
        SL_CASE(morais, section),
    };
    return sl_run_group(argc, argv, "morais", tests, sl_test_setup, sl_test_teardown);
}
