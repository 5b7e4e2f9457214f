/*
 * emit_tex.c — the LaTeX emitter: a table of the model (tabmodel.h) as
 * booktabs floats fitted to the line (emit.h), and the LaTeX text and
 * numbers every LaTeX output writes (tex.h: the run's tables, the pivots,
 * the summaries, the motion tables and the report's prose).
 */
#include "emit.h"
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
    /* a thin space (sl_tab_number's thousands); a zero width non-joiner,
     * what keeps two signs apart: "-{}-" is two hyphens, not a dash */
    {0x2009, "\\,"},                 {0x200C, "{}"},
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

/* ---- tables ---- */

/* Lines of a table per float (a stacked or wrapped row takes more than one):
 * a longer one is split into parts, each a float of its own that fits a
 * page. */
#define TEX_LINES 44
/* Lines of a paged table's float at \small (the pivots', the detail
 * tables'): a page of a 10 pt A4 or letter article (\textheight 592 or
 * 550 pt) holds about 45 rows of 11.5 pt; less the caption, the heads and
 * the rules, and a margin where a folded name takes more than estimated. */
#define TEX_PAGE_LINES 34

/* Nothing is scaled: a table is fitted to the line (an A4 article's 345 pt,
 * \footnotesize, widths estimated by tex.h). A table wider than the line
 * has its "value (where)" cells and headings stacked onto two lines
 * (Moderno's summary tables); text that may wrap (the key columns, and every column of a text
 * table: t->wrap) is set in a \parbox as narrow as its longest word allows;
 * what is still too wide is split by columns into several floats, each
 * repeating the key columns (the first column when all are keys), cut at a
 * group's edge where one is near. */
#define TEX_COLSEP 8.0      /* 2 \tabcolsep of 4 pt */
#define TEX_MINWRAP 40.0    /* a wrapped column is no narrower (pt) */

/* Where a stacked cell breaks: before " (" ("v" above "(where)"); a
 * heading (stack 2) also after ": " ("step ms:" above "median [min-max]").
 * *first: the first line's length; returns the second line, NULL: one line. */
static const char *stack_cut(const char *v, int stack, int *first)
{
    const char *cut = stack ? strstr(v, " (") : NULL;
    if (cut) {
        *first = (int)(cut - v);
        return cut + 1;
    }
    cut = stack == 2 ? strstr(v, ": ") : NULL;
    if (cut) {
        *first = (int)(cut - v) + 1;
        return cut + 2;
    }
    return NULL;
}

/* the plain width (pt, \footnotesize) of a cell; stacked, "v (where)" counts
 * as its longer line; word: its longest word */
static double cell_pt(const char *v, int stack, int word)
{
    char buf[512];
    double w = 0;
    if (word) {
        for (const char *p = v; *p;) {
            size_t n = strcspn(p, " ");
            snprintf(buf, sizeof buf, "%.*s", (int)(n < sizeof buf ? n : sizeof buf - 1), p);
            double x = sl_tex_text_pt(buf);
            w = x > w ? x : w;
            p += n;
            p += *p == ' ';
        }
        return w * SL_TEX_FOOTNOTE * SL_TEX_SLACK;
    }
    int len;
    const char *second = stack_cut(v, stack, &len);
    if (!second)
        return sl_tex_text_pt(v) * SL_TEX_FOOTNOTE * SL_TEX_SLACK;
    snprintf(buf, sizeof buf, "%.*s", len, v);
    double a = sl_tex_text_pt(buf), b = sl_tex_text_pt(second);
    return (a > b ? a : b) * SL_TEX_FOOTNOTE * SL_TEX_SLACK;
}

/* as printed (stacked or not), or (word) its longest word */
static double col_pt(const struct sl_tab *t, int c, int stack, int word)
{
    double w = t->head[c] ? cell_pt(t->head[c], stack ? 2 : 0, word) : 0;
    for (int r = 0; r < t->nrows; r++) {
        double x = cell_pt(sl_tab_at(t, r, c), stack, word);
        w = x > w ? x : w;
    }
    if (word && w < TEX_MINWRAP)
        w = TEX_MINWRAP;
    return w + TEX_COLSEP;
}

/* A cell; stacked, "v (where)" as two lines (v above its "(where)");
 * wrapped (pbox > 0), a ragged \parbox of that width. */
