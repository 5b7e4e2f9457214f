/* table::* — the Markdown, CSV and LaTeX renderers on a known set of cells:
 * exact rows, grouping and order from cells given out of order, CSV quoting,
 * LaTeX escaping, refused duplicates; the pivot (pivot.h): aggregates,
 * where, number text, and LaTeX that is transposed or split to fit. */
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
#include "pivot.h"
#include "summary.h"
#include "table.h"

/* Regions 2 px and image; n = base + 10 r + k, pct = 10 r + k + 0.25, pixels
 * without a percentage. */
static struct sl_cell_record make(const char *vp, int map, uint64_t base, const char *machine)
{
    struct sl_cell_record c;
    memset(&c, 0, sizeof c);
    snprintf(c.scene, sizeof c.scene, "prim_s");
    snprintf(c.viewpoint, sizeof c.viewpoint, "%s", vp);
    snprintf(c.method, sizeof c.method, "nsm");
    snprintf(c.label, sizeof c.label, "nsm_a");
    c.vw = 64;
    c.vh = 32;
    c.map_size = map;
    c.n_pfl = 11;
    c.n_pnfl = 22;
    c.n_background = 33;
    c.n_truth_lit = 44;
    c.n_truth_shadow = 55;
    c.fig.nregions = 2;
    c.fig.background = base + 7777;
    c.fig.wrong_image = base + 99;
    c.fig.r[0].thickness = 2;
    c.fig.r[1].thickness = 0;
    for (int r = 0; r < 2; r++)
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            c.fig.r[r].n[k] = base + 10u * (uint64_t)r + (uint64_t)k;
            c.fig.r[r].pct[k] = k == SL_FIG_pixels ? NAN : 10.0 * r + k + 0.25;
        }
    snprintf(c.git_sha, sizeof c.git_sha, "abc1234");
    snprintf(c.contour_from, sizeof c.contour_from, "nsm");
    snprintf(c.config_hash, sizeof c.config_hash, "0123456789abcdef");
    snprintf(c.machine, sizeof c.machine, "%s", machine);
    return c;
}

/* A 2048 and a 1024 of "side", a 1024 of "with" between them. */
static int three_cells(struct sl_cell_record *c)
{
    c[0] = make("side", 2048, 2000, "h/c/i");
    c[1] = make("with", 1024, 500, "h,1/\"c\"/i");
    c[2] = make("side", 1024, 1000, "h/c/i");
    return 3;
}

/* noinline: GCC -O3 otherwise takes the returned heap buffer for the address
 * of the local that open_memstream filled (-Wdangling-pointer) */
static __attribute__((noinline)) char *render(enum sl_table_format fmt, const char *title,
                                              const struct sl_cell_record *c, int n, enum sl_err want)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    struct sl_diag d;
    assert_int_equal(sl_table_write(f, fmt, title, c, n, &d), want);
    fclose(f);
    return buf;
}

static int count_of(const char *s, const char *what)
{
    int n = 0;
    for (const char *p = strstr(s, what); p; p = strstr(p + 1, what))
        n++;
    return n;
}

static void assert_before(const char *s, const char *a, const char *b)
{
    const char *pa = strstr(s, a), *pb = strstr(s, b);
    assert_non_null(pa);
    assert_non_null(pb);
    assert_true(pa < pb);
}

static void table_markdown_rows(void **st)
{
    (void)st;
    struct sl_cell_record c[3];
    int n = three_cells(c);
    char *md = render(SL_TABLE_MD, "shadowlab: test", c, n, SL_OK);
    assert_true(strncmp(md, "# shadowlab: test\n\n", 19) == 0);
    assert_non_null(strstr(md, "## prim_s / side / 64x32 / nsm_a\n\n"
                               "PFL 11, PnFL 22, background 33; truth: 44 PFL lit, 55 PFL shadowed.\n\n"
                               "| figure | 1024² 2px | 1024² image | 2048² 2px | 2048² image |\n"
                               "|---|---:|---:|---:|---:|\n"
                               "| pixels | 1000 | 1010 | 2000 | 2010 |\n"
                               "| pfl | 1001 (1.25%) | 1011 (11.25%) | 2001 (1.25%) | 2011 (11.25%) |\n"));
    assert_non_null(strstr(md, "\n| light_correct | 1006 (6.25%) | 1016 (16.25%) | 2006 (6.25%) | 2016 (16.25%) |\n"));
    assert_non_null(strstr(md, "\n| wrong_caught | 1011 (11.25%) | 1021 (21.25%) | 2011 (11.25%) | 2021 (21.25%) |\n"));
    /* the last figure's row closes the table, the provenance follows */
    char last[512];
    const int K = SL_FIG_COUNT - 1;
    snprintf(last, sizeof last,
             "\n| %s | %d (%d.25%%) | %d (%d.25%%) | %d (%d.25%%) | %d (%d.25%%) |\n\n"
             "method `nsm`; contours from `nsm` (contour_from); git `abc1234`, config `0123456789abcdef`, "
             "machine `h/c/i`\n",
             sl_figure_name(K), 1000 + K, K, 1010 + K, 10 + K, 2000 + K, K, 2010 + K, 10 + K);
    assert_non_null(strstr(md, last));
    assert_non_null(strstr(md, "## prim_s / with / 64x32 / nsm_a\n\n"));
    assert_non_null(strstr(md, "| figure | 1024² 2px | 1024² image |\n"));
    /* two tables, "side" first (first appearance), each with every figure */
    assert_int_equal(count_of(md, "\n## "), 2);
    assert_before(md, "## prim_s / side", "## prim_s / with");
    assert_int_equal(count_of(md, "| shadow_incorrect |"), 2);
    free(md);
}

static void table_markdown_mixed_provenance(void **st)
{
    (void)st;
    struct sl_cell_record c[2] = {make("side", 1024, 1000, "h/c/i"), make("side", 2048, 2000, "h/c/i")};
    snprintf(c[1].git_sha, sizeof c[1].git_sha, "def5678");
    char *md = render(SL_TABLE_MD, NULL, c, 2, SL_OK);
    assert_true(strncmp(md, "Percentages:", 12) == 0);
    assert_non_null(strstr(md, "- 1024²: method `nsm`; contours from `nsm` (contour_from); git `abc1234`, config "
                               "`0123456789abcdef`, machine `h/c/i`\n"
                               "- 2048²: method `nsm`; contours from `nsm` (contour_from); git `def5678`,"));
    free(md);
}

