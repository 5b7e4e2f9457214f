/* emit::* — the table model (tabmodel.h) and its emitters (emit.h) on one
 * small table: every format's exact text, its escaping (Markdown
 * punctuation, HTML entities, LaTeX specials and signs, CSV quotes, JSON
 * strings and numbers), groups, rules and muted rows, the note and the
 * link, the layouts a writer asks for (a verdict column, a terminal's
 * widths and colour, a quoted CSV column, LaTeX at \small with groups and
 * folded names), the table of emitters, and the example emitter of doc/layout.md
 * (tests/example_emitter/emit_tsv.c, built here): a new format is one file. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "sl_test.h"
#include "emit.h"
#include "tabmodel.h"

int sl_emit_tsv(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);   /* example_emitter/emit_tsv.c */

/* label | map | wrong % : two rows of "a_b", a block of one "x, \"y\"" row, muted */
static void small(struct sl_tab *t)
{
    sl_tab_init(t, "errors of a/b", 3, 2, "Wrong pixels <all> & 512\xC2\xB2");
    sl_tab_head(t, 0, "label");
    sl_tab_head(t, 1, "map");
    sl_tab_head(t, 2, "wrong %%");
    sl_tab_unit(t, 2, "%");
    sl_tab_row(t, 1);
    sl_tab_cell(t, 0, "a_b");
    sl_tab_cell(t, 1, "512\xC2\xB2");
    sl_tab_cell(t, 2, "1.25");
    sl_tab_row(t, 0);
    sl_tab_cell(t, 0, "a_b");
    sl_tab_cell(t, 1, "1024\xC2\xB2");
    sl_tab_row(t, 1);
    sl_tab_muted(t);
    sl_tab_cell(t, 0, "x, \"y\"");
    sl_tab_cell(t, 1, "2048\xC2\xB2");
    sl_tab_cell(t, 2, "-0.5e1");
    sl_tab_notef(t, "Means over %d cells.", 3);
}

static __attribute__((noinline)) char *render(sl_emit_fn fn, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    assert_true(fn(f, t, o) >= 0);
    fclose(f);
    return buf;
}

static void emit_model(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    assert_string_equal(t.id, "errors-of-a-b");
    assert_int_equal(t.nrows, 3);
    assert_int_equal(t.rule[0], 0);   /* a block's rule never before the first row */
    assert_int_equal(t.rule[2], SL_TAB_BLOCK | SL_TAB_MUTED);
    assert_string_equal(sl_tab_at(&t, 1, 2), "");
    assert_string_equal(t.head[2], "wrong %");
    sl_tab_note_cat(&t, " More.");
    assert_string_equal(t.note, "Means over 3 cells. More.");
    assert_true(sl_tab_has_note(&t));
    sl_tab_free(&t);
    assert_null(t.note);
    /* any number of columns */
    sl_tab_init(&t, "", 200, 1, "wide");
    assert_int_equal(t.ncols, 200);
    assert_int_equal(t.oom, 0);
    sl_tab_head(&t, 199, "last");
    assert_string_equal(t.head[199], "last");
    assert_string_equal(t.id, "-");
    /* LaTeX lays out at most SL_TAB_MAXCOLS columns */
    FILE *f = fopen("/dev/null", "w");
    assert_non_null(f);
    assert_int_equal(sl_emit_tex(f, &t, NULL), -1);
    assert_int_equal(sl_emit_md(f, &t, NULL), 0);
    fclose(f);
    sl_tab_free(&t);
}

