/*
 * tabmodel.h — the one table model every table writer builds: a grid of
 * strings (rows x columns; the first nkeys columns are keys, left aligned,
 * the others values, right aligned), its column heads and optional column
 * groups (a row of spanning heads above them), rules before a block of rows,
 * rows set back (muted), a caption (title), a label (id), a paragraph
 * between the title and the table (intro), a note under it,
 * and optionally a unit per column. An emitter (emit.h: one file per
 * format) writes it; the writer never writes a format's syntax itself.
 *
 * Cells are plain UTF-8 text as a reader sees it ("512²", "12.50 (3.1%)",
 * "–"): each emitter escapes it for its format (Markdown's punctuation,
 * HTML's entities, LaTeX's specials and non-ASCII signs, CSV's quotes,
 * JSON's string escapes), so a writer formats its numbers once.
 *
 * Owns: its strings (free with sl_tab_free). Does not: write anything, know
 * any format. A failed allocation is remembered (oom) and makes every later
 * call a no-op; emitters refuse such a table.
 */
#ifndef SL_TABMODEL_H
#define SL_TABMODEL_H
#include <stddef.h>

/* Column groups a table may have; LaTeX lays out at most this many columns
 * (emit_tex.c refuses a wider table), the other formats any number. */
#define SL_TAB_MAXCOLS 64

/* rule[] flags of a row */
enum { SL_TAB_BLOCK = 1, SL_TAB_MUTED = 2, SL_TAB_ALERT = 4 };

struct sl_tab {
    char  id[256];          /* its label: a slug (letters, digits, '.', '_', '-') */
    char  title[1536];      /* its caption (a pivot's names its figure, aggregate and every --where) */
    char *intro;            /* a paragraph between the title and the table (a view's counts); NULL: none */
    char *note;             /* printed under it; NULL: none */
    int   ncols, nkeys;     /* the first nkeys columns are keys (left aligned) */
    int   wrap;             /* long cells may wrap (text tables): HTML class, LaTeX \parbox */
    int   level;            /* 0: the title is the table's caption; k > 0: a heading of level k (Markdown "##") */
    int   plain;            /* cells are names and numbers written as they are in Markdown (no escapes; an empty
                             * cell as "| |"): the run's tables, whose Markdown predates the model */
    int   padded;           /* plain Markdown: a row's empty cell as "|  |", padded like the others (check's
                             * table of what moved, as CI logs have it); an empty head stays "| |" */
    int   verdict;          /* the last column is a row's verdict ("ok", "FAIL"): an SL_TAB_ALERT row's is
                             * bold in Markdown, bold red in a terminal (o->color; the others green) */
    char **head;            /* ncols heads; NULL = empty */
    char **unit;            /* ncols units; NULL: none (JSON's columns name it) */
    char  *align;           /* ncols: 'l' or 'r'; 0: by nkeys (keys left, values right) */
    char  *quote;           /* ncols: CSV, 1: every field of the column quoted, not only those that need it
                             * (costs.csv's machine, as scripts that read the file have always had it) */
    int   ngroups;          /* optional row above the header: spans over columns */
    char  group[SL_TAB_MAXCOLS][64];
    int   span[SL_TAB_MAXCOLS];
    int   nrows, cap;
    char **cell;            /* nrows * ncols; NULL = empty */
    unsigned char *rule;    /* SL_TAB_BLOCK: a block starts at this row; SL_TAB_MUTED: a row set back
                             * (grey in HTML: the thesis's numbers under ours); SL_TAB_ALERT: a row that
                             * fails (its verdict) */
    int   termw[SL_TAB_MAXCOLS];   /* terminal: a column's width in characters (a longer cell runs over);
                             * 0: its widest cell; the last column is never padded */
    int   paged;            /* LaTeX: a table longer than a page, laid out by its writer (as fixed): floats
                             * of a page of rows each, its heads on every one, the later ones numbered as
                             * the first with "(continued)" (a longtable fails in a two-column class) */
    int   nolabel;          /* LaTeX: no \label (a table nothing refers to) */
    int   fixed;            /* LaTeX: one float laid out by its writer, not fitted to the line: nothing
                             * stacked or split; a cell (not a head) wrapped only in its column's parbox */
    double parbox[SL_TAB_MAXCOLS];  /* LaTeX, fixed: the width (pt) of a ragged \parbox around the column's
                             * cells that are not empty; 0: none */
    double fold[SL_TAB_MAXCOLS];    /* LaTeX, fixed or paged: a cell estimated wider than this (pt, tex.h)
                             * set in a ragged \parbox[t] of this width, a break allowed after '_', '-'
                             * and '/' (the pivots' long row names); 0: none */
    int   small;            /* LaTeX, fixed or paged: at \small with LaTeX's own \tabcolsep (the pivots,
                             * whose writer estimates their widths so), not \footnotesize with 4 pt */
    int   squares;          /* LaTeX: a number squared ("512²") in math, $512^2$, not 512\textsuperscript{2} */
    int   stack;            /* LaTeX, fixed: a value cell "v (where)" as two lines, v above "(where)" */
    int   code;             /* LaTeX, fixed: a `span` of the note in backquotes is code, \texttt */
    int   oom;
};