static void table_csv_long_form(void **st)
{
    (void)st;
    struct sl_cell_record c[3];
    int n = three_cells(c);
    char *csv = render(SL_TABLE_CSV, "ignored", c, n, SL_OK);
    const char *header = "scene,viewpoint,viewport,map_size,method,label,region,figure,count,percent,percent_of,"
                         "git_sha,config_hash,machine\n";
    assert_true(strncmp(csv, header, strlen(header)) == 0);
    /* the first data line is side/1024 (its table first, map sizes ascending) */
    const char *first = "prim_s,side,64x32,1024,nsm,nsm_a,2px,pixels,1000,,,abc1234,0123456789abcdef,h/c/i\n";
    assert_true(strncmp(csv + strlen(header), first, strlen(first)) == 0);
    assert_non_null(strstr(csv, "\nprim_s,side,64x32,1024,nsm,nsm_a,2px,light_correct,1006,6.2500,light,"
                                "abc1234,0123456789abcdef,h/c/i\n"));
    assert_non_null(strstr(csv, "\nprim_s,side,64x32,2048,nsm,nsm_a,image,wrong_caught,2021,21.2500,wrong_image,"
                                "abc1234,0123456789abcdef,h/c/i\n"));
    assert_non_null(strstr(csv, "\nprim_s,side,64x32,2048,nsm,nsm_a,image,background,9777,,,"
                                "abc1234,0123456789abcdef,h/c/i\n"));
    /* a machine with a comma and quotes is quoted, quotes doubled */
    assert_non_null(strstr(csv, "\nprim_s,with,64x32,1024,nsm,nsm_a,image,background,8277,,,"
                                "abc1234,0123456789abcdef,\"h,1/\"\"c\"\"/i\"\n"));
    assert_before(csv, "prim_s,side,64x32,1024,", "prim_s,side,64x32,2048,");
    assert_before(csv, "prim_s,side,64x32,2048,", "prim_s,with,64x32,1024,");
    /* header + per cell 2 regions x figures + background */
    assert_int_equal(count_of(csv, "\n"), 1 + 3 * (2 * SL_FIG_COUNT + 1));
    free(csv);
}

static void table_latex_booktabs(void **st)
{
    (void)st;
    struct sl_cell_record c[3];
    int n = three_cells(c);
    snprintf(c[0].machine, sizeof c[0].machine, "a&b#c$d{e}f%%g_h~^\\");
    snprintf(c[2].machine, sizeof c[2].machine, "a&b#c$d{e}f%%g_h~^\\");
    char *tex = render(SL_TABLE_LATEX, "Primitives 50%", c, n, SL_OK);
    /* no heading: the file is \input into a document; the source is a comment */
    assert_null(strstr(tex, "\\section"));
    assert_non_null(strstr(tex, "\n% from: Primitives 50%\n"));
    /* one float per map size, never scaled: two regions fit the line as they are */
    assert_non_null(strstr(tex, "\\caption{prim\\_s / side / 64$\\times$32 / nsm\\_a / $1024^2$ map. PFL 11, "
                                "PnFL 22, background 33; truth: 44 PFL lit, 55 PFL shadowed.}\n"
                                "\\label{tab:prim-s-side-64x32-nsm-a-1024}\n"
                                "\\begin{tabular}{lrr}\n\\toprule\n"
                                "figure & 2px & image \\\\\n\\midrule\n"
                                "pixels & 1000 & 1010 \\\\\n"));
    assert_non_null(strstr(tex, "\\label{tab:prim-s-side-64x32-nsm-a-2048}\n"));
    assert_non_null(strstr(tex, "\nlight\\_correct & 1006 (6.25\\%) & 1016 (16.25\\%) \\\\\n"));
    assert_non_null(strstr(tex, "\nlight\\_correct & 2006 (6.25\\%) & 2016 (16.25\\%) \\\\\n"));
    assert_non_null(strstr(tex, "\nwrong\\_caught & 1011 (11.25\\%) & 1021 (21.25\\%) \\\\\n"));
    {
        char name[64], last[512];
        const int K = SL_FIG_COUNT - 1;
        size_t o = 0;
        for (const char *q = sl_figure_name(K); *q && o + 2 < sizeof name; q++) {
            if (*q == '_')
                name[o++] = '\\';
            name[o++] = *q;
        }
        name[o] = '\0';
        snprintf(last, sizeof last, "\n%s & %d (%d.25\\%%) & %d (%d.25\\%%) \\\\\n\\bottomrule\n\\end{tabular}\n",
                 name, 2000 + K, K, 2010 + K, 10 + K);
        assert_non_null(strstr(tex, last));
    }
    assert_non_null(strstr(tex, "{\\scriptsize\\raggedright method \\texttt{nsm}; contours from \\texttt{nsm} "
                                "(contour\\_from); git \\texttt{abc1234}, config "
                                "\\texttt{0123456789abcdef}, machine "
                                "a\\&b\\#c\\$d\\{e\\}f\\%g\\_h\\textasciitilde{}\\textasciicircum{}"
                                "\\textbackslash{}\\par}\n\\end{table*}\n"));
    assert_int_equal(count_of(tex, "\\begin{table*}"), 3);
    assert_int_equal(count_of(tex, "\\end{table*}"), 3);
    assert_int_equal(count_of(tex, "\\toprule"), 3);
    assert_int_equal(count_of(tex, "\\bottomrule"), 3);
    assert_before(tex, "{prim\\_s / side /", "{prim\\_s / with /");
    /* no unescaped percent sign in a table row: every % is \% */
    assert_null(strstr(tex, "25%"));
    free(tex);
}

/* Rows a method does not produce (0 everywhere, past wrong_caught) are left
 * out of LaTeX and of sl_table_write_rows with `produced`; a zero core figure
 * stays; --figures picks rows; Markdown by default keeps everything. */
