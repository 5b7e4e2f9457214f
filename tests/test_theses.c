/* theses::* — the theses' data files (the CSV files of report/theses/) and
 * their reader (report/theses.c):
 * - shipped: the six files load from the source tree with their row
 *   counts, the arrays end in a zeroed row, every SL_MORAIS_ROWS name is
 *   its enum's, the pages the seeds print are the rows' (Morais Table 7 on
 *   p. 50, Moderno 16 without one) and cited so, and SHADOWLAB_THESES moves
 *   the folder;
 * - quoting: RFC 4180 quotes (a comma, a doubled quote), CRLF line ends, a
 *   byte-order mark, comment lines before and inside the rows, an empty
 *   note read as none;
 * - damaged: a bad header, a non-number count, an unknown enum name, an
 *   unterminated quote, a missing column, a page that is no page or a
 *   second page for one table, and the other malformed files are
 *   each refused (SL_E_DATA) with the file, the line and the column named,
 *   and nothing kept;
 * - mangled: the shipped file cut short and with bytes overwritten, again
 *   and again, loads or is refused, never crashes (ASan in CI). */
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
#include "theses.h"

/* dir/name holding n bytes of text (NUL bytes too); its path in path */
static void put(const char *name, const char *text, size_t n, char *path, size_t np)
{
    snprintf(path, np, "%s/%s", sl_test_dir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    assert_int_equal(fseek(f, 0, SEEK_END), 0);
    long len = ftell(f);
    assert_true(len > 0);
    rewind(f);
    char *b = malloc((size_t)len + 1);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)len, f), (size_t)len);
    fclose(f);
    b[len] = '\0';
    *n = (size_t)len;
    return b;
}

