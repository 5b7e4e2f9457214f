/*
 * theses.c — the theses' data files (the CSV files of report/theses/) read
 * into the rows of theses.h: a small strict CSV reader and a schema per file.
 *
 * The format is RFC 4180's with three restrictions and one addition: a
 * record is one line (LF, or CRLF), so a quoted field may not run past its
 * line and an unclosed quote is caught on the line that opens it; no empty
 * line; every field valid UTF-8 without control characters (a leading
 * byte-order mark is skipped); and a line that starts with '#' is a
 * comment (the transcription's remarks, before each table's rows),
 * allowed anywhere, before the header row too. The header is the first
 * other line and must name the kind's columns exactly,
 * in order; every record has as many fields. Fields are checked as the
 * column says: a count is decimal digits (no sign, no exponent) within its
 * range, a percentage or a time decimal digits with an optional fraction,
 * a name [A-Za-z0-9_.-], an enum one of the names the code gives it
 * (sl_figure_name, SL_MORAIS_ROWS), a page 1-9999 or empty (the thesis's
 * text does not say), a note any text (empty: none). Two rows with the
 * same key (the fields a section looks a value up by) are refused, since
 * the section would only ever find the first; so are two rows of one
 * table with different pages (a table is cited at one page).
 * Invariants: a file is kept only when every line passed; the strings of
 * its rows are its buffer's fields, unquoted in place (an unquoted field is
 * never longer than its quoted form); the rows end in a zeroed row.
 * Every failure names the file, the line (1-based) and the column.
 */
#define _DEFAULT_SOURCE
#include "theses.h"
#include "util.h"
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef SL_THESES_DIR
#define SL_THESES_DIR "report/theses"
#endif

/* The largest file read: the three are 60-140 kB. */
#define MAX_BYTES (8u << 20)
#define MAX_COLS 16
#define MAX_NAME 47     /* the cells' label is 48 bytes */
#define MAX_NOTE 1000

static const char *const row_ids[SL_MR_COUNT] = {
#define SL_MR_ID(id, text) #id,
    SL_MORAIS_ROWS(SL_MR_ID)
#undef SL_MR_ID
};

const char *sl_morais_row_id(enum sl_morais_row r) { return (unsigned)r < SL_MR_COUNT ? row_ids[r] : NULL; }

/* ---- the schemas ---- */

enum col_type { C_INT, C_PAGE, C_U64, C_DEC, C_NAME, C_FIG, C_ROW, C_NOTE };

struct col {
    const char   *name;
    enum col_type type;
    double        lo, hi;      /* C_INT, C_PAGE, C_DEC: the range */
    int           pow2;        /* C_INT: 0 or a power of two */
    size_t        off;         /* into the row */
    int           key;         /* part of the row's key */
};

#define COL(name, type, lo, hi, pow2, st, field, key) {name, type, lo, hi, pow2, offsetof(struct st, field), key}