static void table_rows_produced_and_picked(void **st)
{
    (void)st;
    struct sl_cell_record c[2] = {make("side", 1024, 1000, "m"), make("side", 2048, 2000, "m")};
    for (int i = 0; i < 2; i++)
        for (int r = 0; r < 2; r++) {
            c[i].fig.r[r].n[SL_FIG_hinted] = 0;           /* never produced */
            c[i].fig.r[r].n[SL_FIG_wrong] = 0;            /* a core figure: a result */
            c[i].fig.r[r].n[SL_FIG_confirmed] = i == 1;   /* produced in one column only */
        }
    char *md = render(SL_TABLE_MD, NULL, c, 2, SL_OK);
    assert_non_null(strstr(md, "| hinted |"));
    assert_null(strstr(md, "figures shown"));
    free(md);
    char *tex = render(SL_TABLE_LATEX, NULL, c, 2, SL_OK);
    assert_null(strstr(tex, "\nhinted &"));
    assert_non_null(strstr(tex, "\nwrong & 0 ("));
    assert_non_null(strstr(tex, "\nconfirmed & 0 ("));          /* 0 here, 1 in the 2048 column */
    assert_non_null(strstr(tex, "\nconfirmed & 1 ("));
    char note[128];
    snprintf(note, sizeof note, "%d of %d figures shown", SL_FIG_COUNT - 1, SL_FIG_COUNT);
    assert_non_null(strstr(tex, note));
    free(tex);
    /* the terminal's Markdown */
    struct sl_table_rows rows = {.produced = 1};
    char *buf = NULL;
    size_t len = 0;
    struct sl_diag d;
    FILE *f = open_memstream(&buf, &len);
    assert_int_equal(sl_table_write_rows(f, SL_TABLE_MD, NULL, c, 2, &rows, &d), SL_OK);
    fclose(f);
    assert_null(strstr(buf, "| hinted |"));
    assert_non_null(strstr(buf, "| wrong | 0 ("));
    assert_non_null(strstr(buf, "--figures all"));
    free(buf);
    /* --figures */
    assert_int_equal(sl_table_figures_parse("wrong,light_incorrect,soft_mae", &rows, &d), SL_OK);
    assert_true(rows.picked && rows.pick_hard[SL_FIG_wrong] && rows.pick_hard[SL_FIG_light_incorrect]);
    assert_true(rows.pick_soft[SL_SFIG_soft_mae] && !rows.pick_hard[SL_FIG_pixels]);
    f = open_memstream(&buf, &len);
    assert_int_equal(sl_table_write_rows(f, SL_TABLE_LATEX, NULL, c, 2, &rows, &d), SL_OK);
    fclose(f);
    assert_int_equal(count_of(buf, " \\\\\n"), 2 * (1 + 2));   /* head + 2 rows */
    assert_non_null(strstr(buf, "\nlight\\_incorrect & "));
    assert_before(buf, "\nlight\\_incorrect & ", "\nwrong & ");   /* figures.h's order, not the list's */
    free(buf);
    assert_int_equal(sl_table_figures_parse("all", &rows, &d), SL_OK);
    assert_false(rows.picked || rows.produced);
    assert_int_equal(sl_table_figures_parse("wrong,bogus", &rows, &d), SL_E_USAGE);
    assert_string_equal(d.key, "--figures");
    assert_non_null(strstr(d.msg, "'bogus'"));
}

static void table_duplicate_map_refused(void **st)
{
    (void)st;
    struct sl_cell_record c[2] = {make("side", 1024, 1000, "m"), make("side", 1024, 2000, "m")};
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    struct sl_diag d;
    assert_int_equal(sl_table_write(f, SL_TABLE_MD, NULL, c, 2, &d), SL_E_USAGE);
    assert_string_equal(d.key, "prim_s/side/64x32/nsm_a");
    assert_non_null(strstr(d.msg, "map size 1024"));
    fclose(f);
    free(buf);
    /* a different label is a different table, not a duplicate */
    snprintf(c[1].label, sizeof c[1].label, "nsm_b");
    char *md = render(SL_TABLE_MD, NULL, c, 2, SL_OK);
    assert_int_equal(count_of(md, "## prim_s / side / 64x32 / "), 2);
    free(md);
}

static void table_empty_and_formats(void **st)
{
    (void)st;
    char *md = render(SL_TABLE_MD, "empty", NULL, 0, SL_OK);
    assert_true(strncmp(md, "# empty\n\n", 9) == 0);
    assert_null(strstr(md, "## "));
    free(md);
    assert_int_equal(sl_table_format_parse("md"), SL_TABLE_MD);
    assert_int_equal(sl_table_format_parse("csv"), SL_TABLE_CSV);
    assert_int_equal(sl_table_format_parse("latex"), SL_TABLE_LATEX);
    assert_int_equal(sl_table_format_parse("tex"), -1);
    assert_int_equal(sl_table_format_parse(NULL), -1);
    char *bad = render((enum sl_table_format)7, NULL, NULL, 0, SL_E_USAGE);
    free(bad);
}

/* Summary rows: the average over every (cell, contour), and per map the
 * cells with the highest and lowest percentage, and the named average case. */
