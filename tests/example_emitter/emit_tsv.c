/*
 * emit_tsv.c — a table (tabmodel.h) as tab-separated values: the column
 * heads (on the stream's first table), then a line per row. TSV has no
 * quoting: a tab or a line break inside a cell becomes a space. The title,
 * the note and the rules are not written.
 */
#include "emit.h"

static void field(FILE *f, const char *s)
{
    for (; *s; s++)
        fputc(*s == '\t' || *s == '\n' || *s == '\r' ? ' ' : *s, f);
}

int sl_emit_tsv(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    if (t->oom)
        return -1;
    for (int r = o && !o->first ? 0 : -1; r < t->nrows; r++) {
        for (int c = 0; c < t->ncols; c++) {
            if (c)
                fputc('\t', f);
            field(f, r < 0 ? (t->head[c] ? t->head[c] : "") : sl_tab_at(t, r, c));
        }
        fputc('\n', f);
    }
    return 0;
}
