/*
 * params.c — see params.h.
 */
#include "params.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "suggest.h"
#include "util.h"

#define NAME_(id, text) text,
const char *const sl_param_type_names[SL_PARAM_TYPE_COUNT] = {SL_PARAM_TYPES(NAME_)};
#undef NAME_

int sl_param_index(const struct sl_param *decl, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(decl[i].name, name))
            return i;
    return -1;
}

const char *sl_param_parse(const struct sl_param *p, const char *s, double *x)
{
    switch (p->type) {
    case SL_PARAM_BOOL:
        if (!strcmp(s, "true") || !strcmp(s, "True") || !strcmp(s, "TRUE")) {
            *x = 1;
            return NULL;
        }
        if (!strcmp(s, "false") || !strcmp(s, "False") || !strcmp(s, "FALSE")) {
            *x = 0;
            return NULL;
        }
        return "is not a bool (true or false)";
    case SL_PARAM_CHOICE:
        for (int i = 0; i < SL_PARAM_CHOICES && p->choice[i][0]; i++)
            if (!strcmp(s, p->choice[i])) {
                *x = i;
                return NULL;
            }
        return "is not one of its words";
    case SL_PARAM_INT: {
        const char *t = s + (*s == '+' || *s == '-');
        if (!*t || (t[0] == '0' && t[1]))
            return "is not a whole number (decimal digits)";
        for (const char *q = t; *q; q++)
            if (*q < '0' || *q > '9')
                return "is not a whole number (decimal digits)";
        errno = 0;
        long long v = strtoll(s, NULL, 10);
        if (errno || v < -(1ll << 32) || v > (1ll << 32))
            return "is outside the range of a 32-bit int";
        *x = (double)v;
        return NULL;
    }
    case SL_PARAM_FLOAT:
    default: {
        char *end;
        errno = 0;
        double v = strtod(s, &end);
        if (end == s || *end || errno == ERANGE || !isfinite(v))
            return "is not a finite float";
        if (fabs(v) > 3.4e38)
            return "is outside the range of a 32-bit float";
        *x = v;
        return NULL;
    }
    }
}

void sl_param_text(const struct sl_param *p, double x, char *buf, size_t n)
{
    if (p->type == SL_PARAM_BOOL)
        snprintf(buf, n, "%s", x != 0.0 ? "true" : "false");
    else if (p->type == SL_PARAM_CHOICE)
        snprintf(buf, n, "%s", x >= 0 && x < SL_PARAM_CHOICES ? p->choice[(int)x] : "?");
    else if (p->type == SL_PARAM_INT)
        snprintf(buf, n, "%.0f", x);
    else
        snprintf(buf, n, "%.9g", x);
}

void sl_param_range_text(const struct sl_param *p, char *buf, size_t n)
{
    buf[0] = '\0';
    if (p->type == SL_PARAM_BOOL)
        return;
    if (p->type == SL_PARAM_CHOICE) {
        for (int i = 0; i < SL_PARAM_CHOICES && p->choice[i][0]; i++)
            sl_known_add(buf, n, p->choice[i]);
        return;
    }
    char lo[32] = "-inf", hi[32] = "inf";
    if (p->has_min)
        snprintf(lo, sizeof lo, "%.10g", p->min);
    if (p->has_max)
        snprintf(hi, sizeof hi, "%.10g", p->max);
    snprintf(buf, n, "%s%s, %s%s", p->has_min ? "[" : "(", lo, hi, p->has_max ? "]" : ")");
}

void sl_params_init(struct sl_params *s, const struct sl_param *decl, int n)
{
    memset(s, 0, sizeof *s);
    s->decl = decl;
    s->n = n < SL_PARAM_MAX ? n : SL_PARAM_MAX;
    for (int i = 0; i < s->n; i++)
        s->v[i] = decl[i].def;
}

