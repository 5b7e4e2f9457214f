/*
 * emit_md.c — a table (tabmodel.h) as a GitHub/CommonMark pipe table.
 *
 * The title (where there is one): a bold line (level 0, the report's) or a
 * heading of its level ("## title"), then the intro as a paragraph.
 * Markdown has no spanning cells: a column group's name goes in front of
 * each of its columns' heads. Keys are left aligned, values
 * right aligned ("---:"), unless the table aligns a column itself. Under the
 * table: the note and the link, then a blank line (none where the stream
 * ends: o->tight); a table with neither ends at its last row, so the next
 * one asks for a blank line before it (o->gap). Text is escaped
 * (CommonMark punctuation, a line break as a space) unless the table is
 * plain (t->plain: names and numbers as they are; an empty cell "| |", or
 * in a padded table's rows "|  |"). A verdict column's cell of an alert row
 * is bold.
 */
#include "emit.h"
#include <string.h>

void sl_emit_md_text(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        if (strchr("\\`*_[]<>|#!", *s))
            fputc('\\', f);
        if (*s == '\n')
            fputc(' ', f);
        else
            fputc(*s, f);
    }
}

static void text(FILE *f, const struct sl_tab *t, const char *s)
{
    if (t->plain)
        fputs(s, f);
    else
        sl_emit_md_text(f, s);
}

/* " v |"; plain and empty: " |" (a row's cell of a padded table: "  |");
 * bold: " **v** |" */
static void cell(FILE *f, const struct sl_tab *t, const char *pre, const char *v, int head, int bold)
{
    fputc(' ', f);
    if (pre) {
        text(f, t, pre);
        fputc(' ', f);
    }
    if (t->plain && !pre && !v[0] && (head || !t->padded)) {
        fputc('|', f);
        return;
    }
    fputs(bold ? "**" : "", f);
    text(f, t, v);
    fputs(bold ? "** |" : " |", f);
}

int sl_emit_md(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    static const struct sl_emit_opts none = {0};
    if (t->oom)
        return -1;
    o = o ? o : &none;
    int under = sl_tab_has_note(t) || o->link;
    if (o->gap)
        fputc('\n', f);
    if (t->title[0]) {
        if (t->level > 0) {
            for (int k = 0; k < t->level; k++)
                fputc('#', f);
            fputc(' ', f);
            text(f, t, t->title);
            fputs("\n\n", f);
        } else {
            fputs("**", f);
            text(f, t, t->title);
            fputs("**\n\n", f);
        }
    }
    if (t->intro && t->intro[0]) {
        text(f, t, t->intro);
        fputs("\n\n", f);
    }
    fputc('|', f);
    int g = 0, left = t->ngroups ? t->span[0] : 0;
    for (int c = 0; c < t->ncols; c++) {
        const char *grp = t->ngroups && g < t->ngroups && t->group[g][0] ? t->group[g] : NULL;
        cell(f, t, grp, t->head[c] ? t->head[c] : "", 1, 0);
        if (t->ngroups && --left == 0 && ++g < t->ngroups)
            left = t->span[g];
    }
    fputs("\n|", f);
    for (int c = 0; c < t->ncols; c++)
        fputs(sl_tab_left(t, c) ? "---|" : "---:|", f);
    fputc('\n', f);
    for (int r = 0; r < t->nrows; r++) {
        fputc('|', f);
        for (int c = 0; c < t->ncols; c++)
            cell(f, t, NULL, sl_tab_at(t, r, c), 0,
                 t->verdict && c == t->ncols - 1 && (t->rule[r] & SL_TAB_ALERT));
        fputc('\n', f);
    }
    if (!under)
        return 0;
    fputc('\n', f);
    if (sl_tab_has_note(t))
        text(f, t, t->note);
    if (o->link) {
        if (sl_tab_has_note(t))
            fputc(' ', f);
        fprintf(f, "[LaTeX](%s)", o->link);
    }
    fputs(o->tight ? "\n" : "\n\n", f);
    return 0;
}