static const struct col moderno_cols[] = {
    COL("table", C_INT, 1, 99, 0, sl_thesis_datum, table, 1),
    COL("page", C_PAGE, 1, 9999, 0, sl_thesis_datum, page, 0),
    COL("viewpoint", C_NAME, 0, 0, 0, sl_thesis_datum, viewpoint, 1),
    COL("map_size", C_INT, 16, 16384, 1, sl_thesis_datum, map_size, 1),
    COL("contour", C_INT, 0, 64, 0, sl_thesis_datum, contour, 1),
    COL("label", C_NAME, 0, 0, 0, sl_thesis_datum, label, 1),
    COL("figure", C_FIG, 0, 0, 0, sl_thesis_datum, fig, 1),
    COL("value", C_U64, 0, 0, 0, sl_thesis_datum, value, 0),
    COL("note", C_NOTE, 0, 0, 0, sl_thesis_datum, note, 0),
};
static const struct col morais_cols[] = {
    COL("table", C_INT, 4, 24, 0, sl_morais_datum, table, 1),
    COL("page", C_PAGE, 1, 9999, 0, sl_morais_datum, page, 0),
    COL("scene", C_NAME, 0, 0, 0, sl_morais_datum, scene, 0),
    COL("viewpoint", C_NAME, 0, 0, 0, sl_morais_datum, viewpoint, 0),
    COL("width", C_INT, 1, 16384, 0, sl_morais_datum, vw, 1),
    COL("height", C_INT, 1, 16384, 0, sl_morais_datum, vh, 1),
    COL("map_size", C_INT, 0, 16384, 1, sl_morais_datum, map_size, 1),
    COL("method", C_NAME, 0, 0, 0, sl_morais_datum, method, 0),
    COL("row", C_ROW, 0, 0, 0, sl_morais_datum, row, 1),
    COL("count", C_U64, 0, 0, 0, sl_morais_datum, n, 0),
    COL("percent", C_DEC, 0, 100, 0, sl_morais_datum, pct, 0),
    COL("note", C_NOTE, 0, 0, 0, sl_morais_datum, note, 0),
};
static const struct col times_cols[] = {
    COL("table", C_INT, 25, 30, 0, sl_morais_time, table, 1),
    COL("page", C_PAGE, 1, 9999, 0, sl_morais_time, page, 0),
    COL("scene", C_NAME, 0, 0, 0, sl_morais_time, scene, 0),
    COL("viewpoint", C_NAME, 0, 0, 0, sl_morais_time, viewpoint, 0),
    COL("width", C_INT, 1, 16384, 0, sl_morais_time, vw, 1),
    COL("height", C_INT, 1, 16384, 0, sl_morais_time, vh, 1),
    COL("map_size", C_INT, 16, 16384, 1, sl_morais_time, map_size, 1),
    COL("stage", C_INT, 0, 1, 0, sl_morais_time, stage, 0),
    COL("method", C_NAME, 0, 0, 0, sl_morais_time, method, 1),
    COL("ms", C_DEC, 0, 1e7, 0, sl_morais_time, ms, 0),
    COL("note", C_NOTE, 0, 0, 0, sl_morais_time, note, 0),
};

static const struct col hertel_cols[] = {
    COL("table", C_INT, 2, 2, 0, sl_hertel_row, table, 0),
    COL("page", C_PAGE, 1, 9999, 0, sl_hertel_row, page, 0),
    COL("scene", C_NOTE, 0, 0, 0, sl_hertel_row, scene, 1),
    COL("triangles", C_INT, 1, 1e8, 0, sl_hertel_row, tris, 0),
    COL("rt_class_ms", C_DEC, 0, 1e7, 0, sl_hertel_row, rt_class, 0),
    COL("rt_insec_ms", C_DEC, 0, 1e7, 0, sl_hertel_row, rt_insec, 0),
    COL("rt_opt_ms", C_DEC, 0, 1e7, 0, sl_hertel_row, rt_opt, 0),
    COL("rays", C_U64, 0, 0, 0, sl_hertel_row, rays, 0),
    COL("insec_rays", C_U64, 0, 0, 0, sl_hertel_row, insec, 0),
    COL("note", C_NOTE, 0, 0, 0, sl_hertel_row, note, 0),
};