static void theses_shipped(void **st)
{
    (void)st;
    struct sl_diag d;
    const struct sl_thesis_datum *mo;
    const struct sl_morais_datum *ma;
    const struct sl_morais_time *mt;
    int n;
    assert_int_equal(sl_theses_moderno(&mo, &n, &d), SL_OK);
    assert_int_equal(n, 1434);
    assert_int_equal(mo[n].table, 0);
    assert_null(mo[n].viewpoint);
    assert_int_equal(mo[0].table, 16);
    assert_int_equal(mo[0].fig, SL_FIG_pixels);
    assert_int_equal(mo[0].value, 11000);
    assert_int_equal(sl_theses_morais(&ma, &n, &d), SL_OK);
    assert_int_equal(n, 1332);
    assert_null(ma[n].scene);
    assert_int_equal(ma[0].row, SL_MR_pfl);
    assert_true(ma[2].pct == 64.45);
    assert_int_equal(sl_theses_morais_times(&mt, &n, &d), SL_OK);
    assert_int_equal(n, 216);
    assert_null(mt[n].scene);
    assert_true(mt[0].ms == 1.57);
    const struct sl_hertel_row *he;
    assert_int_equal(sl_theses_hertel(&he, &n, &d), SL_OK);
    assert_int_equal(n, 4);
    assert_null(he[n].scene);
    assert_string_equal(he[1].scene, "Village");
    assert_int_equal(he[1].tris, 247432);
    assert_true(he[2].rt_insec == 2670 && he[3].rays == 198576 && he[3].insec == 967655);
    /* Moderno's appendix on the Bench scenes: nine views, two maps each */
    const struct sl_thesis_scene_view *sv;
    assert_int_equal(sl_theses_moderno_scenes(&sv, &n, &d), SL_OK);
    assert_int_equal(n, 18);
    assert_null(sv[n].scene);
    assert_true(sv[0].table == 64 && !strcmp(sv[0].scene, "bench") && !strcmp(sv[0].viewpoint, "side") &&
                sv[0].map_size == 1024 && sv[0].c2_lit_wrong == 3536 && sv[0].img_shadow == 321387 && !sv[0].note);
    assert_true(sv[8].table == 124 && sv[8].map_size == 1024 && sv[8].img_lit_wrong == 2884 && sv[8].note);
    assert_true(sv[17].table == 186 && sv[17].map_size == 2048 && sv[17].img_shadow_wrong == 3834);
    const struct sl_thesis_table15 *t15;
    assert_int_equal(sl_theses_moderno_table15(&t15, &n, &d), SL_OK);
    assert_int_equal(n, 3);
    assert_null(t15[n].scene);
    assert_true(!strcmp(t15[0].kase, "best") && !strcmp(t15[0].scene, "trees") && t15[0].contour == 6 &&
                t15[0].map_size == 2048 && !strcmp(t15[0].label, "chain_lit") && t15[0].pct == 0.02);
    assert_true(!strcmp(t15[2].kase, "worst") && t15[2].pct == 7.15);
    /* the pages the seeds print (the files' "# page:" lines say where) */
    assert_int_equal(sl_theses_morais(&ma, &n, &d), SL_OK);
    int seen7 = 0;
    for (int i = 0; i < n; i++)
        if (ma[i].table == 7) {
            assert_int_equal(ma[i].page, 50);
            seen7++;
        }
    assert_int_equal(seen7, 72);   /* 3 viewports x 4 maps x 6 rows, all on p. 50 */
    static const struct { enum sl_thesis_kind k; int table, page; } pages[] = {
        {SL_THESIS_MORAIS, 4, 46},        {SL_THESIS_MORAIS, 7, 50},         {SL_THESIS_MORAIS, 19, 73},
        {SL_THESIS_MORAIS, 24, 82},       {SL_THESIS_MORAIS_TIMES, 25, 84},  {SL_THESIS_MORAIS_TIMES, 30, 95},
        {SL_THESIS_MODERNO, 16, 0},       {SL_THESIS_MODERNO, 26, 100},      {SL_THESIS_MODERNO, 30, 111},
        {SL_THESIS_MODERNO, 47, 127},     {SL_THESIS_MODERNO, 53, 131},      {SL_THESIS_MODERNO, 58, 0},
        {SL_THESIS_HERTEL, 2, 0},         {SL_THESIS_MODERNO_SCENES, 124, 0}, {SL_THESIS_MODERNO_TABLE15, 15, 0},
        {SL_THESIS_MORAIS, 3, 0},          /* no such table in the file */
    };
    for (size_t i = 0; i < sizeof pages / sizeof pages[0]; i++)
        if (sl_thesis_page(pages[i].k, pages[i].table) != pages[i].page)
            fail_msg("%s Table %d: page %d, wanted %d", sl_thesis_file_name(pages[i].k), pages[i].table,
                     sl_thesis_page(pages[i].k, pages[i].table), pages[i].page);
    assert_int_equal(mo[0].page, 0);   /* Table 16: the index lost it */
    assert_int_equal(mt[0].page, 84);
    assert_int_equal(he[0].page, 0);
    char cite[40];
    assert_string_equal(sl_thesis_cite(SL_THESIS_MORAIS, 7, cite, sizeof cite), "Table 7, p. 50");
    assert_string_equal(sl_thesis_cite(SL_THESIS_MODERNO, 16, cite, sizeof cite), "Table 16");
    assert_string_equal(sl_thesis_cite(SL_THESIS_HERTEL, 2, cite, sizeof cite), "Table 2");
    /* loaded once: the same rows again */
    const struct sl_thesis_datum *again;
    assert_int_equal(sl_theses_moderno(&again, &n, &d), SL_OK);
    assert_ptr_equal(again, mo);
    for (int r = 0; r < SL_MR_COUNT; r++)
        assert_non_null(sl_morais_row_id((enum sl_morais_row)r));
    assert_string_equal(sl_morais_row_id(SL_MR_light), "light");
    assert_string_equal(sl_morais_row_id(SL_MR_truth_shadow), "truth_shadow");
    assert_null(sl_morais_row_id(SL_MR_COUNT));
    /* SHADOWLAB_THESES: another folder, read after the copies are dropped */
    sl_theses_free();
    char path[1200];
    static const char one[] = "table,page,viewpoint,map_size,contour,label,figure,value,note\n"
                              "16,,side,1024,2,nsm,pixels,7,\n";
    put("moderno-2011.csv", one, sizeof one - 1, path, sizeof path);
    setenv("SHADOWLAB_THESES", sl_test_dir, 1);
    assert_string_equal(sl_theses_dir(), sl_test_dir);
    assert_int_equal(sl_theses_moderno(&mo, &n, &d), SL_OK);
    assert_int_equal(n, 1);
    assert_int_equal(mo[0].value, 7);
    assert_int_equal(sl_theses_morais(&ma, &n, &d), SL_E_IO);   /* not in that folder */
    assert_non_null(strstr(d.file, "morais-2015.csv"));
    assert_null(ma);
    unsetenv("SHADOWLAB_THESES");
    sl_theses_free();
    assert_int_equal(sl_theses_moderno(&mo, &n, &d), SL_OK);
    assert_int_equal(n, 1434);
    sl_theses_free();
}