static void known_names(const struct sl_params *s, char *buf, size_t n)
{
    buf[0] = '\0';
    for (int i = 0; i < s->n; i++)
        sl_known_add(buf, n, s->decl[i].name);
    if (!s->n)
        snprintf(buf, n, "none");
}

enum sl_err sl_params_put(struct sl_params *s, const char *name, double x, struct sl_diag *d)
{
    int i = sl_param_index(s->decl, s->n, name);
    if (i < 0) {
        char known[512], hint[96];
        struct sl_suggest sg;
        known_names(s, known, sizeof known);
        sl_suggest_init(&sg, name);
        for (int k = 0; k < s->n; k++)
            sl_suggest_add(&sg, s->decl[k].name);
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "no parameter '%s'%s (it has: %s)", name,
                       sl_suggest_text(&sg, hint, sizeof hint), known);
    }
    const struct sl_param *p = &s->decl[i];
    if (!isfinite(x))
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "not a finite number");
    if (p->type == SL_PARAM_BOOL && x != 0.0 && x != 1.0)
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "%g: a bool is true or false", x);
    if ((p->type == SL_PARAM_INT || p->type == SL_PARAM_CHOICE) && x != floor(x))
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "%g: an int is a whole number", x);
    if (p->type == SL_PARAM_CHOICE) {
        int nc = 0;
        while (nc < SL_PARAM_CHOICES && p->choice[nc][0])
            nc++;
        if (x < 0 || x >= nc) {
            char words[160];
            sl_param_range_text(p, words, sizeof words);
            return sl_fail(d, SL_E_METHOD, NULL, 0, name, "choice %g: one of %s", x, words);
        }
    } else if ((p->has_min && x < p->min) || (p->has_max && x > p->max) ||
               /* an int without a bound on a side is a 32-bit int on that side (a GLSL int) */
               (p->type == SL_PARAM_INT && ((!p->has_min && x < -2147483648.0) || (!p->has_max && x > 2147483647.0)))) {
        char range[80];
        sl_param_range_text(p, range, sizeof range);
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "%.10g is outside %s%s%s", x, range, p->unit[0] ? " " : "",
                       p->unit);
    }
    s->v[i] = x;
    s->given |= 1u << i;
    return SL_OK;
}

enum sl_err sl_params_put_text(struct sl_params *s, const char *name, const char *text, struct sl_diag *d)
{
    int i = sl_param_index(s->decl, s->n, name);
    if (i < 0)
        return sl_params_put(s, name, 0, d);   /* names the parameters there are */
    const struct sl_param *p = &s->decl[i];
    double x;
    const char *why = sl_param_parse(p, text, &x);
    if (why) {
        if (p->type == SL_PARAM_CHOICE) {
            char words[160];
            sl_param_range_text(p, words, sizeof words);
            return sl_fail(d, SL_E_METHOD, NULL, 0, name, "'%s': one of %s", text, words);
        }
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "'%s' %s", text, why);
    }
    return sl_params_put(s, name, x, d);
}

double sl_params_get(const struct sl_params *s, const char *name)
{
    int i = sl_param_index(s->decl, s->n, name);
    return i < 0 ? NAN : s->v[i];
}

int sl_params_given(const struct sl_params *s, const char *name)
{
    int i = sl_param_index(s->decl, s->n, name);
    return i >= 0 && (s->given >> i & 1u);
}

void sl_params_derive(struct sl_params *s, const char *name, double x)
{
    int i = sl_param_index(s->decl, s->n, name);
    if (i >= 0)
        s->v[i] = x;
}

enum sl_err sl_params_off(struct sl_params *s, const char *name, const char *when, struct sl_diag *d)
{
    int i = sl_param_index(s->decl, s->n, name);
    if (i < 0)
        return SL_OK;
    if (s->given >> i & 1u)
        return sl_fail(d, SL_E_METHOD, NULL, 0, name, "%s applies to %s", name, when);
    s->off |= 1u << i;
    return SL_OK;
}