static const struct col scenes_cols[] = {
    COL("table", C_INT, 1, 999, 0, sl_thesis_scene_view, table, 1),
    COL("page", C_PAGE, 1, 9999, 0, sl_thesis_scene_view, page, 0),
    COL("scene", C_NAME, 0, 0, 0, sl_thesis_scene_view, scene, 1),
    COL("viewpoint", C_NAME, 0, 0, 0, sl_thesis_scene_view, viewpoint, 1),
    COL("map_size", C_INT, 16, 16384, 1, sl_thesis_scene_view, map_size, 1),
    COL("c2_lit_wrong", C_U64, 0, 0, 0, sl_thesis_scene_view, c2_lit_wrong, 0),
    COL("c2_lit", C_U64, 0, 0, 0, sl_thesis_scene_view, c2_lit, 0),
    COL("c2_shadow_wrong", C_U64, 0, 0, 0, sl_thesis_scene_view, c2_shadow_wrong, 0),
    COL("c2_shadow", C_U64, 0, 0, 0, sl_thesis_scene_view, c2_shadow, 0),
    COL("img_lit_wrong", C_U64, 0, 0, 0, sl_thesis_scene_view, img_lit_wrong, 0),
    COL("img_lit", C_U64, 0, 0, 0, sl_thesis_scene_view, img_lit, 0),
    COL("img_shadow_wrong", C_U64, 0, 0, 0, sl_thesis_scene_view, img_shadow_wrong, 0),
    COL("img_shadow", C_U64, 0, 0, 0, sl_thesis_scene_view, img_shadow, 0),
    COL("note", C_NOTE, 0, 0, 0, sl_thesis_scene_view, note, 0),
};
static const struct col table15_cols[] = {
    COL("table", C_INT, 15, 15, 0, sl_thesis_table15, table, 1),
    COL("page", C_PAGE, 1, 9999, 0, sl_thesis_table15, page, 0),
    COL("case", C_NAME, 0, 0, 0, sl_thesis_table15, kase, 1),
    COL("scene", C_NAME, 0, 0, 0, sl_thesis_table15, scene, 0),
    COL("viewpoint", C_NAME, 0, 0, 0, sl_thesis_table15, viewpoint, 0),
    COL("map_size", C_INT, 16, 16384, 1, sl_thesis_table15, map_size, 1),
    COL("contour", C_INT, 0, 64, 0, sl_thesis_table15, contour, 0),
    COL("label", C_NAME, 0, 0, 0, sl_thesis_table15, label, 1),
    COL("percent", C_DEC, 0, 100, 0, sl_thesis_table15, pct, 0),
    COL("note", C_NOTE, 0, 0, 0, sl_thesis_table15, note, 0),
};

static const struct schema {
    const char       *file;
    const struct col *cols;
    int               ncols;
    size_t            size;    /* of a row */
} schemas[SL_THESIS_NKINDS] = {
    [SL_THESIS_MODERNO] = {"moderno-2011.csv", moderno_cols, (int)(sizeof moderno_cols / sizeof moderno_cols[0]),
                           sizeof(struct sl_thesis_datum)},
    [SL_THESIS_MORAIS] = {"morais-2015.csv", morais_cols, (int)(sizeof morais_cols / sizeof morais_cols[0]),
                          sizeof(struct sl_morais_datum)},
    [SL_THESIS_MORAIS_TIMES] = {"morais-2015-times.csv", times_cols, (int)(sizeof times_cols / sizeof times_cols[0]),
                                sizeof(struct sl_morais_time)},
    [SL_THESIS_HERTEL] = {"hertel-2009.csv", hertel_cols, (int)(sizeof hertel_cols / sizeof hertel_cols[0]),
                          sizeof(struct sl_hertel_row)},
    [SL_THESIS_MODERNO_SCENES] = {"moderno-2011-scenes.csv", scenes_cols,
                                  (int)(sizeof scenes_cols / sizeof scenes_cols[0]),
                                  sizeof(struct sl_thesis_scene_view)},
    [SL_THESIS_MODERNO_TABLE15] = {"moderno-2011-table15.csv", table15_cols,
                                   (int)(sizeof table15_cols / sizeof table15_cols[0]),
                                   sizeof(struct sl_thesis_table15)},
};

const char *sl_thesis_file_name(enum sl_thesis_kind k)
{
    return (unsigned)k < SL_THESIS_NKINDS ? schemas[k].file : "?";
}

/* ---- where the files are ---- */

/* The installed share folder (util.h, sl_share_dir), once. */
static const char *installed_dir(void)
{
    static char dir[1024];
    static int done;
    if (!done) {
        done = 1;
        sl_share_dir("theses", dir, sizeof dir);
    }
    return dir;
}

const char *sl_theses_dir(void)
{
    const char *e = getenv("SHADOWLAB_THESES");
    if (e && *e)
        return e;
    const char *inst = installed_dir();
    return inst[0] ? inst : SL_THESES_DIR;
}

/* ---- reading ---- */