static void theses_quoting(void **st)
{
    (void)st;
    static const char text[] =
        "\xEF\xBB\xBF# a comment before the header, after a byte-order mark\r\n"
        "table,page,viewpoint,map_size,contour,label,figure,value,note\r\n"
        "# Table 16\r\n"
        "16,,side,1024,2,nsm,pixels,11000,\"a, b\"\r\n"
        "16,,side,1024,4,nsm,pixels,21482,\"say \"\"21482\"\", not 21842\"\n"
        "16,,side,1024,6,nsm,pixels,31683,\n"
        "16,,side,1024,0,nsm,pixels,1048576,\"\"\n"
        "16,,side,2048,0,nsm,pixels,1048576,plain text, no: one field too many";
    char path[1200];
    struct sl_thesis_file f;
    struct sl_diag d;
    /* the last line has a comma outside quotes: 9 fields */
    put("q.csv", text, sizeof text - 1, path, sizeof path);
    assert_int_equal(sl_thesis_file_load(SL_THESIS_MODERNO, path, &f, &d), SL_E_DATA);
    assert_int_equal(d.line, 8);
    assert_null(f.rows);
    /* without it (and no newline at the end) */
    size_t cut = (size_t)(strrchr(text, '\n') - text);
    put("q.csv", text, cut, path, sizeof path);
    assert_int_equal(sl_thesis_file_load(SL_THESIS_MODERNO, path, &f, &d), SL_OK);
    assert_int_equal(f.n, 4);
    const struct sl_thesis_datum *r = f.rows;
    assert_string_equal(r[0].note, "a, b");
    assert_string_equal(r[1].note, "say \"21482\", not 21842");
    assert_null(r[2].note);
    assert_null(r[3].note);   /* "" is no note */
    assert_int_equal(r[3].contour, 0);
    assert_int_equal(r[3].value, 1048576);
    assert_string_equal(r[3].label, "nsm");
    sl_thesis_file_free(&f);
    assert_null(f.rows);
    sl_thesis_file_free(&f);   /* twice: nothing */
}

#define MODERNO_HEAD "table,page,viewpoint,map_size,contour,label,figure,value,note\n"
#define MODERNO_ROW "16,,side,1024,2,nsm,pixels,11000,\n"
#define MORAIS_HEAD "table,page,scene,viewpoint,width,height,map_size,method,row,count,percent,note\n"
#define MORAIS_ROW "4,46,trees,side,512,512,0,raytrace,pfl,262144,100.00,\n"
#define TIMES_HEAD "table,page,scene,viewpoint,width,height,map_size,stage,method,ms,note\n"
#define TIMES_ROW "25,84,trees,side,512,512,512,0,nsm,1.57,\n"
#define WITH_NUL MODERNO_HEAD "16,,side,1024,2,nsm,pixels,1,a\0b\n"