static void table_summary_rows(void **st)
{
    (void)st;
    struct sl_cell_record c[4];
    memset(c, 0, sizeof c);
    const char *vps[4] = {"side", "with", "side", "with"};
    const int maps[4] = {1024, 1024, 2048, 2048};
    const double v[4][2] = {{90, 95}, {60, 80}, {99, 100}, {70, 85}};   /* 2px, 4px */
    for (int i = 0; i < 4; i++) {
        snprintf(c[i].scene, sizeof c[i].scene, "%s", i % 2 ? "bench" : "prim");
        snprintf(c[i].viewpoint, sizeof c[i].viewpoint, "%s", vps[i]);
        snprintf(c[i].label, sizeof c[i].label, "nsm");
        c[i].map_size = maps[i];
        c[i].fig.nregions = 3;
        c[i].fig.r[0].thickness = 2;
        c[i].fig.r[1].thickness = 4;
        c[i].fig.r[2].thickness = 0;
        for (int r = 0; r < 3; r++)
            for (int k = 0; k < SL_FIG_COUNT; k++)
                c[i].fig.r[r].pct[k] = NAN;
        c[i].fig.r[0].pct[SL_FIG_wrong_caught] = v[i][0];
        c[i].fig.r[1].pct[SL_FIG_wrong_caught] = v[i][1];
        c[i].fig.r[2].pct[SL_FIG_wrong_caught] = 100.0;     /* the whole image: not a contour */
    }
    struct sl_summary_opts o = {.figure = SL_FIG_wrong_caught, .region = -1, .avg_scene = "bench",
                                .avg_viewpoint = "with", .avg_region = 2, .avg_map = 2048};
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    struct sl_diag d;
    assert_int_equal(sl_summary_write(f, SL_TABLE_CSV, c, 4, &o, &d), SL_OK);
    fclose(f);
    assert_non_null(strstr(buf, "wrong_caught,nsm,average,,,,,84.8750\n"));     /* (90+95+60+80+99+100+70+85)/8 */
    assert_non_null(strstr(buf, "wrong_caught,nsm,best,1024,prim,side,4px,95.0000\n"));
    assert_non_null(strstr(buf, "wrong_caught,nsm,worst,1024,bench,with,2px,60.0000\n"));
    assert_non_null(strstr(buf, "wrong_caught,nsm,best,2048,prim,side,4px,100.0000\n"));
    assert_non_null(strstr(buf, "wrong_caught,nsm,worst,2048,bench,with,2px,70.0000\n"));
    assert_non_null(strstr(buf, "wrong_caught,nsm,average case,2048,bench,with,2px,70.0000\n"));
    free(buf);
    /* lower is better swaps best and worst */
    o.lower_is_better = 1;
    f = open_memstream(&buf, &len);
    assert_int_equal(sl_summary_write(f, SL_TABLE_CSV, c, 4, &o, &d), SL_OK);
    fclose(f);
    assert_non_null(strstr(buf, "wrong_caught,nsm,best,1024,bench,with,2px,60.0000\n"));
    free(buf);
    /* several labels: a summary each, in the cells' order, one CSV header */
    snprintf(c[3].label, sizeof c[3].label, "other_x");
    o.lower_is_better = 0;
    f = open_memstream(&buf, &len);
    assert_int_equal(sl_summary_write(f, SL_TABLE_CSV, c, 4, &o, &d), SL_OK);
    fclose(f);
    assert_int_equal(count_of(buf, "figure,label,kind,"), 1);
    assert_non_null(strstr(buf, "wrong_caught,nsm,average,,,,,87.3333\n"));   /* (90+95+60+80+99+100)/6 */
    assert_non_null(strstr(buf, "wrong_caught,other_x,average,,,,,77.5000\n"));
    assert_non_null(strstr(buf, "wrong_caught,other_x,average case,2048,bench,with,2px,70.0000\n"));
    assert_before(buf, "wrong_caught,nsm,average", "wrong_caught,other_x,average");
    free(buf);
    /* a later figure of the same output has no header */
    o.continued = 1;
    f = open_memstream(&buf, &len);
    assert_int_equal(sl_summary_write(f, SL_TABLE_CSV, c, 4, &o, &d), SL_OK);
    fclose(f);
    assert_null(strstr(buf, "figure,label,kind,"));
    free(buf);
    o.continued = 0;
    /* LaTeX: a booktabs float per label, names escaped, numbers as LaTeX, never scaled */
    f = open_memstream(&buf, &len);
    assert_int_equal(sl_summary_write(f, SL_TABLE_LATEX, c, 4, &o, &d), SL_OK);
    fclose(f);
    assert_int_equal(count_of(buf, "\\begin{table*}"), 2);
    assert_int_equal(count_of(buf, "\\toprule"), 2);
    assert_non_null(strstr(buf, "\\caption{Summary of wrong\\_caught (\\% of wrong\\_image), label other\\_x: "));
    assert_non_null(strstr(buf, "\naverage &  &  &  &  & 87.33 \\\\\n"));
    assert_non_null(strstr(buf, "\n$1024^2$ best & prim & side & 4px & $1024^2$ & 95.00 \\\\\n"));
    assert_non_null(strstr(buf, "\naverage case & bench & with & 2px & $2048^2$ & 70.00 \\\\\n"));
    assert_null(strstr(buf, "resizebox"));
    assert_null(strstr(buf, "scalebox"));
    free(buf);
    /* a count is no percentage */
    o.figure = SL_FIG_pixels;
    f = open_memstream(&buf, &len);
    assert_int_equal(sl_summary_write(f, SL_TABLE_CSV, c, 3, &o, &d), SL_E_USAGE);
    fclose(f);
    free(buf);
}

/* A hard method's cell under an area light has soft and hard figures: its
 * soft table comes first, then its hard one against the light's centre; the
 * CSV has both sets of rows and one background row; LaTeX labels differ. */
static void table_soft_and_hard(void **st)
{
    (void)st;
    struct sl_cell_record c[2] = {make("side", 1024, 1000, "h/c/i"), make("side", 512, 100, "h/c/i")};
    for (int i = 0; i < 2; i++) {
        c[i].has_soft = 1;
        for (int k = 0; k < SL_SFIG_COUNT; k++) {
            c[i].soft.n[k] = 300u + (uint64_t)k;
            c[i].soft.pct[k] = 1.5 + k;
        }
    }
    char *md = render(SL_TABLE_MD, NULL, c, 2, SL_OK);
    assert_int_equal(count_of(md, "## prim_s / side / 64x32 / nsm_a"), 2);
    assert_before(md, "Area light: the visible fraction", "truth of the area light's centre: 44 PFL lit");
    assert_int_equal(count_of(md, "| soft_mae |"), 1);
    assert_int_equal(count_of(md, "| wrong |"), 1);
    free(md);
    char *csv = render(SL_TABLE_CSV, NULL, c, 2, SL_OK);
    assert_int_equal(count_of(csv, ",image,background,"), 2);             /* one per cell */
    assert_int_equal(count_of(csv, ",image,soft_mae,"), 2);
    assert_int_equal(count_of(csv, ",image,wrong,"), 2);
    assert_int_equal(count_of(csv, ",2px,wrong,"), 2);
    free(csv);
    char *tex = render(SL_TABLE_LATEX, NULL, c, 2, SL_OK);
    assert_int_equal(count_of(tex, "\\label{tab:prim-s-side-64x32-nsm-a-1024}"), 1);
    assert_int_equal(count_of(tex, "\\label{tab:prim-s-side-64x32-nsm-a-1024-point}"), 1);
    free(tex);
}

/* A spot light's cell: the light in the heading of every format, the
 * pixels outside its cone named apart from the facing-away PnFL ones (a
 * part of n_pnfl), a row of their own in CSV; a directional cell with no
 * such pixels keeps the plain wording. */
