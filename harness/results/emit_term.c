/*
 * emit_term.c — a table (tabmodel.h) for a terminal: the title and the
 * intro as lines of their own, the heads and then a line per row in columns
 * of fixed widths (t->termw; 0: the column's widest cell), one space
 * between them, keys (and left-aligned columns) padded on the right, values
 * on the left; the last column is never padded. A verdict column (t->verdict)
 * is coloured when the caller asks (o->color: a TTY and no NO_COLOR): an
 * alert row's bold red, the others green. The note follows after a blank
 * line. Nothing is escaped: a terminal shows text as it is. Widths count
 * code points (UTF-8), not bytes, so a name with an accent keeps its column.
 */
#include "emit.h"
#include <stdlib.h>
#include <string.h>

/* code points of UTF-8 s: the bytes that do not continue a sequence */
static int width_of(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += ((unsigned char)*s & 0xC0) != 0x80;
    return n;
}

static const char *cell_of(const struct sl_tab *t, int r, int c)
{
    return r < 0 ? (t->head[c] ? t->head[c] : "") : sl_tab_at(t, r, c);
}

static void line(FILE *f, const struct sl_tab *t, const int *w, int r, int color)
{
    for (int c = 0; c < t->ncols; c++) {
        const char *v = cell_of(t, r, c);
        int last = c == t->ncols - 1, pad = last ? 0 : w[c] - width_of(v);
        if (c)
            fputc(' ', f);
        if (!sl_tab_left(t, c))
            for (int k = 0; k < pad; k++)
                fputc(' ', f);
        int paint = color && r >= 0 && t->verdict && last;
        if (paint)
            fputs(t->rule[r] & SL_TAB_ALERT ? "\033[1;31m" : "\033[32m", f);
        fputs(v, f);
        if (paint)
            fputs("\033[0m", f);
        if (sl_tab_left(t, c))
            for (int k = 0; k < pad; k++)
                fputc(' ', f);
    }
    fputc('\n', f);
}

int sl_emit_term(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    if (t->oom)
        return -1;
    int *w = calloc((size_t)t->ncols, sizeof *w);
    if (!w)
        return -1;
    for (int c = 0; c < t->ncols; c++) {
        w[c] = c < SL_TAB_MAXCOLS ? t->termw[c] : 0;
        for (int r = -1; r < t->nrows && !(c < SL_TAB_MAXCOLS && t->termw[c]); r++) {
            int x = width_of(cell_of(t, r, c));
            w[c] = x > w[c] ? x : w[c];
        }
    }
    if (t->title[0])
        fprintf(f, "%s\n\n", t->title);
    if (t->intro && t->intro[0])
        fprintf(f, "%s\n\n", t->intro);
    for (int r = -1; r < t->nrows; r++)
        line(f, t, w, r, o && o->color);
    if (sl_tab_has_note(t))
        fprintf(f, "\n%s\n", t->note);
    free(w);
    return 0;
}
