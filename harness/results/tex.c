/*
 * tex.c — LaTeX text and numbers (tex.h), shared by the run's tables
 * (table.c), the pivots (pivot.c) and the report.
 */
#include "tex.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistr.h>     /* libunistring: u8_mbtoucr */
#include <uninorm.h>    /* u32_normalize (NFD) */

/* Non-ASCII text as LaTeX, for every code point that can occur (a config's
 * label, a scene's or a model's name, a package's parameter doc, the
 * report's own signs), in a form pdflatex reads whatever the document's
 * input encoding, never '?':
 *   1. the signs and symbols below, by code point (math-mode ones in $..$;
 *      all in LaTeX's kernel, no package needed: \k, the ogonek, is T1's,
 *      which the report and any pdflatex document with Polish text use);
 *   2. Greek letters as $\alpha$ ... (capitals that look Latin as the Latin
 *      letter);
 *   3. letters with diacritics by their canonical decomposition (Unicode
 *      NFD, libunistring): the base letter under LaTeX's accent commands,
 *      the last mark outermost (ǘ = \'{\"{u}}); the letters with no decomposition
 *      that LaTeX names (ß, æ, ø, ł, ı, ...) by their commands;
 *   4. anything else as its code point, \textsf{[U+2603]}: visible in the
 *      PDF, never an error (a font with the glyph is not guaranteed).
 * Invalid UTF-8 is written as [U+FFFD]. */

struct tex_sym {
    ucs4_t cp;
    const char *tex;
};