static void emit_markdown(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    const struct sl_emit_opts link = {.link = "tex/e.tex"};
    char *s = render(sl_emit_md, &t, &link);
    assert_string_equal(s, "**Wrong pixels \\<all\\> & 512\xC2\xB2**\n\n"
                           "| label | map | wrong % |\n|---|---|---:|\n"
                           "| a\\_b | 512\xC2\xB2 | 1.25 |\n"
                           "| a\\_b | 1024\xC2\xB2 |  |\n"
                           "| x, \"y\" | 2048\xC2\xB2 | -0.5e1 |\n"
                           "\nMeans over 3 cells. [LaTeX](tex/e.tex)\n\n");
    free(s);
    /* plain, a heading, no note: names as they are, an empty cell "| |",
     * a blank line before a later table's heading */
    t.plain = 1;
    t.level = 3;
    free(t.note);
    t.note = NULL;
    sl_tab_group(&t, 2, "key");
    sl_tab_group(&t, 1, "%s", "");
    const struct sl_emit_opts later = {.gap = 1};
    s = render(sl_emit_md, &t, &later);
    assert_string_equal(s, "\n### Wrong pixels <all> & 512\xC2\xB2\n\n"
                           "| key label | key map | wrong % |\n|---|---|---:|\n"
                           "| a_b | 512\xC2\xB2 | 1.25 |\n"
                           "| a_b | 1024\xC2\xB2 | |\n"
                           "| x, \"y\" | 2048\xC2\xB2 | -0.5e1 |\n");
    free(s);
    sl_tab_free(&t);
}

static void emit_csv(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    char *s = render(sl_emit_csv, &t, NULL);
    assert_string_equal(s, "label,map,wrong %\na_b,512\xC2\xB2,1.25\na_b,1024\xC2\xB2,\n\"x, \"\"y\"\"\",2048\xC2\xB2,-0.5e1\n");
    free(s);
    const struct sl_emit_opts later = {.first = 0};
    s = render(sl_emit_csv, &t, &later);   /* no header after the first */
    assert_string_equal(s, "a_b,512\xC2\xB2,1.25\na_b,1024\xC2\xB2,\n\"x, \"\"y\"\"\",2048\xC2\xB2,-0.5e1\n");
    free(s);
    sl_tab_free(&t);
}

static void emit_html(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    const struct sl_emit_opts named = {.link = "tex/e.tex", .link_named = 1};
    char *s = render(sl_emit_html, &t, &named);
    assert_string_equal(s, "<div class=\"tab\"><table>\n<caption>Wrong pixels &lt;all&gt; &amp; 512\xC2\xB2</caption>\n"
                           "<thead>\n<tr><th class=\"k\">label</th><th class=\"k\">map</th><th>wrong %</th></tr>\n"
                           "</thead>\n<tbody>\n"
                           "<tr><td class=\"k\">a_b</td><td class=\"k\">512\xC2\xB2</td><td>1.25</td></tr>\n"
                           "<tr><td class=\"k\">a_b</td><td class=\"k\">1024\xC2\xB2</td><td></td></tr>\n"
                           "<tr class=\"blk muted\"><td class=\"k\">x, &quot;y&quot;</td><td class=\"k\">2048\xC2\xB2</td>"
                           "<td>-0.5e1</td></tr>\n"
                           "</tbody>\n</table>\n<p class=\"note\">Means over 3 cells. LaTeX: <code>tex/e.tex</code></p></div>\n");
    free(s);
    sl_tab_free(&t);
}

static void emit_json(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    char *s = render(sl_emit_json, &t, NULL);
    assert_string_equal(s, "{\"id\": \"errors-of-a-b\", \"title\": \"Wrong pixels <all> & 512\xC2\xB2\",\n"
                           " \"columns\": [\n  {\"name\": \"label\", \"key\": true},\n"
                           "  {\"name\": \"map\", \"key\": true},\n"
                           "  {\"name\": \"wrong %\", \"key\": false, \"unit\": \"%\"}],\n"
                           " \"rows\": [\n  [\"a_b\", \"512\xC2\xB2\", 1.25],\n  [\"a_b\", \"1024\xC2\xB2\", null],\n"
                           "  [\"x, \\\"y\\\"\", \"2048\xC2\xB2\", -0.5e1]],\n"
                           " \"blocks\": [2],\n \"note\": \"Means over 3 cells.\"}\n");
    free(s);
    /* a value that is not a number as a whole is a string */
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 2, "12 (3%%)");
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 2, "inf");
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 2, "007");
    s = render(sl_emit_json, &t, NULL);
    assert_non_null(strstr(s, "[\"\", \"\", \"12 (3%)\"]"));
    assert_non_null(strstr(s, "[\"\", \"\", \"inf\"]"));
    assert_non_null(strstr(s, "[\"\", \"\", \"007\"]"));
    free(s);
    sl_tab_free(&t);
}