static const struct bad {
    enum sl_thesis_kind kind;
    const char *text;
    size_t len;        /* 0: strlen(text) */
    int line;
    const char *key, *msg;
} bads[] = {
    /* the five the issue names */
    {SL_THESIS_MODERNO, "table,page,viewpoint,map,contour,label,figure,value,note\n" MODERNO_ROW, 0, 1, "map_size",
     "header: column 4 is 'map', expected 'map_size'"},
    {SL_THESIS_MORAIS, MORAIS_HEAD MORAIS_ROW "4,46,trees,side,512,512,0,raytrace,pnfl,12x,0.00,\n", 0, 3, "count",
     "'12x' is not a count"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "# Table 4\n" MORAIS_ROW "4,46,trees,side,512,512,0,raytrace,lite,1,0.00,\n", 0, 4,
     "row", "unknown row 'lite'"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,wrongs,1,\n", 0, 2, "figure", "unknown figure 'wrongs'"},
    {SL_THESIS_MODERNO, MODERNO_HEAD MODERNO_ROW "16,,side,1024,4,nsm,pixels,1,\"printed 1, read 2\n" MODERNO_ROW, 0,
     3, "note", "not closed on its line"},
    {SL_THESIS_MORAIS_TIMES, TIMES_HEAD "25,84,trees,side,512,512,512,0,1.57,\n", 0, 2, "note",
     "10 fields, the header has 11 (this column is missing)"},
    /* the header */
    {SL_THESIS_MODERNO, "table,page,viewpoint,map_size,contour,label,figure,value\n" MODERNO_ROW, 0, 1, "note",
     "header: column 9 is missing"},
    {SL_THESIS_MODERNO, "table,page,viewpoint,map_size,contour,label,figure,value,note,extra\n" MODERNO_ROW, 0, 1, "",
     "header: more than the 9 columns"},
    {SL_THESIS_MORAIS_TIMES, MORAIS_HEAD MORAIS_ROW, 0, 1, "stage", "expected 'stage'"},   /* another file's */
    {SL_THESIS_MODERNO, "", 0, 0, "", "no header row"},
    {SL_THESIS_MODERNO, "# only a comment\n", 0, 1, "", "no header row"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "# no rows\n", 0, 2, "", "no rows"},
    /* the records */
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,11000,,\n", 0, 2, "",
     "10 fields, the header has 9"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,11000,,,\n", 0, 2, "",
     "more than 9 fields"},
    {SL_THESIS_MODERNO, MODERNO_HEAD MODERNO_ROW "\n" MODERNO_ROW, 0, 3, "", "an empty line"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,11000,\"a\"b\n", 0, 2, "note",
     "text after a closing quote"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,11000,a \"b\"\n", 0, 2, "note",
     "a quote inside an unquoted field"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,11000,\"a\n", 0, 2, "note", "not closed"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,11000,\"", 0, 2, "note", "not closed"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,,\n", 0, 2, "value", "'' is not a count"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,-5,\n", 0, 2, "value", "'-5' is not a count"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,18446744073709551616,\n", 0, 2, "value",
     "is not a count"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1000,2,nsm,pixels,1,\n", 0, 2, "map_size", "a power of two"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "0,,side,1024,2,nsm,pixels,1,\n", 0, 2, "table", "out of range"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2.5,nsm,pixels,1,\n", 0, 2, "contour", "not a whole number"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,si de,1024,2,nsm,pixels,1,\n", 0, 2, "viewpoint", "not a name"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,,1024,2,nsm,pixels,1,\n", 0, 2, "viewpoint", "not a name"},
    {SL_THESIS_MODERNO, MODERNO_HEAD MODERNO_ROW "# again\n" MODERNO_ROW, 0, 4, "", "as line 2"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,1,caf\xc3\n", 0, 2, "note", "not UTF-8"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,1,a\tb\n", 0, 2, "note", "a control character"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,,side,1024,2,nsm,pixels,1,a\rb\n", 0, 2, "note", "a control character"},
    {SL_THESIS_MODERNO, WITH_NUL, sizeof WITH_NUL - 1, 2, "", "a NUL byte"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,46,trees,side,512,512,0,raytrace,pfl,1,100.5,\n", 0, 2, "percent",
     "out of range"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,46,trees,side,512,512,0,raytrace,pfl,1,1e2,\n", 0, 2, "percent",
     "not a decimal number"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,46,trees,side,512,512,0,raytrace,pfl,1,.5,\n", 0, 2, "percent",
     "not a decimal number"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,46,trees,side,512,512,0,raytrace,pfl,1,5.,\n", 0, 2, "percent",
     "not a decimal number"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "25,84,trees,side,512,512,0,raytrace,pfl,1,5,\n", 0, 2, "table", "out of range"},
    {SL_THESIS_MORAIS_TIMES, TIMES_HEAD "25,84,trees,side,512,512,512,2,nsm,1.57,\n", 0, 2, "stage", "out of range"},
    {SL_THESIS_MORAIS_TIMES, TIMES_HEAD "25,84,trees,side,512,512,0,0,nsm,1.57,\n", 0, 2, "map_size", "out of range"},
    {SL_THESIS_MORAIS_TIMES, TIMES_HEAD TIMES_ROW "25,84,trees,side,512,512,512,0,nsm,2.00,\n", 0, 3, "",
     "as line 2"},
    /* the page: digits 1-9999 or empty, one per table */
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,p46,trees,side,512,512,0,raytrace,pfl,1,5,\n", 0, 2, "page",
     "'p46' is not a whole number (digits 0-9, or empty: not known)"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,46.5,trees,side,512,512,0,raytrace,pfl,1,5,\n", 0, 2, "page",
     "not a whole number"},
    {SL_THESIS_MORAIS, MORAIS_HEAD "4,-46,trees,side,512,512,0,raytrace,pfl,1,5,\n", 0, 2, "page",
     "not a whole number"},
    {SL_THESIS_MODERNO, MODERNO_HEAD "16,0,side,1024,2,nsm,pixels,1,\n", 0, 2, "page", "0 is out of range (1..9999)"},
    {SL_THESIS_MORAIS_TIMES, TIMES_HEAD "25,10000,trees,side,512,512,512,0,nsm,1.57,\n", 0, 2, "page",
     "10000 is out of range (1..9999)"},
    {SL_THESIS_MORAIS, MORAIS_HEAD MORAIS_ROW "# Table 4 again\n4,47,trees,side,512,512,0,raytrace,pnfl,0,0.00,\n", 0,
     4, "page", "Table 4 is on page 47 here, on page 46 at line 2"},
    {SL_THESIS_MODERNO, MODERNO_HEAD MODERNO_ROW "16,100,side,1024,4,nsm,pixels,1,\n", 0, 3, "page",
     "Table 16 is on page 100 here, on no page at line 2"},
    {SL_THESIS_HERTEL, "table,page,scene,triangles,rt_class_ms,rt_insec_ms,rt_opt_ms,rays,insec_rays,note\n"
                       "2,,Village,247432,422,288,217,236350,905290,\n2,p. 3,Kitchen,103351,956,641,610,198576,967655,\n",
     0, 3, "page", "'p. 3' is not a whole number"},
};