static void tex_cell(FILE *f, const char *v, int stack, char align, double pbox)
{
    if (pbox > 0 && v[0]) {
        fprintf(f, "\\parbox[t]{%.1fpt}{\\raggedright ", pbox);
        sl_tex_text(f, v);
        fputs("\\strut}", f);
        return;
    }
    int len;
    const char *second = stack_cut(v, stack, &len);
    if (!second) {
        sl_tex_text(f, v);
        return;
    }
    char first[512];
    snprintf(first, sizeof first, "%.*s", len, v);
    fprintf(f, "\\begin{tabular}[t]{@{}%c@{}}", align);
    sl_tex_text(f, first);
    fputs("\\\\ ", f);
    sl_tex_text(f, second);
    fputs("\\end{tabular}", f);
}

struct tex_layout {
    int    stack;
    int    nfixed;                      /* columns repeated in every part */
    int    wraps[SL_TAB_MAXCOLS];    /* may be set in a \parbox */
    double w[SL_TAB_MAXCOLS];        /* as printed */
    double minw[SL_TAB_MAXCOLS];     /* wrapped as far as it goes */
    int    cut[SL_TAB_MAXCOLS + 1];  /* columns [cut[k], cut[k+1]) per column part */
    int    ncut;
};

static int in_part(const struct tex_layout *lo, int cp, int c)
{
    return c < lo->nfixed || (c >= lo->cut[cp] && c < lo->cut[cp + 1]);
}

/* a group's heading wider than its columns widens them evenly */
static void group_spread(const struct sl_tab *t, double *w)
{
    for (int g = 0, gs = 0; g < t->ngroups; gs += t->span[g], g++) {
        int n = 0;
        double under = 0;
        for (int c = gs; c < gs + t->span[g] && c < t->ncols; c++, n++)
            under += w[c];
        double head = sl_tex_text_pt(t->group[g]) * SL_TEX_FOOTNOTE + TEX_COLSEP;
        for (int c = gs; n && head > under && c < gs + t->span[g] && c < t->ncols; c++)
            w[c] += (head - under) / n;
    }
}

/* The \parbox widths of part cp (0: not wrapped): the wrapping columns share
 * what the others leave, each no narrower than its longest word, the
 * narrowest kept whole first. */
static void part_boxes(const struct tex_layout *lo, const struct sl_tab *t, int cp, double *box)
{
    double fixed = 0, nat = 0;
    for (int c = 0; c < t->ncols; c++) {
        box[c] = 0;
        if (in_part(lo, cp, c)) {
            nat += lo->w[c];
            fixed += lo->wraps[c] ? 0 : lo->w[c];
        }
    }
    if (nat <= SL_TEX_BUDGET)
        return;
    /* the cap C: sum over wrapping columns of clamp(w, minw, C) = what is left */
    double left = SL_TEX_BUDGET - fixed, lo_c = 0, hi_c = SL_TEX_BUDGET;
    for (int it = 0; it < 40; it++) {
        double mid = (lo_c + hi_c) / 2, sum = 0;
        for (int c = 0; c < t->ncols; c++)
            if (in_part(lo, cp, c) && lo->wraps[c]) {
                double x = lo->w[c] < mid ? lo->w[c] : mid;
                sum += x > lo->minw[c] ? x : lo->minw[c];
            }
        if (sum > left)
            hi_c = mid;
        else
            lo_c = mid;
    }
    for (int c = 0; c < t->ncols; c++)
        if (in_part(lo, cp, c) && lo->wraps[c] && lo->w[c] > lo_c) {
            double x = lo_c > lo->minw[c] ? lo_c : lo->minw[c];
            box[c] = x - TEX_COLSEP;
        }
}