/* "a b/c" -> "a-b-c": letters, digits, '.', '_' and '-' only; never empty,
 * never starting with '.'. */
void sl_tab_slug(const char *s, char *buf, size_t n);

/* A table of ncols columns (at least 1) whose first nkeys are keys; id is
 * slugged; the title is printf-formatted. */
void sl_tab_init(struct sl_tab *t, const char *id, int ncols, int nkeys, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
void sl_tab_head(struct sl_tab *t, int col, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void sl_tab_unit(struct sl_tab *t, int col, const char *unit);
void sl_tab_align(struct sl_tab *t, int col, char lr);   /* 'l' or 'r' */
void sl_tab_quote(struct sl_tab *t, int col);            /* CSV: quote every field of the column */
/* Whether column c is left aligned: its align, else whether it is a key. */
int sl_tab_left(const struct sl_tab *t, int c);
void sl_tab_group(struct sl_tab *t, int span, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
void sl_tab_row(struct sl_tab *t, int block);   /* block: a rule before it */
void sl_tab_muted(struct sl_tab *t);            /* the last row started: set back */
void sl_tab_alert(struct sl_tab *t);            /* the last row started: it fails */
void sl_tab_cell(struct sl_tab *t, int col, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The intro: a copy of text (NULL: none). */
void sl_tab_intro(struct sl_tab *t, const char *text);
/* The note: set (notef) or appended to as it is (note_cat); printf-formatted. */
void sl_tab_notef(struct sl_tab *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void sl_tab_note_cat(struct sl_tab *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* 1 if the table has a note that is not empty. */
int sl_tab_has_note(const struct sl_tab *t);
void sl_tab_free(struct sl_tab *t);

/* v with dec decimals as a reader reads it, for a cell: the thousands (of
 * four digits or more) split by thin spaces (U+2009), a minus sign (U+2212)
 * unless it rounds to zero, an en dash (U+2013) for NaN. LaTeX writes them
 * as \, and $-$ and --, sl_tex_number's forms. */
void sl_tab_number(char *out, size_t n, double v, int dec);

/* v for a paper's table (sl_tab_number's signs): an exact zero as "0"; a
 * value that dec decimals would show with fewer than two significant
 * digits with as many more as give it two (dec 2: 0.0034 stays 0.0034, not
 * 0.00; 0.05 is 0.050), at most SL_TAB_SIG_MAXDEC; counts (dec 0) as they
 * are. A column of such numbers mixes decimals; that is the choice: a small
 * error that 0.00 hides is a claim the table would get wrong, a ragged
 * column is not. sl_tab_sig_decimals: the decimals it writes v with. */
#define SL_TAB_SIG_MAXDEC 8
void sl_tab_sig(char *out, size_t n, double v, int dec);
int  sl_tab_sig_decimals(double v, int dec);

/* Cell r, c ("" when empty). */
const char *sl_tab_at(const struct sl_tab *t, int r, int c);

#endif