static void table_spot_light(void **st)
{
    (void)st;
    struct sl_cell_record c[2];
    c[0] = make("side", 1024, 100, "h/c/i");
    snprintf(c[0].light, sizeof c[0].light, "spot light, 70\xC2\xB0");
    c[0].n_outside_cone = 16;   /* of n_pnfl 22; the image: 11 + 22 + 33 px */
    c[1] = make("with", 1024, 100, "h/c/i");
    snprintf(c[1].light, sizeof c[1].light, "directional light");
    char *md = render(SL_TABLE_MD, "t", c, 2, SL_OK);
    assert_non_null(strstr(md, "## prim_s (spot light, 70\xC2\xB0) / side / 64x32 / nsm_a\n"));
    assert_non_null(strstr(md, "PFL 11, PnFL 6 facing away, outside the spot's cone 16 (24.24% of the image; "));
    assert_non_null(strstr(md, "## prim_s (directional light) / with / 64x32 / nsm_a\n"));
    assert_non_null(strstr(md, "PFL 11, PnFL 22, background 33;"));
    assert_int_equal(count_of(md, "outside the spot's cone"), 1);
    free(md);
    char *tex = render(SL_TABLE_LATEX, "t", c, 2, SL_OK);
    assert_non_null(strstr(tex, "\\caption{prim\\_s (spot light, 70$^\\circ$) / side"));
    assert_non_null(strstr(tex, "outside the spot's cone 16 (24.24\\% of the image"));
    free(tex);
    char *csv = render(SL_TABLE_CSV, "t", c, 2, SL_OK);
    assert_non_null(strstr(csv, "prim_s,side,64x32,1024,nsm,nsm_a,image,outside_cone,16,,"));
    assert_int_equal(count_of(csv, "outside_cone"), 1);
    free(csv);
}

static __attribute__((noinline)) char *pivot(enum sl_table_format fmt, const struct sl_cell_record *c, int n,
                                             const struct sl_pivot_desc *p, struct sl_pivot_info *info,
                                             enum sl_err want)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    struct sl_diag d;
    assert_int_equal(sl_pivot_write(f, fmt, c, n, p, info, &d), want);
    fclose(f);
    return buf;
}

/* A package's cells under a hard light (frac): the soft table names the
 * light its truth was computed for and the class tolerance, never "area
 * light"; the hard twin's truth is the light's own, not an area light's
 * centre; a cell with values not finite carries the NON-FINITE note in
 * LaTeX as in Markdown, and so do the pivot (md, LaTeX) and the run's
 * detail longtable names the light. */
static void table_hard_light_fractional(void **st)
{
    (void)st;
    struct sl_cell_record c[2] = {make("side", 1024, 1000, "h/c/i"), make("side", 512, 100, "h/c/i")};
    for (int i = 0; i < 2; i++) {
        c[i].has_soft = 1;
        c[i].frac = 1;
        snprintf(c[i].light, sizeof c[i].light, "directional light");
        snprintf(c[i].study, sizeof c[i].study, "prim_study");
        for (int k = 0; k < SL_SFIG_COUNT; k++) {
            c[i].soft.n[k] = 300u + (uint64_t)k;
            c[i].soft.pct[k] = 1.5 + k;
        }
    }
    c[0].nonfinite = 7;
    char *md = render(SL_TABLE_MD, NULL, c, 2, SL_OK);
    assert_null(strstr(md, "rea light"));
    assert_non_null(strstr(md, "Directional light: the visibility against the light's 0/1 truth over the PFL pixels"));
    assert_non_null(strstr(md, "within \xCE\xB5 = 0.05 of 1"));
    assert_non_null(strstr(md, "|v \xE2\x88\x92 truth| \xE2\x89\xA4 0.05"));
    assert_non_null(strstr(md, "; truth: 44 PFL lit"));
    assert_int_equal(count_of(md, "NON-FINITE: 1024\xC2\xB2: 7 value(s)"), 2);   /* soft and hard table */
    free(md);
    char *tex = render(SL_TABLE_LATEX, NULL, c, 2, SL_OK);
    assert_null(strstr(tex, "rea light"));
    assert_non_null(strstr(tex, "Directional light: the visibility against the light's 0/\\allowbreak{}1 truth"));
    assert_non_null(strstr(tex, "0.05 of 1"));
    /* the soft and the hard float of the 1024, not the 512 */
    assert_int_equal(count_of(tex, "NON-FINITE: 7 value(s) not finite (NaN, $\\pm$inf)"), 2);
    free(tex);
    struct sl_pivot_desc p = {.figure = "leaking"};
    md = pivot(SL_TABLE_MD, c, 2, &p, NULL, SL_OK);
    assert_non_null(strstr(md, "NON-FINITE: 1 cell(s) of the table hold 7 value(s) not finite"));
    free(md);
    tex = pivot(SL_TABLE_LATEX, c, 2, &p, NULL, SL_OK);
    assert_non_null(strstr(tex, "NON-FINITE: 1 cell(s) of the table hold 7 value(s) not finite"));
    /* a class figure's pivot states the tolerance; leaking's has none to state */
    assert_null(strstr(tex, "\xCE\xB5"));
    free(tex);
    struct sl_pivot_desc cls = {.figure = "soft_class_right"};
    md = pivot(SL_TABLE_MD, c, 2, &cls, NULL, SL_OK);
    assert_non_null(strstr(md, "; against the truth of the directional light; under a hard light lit within "
                               "\xCE\xB5 = 0.05 of 1 and umbra within \xCE\xB5 of 0"));
    free(md);
    /* two lights, each named once */
    snprintf(c[1].light, sizeof c[1].light, "spot light, 70\xC2\xB0");
    struct sl_cell_record three[3] = {c[0], c[1], c[0]};
    three[2].map_size = 2048;
    md = pivot(SL_TABLE_MD, three, 3, &cls, NULL, SL_OK);
    assert_non_null(strstr(md, "; against the truth of the directional light and spot light, 70\xC2\xB0;"));
    free(md);
    snprintf(c[1].light, sizeof c[1].light, "directional light");
    c[0].nonfinite = 0;
    tex = pivot(SL_TABLE_LATEX, c, 2, &p, NULL, SL_OK);
    assert_null(strstr(tex, "NON-FINITE"));
    free(tex);
    char *det = render(SL_TABLE_LATEX_DETAIL, "shadowlab: prim", c, 2, SL_OK);
    assert_null(strstr(det, "rea light"));
    assert_non_null(strstr(det, "viewport 64$\\times$32, directional light, per method and shadow-map size: the "
                                "visibility against its 0/\\allowbreak{}1 truth"));
    free(det);
}

/* wrong (figure 10) is 10.25 % in the 2 px region and 20.25 % in the image of
 * every cell; its count base + 10 r + 10 */