/* A field as the messages quote it: at most 40 bytes, control bytes as '?'. */
static const char *shown(const char *s, char *buf, size_t n)
{
    size_t k = 0;
    for (; s[k] && k + 4 < n && k < 40; k++)
        buf[k] = (unsigned char)s[k] < 0x20 || s[k] == 0x7f ? '?' : s[k];
    snprintf(buf + k, n - k, "%s", s[k] ? "..." : "");
    return buf;
}

/* Length of the valid UTF-8 sequence at s (no overlongs, surrogates or
 * code points past U+10FFFF), 0 if it is not one. */
static int utf8_len(const unsigned char *s)
{
    if (s[0] < 0x80)
        return 1;
    int n = s[0] >= 0xf0 && s[0] <= 0xf4 ? 4 : s[0] >= 0xe0 ? 3 : s[0] >= 0xc2 && s[0] < 0xe0 ? 2 : 0;
    if (n == 3 && s[0] > 0xef)
        n = 0;
    for (int i = 1; i < n; i++)
        if ((s[i] & 0xc0) != 0x80)
            return 0;
    if ((n == 3 && s[0] == 0xe0 && s[1] < 0xa0) || (n == 3 && s[0] == 0xed && s[1] >= 0xa0) ||
        (n == 4 && s[0] == 0xf0 && s[1] < 0x90) || (n == 4 && s[0] == 0xf4 && s[1] >= 0x90))
        return 0;
    return n;
}

/* Split the line (NUL-terminated, no line end) into fields in place:
 * RFC 4180 quoting, "" a quote inside a quoted field. Returns the count, -1
 * with d filled when the line is malformed (col: the column it was in). */
static int split(char *line, char **field, int max, const char *path, int ln, const struct schema *s,
                 struct sl_diag *d)
{
    int nf = 0;
    char *p = line;
    for (;;) {
        const char *col = nf < s->ncols ? s->cols[nf].name : "";
        if (nf == max) {
            sl_fail(d, SL_E_DATA, path, ln, "", "more than %d fields (the header has %d)", max - 1, s->ncols);
            return -1;
        }
        if (*p == '"') {
            char *w = p, *r = p + 1;
            for (;;) {
                if (!*r) {
                    sl_fail(d, SL_E_DATA, path, ln, col, "a quote opened and not closed on its line (a record "
                            "is one line)");
                    return -1;
                }
                if (*r == '"') {
                    if (r[1] != '"')
                        break;
                    *w++ = '"';
                    r += 2;
                } else {
                    *w++ = *r++;
                }
            }
            r++;   /* the closing quote */
            if (*r && *r != ',') {
                sl_fail(d, SL_E_DATA, path, ln, col, "text after a closing quote");
                return -1;
            }
            int last = !*r;
            *w = '\0';   /* w < r: the field is at least its two quotes shorter */
            field[nf++] = p;
            if (last)
                return nf;
            p = r + 1;
        } else {
            char *e = p + strcspn(p, ",\"");
            if (*e == '"') {
                sl_fail(d, SL_E_DATA, path, ln, col, "a quote inside an unquoted field (quote the field and "
                        "double the quote)");
                return -1;
            }
            field[nf++] = p;
            if (!*e)
                return nf;
            *e = '\0';
            p = e + 1;
        }
    }
}

/* The field's text: valid UTF-8 without control characters. */
static enum sl_err check_text(const char *f, const char *path, int ln, const char *col, struct sl_diag *d)
{
    for (const unsigned char *u = (const unsigned char *)f; *u;) {
        int k = utf8_len(u);
        if (!k || *u < 0x20 || *u == 0x7f)
            return sl_fail(d, SL_E_DATA, path, ln, col, "%s at byte %d", k ? "a control character" : "not UTF-8",
                           (int)((const char *)u - f) + 1);
        u += k;
    }
    return SL_OK;
}