static void theses_damaged(void **st)
{
    (void)st;
    for (size_t i = 0; i < sizeof bads / sizeof bads[0]; i++) {
        const struct bad *b = &bads[i];
        char name[64], path[1200];
        snprintf(name, sizeof name, "bad%zu-%s", i, sl_thesis_file_name(b->kind));
        put(name, b->text, b->len ? b->len : strlen(b->text), path, sizeof path);
        struct sl_thesis_file f;
        struct sl_diag d;
        memset(&f, 0x5a, sizeof f);
        enum sl_err e = sl_thesis_file_load(b->kind, path, &f, &d);
        char line[1400];
        sl_diag_format(&d, e, line, sizeof line);
        if (e != SL_E_DATA || d.line != b->line || strcmp(d.key, b->key) || strcmp(d.file, path) ||
            !strstr(d.msg, b->msg))
            fail_msg("case %zu: got %s (error %d), wanted line %d, column '%s', '%s'", i, line, (int)e, b->line,
                     b->key, b->msg);
        assert_null(f.rows);
        assert_null(f.buf);
        assert_int_equal(f.n, 0);
    }
    /* no file at all */
    struct sl_thesis_file f;
    struct sl_diag d;
    char path[1200];
    snprintf(path, sizeof path, "%s/none.csv", sl_test_dir);
    assert_int_equal(sl_thesis_file_load(SL_THESIS_MODERNO, path, &f, &d), SL_E_IO);
    assert_string_equal(d.file, path);
    assert_int_equal(sl_thesis_file_load(SL_THESIS_MODERNO, sl_test_dir, &f, &d), SL_E_IO);   /* a folder */
    assert_int_equal(sl_thesis_file_load(SL_THESIS_NKINDS, path, &f, &d), SL_E_INTERNAL);
    /* each of the three good rows loads */
    static const struct { enum sl_thesis_kind k; const char *text; } good[] = {
        {SL_THESIS_MODERNO, MODERNO_HEAD MODERNO_ROW},
        {SL_THESIS_MORAIS, MORAIS_HEAD MORAIS_ROW},
        {SL_THESIS_MORAIS_TIMES, TIMES_HEAD TIMES_ROW},
    };
    for (int k = 0; k < 3; k++) {
        put("good.csv", good[k].text, strlen(good[k].text), path, sizeof path);
        assert_int_equal(sl_thesis_file_load(good[k].k, path, &f, &d), SL_OK);
        assert_int_equal(f.n, 1);
        sl_thesis_file_free(&f);
    }
}