static void table_pivot_values(void **st)
{
    (void)st;
    struct sl_cell_record c[3];
    int n = three_cells(c);
    struct sl_pivot_desc p = {0};
    char *csv = pivot(SL_TABLE_CSV, c, n, &p, NULL, SL_OK);
    assert_string_equal(csv, "label,1024,2048\nnsm_a,20.25,20.25\n");
    free(csv);
    p.of = "count";
    p.agg = SL_AGG_SUM;
    csv = pivot(SL_TABLE_CSV, c, n, &p, NULL, SL_OK);
    assert_string_equal(csv, "label,1024,2048\nnsm_a,1540,2020\n");   /* (500+20) + (1000+20); 2000+20 */
    free(csv);
    p.agg = SL_AGG_MEDIAN;
    p.rows = SL_PK_viewpoint;
    p.cols = SL_PK_region;
    csv = pivot(SL_TABLE_CSV, c, n, &p, NULL, SL_OK);
    assert_string_equal(csv, "viewpoint,2px,image\nside,1510,1520\nwith,510,520\n");
    free(csv);
    /* a base of another figure: wrong of pfl (figure 1) */
    struct sl_pivot_desc q = {.of = "pfl", .agg = SL_AGG_MAX};
    assert_int_equal(sl_pivot_where_parse(&q, "viewpoint=with", NULL), SL_OK);
    csv = pivot(SL_TABLE_CSV, c, n, &q, NULL, SL_OK);
    assert_string_equal(csv, "label,1024\nnsm_a,101.7612524\n");   /* 520 / 511 */
    free(csv);
    /* a time: an entry with a cell timed once (runs 1) carries a dagger, its
     * table a footnote; md and LaTeX (CSV keeps plain numbers) */
    for (int i = 0; i < n; i++) {
        c[i].runs = 3, c[i].ms_method = 1.5 + i;
        snprintf(c[i].gl_renderer, sizeof c[i].gl_renderer, "llvmpipe (LLVM 15.0.6, 256 bits)");
    }
    struct sl_pivot_desc tm = {.figure = "ms_method"};
    char *md = pivot(SL_TABLE_MD, c, n, &tm, NULL, SL_OK);
    assert_null(strstr(md, "\xE2\x80\xA0"));
    /* a time names its renderer, and on llvmpipe says what its GL times are */
    assert_non_null(strstr(md, "llvmpipe (LLVM 15.0.6, 256 bits)"));
    assert_non_null(strstr(md, "CPU-emulated GL times"));
    free(md);
    /* another renderer: named, no such words; two: said so */
    snprintf(c[0].gl_renderer, sizeof c[0].gl_renderer, "NVIDIA H200/PCIe/SSE2");
    md = pivot(SL_TABLE_MD, c, n, &tm, NULL, SL_OK);
    assert_non_null(strstr(md, "several GL renderers"));
    free(md);
    for (int i = 0; i < n; i++)
        snprintf(c[i].gl_renderer, sizeof c[i].gl_renderer, "NVIDIA H200/PCIe/SSE2");
    md = pivot(SL_TABLE_MD, c, n, &tm, NULL, SL_OK);
    assert_non_null(strstr(md, "NVIDIA H200/PCIe/SSE2"));
    assert_null(strstr(md, "CPU-emulated"));
    free(md);
    c[1].runs = 1;   /* the 1024 of "with" */
    md = pivot(SL_TABLE_MD, c, n, &tm, NULL, SL_OK);
    assert_non_null(strstr(md, "timed once"));
    assert_non_null(strstr(md, "| nsm_a | 3.00\xE2\x80\xA0 | 1.50 |"));   /* 1024: mean of 2.5 (once) and 3.5 */
    free(md);
    char *tex = pivot(SL_TABLE_LATEX, c, n, &tm, NULL, SL_OK);
    assert_non_null(strstr(tex, "nsm\\_a & 3.00$^\\dagger$ & 1.50 \\\\"));
    assert_non_null(strstr(tex, "$^\\dagger$ timed once"));
    free(tex);
    csv = pivot(SL_TABLE_CSV, c, n, &tm, NULL, SL_OK);
    assert_string_equal(csv, "label,1024,2048\nnsm_a,3,1.5\n");
    free(csv);
    char *js = pivot(SL_TABLE_JSON, c, n, &tm, NULL, SL_OK);
    assert_non_null(strstr(js, "\"n\": [2, 1], \"timed_once\": [true, false]}"));
    free(js);
    c[1].runs = 3;
    /* refused: an unknown figure, rows = cols, a time of a base */
    struct sl_pivot_desc bad = {.figure = "nope"};
    free(pivot(SL_TABLE_CSV, c, n, &bad, NULL, SL_E_USAGE));
    bad = (struct sl_pivot_desc){.rows = SL_PK_scene, .cols = SL_PK_scene};
    free(pivot(SL_TABLE_CSV, c, n, &bad, NULL, SL_E_USAGE));
    bad = (struct sl_pivot_desc){.figure = "ms_method", .of = "pixels"};
    free(pivot(SL_TABLE_CSV, c, n, &bad, NULL, SL_E_USAGE));
    struct sl_diag d;
    assert_int_equal(sl_pivot_where_parse(&bad, "colour=red", &d), SL_E_USAGE);
    assert_int_equal(sl_pivot_where_parse(&bad, "label", &d), SL_E_USAGE);
    char num[64];
    sl_tex_number(num, sizeof num, 1234567.891, 2);
    assert_string_equal(num, "1\\,234\\,567.89");
    sl_tex_number(num, sizeof num, -1234, 0);
    assert_string_equal(num, "$-$1\\,234");
    sl_tex_number(num, sizeof num, -0.001, 2);
    assert_string_equal(num, "0.00");
    sl_tex_number(num, sizeof num, 999, 0);
    assert_string_equal(num, "999");
    sl_tex_number(num, sizeof num, NAN, 0);
    assert_string_equal(num, "--");
}

/* LaTeX text for every code point that can occur (emit_tex.c): the report's
 * |v − t| (U+2212, printed '?' before), accented letters by their
 * decomposition, Greek, letters LaTeX names, anything else as a visible
 * [U+XXXX], invalid UTF-8 as [U+FFFD]; never '?'. Where pdflatex is
 * installed the text compiles in the report's preamble (T1, utf8). */