static const struct tex_sym tex_signs[] = {
    {0x00A0, "~"},                    {0x00A1, "\\textexclamdown{}"}, {0x00A7, "\\S{}"},
    {0x00A9, "\\copyright{}"},        {0x00AB, "$\\ll$"},            {0x00AC, "$\\neg$"},
    {0x00AE, "\\textregistered{}"},   {0x00B0, "$^\\circ$"},         {0x00B1, "$\\pm$"},
    {0x00B2, "\\textsuperscript{2}"}, {0x00B3, "\\textsuperscript{3}"}, {0x00B5, "$\\mu$"},
    {0x00B6, "\\P{}"},                {0x00B7, "$\\cdot$"},          {0x00B9, "\\textsuperscript{1}"},
    {0x00BB, "$\\gg$"},               {0x00BC, "$\\frac{1}{4}$"},    {0x00BD, "$\\frac{1}{2}$"},
    {0x00BE, "$\\frac{3}{4}$"},       {0x00BF, "\\textquestiondown{}"}, {0x00D7, "$\\times$"},
    {0x00F7, "$\\div$"},              {0x2010, "-"},                 {0x2011, "-"},
    {0x2012, "--"},                   {0x2013, "--"},                {0x2014, "---"},
    {0x2015, "---"},                  {0x2016, "$\\|$"},             {0x2018, "`"},
    {0x2019, "'"},                    {0x201A, ","},                 {0x201C, "``"},
    {0x201D, "''"},                   {0x201E, ",,"},                {0x2020, "$^\\dagger$"},
    {0x2021, "$^\\ddagger$"},         {0x2022, "$\\bullet$"},        {0x2026, "\\ldots{}"},
    {0x2030, "\\textperthousand{}"},  {0x2032, "$'$"},               {0x2033, "$''$"},
    {0x2039, "\\textless{}"},        {0x203A, "\\textgreater{}"},                 {0x2044, "/"},
    {0x2070, "\\textsuperscript{0}"}, {0x2074, "\\textsuperscript{4}"}, {0x2075, "\\textsuperscript{5}"},
    {0x2076, "\\textsuperscript{6}"}, {0x2077, "\\textsuperscript{7}"}, {0x2078, "\\textsuperscript{8}"},
    {0x2079, "\\textsuperscript{9}"}, {0x207A, "\\textsuperscript{+}"}, {0x207B, "\\textsuperscript{$-$}"},
    {0x2080, "\\textsubscript{0}"},   {0x2081, "\\textsubscript{1}"},  {0x2082, "\\textsubscript{2}"},
    {0x2083, "\\textsubscript{3}"},   {0x20AC, "EUR"},               {0x2116, "No."},
    {0x2122, "\\texttrademark{}"},    {0x2190, "$\\leftarrow$"},     {0x2191, "$\\uparrow$"},
    {0x2192, "$\\to$"},               {0x2193, "$\\downarrow$"},     {0x2194, "$\\leftrightarrow$"},
    {0x21D0, "$\\Leftarrow$"},        {0x21D2, "$\\Rightarrow$"},    {0x21D4, "$\\Leftrightarrow$"},
    {0x2200, "$\\forall$"},           {0x2202, "$\\partial$"},       {0x2203, "$\\exists$"},
    {0x2205, "$\\emptyset$"},         {0x2207, "$\\nabla$"},         {0x2208, "$\\in$"},
    {0x2209, "$\\notin$"},            {0x2211, "$\\sum$"},           {0x2212, "$-$"},
    {0x2213, "$\\mp$"},               {0x2215, "/"},                 {0x2217, "$\\ast$"},
    {0x2218, "$\\circ$"},             {0x2219, "$\\cdot$"},          {0x221A, "$\\surd$"},
    {0x221D, "$\\propto$"},           {0x221E, "$\\infty$"},         {0x2220, "$\\angle$"},
    {0x2223, "$\\mid$"},              {0x2225, "$\\parallel$"},      {0x2227, "$\\wedge$"},
    {0x2228, "$\\vee$"},              {0x2229, "$\\cap$"},           {0x222A, "$\\cup$"},
    {0x222B, "$\\int$"},              {0x223C, "$\\sim$"},           {0x2243, "$\\simeq$"},
    {0x2245, "$\\cong$"},             {0x2248, "$\\approx$"},        {0x2260, "$\\neq$"},
    {0x2261, "$\\equiv$"},            {0x2264, "$\\le$"},            {0x2265, "$\\ge$"},
    {0x226A, "$\\ll$"},               {0x226B, "$\\gg$"},            {0x2282, "$\\subset$"},
    {0x2283, "$\\supset$"},           {0x2286, "$\\subseteq$"},      {0x2287, "$\\supseteq$"},
    {0x2295, "$\\oplus$"},            {0x2297, "$\\otimes$"},        {0x22A5, "$\\perp$"},
    {0x22C5, "$\\cdot$"},             {0x2308, "$\\lceil$"},         {0x2309, "$\\rceil$"},
    {0x230A, "$\\lfloor$"},           {0x230B, "$\\rfloor$"},        {0x2605, "$\\star$"},
    {0x27E8, "$\\langle$"},           {0x27E9, "$\\rangle$"},
    /* the letters LaTeX names that have no canonical decomposition */
    {0x00C6, "\\AE{}"},               {0x00D0, "D"},                 {0x00D8, "\\O{}"},
    {0x00DE, "Th"},                   {0x00DF, "\\ss{}"},            {0x00E6, "\\ae{}"},
    {0x00F0, "d"},                    {0x00F8, "\\o{}"},             {0x00FE, "th"},
    {0x0110, "D"},                    {0x0111, "d"},                 {0x0131, "\\i{}"},
    {0x0141, "\\L{}"},                {0x0142, "\\l{}"},             {0x0152, "\\OE{}"},
    {0x0153, "\\oe{}"},               {0x0237, "\\j{}"},
};

/* Greek, U+0391..U+03A9 and U+03B1..U+03C9 in order (U+03A2 is unassigned;
 * U+03C2, final sigma, is \varsigma); a capital that looks Latin is that
 * letter. */
static const char *const greek_upper[] = {
    "A", "B", "$\\Gamma$", "$\\Delta$", "E", "Z", "H", "$\\Theta$", "I", "K", "$\\Lambda$", "M", "N",
    "$\\Xi$", "O", "$\\Pi$", "P", NULL, "$\\Sigma$", "T", "$\\Upsilon$", "$\\Phi$", "X", "$\\Psi$", "$\\Omega$"};
