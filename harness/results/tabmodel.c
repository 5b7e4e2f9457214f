/*
 * tabmodel.c — see tabmodel.h. Invariant: cell has nrows * ncols slots and
 * rule nrows flags; a row's slots are NULL until a cell is set.
 */
#include "tabmodel.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "util.h"

void sl_tab_slug(const char *s, char *buf, size_t n)
{
    size_t k = 0;
    for (; s && *s && k + 1 < n; s++) {
        char c = *s;
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                 c == '-' || c == '.';
        buf[k++] = ok ? c : '-';
    }
    if (k > 0 && buf[0] == '.')
        buf[0] = '-';
    if (k == 0 && n > 1)
        buf[k++] = '-';
    if (n)
        buf[k < n ? k : n - 1] = '\0';
}

void sl_tab_init(struct sl_tab *t, const char *id, int ncols, int nkeys, const char *fmt, ...)
{
    memset(t, 0, sizeof *t);
    sl_tab_slug(id, t->id, sizeof t->id);
    t->ncols = ncols < 1 ? 1 : ncols;
    t->nkeys = nkeys;
    t->head = calloc((size_t)t->ncols, sizeof *t->head);
    t->unit = calloc((size_t)t->ncols, sizeof *t->unit);
    t->align = calloc((size_t)t->ncols, 1);
    t->quote = calloc((size_t)t->ncols, 1);
    t->oom = !t->head || !t->unit || !t->align || !t->quote;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->title, sizeof t->title, fmt, ap);
    va_end(ap);
}

void sl_tab_head(struct sl_tab *t, int col, const char *fmt, ...)
{
    if (t->oom || col < 0 || col >= t->ncols)
        return;
    va_list ap;
    va_start(ap, fmt);
    free(t->head[col]);
    t->head[col] = sl_vformat(fmt, ap);
    va_end(ap);
    t->oom |= !t->head[col];
}

void sl_tab_unit(struct sl_tab *t, int col, const char *unit)
{
    if (t->oom || col < 0 || col >= t->ncols || !unit)
        return;
    free(t->unit[col]);
    size_t n = strlen(unit) + 1;
    t->unit[col] = malloc(n);
    if (t->unit[col])
        memcpy(t->unit[col], unit, n);
    t->oom |= !t->unit[col];
}

void sl_tab_align(struct sl_tab *t, int col, char lr)
{
    if (!t->oom && col >= 0 && col < t->ncols && (lr == 'l' || lr == 'r'))
        t->align[col] = lr;
}

void sl_tab_quote(struct sl_tab *t, int col)
{
    if (!t->oom && col >= 0 && col < t->ncols)
        t->quote[col] = 1;
}

int sl_tab_left(const struct sl_tab *t, int c)
{
    return t->align && t->align[c] ? t->align[c] == 'l' : c < t->nkeys;
}

void sl_tab_group(struct sl_tab *t, int span, const char *fmt, ...)
{
    if (t->ngroups >= SL_TAB_MAXCOLS)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->group[t->ngroups], sizeof t->group[0], fmt, ap);
    va_end(ap);
    t->span[t->ngroups++] = span;
}

void sl_tab_row(struct sl_tab *t, int block)
{
    if (t->oom)
        return;
    if (t->nrows == t->cap) {
        int cap = t->cap ? 2 * t->cap : 16;
        char **c = realloc(t->cell, (size_t)cap * (size_t)t->ncols * sizeof *c);
        if (!c) {
            t->oom = 1;
            return;
        }
        t->cell = c;
        unsigned char *r = realloc(t->rule, (size_t)cap);
        if (!r) {
            t->oom = 1;
            return;
        }
        t->rule = r;
        t->cap = cap;
    }
    for (int k = 0; k < t->ncols; k++)
        t->cell[(size_t)t->nrows * (size_t)t->ncols + (size_t)k] = NULL;
    t->rule[t->nrows] = (unsigned char)(block && t->nrows > 0 ? SL_TAB_BLOCK : 0);
    t->nrows++;
}

void sl_tab_muted(struct sl_tab *t)
{
    if (t->nrows > 0 && !t->oom)
        t->rule[t->nrows - 1] |= SL_TAB_MUTED;
}

