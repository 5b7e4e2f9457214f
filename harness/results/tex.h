/*
 * tex.h — LaTeX text and numbers: what the run's tables, the pivots and the
 * report write into .tex files, in one place (table.c and pivot.c both use
 * it; neither calls the other for it).
 */
#ifndef SL_TEX_H
#define SL_TEX_H
#include <stddef.h>
#include <stdio.h>

/* s as LaTeX text: the ten specials escaped, and the few non-ASCII signs
 * shadowlab writes (², ×, –, →) as LaTeX. */
void sl_tex_text(FILE *f, const char *s);

/* v with dec decimals as LaTeX: thousands separated by thin spaces (\,), a
 * real minus sign, "--" for NaN. */
void sl_tex_number(char *out, size_t n, double v, int dec);

#endif