static void emit_latex(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    char *s = render(sl_emit_tex, &t, NULL);
    assert_string_equal(s, "% shadowlab report table; needs \\usepackage{booktabs}; a wide one is split, never scaled\n"
                           "\\begin{table*}[tbp]\n\\centering\n\\footnotesize\n\\setlength{\\tabcolsep}{4pt}\n"
                           "\\caption{Wrong pixels \\textless{}all\\textgreater{} \\& 512\\textsuperscript{2}}\n\\label{tab:errors-of-a-b}\n"
                           "\\begin{tabular}{llr}\n\\toprule\nlabel & map & wrong \\% \\\\\n\\midrule\n"
                           "a\\_b & 512\\textsuperscript{2} & 1.25 \\\\\n"
                           "a\\_b & 1024\\textsuperscript{2} &  \\\\\n"
                           "\\addlinespace\n"
                           "x, \"y\" & 2048\\textsuperscript{2} & -0.5e1 \\\\\n"
                           "\\bottomrule\n\\end{tabular}\n\n\\smallskip\n"
                           "\\parbox{\\linewidth}{\\scriptsize\\raggedright Means over 3 cells.\\par}\n\\end{table*}\n");
    free(s);
    sl_tab_free(&t);
}

static void emit_emitters(void **state)
{
    (void)state;
    assert_ptr_equal(sl_emit_find("md"), sl_emit_md);
    assert_ptr_equal(sl_emit_find("csv"), sl_emit_csv);
    assert_ptr_equal(sl_emit_find("latex"), sl_emit_tex);
    assert_ptr_equal(sl_emit_find("html"), sl_emit_html);
    assert_ptr_equal(sl_emit_find("json"), sl_emit_json);
    assert_ptr_equal(sl_emit_find("term"), sl_emit_term);
    assert_null(sl_emit_find("tsv"));   /* the doc's example is not shipped */
    assert_null(sl_emit_find(NULL));
    int n = 0;
    while (sl_emitters[n].name)
        n++;
    assert_int_equal(n, 6);
    /* an out-of-memory model is refused by every emitter */
    struct sl_tab t;
    small(&t);
    t.oom = 1;
    FILE *f = fopen("/dev/null", "w");
    assert_non_null(f);
    for (int k = 0; k < n; k++)
        assert_int_equal(sl_emitters[k].emit(f, &t, NULL), -1);
    assert_int_equal(sl_emit_tsv(f, &t, NULL), -1);
    fclose(f);
    t.oom = 0;
    sl_tab_free(&t);
}

/* A table with a verdict column: an ok row and a failing one with an empty
 * cell (check's table of what moved) */
static void verdict(struct sl_tab *t)
{
    sl_tab_init(t, "moved", 4, 1, "%s", "");
    t->plain = 1;
    t->padded = 1;
    t->verdict = 1;
    static const char *const heads[] = {"cell", "now", "moved", ""};
    for (int k = 0; k < 4; k++)
        sl_tab_head(t, k, "%s", heads[k]);
    sl_tab_align(t, 3, 'l');
    t->termw[0] = 8;
    t->termw[1] = 5;
    sl_tab_row(t, 0);
    sl_tab_cell(t, 0, "\xC3\xA9t\xC3\xA9_a");
    sl_tab_cell(t, 1, "12");
    sl_tab_cell(t, 2, "+0.1 pp");
    sl_tab_cell(t, 3, "ok");
    sl_tab_row(t, 0);
    sl_tab_alert(t);
    sl_tab_cell(t, 0, "b");
    sl_tab_cell(t, 1, "missing");
    sl_tab_cell(t, 3, "FAIL");
}

