/*
 * tex.h — LaTeX text and numbers: what the run's tables, the pivots and the
 * report write into .tex files, in one place (table.c and pivot.c both use
 * it; neither calls the other for it).
 */
#ifndef SL_TEX_H
#define SL_TEX_H
#include <stddef.h>
#include <stdio.h>

/* s (UTF-8) as LaTeX text: the ten specials escaped; every non-ASCII code
 * point as LaTeX reads it (signs and symbols, Greek, accented letters by
 * their decomposition) or, with no LaTeX form, as a visible \textsf{[U+XXXX]};
 * never '?' (emit_tex.c). */
void sl_tex_text(FILE *f, const char *s);

/* v with dec decimals as LaTeX: thousands separated by thin spaces (\,), a
 * real minus sign, "--" for NaN. */
void sl_tex_number(char *out, size_t n, double v, int dec);

/* Width estimates (pt) for tables that must fit at 100%, never scaled: the
 * plain text (no LaTeX markup) s at \small in a 10 pt article (9 pt Computer
 * Modern: digits 4.5 pt, lower case about as wide, capitals and m/w wider).
 * A number's thousands separators add a thin space each. At \footnotesize
 * multiply by SL_TEX_FOOTNOTE. */
#define SL_TEX_COLUMNWIDTH 345.0   /* a plain A4 article's \columnwidth */
#define SL_TEX_BUDGET      335.0   /* what a table may fill: the estimate is rough */
#define SL_TEX_FOOTNOTE    (8.0 / 9.0)
#define SL_TEX_SLACK       1.06    /* low for parentheses, '/' and T1's '_': a margin where a box must not overflow */
double sl_tex_text_pt(const char *s);
double sl_tex_number_pt(const char *plain);

#endif