void sl_tab_alert(struct sl_tab *t)
{
    if (t->nrows > 0 && !t->oom)
        t->rule[t->nrows - 1] |= SL_TAB_ALERT;
}

void sl_tab_cell(struct sl_tab *t, int col, const char *fmt, ...)
{
    if (t->oom || t->nrows == 0 || col < 0 || col >= t->ncols)
        return;
    char **slot = &t->cell[(size_t)(t->nrows - 1) * (size_t)t->ncols + (size_t)col];
    va_list ap;
    va_start(ap, fmt);
    free(*slot);
    *slot = sl_vformat(fmt, ap);
    va_end(ap);
    t->oom |= !*slot;
}

void sl_tab_intro(struct sl_tab *t, const char *text)
{
    free(t->intro);
    t->intro = NULL;
    if (!text)
        return;
    size_t n = strlen(text) + 1;
    t->intro = malloc(n);
    if (t->intro)
        memcpy(t->intro, text, n);
    t->oom |= !t->intro;
}

void sl_tab_notef(struct sl_tab *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    free(t->note);
    t->note = sl_vformat(fmt, ap);
    va_end(ap);
    t->oom |= !t->note;
}

void sl_tab_note_cat(struct sl_tab *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *more = sl_vformat(fmt, ap);
    va_end(ap);
    size_t n = t->note ? strlen(t->note) : 0, m = more ? strlen(more) : 0;
    char *s = more ? realloc(t->note, n + m + 1) : NULL;
    if (!s) {
        free(more);
        t->oom = 1;
        return;
    }
    memcpy(s + n, more, m + 1);
    t->note = s;
    free(more);
}

int sl_tab_has_note(const struct sl_tab *t) { return t->note && t->note[0]; }

void sl_tab_free(struct sl_tab *t)
{
    for (int k = 0; k < t->ncols; k++) {
        free(t->head ? t->head[k] : NULL);
        free(t->unit ? t->unit[k] : NULL);
    }
    free(t->head);
    free(t->unit);
    free(t->align);
    free(t->quote);
    for (size_t i = 0; t->cell && i < (size_t)t->nrows * (size_t)t->ncols; i++)
        free(t->cell[i]);
    free(t->cell);
    free(t->rule);
    free(t->note);
    free(t->intro);
    memset(t, 0, sizeof *t);
}

const char *sl_tab_at(const struct sl_tab *t, int r, int c)
{
    const char *s = t->cell[(size_t)r * (size_t)t->ncols + (size_t)c];
    return s ? s : "";
}

void sl_tab_number(char *out, size_t n, double v, int dec)
{
    if (isnan(v)) {
        snprintf(out, n, "\xE2\x80\x93");
        return;
    }
    char raw[64];
    snprintf(raw, sizeof raw, "%.*f", dec, fabs(v));
    /* a value that rounds to zero has no sign */
    int zero = strspn(raw, "0.") == strlen(raw);
    size_t o = (size_t)snprintf(out, n, "%s", v < 0 && !zero ? "\xE2\x88\x92" : "");
    const char *dot = strchr(raw, '.');
    size_t ilen = dot ? (size_t)(dot - raw) : strlen(raw);
    for (size_t i = 0; i < ilen && o + 8 < n; i++) {
        if (i > 0 && (ilen - i) % 3 == 0 && ilen >= 4)
            o += (size_t)snprintf(out + o, n - o, "\xE2\x80\x89");
        out[o++] = raw[i];
    }
    if (o < n)
        out[o] = '\0';
    if (dot && o < n)
        snprintf(out + o, n - o, "%s", dot);
}

int sl_tab_sig_decimals(double v, int dec)
{
    if (!isfinite(v) || v == 0.0 || dec <= 0)
        return dec > 0 && v == 0.0 ? 0 : dec;
    int d = 1 - (int)floor(log10(fabs(v)));
    d = d > dec ? d : dec;
    return d < SL_TAB_SIG_MAXDEC ? d : SL_TAB_SIG_MAXDEC;
}

void sl_tab_sig(char *out, size_t n, double v, int dec)
{
    sl_tab_number(out, n, v, sl_tab_sig_decimals(v, dec));
}