static void tex_part(FILE *f, const struct sl_tab *t, const struct tex_layout *lo, int cp, int from, int to,
                     int part, int parts)
{
    double box[SL_TAB_MAXCOLS];
    part_boxes(lo, t, cp, box);
    fputs("\\begin{table*}[tbp]\n\\centering\n\\footnotesize\n\\setlength{\\tabcolsep}{4pt}\n\\caption{", f);
    sl_tex_text(f, t->title);
    if (t->intro && t->intro[0] && part == 0) {
        fputs(". ", f);
        sl_tex_text(f, t->intro);
    }
    if (parts > 1)
        fprintf(f, " (part %d of %d)", part + 1, parts);
    fputc('}', f);
    if (part == 0)
        fprintf(f, "\n\\label{tab:%s}", t->id);
    fputs("\n\\begin{tabular}{", f);
    for (int c = 0; c < t->ncols; c++)
        if (in_part(lo, cp, c))
            fputc(sl_tab_left(t, c) || box[c] > 0 ? 'l' : 'r', f);
    fputs("}\n\\toprule\n", f);
    if (t->ngroups) {
        int first = 1, col = 1;
        char rules[512] = "";
        size_t rl = 0;
        for (int g = 0, gs = 0; g < t->ngroups; gs += t->span[g], g++) {
            int n = 0;
            for (int c = gs; c < gs + t->span[g] && c < t->ncols; c++)
                n += in_part(lo, cp, c);
            if (n == 0)
                continue;
            fprintf(f, "%s\\multicolumn{%d}{c}{", first ? "" : " & ", n);
            first = 0;
            sl_tex_text(f, t->group[g]);
            fputc('}', f);
            if (t->group[g][0] && rl < sizeof rules - 32)
                rl += (size_t)snprintf(rules + rl, sizeof rules - rl, "\\cmidrule(lr){%d-%d}", col, col + n - 1);
            col += n;
        }
        fprintf(f, " \\\\\n%s\n", rules);
    }
    int first = 1;
    for (int c = 0; c < t->ncols; c++) {
        if (!in_part(lo, cp, c))
            continue;
        if (!first)
            fputs(" & ", f);
        first = 0;
        tex_cell(f, t->head[c] ? t->head[c] : "", lo->stack && !lo->wraps[c] ? 2 : 0, sl_tab_left(t, c) ? 'l' : 'r',
                 box[c]);
    }
    fputs(" \\\\\n\\midrule\n", f);
    for (int r = from; r < to; r++) {
        if ((t->rule[r] & SL_TAB_BLOCK) && r > from)
            fputs("\\addlinespace\n", f);
        first = 1;
        for (int c = 0; c < t->ncols; c++) {
            if (!in_part(lo, cp, c))
                continue;
            if (!first)
                fputs(" & ", f);
            first = 0;
            tex_cell(f, sl_tab_at(t, r, c), lo->stack && !lo->wraps[c], sl_tab_left(t, c) ? 'l' : 'r', box[c]);
        }
        fputs(" \\\\\n", f);
    }
    fputs("\\bottomrule\n\\end{tabular}\n", f);
    if (sl_tab_has_note(t) && part == parts - 1) {
        fputs("\n\\smallskip\n\\parbox{\\linewidth}{\\scriptsize\\raggedright ", f);
        sl_tex_text(f, t->note);
        fputs("\\par}\n", f);
    }
    fputs("\\end{table*}\n", f);
}

static void tex_fit(const struct sl_tab *t, struct tex_layout *lo)
{
    memset(lo, 0, sizeof *lo);
    lo->nfixed = t->nkeys < t->ncols ? t->nkeys : 1;
    double all = 0;
    for (int c = 0; c < t->ncols; c++)
        all += col_pt(t, c, 0, 0);
    lo->stack = all > SL_TEX_BUDGET;
    for (int c = 0; c < t->ncols; c++) {
        lo->wraps[c] = t->wrap || c < t->nkeys;
        lo->w[c] = col_pt(t, c, lo->stack && !lo->wraps[c], 0);
        lo->minw[c] = lo->wraps[c] ? col_pt(t, c, 0, 1) : lo->w[c];
        if (lo->minw[c] > lo->w[c])
            lo->minw[c] = lo->w[c];
    }
    group_spread(t, lo->w);
    group_spread(t, lo->minw);
    /* a group's edges: where a cut keeps the groups whole */
    unsigned char edge[SL_TAB_MAXCOLS + 1] = {0};
    for (int g = 0, gs = 0; g < t->ngroups && gs + t->span[g] <= SL_TAB_MAXCOLS; g++)
        edge[gs += t->span[g]] = 1;
    double keys = 0;
    for (int c = 0; c < lo->nfixed; c++)
        keys += lo->minw[c];
    lo->cut[0] = lo->nfixed;
    double sum = keys;
    for (int c = lo->nfixed; c < t->ncols; c++) {
        int start = lo->cut[lo->ncut];
        if (c > start && sum + lo->minw[c] > SL_TEX_BUDGET) {
            int at = c;
            for (int e = c; t->ngroups && e > start; e--)
                if (edge[e]) {
                    at = e;
                    break;
                }
            lo->cut[++lo->ncut] = at;
            sum = keys;
            for (int k = at; k < c; k++)
                sum += lo->minw[k];
        }
        sum += lo->minw[c];
    }
    lo->cut[++lo->ncut] = t->ncols;
}