/* The shipped Morais file cut at many lengths and with bytes overwritten by
 * a fixed sequence: loads (a cut at a line's end) or is refused with a
 * line inside the file, never crashes or reads past it. */
static void theses_mangled(void **st)
{
    (void)st;
    char src[1200];
    snprintf(src, sizeof src, "%s/%s", sl_theses_dir(), sl_thesis_file_name(SL_THESIS_MORAIS));
    size_t n;
    char *orig = slurp(src, &n);
    int lines = 0;
    for (size_t i = 0; i < n; i++)
        lines += orig[i] == '\n';
    char *buf = malloc(n);
    assert_non_null(buf);
    char path[1200];
    int ok = 0, refused = 0;
    unsigned x = 12345;
    for (int it = 0; it < 120; it++) {
        size_t len = n;
        memcpy(buf, orig, n);
        if (it % 2 == 0) {
            len = (size_t)it * 997 % n;   /* cut short */
        } else {
            for (int k = 0; k < 4; k++) {  /* four bytes overwritten */
                x = x * 1103515245u + 12345u;
                size_t at = (x >> 8) % n;
                static const char pick[] = ",\"\n\r#x9.\xc3\xff";
                buf[at] = pick[(x >> 4) % (sizeof pick - 1)];
            }
        }
        put("mangled.csv", buf, len, path, sizeof path);
        struct sl_thesis_file f;
        struct sl_diag d;
        enum sl_err e = sl_thesis_file_load(SL_THESIS_MORAIS, path, &f, &d);
        if (e == SL_OK) {
            ok++;
            assert_true(f.n > 0 && f.n <= 1332);
            sl_thesis_file_free(&f);
        } else {
            refused++;
            assert_int_equal(e, SL_E_DATA);
            assert_string_equal(d.file, path);
            assert_true(d.line >= 0 && d.line <= lines + 1);   /* 0: an empty file */
        }
    }
    assert_true(refused > 0);
    free(buf);
    free(orig);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(theses, shipped),
        SL_CASE(theses, quoting),
        SL_CASE(theses, damaged),
        SL_CASE(theses, mangled),
    };
    return sl_run_group(argc, argv, "theses", tests, sl_test_setup, sl_test_teardown);
}