/* digits only, at least one; *v the value, 0 on overflow */
static int parse_u64(const char *f, uint64_t *v)
{
    if (!*f)
        return 0;
    uint64_t x = 0;
    for (const char *p = f; *p; p++) {
        if (*p < '0' || *p > '9')
            return 0;
        unsigned dgt = (unsigned)(*p - '0');
        if (x > (UINT64_MAX - dgt) / 10)
            return 0;
        x = x * 10 + dgt;
    }
    *v = x;
    return 1;
}

/* digits, optionally '.' and digits: "64.45", "100.00", "15" */
static int parse_dec(const char *f, double *v)
{
    const char *p = f;
    size_t a = strspn(p, "0123456789");
    if (!a || a > 12)
        return 0;
    p += a;
    if (*p == '.') {
        size_t b = strspn(p + 1, "0123456789");
        if (!b || b > 12)
            return 0;
        p += 1 + b;
    }
    if (*p)
        return 0;
    errno = 0;
    char *end;
    *v = strtod(f, &end);   /* the C locale's '.': shadowlab never sets a locale */
    return *end == '\0' && errno == 0 && isfinite(*v);
}

static enum sl_err field_value(const struct col *c, char *f, void *row, const char *path, int ln, struct sl_diag *d)
{
    char b[64];
    char *at = (char *)row + c->off;
    if (c->type == C_PAGE && !*f) {   /* the thesis's text does not say */
        *(int *)at = 0;
        return SL_OK;
    }
    switch (c->type) {
    case C_INT:
    case C_PAGE: {
        uint64_t v;
        if (!parse_u64(f, &v))
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "'%s' is not a whole number (digits 0-9%s)",
                           shown(f, b, sizeof b), c->type == C_PAGE ? ", or empty: not known" : "");
        if ((double)v < c->lo || (double)v > c->hi || (c->pow2 && v && (v & (v - 1))))
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "%llu is out of range (%.0f..%.0f%s)",
                           (unsigned long long)v, c->lo, c->hi,
                           c->pow2 ? (c->lo > 0 ? ", a power of two" : ", 0 or a power of two") : "");
        *(int *)at = (int)v;
        return SL_OK;
    }
    case C_U64:
        if (!parse_u64(f, (uint64_t *)at))
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "'%s' is not a count (digits 0-9, below 2^64)",
                           shown(f, b, sizeof b));
        return SL_OK;
    case C_DEC: {
        double v;
        if (!parse_dec(f, &v))
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "'%s' is not a decimal number (digits, '.' and digits)",
                           shown(f, b, sizeof b));
        if (v < c->lo || v > c->hi)
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "%s is out of range (%g..%g)", f, c->lo, c->hi);
        *(double *)at = v;
        return SL_OK;
    }
    case C_NAME: {
        size_t n = strlen(f);
        if (!n || n > MAX_NAME || strspn(f, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.-") != n)
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "'%s' is not a name (1-%d of A-Z a-z 0-9 _ . -)",
                           shown(f, b, sizeof b), MAX_NAME);
        *(const char **)at = f;
        return SL_OK;
    }
    case C_FIG:
        for (int i = 0; i < SL_FIG_COUNT; i++)
            if (!strcmp(f, sl_figure_name((enum sl_figure)i))) {
                *(enum sl_figure *)at = (enum sl_figure)i;
                return SL_OK;
            }
        return sl_fail(d, SL_E_DATA, path, ln, c->name, "unknown figure '%s' (the names of SL_FIGURES, figrec.h)",
                       shown(f, b, sizeof b));
    case C_ROW:
        for (int i = 0; i < SL_MR_COUNT; i++)
            if (!strcmp(f, row_ids[i])) {
                *(enum sl_morais_row *)at = (enum sl_morais_row)i;
                return SL_OK;
            }
        return sl_fail(d, SL_E_DATA, path, ln, c->name, "unknown row '%s' (the names of SL_MORAIS_ROWS, theses.h)",
                       shown(f, b, sizeof b));
    case C_NOTE:
        if (strlen(f) > MAX_NOTE)
            return sl_fail(d, SL_E_DATA, path, ln, c->name, "longer than %d bytes", MAX_NOTE);
        *(const char **)at = *f ? f : NULL;
        return SL_OK;
    }
    return sl_fail(d, SL_E_INTERNAL, path, ln, c->name, "no such column type");
}