/* Lines row r takes in part cp: a stacked cell two, a wrapped one as many
 * as its text needs at its box's width (a third more: words do not fill a
 * line); the space before a block half a line. */
static double row_lines(const struct sl_tab *t, const struct tex_layout *lo, int cp, const double *box, int r)
{
    double lines = 1;
    for (int c = 0; c < t->ncols; c++) {
        if (!in_part(lo, cp, c))
            continue;
        const char *v = sl_tab_at(t, r, c);
        double n = 1;
        if (box[c] > 0)
            n = (double)(int)(cell_pt(v, 0, 0) * 1.33 / box[c]) + 1;
        else if (lo->stack && !lo->wraps[c] && strstr(v, " ("))
            n = 2;
        lines = n > lines ? n : lines;
    }
    return lines + ((t->rule[r] & SL_TAB_BLOCK) ? 0.5 : 0);
}

/* the rows [cut[k], cut[k+1]) of each float of part cp; returns how many */
static int row_cuts(const struct sl_tab *t, const struct tex_layout *lo, int cp, int *cut)
{
    double box[SL_TAB_MAXCOLS];
    part_boxes(lo, t, cp, box);
    int n = 0;
    double lines = 0;
    cut[0] = 0;
    for (int r = 0; r < t->nrows; r++) {
        double k = row_lines(t, lo, cp, box, r);
        if (r > cut[n] && lines + k > TEX_LINES) {
            cut[++n] = r;
            lines = 0;
        }
        lines += k;
    }
    cut[++n] = t->nrows;
    return n;
}

void sl_emit_tex_clearpage(FILE *f)
{
    fputs("\\clearpage\n\n", f);
}

void sl_emit_tex_comment(FILE *f, const char *comment, int blank)
{
    if (comment)
        fprintf(f, "%% %s\n%s", comment, blank ? "\n" : "");
    else
        fputs("% shadowlab report table; needs \\usepackage{booktabs}; a wide one is split, never scaled\n", f);
}

/* s as LaTeX text; squares: a run of digits followed by "²" as $N^2$ */
static void tab_text(FILE *f, const char *s, int squares)
{
    const char *seg = s, *p = s;
    while (squares && *p) {
        if (*p < '0' || *p > '9' || (p > s && p[-1] >= '0' && p[-1] <= '9')) {
            p++;
            continue;
        }
        const char *q = p;
        while (*q >= '0' && *q <= '9')
            q++;
        if (strncmp(q, "\xC2\xB2", 2) != 0) {
            p = q;
            continue;
        }
        char *before = malloc((size_t)(p - seg) + 1);
        if (before) {
            memcpy(before, seg, (size_t)(p - seg));
            before[p - seg] = '\0';
            sl_tex_text(f, before);
            free(before);
        }
        fprintf(f, "$%.*s^2$", (int)(q - p), p);
        seg = p = q + 2;
    }
    sl_tex_text(f, seg);
}

/* s with a break allowed after each '_' and '-' (sl_tex_text allows one
 * after '/'), cut between whole characters */
static void tex_breakable(FILE *f, const char *s, int squares)
{
    char *buf = malloc(strlen(s) + 1);
    if (!buf) {
        tab_text(f, s, squares);
        return;
    }
    while (*s) {
        size_t n = strcspn(s, "_-");
        n += s[n] != '\0';
        memcpy(buf, s, n);
        buf[n] = '\0';
        tab_text(f, buf, squares);
        if (buf[n - 1] == '_' || buf[n - 1] == '-')
            fputs("\\allowbreak{}", f);
        s += n;
    }
    free(buf);
}

/* A row of cells (the heads: r = -1) joined by " & ", ended by " \\"; a
 * cell that is not empty in its column's \parbox where it has one, one
 * wider than its column's fold in a \parbox of that width. */
