/*
 * emit_csv.c — a table (tabmodel.h) as CSV (RFC 4180): a header line of the
 * column heads (a column group's name in front of its columns' heads) when
 * the table is the stream's first (o->first; the tables of one stream share
 * its columns), then a line per row. A field holding a comma, a quote or a
 * line break is quoted, its quotes doubled (every field of a column the
 * table quotes: t->quote); an empty cell is an empty field.
 * Title, note, rules and muted rows are not written: CSV is data.
 */
#include "emit.h"
#include <string.h>
#include "util.h"   /* sl_csv_field: RFC 4180 quoting, shared with the run's CSV files */

/* v quoted whether or not it needs it, its quotes doubled */
static void quoted(FILE *f, const char *v)
{
    fputc('"', f);
    for (; *v; v++) {
        if (*v == '"')
            fputc('"', f);
        fputc(*v, f);
    }
    fputc('"', f);
}

int sl_emit_csv(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    if (t->oom)
        return -1;
    if (!o || o->first) {
        int g = 0, left = t->ngroups ? t->span[0] : 0;
        for (int c = 0; c < t->ncols; c++) {
            if (c)
                fputc(',', f);
            if (t->ngroups && g < t->ngroups && t->group[g][0]) {
                char h[400];
                snprintf(h, sizeof h, "%s %s", t->group[g], t->head[c] ? t->head[c] : "");
                sl_csv_field(f, h);
            } else
                sl_csv_field(f, t->head[c] ? t->head[c] : "");
            if (t->ngroups && --left == 0 && ++g < t->ngroups)
                left = t->span[g];
        }
        fputc('\n', f);
    }
    for (int r = 0; r < t->nrows; r++) {
        for (int c = 0; c < t->ncols; c++) {
            if (c)
                fputc(',', f);
            const char *v = sl_tab_at(t, r, c);
            if (t->quote && t->quote[c])
                quoted(f, v);
            else
                sl_csv_field(f, v);
        }
        fputc('\n', f);
    }
    return 0;
}