/* 1 if rows a and b have the same key */
static int same_key(const struct schema *s, const char *a, const char *b)
{
    for (int c = 0; c < s->ncols; c++) {
        const struct col *k = &s->cols[c];
        if (!k->key)
            continue;
        const char *x = a + k->off, *y = b + k->off;
        switch (k->type) {
        case C_INT:  if (*(const int *)x != *(const int *)y) return 0; break;
        case C_NAME: if (strcmp(*(const char *const *)x, *(const char *const *)y)) return 0; break;
        case C_NOTE: {   /* a free-text key (Hertel's scene names): NULL is the empty text */
            const char *p = *(const char *const *)x, *q = *(const char *const *)y;
            if (strcmp(p ? p : "", q ? q : "")) return 0;
            break;
        }
        case C_FIG:  if (*(const enum sl_figure *)x != *(const enum sl_figure *)y) return 0; break;
        case C_ROW:  if (*(const enum sl_morais_row *)x != *(const enum sl_morais_row *)y) return 0; break;
        default:     break;   /* no key of these types */
        }
    }
    return 1;
}

/* The schema's page column, -1 when it has none. */
static int page_col(const struct schema *s)
{
    for (int c = 0; c < s->ncols; c++)
        if (s->cols[c].type == C_PAGE)
            return c;
    return -1;
}

/* An int column of a row: its table (every schema's first column), its page. */
static int row_int(const char *row, const struct col *c) { return *(const int *)(row + c->off); }

/* A row's page against the first earlier row of its table: a table is on
 * one page, so a second page is a transcription slip. */
static enum sl_err check_page(const struct schema *s, const char *rows, int n, const int *lines, const char *row,
                              const char *path, int ln, struct sl_diag *d)
{
    const int pc = page_col(s);
    if (pc < 0)
        return SL_OK;
    const struct col *tc = &s->cols[0], *p = &s->cols[pc];
    for (int j = 0; j < n; j++) {
        const char *o = rows + (size_t)j * s->size;
        if (row_int(o, tc) != row_int(row, tc))
            continue;
        if (row_int(o, p) == row_int(row, p))
            return SL_OK;
        char a[24] = "no page", b[24] = "no page";
        if (row_int(row, p))
            snprintf(a, sizeof a, "page %d", row_int(row, p));
        if (row_int(o, p))
            snprintf(b, sizeof b, "page %d", row_int(o, p));
        return sl_fail(d, SL_E_DATA, path, ln, p->name, "Table %d is on %s here, on %s at line %d (a table has one "
                       "page)", row_int(row, tc), a, b, lines[j]);
    }
    return SL_OK;
}

static enum sl_err read_all(const char *path, char **buf, size_t *len, struct sl_diag *d)
{
    *buf = NULL;
    FILE *f = fopen(path, "rb");
    if (!f)
        return sl_fail(d, SL_E_IO, path, 0, "", "cannot open: %s", strerror(errno));
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > (off_t)MAX_BYTES) {
        fclose(f);
        return sl_fail(d, SL_E_IO, path, 0, "", "not a regular file of at most %u bytes", MAX_BYTES);
    }
    char *b = malloc((size_t)st.st_size + 1);
    if (!b) {
        fclose(f);
        return sl_fail(d, SL_E_NOMEM, path, 0, "", "%lld bytes", (long long)st.st_size);
    }
    size_t n = fread(b, 1, (size_t)st.st_size + 1, f);
    int bad = ferror(f) || n > (size_t)st.st_size;   /* it grew while read */
    fclose(f);
    if (bad) {
        free(b);
        return sl_fail(d, SL_E_IO, path, 0, "", "read failed");
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return SL_OK;
}