/* Markdown of a padded plain table: an empty head "| |", an empty cell
 * "|  |", the alert row's verdict bold */
static void emit_verdict_markdown(void **state)
{
    (void)state;
    struct sl_tab t;
    verdict(&t);
    char *s = render(sl_emit_md, &t, NULL);
    assert_string_equal(s, "| cell | now | moved | |\n|---|---:|---:|---|\n"
                           "| \xC3\xA9t\xC3\xA9_a | 12 | +0.1 pp | ok |\n| b | missing |  | **FAIL** |\n");
    free(s);
    sl_tab_free(&t);
}

/* The terminal: fixed widths counted in characters (a longer cell runs
 * over), the widest cell where no width is set, the last column unpadded,
 * the verdict in colour only when asked */
static void emit_terminal(void **state)
{
    (void)state;
    struct sl_tab t;
    verdict(&t);
    char *s = render(sl_emit_term, &t, NULL);
    assert_string_equal(s, "cell       now   moved \n"
                           "\xC3\xA9t\xC3\xA9_a       12 +0.1 pp ok\n"
                           "b        missing         FAIL\n");
    free(s);
    const struct sl_emit_opts color = {.color = 1};
    s = render(sl_emit_term, &t, &color);
    assert_non_null(strstr(s, " \033[32mok\033[0m\n"));
    assert_non_null(strstr(s, " \033[1;31mFAIL\033[0m\n"));
    assert_null(strstr(s, "cell       now   moved \033"));   /* the heads are not coloured */
    free(s);
    sl_tab_free(&t);
}

/* CSV: a quoted column quotes every field (its quotes doubled), the others
 * only where RFC 4180 needs it; the header is not quoted */
static void emit_csv_quote(void **state)
{
    (void)state;
    struct sl_tab t;
    sl_tab_init(&t, "costs", 3, 0, "costs");
    sl_tab_head(&t, 0, "label");
    sl_tab_head(&t, 1, "n");
    sl_tab_head(&t, 2, "machine");
    sl_tab_quote(&t, 2);
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 0, "a,b");
    sl_tab_cell(&t, 1, "3");
    sl_tab_cell(&t, 2, "h/c/i");
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 0, "c");
    sl_tab_cell(&t, 2, "h \"x\"");
    char *s = render(sl_emit_csv, &t, NULL);
    assert_string_equal(s, "label,n,machine\n\"a,b\",3,\"h/c/i\"\nc,,\"h \"\"x\"\"\"\n");
    free(s);
    sl_tab_free(&t);
}

/* occurrences of needle in s */
static int count_of(const char *s, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(s, needle); p; p = strstr(p + strlen(needle), needle))
        n++;
    return n;
}

/* LaTeX laid out by its writer at \small (a pivot): the column key's group
 * over the values with a rule trimmed where a column is beside it, a long
 * row name folded into a \parbox with breaks after '_' and '-' (whole
 * characters: an accent stays a letter); table* floats, which a one- and
 * a two-column class both take. Paged (rows more than a page holds): a
 * float per 34 rows, each with the heads, the later ones "(continued)"
 * under the first's number, one \label. */
