/*
 * suggest.c — see suggest.h. Three rows of the distance matrix (the swap
 * looks two back); no allocation.
 */
#include "suggest.h"
#include <ctype.h>
#include <stdio.h>
#include <string.h>

enum { WMAX = 63, FAR = 1000 };

int sl_edit_distance(const char *a, const char *b)
{
    size_t na = strlen(a), nb = strlen(b);
    if (na > WMAX || nb > WMAX)
        return FAR;
    int r0[WMAX + 1], r1[WMAX + 1], r2[WMAX + 1];
    int *pp = r0, *p = r1, *c = r2;   /* rows i-2, i-1, i */
    for (size_t j = 0; j <= nb; j++)
        p[j] = (int)j;
    for (size_t i = 1; i <= na; i++) {
        c[0] = (int)i;
        int ai = tolower((unsigned char)a[i - 1]);
        for (size_t j = 1; j <= nb; j++) {
            int bj = tolower((unsigned char)b[j - 1]);
            int v = p[j - 1] + (ai != bj);
            if (p[j] + 1 < v)
                v = p[j] + 1;
            if (c[j - 1] + 1 < v)
                v = c[j - 1] + 1;
            if (i > 1 && j > 1 && ai == tolower((unsigned char)b[j - 2]) &&
                tolower((unsigned char)a[i - 2]) == bj && pp[j - 2] + 1 < v)
                v = pp[j - 2] + 1;
            c[j] = v;
        }
        int *t = pp;
        pp = p;
        p = c;
        c = t;
    }
    return p[nb];
}

void sl_suggest_init(struct sl_suggest *s, const char *word)
{
    s->word = word ? word : "";
    s->best = NULL;
    s->dist = FAR;
    s->ties = 0;
}

void sl_suggest_add(struct sl_suggest *s, const char *candidate)
{
    if (!candidate || !candidate[0])
        return;
    int d = sl_edit_distance(s->word, candidate);
    if (d < s->dist) {
        s->best = candidate;
        s->dist = d;
        s->ties = 0;
    } else if (d == s->dist && s->best && strcmp(s->best, candidate) != 0) {
        s->ties++;
    }
}

const char *sl_suggest_best(const struct sl_suggest *s)
{
    size_t len = strlen(s->word);
    int limit = len / 3 > 1 ? (int)(len / 3) : 1;
    if (!s->best || s->dist == 0 || s->dist > limit || s->ties)
        return NULL;
    return s->best;
}

const char *sl_suggest_text(const struct sl_suggest *s, char *buf, size_t n)
{
    const char *b = sl_suggest_best(s);
    if (!n)
        return buf;
    if (b)
        snprintf(buf, n, " (did you mean '%s'?)", b);
    else
        buf[0] = '\0';
    return buf;
}