static void table_latex_unicode(void **st)
{
    (void)st;
    static const struct { const char *in, *tex; } want[] = {
        {"|v \xE2\x88\x92 t|", "|v $-$ t|"},
        {"caf\xC3\xA9 na\xC3\xAFve", "caf\\'{e} na\\\"{\\i}ve"},
        {"\xC3\x86r\xC3\xB8 Stra\xC3\x9F" "e", "\\AE{}r\\o{} Stra\\ss{}e"},
        {"\xC5\x81\xC3\xB3" "d\xC5\xBA \xC4\x85", "\\L{}\\'{o}d\\'{z} \\k{a}"},
        {"\xC7\x98", "\\'{\\\"{u}}"},                       /* ǘ: two marks, the last outermost */
        {"\xCE\xB1\xCE\xB2 \xCE\xA9 \xCE\x91", "$\\alpha$$\\beta$ $\\Omega$ A"},
        {"2048\xC2\xB2 \xC3\x97 \xE2\x89\xA4 \xE2\x88\x9E", "2048\\textsuperscript{2} $\\times$ $\\le$ $\\infty$"},
        {"\xE6\x97\xA5 \xE2\x98\x83 \xF0\x9F\x98\x80", "\\textsf{[U+65E5]} \\textsf{[U+2603]} \\textsf{[U+1F600]}"},
        {"a\xFF" "b\xE2\x88", "a\\textsf{[U+FFFD]}b\\textsf{[U+FFFD]}\\textsf{[U+FFFD]}"},
        {"50% of a_b", "50\\% of a\\_b"},
    };
    char *all = NULL;
    size_t all_len = 0;
    FILE *doc = open_memstream(&all, &all_len);
    assert_non_null(doc);
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        char *out = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&out, &len);
        assert_non_null(f);
        sl_tex_text(f, want[i].in);
        fclose(f);
        assert_string_equal(out, want[i].tex);
        assert_null(strchr(out, '?'));
        fprintf(doc, "%s\\par\n", out);
        free(out);
    }
    fclose(doc);
    /* every code point of a few blocks (Latin-1, Latin Extended-A and B,
     * Greek, punctuation, arrows, maths): never '?', and it compiles */
    char *block = NULL;
    size_t block_len = 0;
    FILE *b = open_memstream(&block, &block_len);
    assert_non_null(b);
    static const unsigned ranges[][2] = {{0xA0, 0x24F}, {0x370, 0x3FF}, {0x2000, 0x206F}, {0x2190, 0x21FF},
                                         {0x2200, 0x22FF}};
    for (size_t r = 0; r < sizeof ranges / sizeof ranges[0]; r++)
        for (unsigned c = ranges[r][0]; c <= ranges[r][1]; c++) {
            char u[5] = {0};
            if (c < 0x800)
                u[0] = (char)(0xC0 | (c >> 6)), u[1] = (char)(0x80 | (c & 0x3F));
            else
                u[0] = (char)(0xE0 | (c >> 12)), u[1] = (char)(0x80 | ((c >> 6) & 0x3F)),
                u[2] = (char)(0x80 | (c & 0x3F));
            sl_tex_text(b, u);
            fputc(' ', b);
        }
    fclose(b);
    assert_null(strchr(block, '?'));
    if (system("command -v pdflatex >/dev/null 2>&1") == 0) {
        char dir[600], cmd[1400];
        snprintf(dir, sizeof dir, "%s/unicode-tex", sl_test_dir);
        snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
        assert_int_equal(system(cmd), 0);
        char path[700];
        snprintf(path, sizeof path, "%s/u.tex", dir);
        FILE *t = fopen(path, "w");
        assert_non_null(t);
        fprintf(t, "\\documentclass{article}\n\\usepackage[utf8]{inputenc}\n\\usepackage[T1]{fontenc}\n"
                   "\\usepackage{lmodern}\n\\begin{document}\n%s\n%s\n\\end{document}\n", all, block);
        assert_int_equal(fclose(t), 0);
        snprintf(cmd, sizeof cmd, "cd '%s' && pdflatex -interaction=nonstopmode -halt-on-error u.tex >/dev/null 2>&1 || "
                 "{ grep -A3 '^!' u.log | head -8; exit 1; }", dir);
        assert_int_equal(system(cmd), 0);
    }
    free(block);
    free(all);
}

/* 12 labels as columns do not fit \columnwidth: transposed (2 map sizes as
 * columns); 12 labels x 12 scenes fit neither way: split, each part with the
 * row names, no part over 8 numeric columns, never scaled. */
static void table_pivot_latex_fits(void **st)
{
    (void)st;
    enum { L = 12, S = 12 };
    struct sl_cell_record *c = calloc(L * S * 2, sizeof *c);
    assert_non_null(c);
    int n = 0;
    for (int s = 0; s < S; s++)
        for (int l = 0; l < L; l++)
            for (int m = 0; m < 2; m++) {
                c[n] = make("side", 1024 << m, 100000, "h");
                snprintf(c[n].scene, sizeof c[n].scene, "scene_%02d", s);
                snprintf(c[n].label, sizeof c[n].label, "label_%02d", l);
                n++;
            }
    struct sl_pivot_desc p = {.rows = SL_PK_map_size, .cols = SL_PK_label, .of = "count"};
    struct sl_pivot_info info;
    char *tex = pivot(SL_TABLE_LATEX, c, n, &p, &info, SL_OK);
    assert_int_equal(info.transposed, 1);
    assert_int_equal(info.parts, 1);
    assert_non_null(strstr(tex, "\\begin{tabular}{lrr}\n"));
    assert_non_null(strstr(tex, "\nlabel\\_00 & 100\\,020.0 & 100\\,020.0 \\\\\n"));
    assert_null(strstr(tex, "resizebox"));
    free(tex);
    p = (struct sl_pivot_desc){.rows = SL_PK_label, .cols = SL_PK_scene};
    tex = pivot(SL_TABLE_LATEX, c, n, &p, &info, SL_OK);
    assert_int_equal(info.transposed, 0);
    assert_true(info.parts >= 2);
    assert_int_equal(count_of(tex, "\\begin{table*}"), info.parts);
    assert_int_equal(count_of(tex, "\\toprule"), info.parts);
    assert_int_equal(count_of(tex, "\nlabel\\_05 & "), info.parts);
    assert_null(strstr(tex, "{lrrrrrrrrr"));   /* never more than 8 numeric columns */
    assert_null(strstr(tex, "resizebox"));
    free(tex);
    /* md, csv and json are never split */
    char *md = pivot(SL_TABLE_MD, c, n, &p, &info, SL_OK);
    assert_int_equal(info.parts, 1);
    assert_non_null(strstr(md, "| label \\ scene | scene_00 |"));
    free(md);
    char *js = pivot(SL_TABLE_JSON, c, n, &p, &info, SL_OK);
    assert_non_null(strstr(js, "\"columns\": [\"scene_00\", "));
    assert_non_null(strstr(js, "\"n\": [2, 2, "));
    free(js);
    free(c);
}

