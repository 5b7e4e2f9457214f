/*
 * emit_json.c — a table (tabmodel.h) as one JSON object:
 *   {"id": ..., "title": ..., "intro": ... (where there is one), "columns": [{"name": ..., "key": true|false,
 *    "group": ..., "unit": ...}], "rows": [[...], ...], "blocks": [row, ...],
 *    "note": ...}
 * A key cell is a string; a value cell that is a number as a whole (strtod
 * reads all of it, finite) is a JSON number written as it stands, an empty
 * one null, any other a string. Strings escape '"', '\\' and the control
 * characters (\uXXXX); UTF-8 passes through. Tables of one stream after the
 * first (not o->first) are preceded by ",\n" so that a caller's "[" ... "]"
 * makes an array.
 */
#include "emit.h"
#include <math.h>
#include <stdlib.h>

void sl_emit_json_text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            fprintf(f, "\\%c", ch);
        else if (ch < 0x20)
            fprintf(f, "\\u%04x", ch);
        else
            fputc(ch, f);
    }
    fputc('"', f);
}

/* a JSON number as it stands: an optional '-', digits, an optional
 * fraction and exponent (strtod alone takes "inf", "0x1p3", " 1") */
static int is_number(const char *s)
{
    const char *p = s;
    if (*p == '-')
        p++;
    if (*p < '0' || *p > '9' || (p[0] == '0' && p[1] >= '0' && p[1] <= '9'))
        return 0;
    char *end;
    double v = strtod(s, &end);
    if (*end || !isfinite(v))
        return 0;
    for (; *p; p++)
        if (!((*p >= '0' && *p <= '9') || *p == '.' || *p == 'e' || *p == 'E' || *p == '+' || *p == '-'))
            return 0;
    return 1;
}

int sl_emit_json(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    if (t->oom)
        return -1;
    if (o && !o->first)
        fputs(",\n", f);
    fputs("{\"id\": ", f);
    sl_emit_json_text(f, t->id);
    fputs(", \"title\": ", f);
    sl_emit_json_text(f, t->title);
    if (t->intro && t->intro[0]) {
        fputs(", \"intro\": ", f);
        sl_emit_json_text(f, t->intro);
    }
    fputs(",\n \"columns\": [", f);
    int g = 0, left = t->ngroups ? t->span[0] : 0;
    for (int c = 0; c < t->ncols; c++) {
        fputs(c ? ",\n  {\"name\": " : "\n  {\"name\": ", f);
        sl_emit_json_text(f, t->head[c] ? t->head[c] : "");
        fprintf(f, ", \"key\": %s", c < t->nkeys ? "true" : "false");
        if (t->ngroups && g < t->ngroups && t->group[g][0]) {
            fputs(", \"group\": ", f);
            sl_emit_json_text(f, t->group[g]);
        }
        if (t->unit[c]) {
            fputs(", \"unit\": ", f);
            sl_emit_json_text(f, t->unit[c]);
        }
        fputc('}', f);
        if (t->ngroups && --left == 0 && ++g < t->ngroups)
            left = t->span[g];
    }
    fputs("],\n \"rows\": [", f);
    for (int r = 0; r < t->nrows; r++) {
        fputs(r ? ",\n  [" : "\n  [", f);
        for (int c = 0; c < t->ncols; c++) {
            const char *v = sl_tab_at(t, r, c);
            if (c)
                fputs(", ", f);
            if (c >= t->nkeys && !v[0])
                fputs("null", f);
            else if (c >= t->nkeys && is_number(v))
                fputs(v, f);
            else
                sl_emit_json_text(f, v);
        }
        fputc(']', f);
    }
    fputs("],\n \"blocks\": [", f);
    for (int r = 0, n = 0; r < t->nrows; r++)
        if (t->rule[r] & SL_TAB_BLOCK)
            fprintf(f, "%s%d", n++ ? ", " : "", r);
    fputs("],\n \"note\": ", f);
    sl_emit_json_text(f, t->note);
    fputs("}\n", f);
    return 0;
}