enum sl_err sl_thesis_file_load(enum sl_thesis_kind k, const char *path, struct sl_thesis_file *f, struct sl_diag *d)
{
    memset(f, 0, sizeof *f);
    if ((unsigned)k >= SL_THESIS_NKINDS)
        return sl_fail(d, SL_E_INTERNAL, path, 0, "", "no such thesis file kind %d", (int)k);
    const struct schema *s = &schemas[k];
    char *buf;
    size_t len = 0;
    enum sl_err e = read_all(path, &buf, &len, d);
    if (e)
        return e;
    if (memchr(buf, '\0', len)) {
        int ln = 1;
        for (const char *p = buf; *p; p++)
            ln += *p == '\n';
        free(buf);
        return sl_fail(d, SL_E_DATA, path, ln, "", "a NUL byte");
    }
    /* at most one row a line */
    int cap = 1;
    for (size_t i = 0; i < len; i++)
        cap += buf[i] == '\n';
    char *rows = calloc((size_t)cap + 1, s->size);
    int *lines = malloc((size_t)cap * sizeof *lines);
    if (!rows || !lines) {
        free(rows);
        free(lines);
        free(buf);
        return sl_fail(d, SL_E_NOMEM, path, 0, "", "%d rows", cap);
    }
    int n = 0, header = 0, ln = 0;
    char *p = buf;
    if (len >= 3 && !memcmp(p, "\xEF\xBB\xBF", 3))
        p += 3;   /* a byte-order mark, as a spreadsheet may save one */
    while (!e && *p) {
        ln++;
        char *nl = strchr(p, '\n'), *next = nl ? nl + 1 : p + strlen(p);
        if (nl) {
            *nl = '\0';
            if (nl > p && nl[-1] == '\r')
                nl[-1] = '\0';
        }
        char *line = p;
        p = next;
        if (line[0] == '#')
            continue;
        if (!line[0]) {
            e = sl_fail(d, SL_E_DATA, path, ln, "", "an empty line (a comment starts with '#')");
            break;
        }
        char *field[MAX_COLS + 1];
        int nf = split(line, field, s->ncols + 1, path, ln, s, d);
        if (nf < 0) {
            e = SL_E_DATA;
            break;
        }
        for (int c = 0; c < nf && !e; c++)
            e = check_text(field[c], path, ln, c < s->ncols ? s->cols[c].name : "", d);
        if (e)
            break;
        if (!header) {
            for (int c = 0; c < s->ncols && !e; c++)
                if (c >= nf || strcmp(field[c], s->cols[c].name)) {
                    char b[64];
                    e = sl_fail(d, SL_E_DATA, path, ln, s->cols[c].name, "header: column %d is %s%s%s, expected '%s'",
                                c + 1, c < nf ? "'" : "", c < nf ? shown(field[c], b, sizeof b) : "missing",
                                c < nf ? "'" : "", s->cols[c].name);
                }
            if (!e && nf > s->ncols)
                e = sl_fail(d, SL_E_DATA, path, ln, "", "header: more than the %d columns %s has", s->ncols, s->file);
            header = 1;
            continue;
        }
        if (nf != s->ncols) {
            e = sl_fail(d, SL_E_DATA, path, ln, nf < s->ncols ? s->cols[nf].name : "",
                        "%d fields, the header has %d%s", nf, s->ncols, nf < s->ncols ? " (this column is missing)" : "");
            break;
        }
        char *row = rows + (size_t)n * s->size;
        for (int c = 0; c < nf && !e; c++)
            e = field_value(&s->cols[c], field[c], row, path, ln, d);
        for (int j = 0; j < n && !e; j++)
            if (same_key(s, rows + (size_t)j * s->size, row))
                e = sl_fail(d, SL_E_DATA, path, ln, "", "the same table, place and %s as line %d",
                            k == SL_THESIS_MODERNO ? "figure" : k == SL_THESIS_MORAIS ? "row"
                            : k == SL_THESIS_MODERNO_SCENES || k == SL_THESIS_MODERNO_TABLE15 ? "map size"
                                                                                                : "method",
                            lines[j]);
        if (!e)
            e = check_page(s, rows, n, lines, row, path, ln, d);
        lines[n++] = ln;
    }
    if (!e && !header)
        e = sl_fail(d, SL_E_DATA, path, ln, "", "no header row");
    if (!e && n == 0)
        e = sl_fail(d, SL_E_DATA, path, ln, "", "no rows");
    free(lines);
    if (e) {
        free(rows);
        free(buf);
        return e;
    }
    f->kind = k;
    f->rows = rows;
    f->n = n;
    f->buf = buf;
    return SL_OK;
}