/* Five regions of nine-digit counts are wider than the line: never scaled;
 * a few rows are stacked (the count above its percentage) in one float,
 * every row split by regions into floats that each repeat the figure names. */
static void table_latex_wide(void **st)
{
    (void)st;
    struct sl_cell_record c = make("side", 1024, 100000000, "h");
    c.fig.nregions = 5;
    for (int r = 0; r < 5; r++) {
        c.fig.r[r].thickness = r < 4 ? 2 * (r + 1) : 0;
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            c.fig.r[r].n[k] = 100000000u + 10u * (uint64_t)r + (uint64_t)k;
            c.fig.r[r].pct[k] = k == SL_FIG_pixels ? NAN : 10.0 * r + k + 0.25;
        }
    }
    char *tex = render(SL_TABLE_LATEX, NULL, &c, 1, SL_OK);
    int floats = count_of(tex, "\\begin{table*}");
    assert_true(floats >= 2);
    assert_int_equal(count_of(tex, "\nfigure & "), floats);
    assert_int_equal(count_of(tex, "\nwrong & "), floats);
    assert_non_null(strstr(tex, "(part 1 of "));
    assert_null(strstr(tex, "resizebox"));
    assert_null(strstr(tex, "scalebox"));
    free(tex);
    struct sl_table_rows rows;
    struct sl_diag d;
    assert_int_equal(sl_table_figures_parse("wrong,light_incorrect", &rows, &d), SL_OK);
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_int_equal(sl_table_write_rows(f, SL_TABLE_LATEX, NULL, &c, 1, &rows, &d), SL_OK);
    fclose(f);
    assert_int_equal(count_of(buf, "\\begin{table*}"), 1);
    assert_non_null(strstr(buf, "\nfigure & 2px & 4px & 6px & 8px & image \\\\\n"));
    assert_non_null(strstr(buf, "\\begin{tabular}[t]{@{}r@{}}100000010\\\\ (10.25\\%)\\end{tabular}"));
    assert_null(strstr(buf, "resizebox"));
    free(buf);
}

/* The run's LaTeX: a few summary floats of the study (a sentence for one
 * whose entries are all 0), and floats per view with every label and map
 * size; no longtable, no scaling anywhere. */
static void table_run_latex(void **st)
{
    (void)st;
    struct sl_cell_record c[3];
    int n = three_cells(c);
    for (int i = 0; i < n; i++)
        snprintf(c[i].study, sizeof c[i].study, "prim_study");
    /* the time 0 in every cell (these cells were never timed): a sentence,
     * not a table of zeros */
    char *sum = render(SL_TABLE_LATEX_SUMMARY, "shadowlab: prim", c, n, SL_OK);
    assert_int_equal(count_of(sum, "\\begin{table*}"), 2);
    assert_non_null(strstr(sum, "% prim-study-ms-cost-map-size: every entry is 0, a sentence instead of a table\n"
                                "\\par\\noindent Total time of the cell's stages summed: map pass, post, lookup, "
                                "readback, rays (medians over the timed runs), ms, is 0 for every method and "
                                "shadow-map size: "));
    free(sum);
    /* one entry not 0 (a small one: 0.0034 ms, not 0.00): a table of wrong,
     * uncertain and ms_cost (the stages summed) by label x map size; one
     * scene: no label x scene */
    c[1].ms_cost = 0.0034;
    sum = render(SL_TABLE_LATEX_SUMMARY, "shadowlab: prim", c, n, SL_OK);
    assert_int_equal(count_of(sum, "\\begin{table*}"), 3);
    assert_null(strstr(sum, "a sentence instead"));
    assert_non_null(strstr(sum, "\nnsm\\_a & 0.0017 & 0 \\\\\n"));
    assert_non_null(strstr(sum, "\\label{tab:prim-study-wrong-map-size}\n"));
    assert_non_null(strstr(sum, "\nnsm\\_a & 20.25 & 20.25 \\\\\n"));
    /* the caption in words: the figure, its base, the keys, what an entry
     * aggregates, what every entry shares, the study; no internal id */
    assert_non_null(strstr(sum, "\\caption{Wrong pixels (both kinds), \\% of the image's pixels (background "
                                "excluded), for every method and shadow-map size: the mean over 2 viewpoints (side "
                                "and with), 1 to 2 values an entry; scene prim\\_s; viewport 64$\\times$32; the whole "
                                "image (study prim\\_study).}"));
    assert_null(strstr(sum, "ms\\_method"));
    assert_null(strstr(sum, "at most"));
    assert_non_null(strstr(sum, "% git abc1234, config 0123456789abcdef, machine h/c/i\n"));
    assert_null(strstr(sum, "resizebox"));
    free(sum);
    char *det = render(SL_TABLE_LATEX_DETAIL, "shadowlab: prim", c, n, SL_OK);
    /* floats a two-column class takes: no longtable */
    assert_int_equal(count_of(det, "\\begin{table*}"), count_of(det, "\\end{table*}"));
    assert_true(count_of(det, "\\begin{table*}") >= 2);   /* a view each: side, with */
    assert_null(strstr(det, "longtable"));
    assert_before(det, "Scene prim\\_s, viewpoint side, viewport 64$\\times$32",
                  "Scene prim\\_s, viewpoint with, viewport 64$\\times$32");
    /* side: the 1024 before the 2048 whatever the cells' order; wrong 1020 (20.25 %) */
    assert_before(det, "\nnsm\\_a & $1024^2$ & ", "\nnsm\\_a & $2048^2$ & ");
    assert_non_null(strstr(det, " & 1\\,020 & 20.25"));
    assert_null(strstr(det, "resizebox"));
    free(det);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(table, summary_rows),
        SL_CASE(table, markdown_rows),
        SL_CASE(table, markdown_mixed_provenance),
        SL_CASE(table, csv_long_form),
        SL_CASE(table, latex_booktabs),
        SL_CASE(table, latex_wide),
        SL_CASE(table, latex_unicode),
        SL_CASE(table, rows_produced_and_picked),
        SL_CASE(table, duplicate_map_refused),
        SL_CASE(table, empty_and_formats),
        SL_CASE(table, soft_and_hard),
        SL_CASE(table, spot_light),
        SL_CASE(table, hard_light_fractional),
        SL_CASE(table, pivot_values),
        SL_CASE(table, pivot_latex_fits),
        SL_CASE(table, run_latex),
    };
    return sl_run_group(argc, argv, "table", tests, NULL, NULL);
}