static const char *const greek_lower[] = {
    "$\\alpha$", "$\\beta$", "$\\gamma$", "$\\delta$", "$\\epsilon$", "$\\zeta$", "$\\eta$", "$\\theta$",
    "$\\iota$", "$\\kappa$", "$\\lambda$", "$\\mu$", "$\\nu$", "$\\xi$", "o", "$\\pi$", "$\\rho$",
    "$\\varsigma$", "$\\sigma$", "$\\tau$", "$\\upsilon$", "$\\phi$", "$\\chi$", "$\\psi$", "$\\omega$"};

/* Combining marks LaTeX writes as text accents. */
static const struct tex_sym tex_accents[] = {
    {0x0300, "\\`"}, {0x0301, "\\'"}, {0x0302, "\\^"}, {0x0303, "\\~"}, {0x0304, "\\="},
    {0x0306, "\\u"}, {0x0307, "\\."}, {0x0308, "\\\""}, {0x030A, "\\r"}, {0x030B, "\\H"},
    {0x030C, "\\v"}, {0x0323, "\\d"}, {0x0327, "\\c"}, {0x0328, "\\k"}, {0x0331, "\\b"},
};

static const char *sym_find(const struct tex_sym *t, size_t n, ucs4_t c)
{
    for (size_t k = 0; k < n; k++)
        if (t[k].cp == c)
            return t[k].tex;
    return NULL;
}

/* c as its decomposition's accents over an ASCII letter, or 0 when it is
 * not such a letter. */
static int tex_decomposed(FILE *f, ucs4_t c)
{
    ucs4_t buf[16];
    size_t len = sizeof buf / sizeof buf[0];
    ucs4_t *d = u32_normalize(UNINORM_NFD, &c, 1, buf, &len);
    if (!d)
        return 0;
    int ok = len >= 2 && len <= 8 && d[0] < 0x80 &&
             ((d[0] >= 'a' && d[0] <= 'z') || (d[0] >= 'A' && d[0] <= 'Z'));
    for (size_t k = 1; ok && k < len; k++)
        ok = sym_find(tex_accents, sizeof tex_accents / sizeof tex_accents[0], d[k]) != NULL;
    if (ok) {
        /* outermost accent (the last mark) first: \'{\"{u}} */
        for (size_t k = len - 1; k >= 1; k--)
            fprintf(f, "%s{", sym_find(tex_accents, sizeof tex_accents / sizeof tex_accents[0], d[k]));
        /* an accent above i or j goes on the dotless letter */
        if ((d[0] == 'i' || d[0] == 'j') && d[len - 1] != 0x0323 && d[len - 1] != 0x0327 && d[len - 1] != 0x0328 &&
            d[len - 1] != 0x0331)
            fputs(d[0] == 'i' ? "\\i" : "\\j", f);
        else
            fputc((int)d[0], f);
        for (size_t k = 1; k < len; k++)
            fputc('}', f);
    }
    if (d != buf)
        free(d);
    return ok;
}

static void tex_codepoint(FILE *f, ucs4_t c)
{
    const char *t = sym_find(tex_signs, sizeof tex_signs / sizeof tex_signs[0], c);
    if (!t && c >= 0x0391 && c <= 0x03A9)
        t = greek_upper[c - 0x0391];
    if (!t && c >= 0x03B1 && c <= 0x03C9)
        t = greek_lower[c - 0x03B1];
    if (t)
        fputs(t, f);
    else if (!tex_decomposed(f, c))
        fprintf(f, "\\textsf{[U+%04X]}", (unsigned)c);
}

void sl_tex_text(FILE *f, const char *s)
{
    const uint8_t *u = (const uint8_t *)s, *end = u ? u + strlen(s) : NULL;
    for (; u && *u; u++) {
        if (*u >= 0x80) {
            ucs4_t c;
            int n = u8_mbtoucr(&c, u, (size_t)(end - u));
            if (n < 1) {   /* invalid or cut short: one byte as U+FFFD */
                c = 0xFFFD;
                n = 1;
            }
            tex_codepoint(f, c);
            u += n - 1;
            continue;
        }
        switch (*u) {
        case '_': case '%': case '&': case '#': case '$': case '{': case '}':
            fputc('\\', f);
            fputc(*u, f);
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
        default:   fputc(*u, f);
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