static void long_row(FILE *f, const struct sl_tab *t, int r)
{
    for (int c = 0; c < t->ncols; c++) {
        if (c)
            fputs(" & ", f);
        const char *v = r < 0 ? (t->head[c] ? t->head[c] : "") : sl_tab_at(t, r, c);
        if (r >= 0 && t->fold[c] > 0 && sl_tex_text_pt(v) > t->fold[c]) {
            fprintf(f, "\\parbox[t]{%gpt}{\\raggedright ", t->fold[c]);
            tex_breakable(f, v, t->squares);
            fputc('}', f);
        } else if (r >= 0 && t->fixed && t->stack && !sl_tab_left(t, c))
            tex_cell(f, v, 1, 'r', 0);
        else if (r >= 0 && t->fixed && t->parbox[c] > 0 && v[0]) {
            fprintf(f, "\\parbox[t]{%.1fpt}{\\raggedright ", t->parbox[c]);
            tab_text(f, v, t->squares);
            fputs("\\strut}", f);
        } else
            tab_text(f, v, t->squares);
    }
    fputs(" \\\\\n", f);
}

/* the note; t->code: its `spans` as \texttt */
static void note_text(FILE *f, const struct sl_tab *t)
{
    const char *s = t->note;
    char *buf = malloc(strlen(s) + 1);
    if (!t->code || !buf) {
        free(buf);
        tab_text(f, s, t->squares);
        return;
    }
    for (int code = 0; *s; code = !code) {
        size_t n = strcspn(s, "`");
        memcpy(buf, s, n);
        buf[n] = '\0';
        if (code) {
            fputs("\\texttt{", f);
            sl_tex_text(f, buf);
            fputc('}', f);
        } else
            tab_text(f, buf, t->squares);
        s += n + (s[n] == '`');
    }
    free(buf);
}

/* The row of column groups above the heads (where the table has them): a
 * group's name over its columns, an unnamed group of one column an empty
 * cell; a rule under each named group, trimmed on a side where a column
 * is beside it. */
static void group_row(FILE *f, const struct sl_tab *t)
{
    if (!t->ngroups)
        return;
    char rules[1024] = "";
    size_t rl = 0;
    for (int g = 0, gs = 0; g < t->ngroups; gs += t->span[g], g++) {
        if (g)
            fputs(" & ", f);
        if (t->span[g] == 1 && !t->group[g][0])
            continue;
        fprintf(f, "\\multicolumn{%d}{c}{", t->span[g]);
        tab_text(f, t->group[g], t->squares);
        fputc('}', f);
        int a = gs + 1, b = gs + t->span[g], l = a > 1, rt = b < t->ncols;
        if (t->group[g][0] && rl < sizeof rules - 48)
            rl += (size_t)snprintf(rules + rl, sizeof rules - rl, "\\cmidrule%s%s%s%s{%d-%d}", l || rt ? "(" : "",
                                   l ? "l" : "", rt ? "r" : "", l || rt ? ")" : "", a, b);
    }
    fprintf(f, " \\\\\n%s\n", rules);
}

/* The lines row r of a fixed or paged table takes: a folded or parboxed
 * cell as many as its text needs at its width (a third more: words do not
 * fill a line), a stacked one two; the space before a block half a line. */
static double fixed_row_lines(const struct sl_tab *t, int r)
{
    double lines = 1;
    for (int c = 0; c < t->ncols; c++) {
        const char *v = sl_tab_at(t, r, c);
        double w = t->fold[c] > 0 && sl_tex_text_pt(v) > t->fold[c] ? t->fold[c]
                   : t->fixed && t->parbox[c] > 0 && v[0]               ? t->parbox[c]
                                                                        : 0;
        double n = w > 0 ? (double)(int)(sl_tex_text_pt(v) * 1.33 / w) + 1
                   : t->fixed && t->stack && !sl_tab_left(t, c) && strstr(v, " (") ? 2
                                                                                    : 1;
        lines = n > lines ? n : lines;
    }
    return lines + ((t->rule[r] & SL_TAB_BLOCK) && r > 0 ? 0.5 : 0);
}

/* One float of rows [from, to) as its writer laid it out (t->fixed, or a
 * part of a paged table): nothing stacked, wrapped (but in a column's
 * parbox) or split by columns. A table* (two-column safe: in a one-column
 * document it is a table, in a two-column one it spans the page); a part
 * after the first repeats the heads and its table's number, its caption
 * ending "(continued)", and carries no label. */