static void emit_latex_layout(void **state)
{
    (void)state;
    struct sl_tab t;
    sl_tab_init(&t, "pivot-wrong-label-map-size", 3, 1, "wrong: 50%%");
    t.fixed = 1;
    t.small = 1;
    t.fold[0] = 40;
    sl_tab_group(&t, 1, "%s", "");
    sl_tab_group(&t, 2, "map size");
    sl_tab_head(&t, 0, "label");
    sl_tab_head(&t, 1, "512\xC2\xB2");
    sl_tab_head(&t, 2, "1\xE2\x80\x89" "024\xC2\xB2");
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 0, "nsm");
    sl_tab_cell(&t, 1, "\xE2\x88\x92" "1.50\xE2\x80\xA0");
    sl_tab_cell(&t, 2, "\xE2\x80\x93");
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 0, "\xC3\xBC" "ber_lang-name/x");
    const struct sl_emit_opts blank = {.blank = 1};
    char *s = render(sl_emit_tex, &t, &blank);
    assert_string_equal(s, "\\begin{table*}[tbp]\n\\centering\n\\small\n\\caption{wrong: 50\\%}\n"
                           "\\label{tab:pivot-wrong-label-map-size}\n\\begin{tabular}{lrr}\n\\toprule\n"
                           " & \\multicolumn{2}{c}{map size} \\\\\n\\cmidrule(l){2-3}\n"
                           "label & 512\\textsuperscript{2} & 1\\,024\\textsuperscript{2} \\\\\n\\midrule\n"
                           "nsm & $-$1.50$^\\dagger$ & -- \\\\\n"
                           "\\parbox[t]{40pt}{\\raggedright \\\"{u}ber\\_\\allowbreak{}lang-\\allowbreak{}name/"
                           "\\allowbreak{}x} &  &  \\\\\n"
                           "\\bottomrule\n\\end{tabular}\n\\end{table*}\n\n");
    free(s);
    /* 2 + 78 rows of one line each: floats of 34, 34 and 12 rows */
    t.fixed = 0;
    t.paged = 1;
    t.fold[0] = 0;
    for (int r = 0; r < 78; r++) {
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "row%d", r);
    }
    const struct sl_emit_opts alone = {0};
    s = render(sl_emit_tex, &t, &alone);
    assert_int_equal(count_of(s, "\\begin{table*}[tbp]"), 3);
    assert_int_equal(count_of(s, "\\end{table*}"), 3);
    assert_int_equal(count_of(s, "\\label{"), 1);
    assert_int_equal(count_of(s, "\\addtocounter{table}{-1}\n\\caption{wrong: 50\\% (continued)}"), 2);
    assert_int_equal(count_of(s, "\\multicolumn{2}{c}{map size}"), 3);
    assert_int_equal(count_of(s, "row"), 78);
    assert_null(strstr(s, "longtable"));
    /* the third float: rows 66 to 77 (the model's 68th to 80th) */
    const char *third = strstr(strstr(strstr(s, "(continued)") + 1, "(continued)"), "\\midrule\n");
    assert_non_null(third);
    assert_true(strncmp(third, "\\midrule\nrow66 &", strlen("\\midrule\nrow66 &")) == 0);
    free(s);
    sl_tab_free(&t);
}

/* doc/layout.md's example: TSV from the same model, no quoting */
static void emit_example_tsv(void **state)
{
    (void)state;
    struct sl_tab t;
    small(&t);
    sl_tab_row(&t, 0);
    sl_tab_cell(&t, 0, "tab\there");
    sl_tab_cell(&t, 1, "two\nlines");
    char *s = render(sl_emit_tsv, &t, NULL);
    assert_string_equal(s, "label\tmap\twrong %\na_b\t512\xC2\xB2\t1.25\na_b\t1024\xC2\xB2\t\n"
                           "x, \"y\"\t2048\xC2\xB2\t-0.5e1\ntab here\ttwo lines\t\n");
    free(s);
    const struct sl_emit_opts later = {.first = 0};
    s = render(sl_emit_tsv, &t, &later);
    assert_string_equal(s, "a_b\t512\xC2\xB2\t1.25\na_b\t1024\xC2\xB2\t\nx, \"y\"\t2048\xC2\xB2\t-0.5e1\n"
                           "tab here\ttwo lines\t\n");
    free(s);
    sl_tab_free(&t);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(emit, model),
        SL_CASE(emit, markdown),
        SL_CASE(emit, csv),
        SL_CASE(emit, html),
        SL_CASE(emit, json),
        SL_CASE(emit, latex),
        SL_CASE(emit, emitters),
        SL_CASE(emit, verdict_markdown),
        SL_CASE(emit, terminal),
        SL_CASE(emit, csv_quote),
        SL_CASE(emit, latex_layout),
        SL_CASE(emit, example_tsv),
    };
    return sl_run_group(argc, argv, "emit", tests, NULL, NULL);
}
