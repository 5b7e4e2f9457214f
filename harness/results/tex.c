/*
 * tex.c — LaTeX text and numbers (tex.h), shared by the run's tables
 * (table.c), the pivots (pivot.c) and the report.
 */
#include "tex.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* LaTeX: the ten specials, and the non-ASCII signs the report writes; any
 * other non-ASCII character becomes '?', so a name can never stop pdflatex
 * (inputenc has no glyph for most of them). */
void sl_tex_text(FILE *f, const char *s)
{
    static const struct { const char *utf8, *tex; } signs[] = {
        {"\xC2\xB2", "\\textsuperscript{2}"}, {"\xC3\x97", "$\\times$"},   {"\xE2\x80\x93", "--"},
        {"\xE2\x80\x94", "---"},              {"\xE2\x86\x92", "$\\to$"},  {"\xE2\x89\xA4", "$\\le$"},
        {"\xE2\x89\xA5", "$\\ge$"},           {"\xC2\xB1", "$\\pm$"},      {"\xC2\xB5", "$\\mu$"},
        {"\xC2\xB7", "$\\cdot$"},             {"\xE2\x80\x99", "'"},       {"\xE2\x80\x98", "`"},
        {"\xE2\x80\x9C", "``"},               {"\xE2\x80\x9D", "''"},      {"\xE2\x80\xA6", "\\ldots{}"},
        {"\xC2\xA0", "~"},                    {"\xE2\x89\x88", "$\\approx$"}, {"\xC2\xB0", "$^\\circ$"},
        {"\xE2\x80\xA0", "$^\\dagger$"},
    };
    for (; s && *s; s++) {
        const unsigned char *u = (const unsigned char *)s;
        if (u[0] >= 0x80) {
            size_t len = 1;
            while (len < 4 && (u[len] & 0xC0) == 0x80)
                len++;
            const char *tex = "?";
            for (size_t k = 0; k < sizeof signs / sizeof signs[0]; k++)
                if (strlen(signs[k].utf8) == len && memcmp(signs[k].utf8, s, len) == 0)
                    tex = signs[k].tex;
            fputs(tex, f);
            s += len - 1;
            continue;
        }
        switch (*s) {
        case '_': case '%': case '&': case '#': case '$': case '{': case '}':
            fputc('\\', f);
            fputc(*s, f);
            break;
        case '\\': fputs("\\textbackslash{}", f); break;
        case '~':  fputs("\\textasciitilde{}", f); break;
        case '^':  fputs("\\textasciicircum{}", f); break;
        case '<':  fputs("\\textless{}", f); break;
        case '>':  fputs("\\textgreater{}", f); break;
        case '\n': fputc(' ', f); break;
        /* a path may break after each '/' where a paragraph or a wrapped
         * cell needs it (a long temporary folder's path ran 1.4 pt past a
         * report cell); in an l column nothing breaks, as before */
        case '/':  fputs("/\\allowbreak{}", f); break;
        default:   fputc(*s, f);
        }
    }
}

/* digits of |v| with `dec` decimals, groups of three split by sep */
static void grouped(char *out, size_t n, double v, int dec, const char *sep)
{
    char raw[64];
    snprintf(raw, sizeof raw, "%.*f", dec, fabs(v));
    const char *dot = strchr(raw, '.');
    size_t ilen = dot ? (size_t)(dot - raw) : strlen(raw);
    size_t o = 0;
    for (size_t i = 0; i < ilen && o + 8 < n; i++) {
        if (i > 0 && (ilen - i) % 3 == 0 && ilen >= 4)
            o += (size_t)snprintf(out + o, n - o, "%s", sep);
        out[o++] = raw[i];
    }
    out[o] = '\0';
    if (dot)
        snprintf(out + o, n - o, "%s", dot);
}

void sl_tex_number(char *out, size_t n, double v, int dec)
{
    if (isnan(v)) {
        snprintf(out, n, "--");
        return;
    }
    char g[80];
    grouped(g, sizeof g, v, dec, "\\,");
    /* a value that rounds to zero has no sign */
    char z[64];
    snprintf(z, sizeof z, "%.*f", dec, fabs(v));
    int zero = strspn(z, "0.") == strlen(z);
    snprintf(out, n, "%s%s", v < 0 && !zero ? "$-$" : "", g);
}


double sl_tex_text_pt(const char *s)
{
    double w = 0;
    for (const unsigned char *u = (const unsigned char *)s; u && *u; u++) {
        if ((*u & 0xC0) == 0x80)
            continue;
        if (*u == '.' || *u == ',' || *u == ' ' || *u == '(' || *u == ')' || *u == 'i' || *u == 'l')
            w += 2.6;
        else if ((*u >= 'A' && *u <= 'Z') || *u == 'm' || *u == 'w' || *u == '%' || *u == '_')
            w += 6.8;
        else
            w += 4.6;
    }
    return w;
}

double sl_tex_number_pt(const char *plain)
{
    size_t ilen = strcspn(plain, ".");
    if (plain[0] == '-')
        ilen--;
    return sl_tex_text_pt(plain) + (ilen >= 4 ? (double)((ilen - 1) / 3) * 1.5 : 0.0);
}