static void fixed_float(FILE *f, const struct sl_tab *t, int from, int to, int part, int parts)
{
    fputs("\\begin{table*}[tbp]\n\\centering\n", f);
    fputs(t->small ? "\\small\n" : "\\footnotesize\n\\setlength{\\tabcolsep}{4pt}\n", f);
    if (part > 0)
        fputs("\\addtocounter{table}{-1}\n", f);
    fputs("\\caption{", f);
    tab_text(f, t->title, t->squares);
    if (t->intro && t->intro[0] && part == 0) {
        fputs(". ", f);
        tab_text(f, t->intro, t->squares);
    }
    if (part > 0)
        fputs(" (continued)", f);
    fputc('}', f);
    if (!t->nolabel && part == 0)
        fprintf(f, "\n\\label{tab:%s}", t->id);
    fputs("\n\\begin{tabular}{", f);
    for (int c = 0; c < t->ncols; c++)
        fputc(sl_tab_left(t, c) ? 'l' : 'r', f);
    fputs("}\n\\toprule\n", f);
    group_row(f, t);
    long_row(f, t, -1);
    fputs("\\midrule\n", f);
    for (int r = from; r < to; r++) {
        if ((t->rule[r] & SL_TAB_BLOCK) && r > from)
            fputs("\\addlinespace\n", f);
        long_row(f, t, r);
    }
    fputs("\\bottomrule\n\\end{tabular}\n", f);
    if (sl_tab_has_note(t) && part == parts - 1) {
        fputs("\n\\smallskip\n\\parbox{\\linewidth}{\\scriptsize\\raggedright ", f);
        note_text(f, t);
        fputs("\\par}\n", f);
    }
    fputs("\\end{table*}\n", f);
}

/* A fixed table: one float. A paged one (t->paged): floats of at most
 * TEX_PAGE_LINES lines each, the heads on every one, a \clearpage before
 * every eighth (LaTeX holds at most 18 floats it has not placed). */
static int tex_fixed(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    if (o && o->clear)
        fputs("\\clearpage\n\n", f);
    int parts = 1, *cut = malloc(((size_t)t->nrows + 2) * sizeof *cut);
    if (!cut)
        return -1;
    cut[0] = 0;
    if (t->paged) {
        double lines = 0;
        parts = 0;
        for (int r = 0; r < t->nrows; r++) {
            double k = fixed_row_lines(t, r);
            if (r > cut[parts] && lines + k > TEX_PAGE_LINES) {
                cut[++parts] = r;
                lines = 0;
            }
            lines += k;
        }
        parts++;
    }
    cut[parts] = t->nrows;
    for (int p = 0; p < parts; p++) {
        if (p > 0 && p % 8 == 0)
            fputs("\\clearpage\n", f);
        fixed_float(f, t, cut[p], cut[p + 1], p, parts);
        if (o && o->blank)
            fputc('\n', f);
    }
    free(cut);
    return parts % 8 ? parts % 8 : 8;
}

int sl_emit_tex(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o)
{
    if (t->oom || t->ncols > SL_TAB_MAXCOLS || t->ngroups > SL_TAB_MAXCOLS)
        return -1;
    if (!o || o->first)
        sl_emit_tex_comment(f, o ? o->comment : NULL, t->paged);
    if (t->fixed || t->paged)
        return tex_fixed(f, t, o);
    struct tex_layout lo;
    tex_fit(t, &lo);
    int *cut = malloc(((size_t)t->nrows + 2) * sizeof *cut);
    if (!cut)
        return 0;
    int parts = 0;
    for (int cp = 0; cp < lo.ncut; cp++)
        parts += row_cuts(t, &lo, cp, cut);
    for (int cp = 0, part = 0; cp < lo.ncut; cp++) {
        int n = row_cuts(t, &lo, cp, cut);
        for (int p = 0; p < n; p++, part++) {
            /* LaTeX holds at most 18 floats it has not placed */
            if (part > 0 && part % 8 == 0)
                fputs("\\clearpage\n", f);
            tex_part(f, t, &lo, cp, cut[p], cut[p + 1], part, parts);
        }
    }
    free(cut);
    return parts % 8 ? parts % 8 : 8;
}
