/*
 * emit_html.c — a table (tabmodel.h) as an HTML table inside
 * <div class="tab">: the title as its <caption>, the column groups as a
 * row of spanning heads (class "grp" where named), key cells of class "k",
 * a block's first row of class "blk", a muted row "muted", a text table
 * (t->wrap) of class "wrap"; under it a paragraph of class "note" with the
 * note and the companion file (o->link: linked, or named when the page must
 * refer to nothing outside); the intro, where there is one, is a paragraph
 * of class "intro" before the table. Every text is escaped (& < > " ').
 */
#include "emit.h"

void sl_emit_html_text(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default: fputc(*s, f);
        }
    }
}

int sl_emit_html(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    static const struct sl_emit_opts none = {0};
    if (t->oom)
        return -1;
    o = o ? o : &none;
    if (t->intro && t->intro[0]) {
        fputs("<p class=\"intro\">", f);
        sl_emit_html_text(f, t->intro);
        fputs("</p>\n", f);
    }
    fputs(t->wrap ? "<div class=\"tab\"><table class=\"wrap\">\n<caption>" : "<div class=\"tab\"><table>\n<caption>", f);
    sl_emit_html_text(f, t->title);
    fputs("</caption>\n<thead>\n", f);
    if (t->ngroups) {
        fputs("<tr>", f);
        for (int g = 0; g < t->ngroups; g++) {
            fprintf(f, "<th colspan=\"%d\"%s>", t->span[g], t->group[g][0] ? " class=\"grp\"" : "");
            sl_emit_html_text(f, t->group[g]);
            fputs("</th>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("<tr>", f);
    for (int c = 0; c < t->ncols; c++) {
        fputs(c < t->nkeys ? "<th class=\"k\">" : "<th>", f);
        sl_emit_html_text(f, t->head[c] ? t->head[c] : "");
        fputs("</th>", f);
    }
    fputs("</tr>\n</thead>\n<tbody>\n", f);
    for (int r = 0; r < t->nrows; r++) {
        static const char *const tr[4] = {"<tr>", "<tr class=\"blk\">", "<tr class=\"muted\">",
                                          "<tr class=\"blk muted\">"};
        fputs(tr[t->rule[r] & 3], f);
        for (int c = 0; c < t->ncols; c++) {
            fputs(c < t->nkeys ? "<td class=\"k\">" : "<td>", f);
            sl_emit_html_text(f, sl_tab_at(t, r, c));
            fputs("</td>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("</tbody>\n</table>\n<p class=\"note\">", f);
    if (sl_tab_has_note(t)) {
        sl_emit_html_text(f, t->note);
        fputc(' ', f);
    }
    if (o->link && o->link_named) {
        fputs("LaTeX: <code>", f);
        sl_emit_html_text(f, o->link);
        fputs("</code>", f);
    } else if (o->link) {
        fputs("<a href=\"", f);
        sl_emit_html_text(f, o->link);
        fputs("\">LaTeX</a>", f);
    }
    fputs("</p></div>\n", f);
    return 0;
}