void sl_thesis_file_free(struct sl_thesis_file *f)
{
    if (!f)
        return;
    free(f->rows);
    free(f->buf);
    memset(f, 0, sizeof *f);
}

/* ---- the process's copies ---- */

static struct sl_thesis_file loaded[SL_THESIS_NKINDS];

static enum sl_err get(enum sl_thesis_kind k, const void **rows, int *n, struct sl_diag *d)
{
    struct sl_thesis_file *f = &loaded[k];
    if (!f->rows) {
        char path[1200];
        const char *dir = sl_theses_dir();
        if (snprintf(path, sizeof path, "%s/%s", dir, schemas[k].file) >= (int)sizeof path)
            return sl_fail(d, SL_E_IO, dir, 0, "SHADOWLAB_THESES", "the folder's path is too long");
        enum sl_err e = sl_thesis_file_load(k, path, f, d);
        if (e) {
            *rows = NULL;
            *n = 0;
            return e;
        }
    }
    *rows = f->rows;
    *n = f->n;
    return SL_OK;
}

enum sl_err sl_theses_moderno(const struct sl_thesis_datum **rows, int *n, struct sl_diag *d)
{
    const void *r;
    enum sl_err e = get(SL_THESIS_MODERNO, &r, n, d);
    *rows = r;
    return e;
}

enum sl_err sl_theses_morais(const struct sl_morais_datum **rows, int *n, struct sl_diag *d)
{
    const void *r;
    enum sl_err e = get(SL_THESIS_MORAIS, &r, n, d);
    *rows = r;
    return e;
}

enum sl_err sl_theses_morais_times(const struct sl_morais_time **rows, int *n, struct sl_diag *d)
{
    const void *r;
    enum sl_err e = get(SL_THESIS_MORAIS_TIMES, &r, n, d);
    *rows = r;
    return e;
}

enum sl_err sl_theses_hertel(const struct sl_hertel_row **rows, int *n, struct sl_diag *d)
{
    const void *r;
    enum sl_err e = get(SL_THESIS_HERTEL, &r, n, d);
    *rows = r;
    return e;
}

enum sl_err sl_theses_moderno_scenes(const struct sl_thesis_scene_view **rows, int *n, struct sl_diag *d)
{
    const void *r;
    enum sl_err e = get(SL_THESIS_MODERNO_SCENES, &r, n, d);
    *rows = r;
    return e;
}

enum sl_err sl_theses_moderno_table15(const struct sl_thesis_table15 **rows, int *n, struct sl_diag *d)
{
    const void *r;
    enum sl_err e = get(SL_THESIS_MODERNO_TABLE15, &r, n, d);
    *rows = r;
    return e;
}

int sl_thesis_page(enum sl_thesis_kind k, int table)
{
    const void *rows;
    int n;
    if ((unsigned)k >= SL_THESIS_NKINDS || get(k, &rows, &n, NULL))
        return 0;
    const struct schema *s = &schemas[k];
    const int pc = page_col(s);
    for (int i = 0; i < n && pc >= 0; i++) {
        const char *r = (const char *)rows + (size_t)i * s->size;
        if (row_int(r, &s->cols[0]) == table)
            return row_int(r, &s->cols[pc]);
    }
    return 0;
}

const char *sl_thesis_cite(enum sl_thesis_kind k, int table, char *buf, size_t n)
{
    const int page = sl_thesis_page(k, table);
    if (page)
        snprintf(buf, n, "Table %d, p. %d", table, page);
    else
        snprintf(buf, n, "Table %d", table);
    return buf;
}

void sl_theses_free(void)
{
    for (int k = 0; k < SL_THESIS_NKINDS; k++)
        sl_thesis_file_free(&loaded[k]);
}
