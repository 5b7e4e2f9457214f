/*
 * doc.c — the staging folder, the table grid and the two pages (see
 * report_int.h).
 *
 * Invariants:
 * - Every file of the report is registered with sl_report_out_path before
 *   it is written, so commit moves exactly those files and abort removes
 *   exactly those (never anything it did not write: no recursive deletes).
 * - Registered paths are relative, made of [A-Za-z0-9._-] and '/', and never
 *   start with '.' or contain "..": a cell's names cannot escape the folder.
 * - Text reaches a page only through the escapers here (html_text, md_text,
 *   sl_tex_text in table.c), so a label or path can never break a page or a table.
 * - Write errors on the pages are found by ferror at the end (report.c).
 */
#define _POSIX_C_SOURCE 200809L
#include "report_int.h"
#include <errno.h>
#include <stddef.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "util.h"

/* ---- out ---- */

void sl_report_slug(const char *s, char *buf, size_t n)
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

static int rel_ok(const char *rel)
{
    if (!rel || !rel[0] || rel[0] == '/' || rel[0] == '.' || strstr(rel, "..") || strstr(rel, "//"))
        return 0;
    for (const char *p = rel; *p; p++) {
        char c = *p;
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
              c == '-' || c == '.' || c == '/'))
            return 0;
    }
    return rel[strlen(rel) - 1] != '/';
}

/* mkdir -p of the folder part of path (quiet: the caller reports) */
static int make_parent(const char *path)
{
    char buf[1400];
    snprintf(buf, sizeof buf, "%s", path);
    char *slash = strrchr(buf, '/');
    if (!slash)
        return 0;
    *slash = '\0';
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return (mkdir(buf, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

enum sl_err sl_report_out_begin(struct sl_report_out *o, const char *dir, struct sl_diag *d)
{
    memset(o, 0, sizeof *o);
    if (!dir || !dir[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--out", "empty output folder");
    if (snprintf(o->dir, sizeof o->dir, "%s", dir) >= (int)sizeof o->dir)
        return sl_fail(d, SL_E_OUTPUT, dir, 0, NULL, "path too long");
    size_t len = strlen(o->dir);
    while (len > 1 && o->dir[len - 1] == '/')
        o->dir[--len] = '\0';
    enum sl_err e = sl_mkdirs(o->dir, d);
    if (e)
        return e;
    snprintf(o->stage, sizeof o->stage, "%s/.staging-%ld", o->dir, (long)getpid());
    if (mkdir(o->stage, 0777) != 0)
        return sl_fail(d, SL_E_OUTPUT, o->stage, 0, NULL, "cannot create the staging folder: %s", strerror(errno));
    return SL_OK;
}

int sl_report_out_has(const struct sl_report_out *o, const char *rel)
{
    for (int i = 0; i < o->n; i++)
        if (strcmp(o->files[i].rel, rel) == 0)
            return 1;
    return 0;
}

enum sl_err sl_report_out_path(struct sl_report_out *o, const char *rel, int keep, char *path, size_t n,
                               struct sl_diag *d)
{
    if (!rel_ok(rel))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, rel, "not a report file name");
    if (sl_report_out_has(o, rel))
        return sl_fail(d, SL_E_INTERNAL, NULL, 0, rel, "report file written twice");
    if (snprintf(path, n, "%s/%s", o->stage, rel) >= (int)n)
        return sl_fail(d, SL_E_OUTPUT, o->dir, 0, rel, "path too long");
    if (o->n == o->cap) {
        int cap = o->cap ? 2 * o->cap : 64;
        struct sl_report_file *f = realloc(o->files, (size_t)cap * sizeof *f);
        if (!f)
            return sl_fail(d, SL_E_NOMEM, NULL, 0, rel, "report file list");
        o->files = f;
        o->cap = cap;
    }
    char *copy = strdup(rel);
    if (!copy)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, rel, "report file list");
    o->files[o->n++] = (struct sl_report_file){copy, keep};
    if (make_parent(path) != 0)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot create its folder: %s", strerror(errno));
    return SL_OK;
}

/* rmdir the folders of rel inside root, deepest first; non-empty ones stay */
static void remove_parents(const char *root, const char *rel)
{
    char buf[1400];
    snprintf(buf, sizeof buf, "%s/%s", root, rel);
    size_t rootlen = strlen(root);
    for (;;) {
        char *slash = strrchr(buf, '/');
        if (!slash || (size_t)(slash - buf) <= rootlen)
            break;
        *slash = '\0';
        rmdir(buf);
    }
}

static void out_free(struct sl_report_out *o)
{
    for (int i = 0; i < o->n; i++)
        free(o->files[i].rel);
    free(o->files);
    o->files = NULL;
    o->n = o->cap = 0;
}

enum sl_err sl_report_out_commit(struct sl_report_out *o, struct sl_diag *d)
{
    char from[1400], to[1400];
    enum sl_err e = SL_OK;
    /* staged files exist: checked before anything moves */
    for (int i = 0; i < o->n && !e; i++) {
        struct stat st;
        snprintf(from, sizeof from, "%s/%s", o->stage, o->files[i].rel);
        if (o->files[i].keep && stat(from, &st) != 0)
            e = sl_fail(d, SL_E_INTERNAL, from, 0, NULL, "a registered report file was not written");
    }
    /* pass 0: scratch removed, files moved; pass 1: the pages (keep > 1), last */
    for (int pass = 0; pass < 2 && !e; pass++)
        for (int i = 0; i < o->n && !e; i++) {
            int keep = o->files[i].keep;
            if ((pass == 0) != (keep <= 1))
                continue;
            snprintf(from, sizeof from, "%s/%s", o->stage, o->files[i].rel);
            if (!keep) {
                remove(from);
                continue;
            }
            snprintf(to, sizeof to, "%s/%s", o->dir, o->files[i].rel);
            if (make_parent(to) != 0 || rename(from, to) != 0)
                e = sl_fail(d, SL_E_OUTPUT, to, 0, NULL, "cannot move into place: %s", strerror(errno));
        }
    if (e) {
        sl_report_out_abort(o);
        return e;
    }
    for (int i = o->n - 1; i >= 0; i--)
        remove_parents(o->stage, o->files[i].rel);
    rmdir(o->stage);
    out_free(o);
    return SL_OK;
}

void sl_report_out_abort(struct sl_report_out *o)
{
    char p[1400], tmp[1410];
    for (int i = o->n - 1; i >= 0; i--) {
        snprintf(p, sizeof p, "%s/%s", o->stage, o->files[i].rel);
        snprintf(tmp, sizeof tmp, "%s.tmp", p);
        remove(p);
        remove(tmp);
        remove_parents(o->stage, o->files[i].rel);
    }
    if (o->stage[0])
        rmdir(o->stage);
    out_free(o);
}

/* ---- tab ---- */

static char *vformat(const char *fmt, va_list ap)
{
    va_list aq;
    va_copy(aq, ap);
    int len = vsnprintf(NULL, 0, fmt, aq);
    va_end(aq);
    if (len < 0)
        return NULL;
    char *s = malloc((size_t)len + 1);
    if (s)
        vsnprintf(s, (size_t)len + 1, fmt, ap);
    return s;
}

void sl_report_tab_init(struct sl_report_tab *t, const char *id, int ncols, int nkeys, const char *fmt, ...)
{
    memset(t, 0, sizeof *t);
    sl_report_slug(id, t->id, sizeof t->id);
    t->ncols = ncols < 1 ? 1 : ncols > SL_REPORT_MAXCOLS ? SL_REPORT_MAXCOLS : ncols;
    t->oom = ncols != t->ncols;
    t->nkeys = nkeys;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->title, sizeof t->title, fmt, ap);
    va_end(ap);
}

void sl_report_tab_head(struct sl_report_tab *t, int col, const char *fmt, ...)
{
    if (col < 0 || col >= t->ncols)
        return;
    va_list ap;
    va_start(ap, fmt);
    free(t->head[col]);
    t->head[col] = vformat(fmt, ap);
    va_end(ap);
    t->oom |= !t->head[col];
}

void sl_report_tab_group(struct sl_report_tab *t, int span, const char *fmt, ...)
{
    if (t->ngroups >= SL_REPORT_MAXCOLS)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(t->group[t->ngroups], sizeof t->group[0], fmt, ap);
    va_end(ap);
    t->span[t->ngroups++] = span;
}

void sl_report_tab_row(struct sl_report_tab *t, int block)
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

void sl_report_tab_muted(struct sl_report_tab *t)
{
    if (t->nrows > 0 && !t->oom)
        t->rule[t->nrows - 1] |= SL_TAB_MUTED;
}

void sl_report_tab_cell(struct sl_report_tab *t, int col, const char *fmt, ...)
{
    if (t->oom || t->nrows == 0 || col < 0 || col >= t->ncols)
        return;
    char **slot = &t->cell[(size_t)(t->nrows - 1) * (size_t)t->ncols + (size_t)col];
    va_list ap;
    va_start(ap, fmt);
    free(*slot);
    *slot = vformat(fmt, ap);
    va_end(ap);
    t->oom |= !*slot;
}

void sl_report_tab_once(struct sl_report_tab *t)
{
    static const char once[] = SL_REPORT_ONCE " timed once (repetitions runs: 1): one measurement, no median.";
    size_t n = strlen(t->note);
    /* whole or not at all: cut short it could end inside the mark's UTF-8 bytes */
    if (!strstr(t->note, once) && n + 1 + strlen(once) < sizeof t->note)
        snprintf(t->note + n, sizeof t->note - n, "%s%s", n ? " " : "", once);
}

void sl_report_tab_free(struct sl_report_tab *t)
{
    for (int k = 0; k < SL_REPORT_MAXCOLS; k++)
        free(t->head[k]);
    for (size_t i = 0; t->cell && i < (size_t)t->nrows * (size_t)t->ncols; i++)
        free(t->cell[i]);
    free(t->cell);
    free(t->rule);
    memset(t, 0, sizeof *t);
}

static const char *tab_at(const struct sl_report_tab *t, int r, int c)
{
    const char *s = t->cell[(size_t)r * (size_t)t->ncols + (size_t)c];
    return s ? s : "";
}

/* ---- escapers ---- */

void sl_report_html_text(FILE *f, const char *s)
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

/* CommonMark: backslash-escape the punctuation that could start markup */
void sl_report_md_text(FILE *f, const char *s)
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


#define html_text sl_report_html_text
#define md_text sl_report_md_text

/* ---- doc ---- */


enum sl_err sl_report_doc_open(struct sl_report_doc *doc, int latex, struct sl_diag *d)
{
    doc->html = open_memstream(&doc->html_buf, &doc->html_len);
    doc->md = open_memstream(&doc->md_buf, &doc->md_len);
    doc->tex = latex ? open_memstream(&doc->tex_buf, &doc->tex_len) : NULL;
    if (!doc->html || !doc->md || (latex && !doc->tex))
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report pages");
    return SL_OK;
}

void sl_report_doc_free(struct sl_report_doc *doc)
{
    FILE **f[3] = {&doc->html, &doc->md, &doc->tex};
    for (int k = 0; k < 3; k++)
        if (*f[k]) {
            fclose(*f[k]);
            *f[k] = NULL;
        }
    free(doc->html_buf);
    free(doc->md_buf);
    free(doc->tex_buf);
    free(doc->heads);
    doc->html_buf = doc->md_buf = doc->tex_buf = NULL;
    doc->heads = NULL;
    doc->nheads = doc->capheads = 0;
}

/* LaTeX text of the report's prose: sl_tex_text (which maps the signs it
 * knows and replaces any other non-ASCII one, so pdflatex never stops). */
static void tex_para(FILE *f, const char *s)
{
    if (f)
        sl_tex_text(f, s);
}

/* A unique id for a heading: the anchor asked for, else a slug of its text. */
static void heading_id(struct sl_report_doc *doc, int level, const char *anchor, const char *text, char *id,
                       size_t n)
{
    char base[80];
    if (anchor && anchor[0]) {
        snprintf(base, sizeof base, "%s", anchor);
    } else {
        size_t k = 0;
        int dash = 1;
        for (const char *p = text; *p && k + 1 < sizeof base && k < 60; p++) {
            char c = *p;
            if (c >= 'A' && c <= 'Z')
                c = (char)(c - 'A' + 'a');
            if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) {
                base[k++] = c;
                dash = 0;
            } else if (!dash) {
                base[k++] = '-';
                dash = 1;
            }
        }
        while (k > 0 && base[k - 1] == '-')
            k--;
        base[k] = '\0';
        if (!k)
            snprintf(base, sizeof base, "s");
    }
    snprintf(id, n, "%s", base);
    for (int k = 2;; k++) {
        int used = 0;
        for (int i = 0; i < doc->nheads && !used; i++)
            used = strcmp(doc->heads[i].id, id) == 0;
        if (!used)
            break;
        snprintf(id, n, "%.80s-%d", base, k);
    }
    if (doc->nheads == doc->capheads) {
        int cap = doc->capheads ? 2 * doc->capheads : 64;
        struct sl_report_heading *h = realloc(doc->heads, (size_t)cap * sizeof *h);
        if (!h) {
            doc->oom = 1;
            return;
        }
        doc->heads = h;
        doc->capheads = cap;
    }
    struct sl_report_heading *h = &doc->heads[doc->nheads++];
    memset(h, 0, sizeof *h);
    h->level = level;
    snprintf(h->id, sizeof h->id, "%s", id);
    snprintf(h->text, sizeof h->text, "%s", text);
}

static void tex_heading(struct sl_report_doc *doc, int level, const char *text)
{
    static const char *const cmd[] = {"section", "section", "section", "subsection", "subsubsection", "paragraph"};
    if (!doc->tex || level < 2)
        return;
    if (level == 2) {
        fputs("\\clearpage\n", doc->tex);
        doc->tex_floats = 0;
    }
    fprintf(doc->tex, "\\%s{", cmd[level > 5 ? 5 : level]);
    tex_para(doc->tex, text);
    fputs("}\n\n", doc->tex);
}

static void heading_at(struct sl_report_doc *doc, int level, const char *anchor, const char *text, int in_summary)
{
    char id[100];
    if (level < 1)
        level = 1;
    if (level > 5)
        level = 5;
    heading_id(doc, level, anchor, text, id, sizeof id);
    if (in_summary) {
        fputs("<details class=\"sec\" id=\"", doc->html);
        html_text(doc->html, id);
        fprintf(doc->html, "\"><summary><h%d>", level);
    } else {
        fprintf(doc->html, "<h%d id=\"", level);
        html_text(doc->html, id);
        fputs("\">", doc->html);
    }
    html_text(doc->html, text);
    if (level > 1) {
        fputs(" <a class=\"anc\" href=\"#", doc->html);
        html_text(doc->html, id);
        fputs("\" title=\"link to this section\">#</a>", doc->html);
    }
    fprintf(doc->html, "</h%d>%s\n", level, in_summary ? "</summary>" : "");
    fprintf(doc->md, "<a id=\"%s\"></a>\n\n", id);   /* ids are slugs: nothing to escape */
    for (int i = 0; i < level; i++)
        fputc('#', doc->md);
    fputc(' ', doc->md);
    md_text(doc->md, text);
    fputs("\n\n", doc->md);
    tex_heading(doc, level, text);
}

void sl_report_doc_heading(struct sl_report_doc *doc, int level, const char *anchor, const char *fmt, ...)
{
    char text[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    heading_at(doc, level, anchor, text, 0);
}

void sl_report_doc_section_begin(struct sl_report_doc *doc, int level, const char *anchor, const char *fmt, ...)
{
    char text[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    heading_at(doc, level, anchor, text, 1);
}

void sl_report_doc_section_end(struct sl_report_doc *doc)
{
    fputs("</details>\n", doc->html);
}

void sl_report_doc_raw_html(struct sl_report_doc *doc, const char *html)
{
    fputs(html, doc->html);
}

void sl_report_doc_para(struct sl_report_doc *doc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *text = vformat(fmt, ap);
    va_end(ap);
    fputs("<p>", doc->html);
    html_text(doc->html, text ? text : "(out of memory)");
    fputs("</p>\n", doc->html);
    md_text(doc->md, text ? text : "(out of memory)");
    fputs("\n\n", doc->md);
    if (doc->tex) {
        tex_para(doc->tex, text ? text : "(out of memory)");
        fputs("\n\n", doc->tex);
    }
    free(text);
}

/* ---- a report file as the page names it: rel, or a data: URI ---- */

/* Here beside sl_report_doc_src, not with the finished pages (page.c): every
 * src/href a body writes goes through it, the gallery's included, so page.c
 * calls doc.c and never the other way. */

char *sl_report_doc_uri(struct sl_report_doc *doc, const char *rel)
{
    if (!doc->self_contained || rel[0] == '#')
        return NULL;
    const char *ext = strrchr(rel, '.');
    const char *mime = !ext                      ? NULL
                       : !strcmp(ext, ".png")    ? "image/png"
                       : !strcmp(ext, ".svg")    ? "image/svg+xml"
                       : !strcmp(ext, ".jpg")    ? "image/jpeg"
                                                 : NULL;
    if (!mime)
        return NULL;
    char path[1400];
    snprintf(path, sizeof path, "%s/%s", doc->out->stage, rel);
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 65536, len = 0;
    unsigned char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + len, 1, cap - len, f)) > 0) {
        len += got;
        if (len == cap) {
            unsigned char *b = realloc(buf, cap * 2);
            if (!b) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = b;
            cap *= 2;
        }
    }
    fclose(f);
    if (!buf)
        return NULL;
    static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t head = strlen(mime) + 14, n = head + 4 * ((len + 2) / 3) + 1;
    char *uri = malloc(n);
    if (uri) {
        size_t k = (size_t)snprintf(uri, n, "data:%s;base64,", mime);
        for (size_t i = 0; i < len; i += 3) {
            unsigned v = (unsigned)buf[i] << 16 | (i + 1 < len ? (unsigned)buf[i + 1] << 8 : 0u) |
                         (i + 2 < len ? buf[i + 2] : 0u);
            uri[k++] = b64[v >> 18 & 63];
            uri[k++] = b64[v >> 12 & 63];
            uri[k++] = i + 1 < len ? b64[v >> 6 & 63] : '=';
            uri[k++] = i + 2 < len ? b64[v & 63] : '=';
        }
        uri[k] = '\0';
    }
    free(buf);
    return uri;
}

/* src/href value of rel: a data: URI when self-contained, else rel */
void sl_report_doc_src(struct sl_report_doc *doc, const char *rel)
{
    char *uri = sl_report_doc_uri(doc, rel);
    html_text(doc->html, uri ? uri : rel);
    free(uri);
}

void sl_report_doc_links(struct sl_report_doc *doc, const char *prefix, const char *const *rel,
                         const char *const *text, int n)
{
    fputs("<p>", doc->html);
    if (prefix) {
        html_text(doc->html, prefix);
        md_text(doc->md, prefix);
    }
    for (int i = 0; i < n; i++) {
        fputs(i ? ", " : (prefix ? " " : ""), doc->html);
        /* a self-contained page links nothing outside itself: files are named, not linked */
        int link = !doc->self_contained || rel[i][0] == '#';
        if (link) {
            fputs("<a href=\"", doc->html);
            html_text(doc->html, rel[i]);
            fputs("\">", doc->html);
            html_text(doc->html, text[i]);
            fputs("</a>", doc->html);
        } else {
            html_text(doc->html, text[i]);
            fputs(" (<code>", doc->html);
            html_text(doc->html, rel[i]);
            fputs("</code>)", doc->html);
        }
        fputs(i ? ", [" : (prefix ? " [" : "["), doc->md);
        md_text(doc->md, text[i]);
        fprintf(doc->md, "](%s)", rel[i]);   /* rel is a checked file name */
    }
    fputs("</p>\n", doc->html);
    fputs("\n\n", doc->md);
}

void sl_report_doc_link(struct sl_report_doc *doc, const char *rel, const char *text)
{
    sl_report_doc_links(doc, NULL, &rel, &text, 1);
}

void sl_report_doc_image(struct sl_report_doc *doc, const char *rel, const char *caption)
{
    fputs("<figure><img src=\"", doc->html);
    sl_report_doc_src(doc, rel);
    fputs("\" alt=\"", doc->html);
    html_text(doc->html, caption);
    fputs("\"><figcaption>", doc->html);
    html_text(doc->html, caption);
    fputs("</figcaption></figure>\n", doc->html);
    fputs("![", doc->md);
    md_text(doc->md, caption);
    fprintf(doc->md, "](%s)\n\n", rel);
    md_text(doc->md, caption);
    fputs("\n\n", doc->md);
}

void sl_report_doc_tex_figure(struct sl_report_doc *doc, const char *pdf_rel, const char *caption)
{
    if (!doc->tex)
        return;
    fprintf(doc->tex, "\\begin{figure}[htbp]\n\\centering\n\\includegraphics[width=\\linewidth]{%s}\n\\caption{",
            pdf_rel);   /* a checked file name: letters, digits, . _ - / */
    tex_para(doc->tex, caption);
    fputs("}\n\\end{figure}\n\n", doc->tex);
}

void sl_report_doc_details(struct sl_report_doc *doc, const char *summary, const char *text)
{
    fputs("<details><summary>", doc->html);
    html_text(doc->html, summary);
    fputs("</summary><pre>", doc->html);
    html_text(doc->html, text);
    fputs("</pre></details>\n", doc->html);
    md_text(doc->md, summary);
    /* a fence longer than any run of backticks in the text */
    int run = 0, longest = 0;
    for (const char *p = text; p && *p; p++) {
        run = *p == '`' ? run + 1 : 0;
        if (run > longest)
            longest = run;
    }
    int fence = longest < 3 ? 3 : longest + 1;
    fputs(":\n\n", doc->md);
    for (int i = 0; i < fence; i++)
        fputc('`', doc->md);
    fputs("yaml\n", doc->md);
    fputs(text ? text : "", doc->md);
    if (text && text[0] && text[strlen(text) - 1] != '\n')
        fputc('\n', doc->md);
    for (int i = 0; i < fence; i++)
        fputc('`', doc->md);
    fputs("\n\n", doc->md);
}

void sl_report_doc_list(struct sl_report_doc *doc, const char *const *items, int n)
{
    fputs("<ul>\n", doc->html);
    for (int i = 0; i < n; i++) {
        fputs("<li>", doc->html);
        html_text(doc->html, items[i]);
        fputs("</li>\n", doc->html);
        fputs("- ", doc->md);
        md_text(doc->md, items[i]);
        fputc('\n', doc->md);
    }
    fputs("</ul>\n", doc->html);
    fputc('\n', doc->md);
}

static void html_table(FILE *f, const struct sl_report_tab *t, const char *texrel, int self_contained)
{
    fputs(t->wrap ? "<div class=\"tab\"><table class=\"wrap\">\n<caption>" : "<div class=\"tab\"><table>\n<caption>", f);
    html_text(f, t->title);
    fputs("</caption>\n<thead>\n", f);
    if (t->ngroups) {
        fputs("<tr>", f);
        for (int g = 0; g < t->ngroups; g++) {
            fprintf(f, "<th colspan=\"%d\"%s>", t->span[g], t->group[g][0] ? " class=\"grp\"" : "");
            html_text(f, t->group[g]);
            fputs("</th>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("<tr>", f);
    for (int c = 0; c < t->ncols; c++) {
        fputs(c < t->nkeys ? "<th class=\"k\">" : "<th>", f);
        html_text(f, t->head[c] ? t->head[c] : "");
        fputs("</th>", f);
    }
    fputs("</tr>\n</thead>\n<tbody>\n", f);
    for (int r = 0; r < t->nrows; r++) {
        static const char *const tr[4] = {"<tr>", "<tr class=\"blk\">", "<tr class=\"muted\">",
                                          "<tr class=\"blk muted\">"};
        fputs(tr[t->rule[r] & 3], f);
        for (int c = 0; c < t->ncols; c++) {
            fputs(c < t->nkeys ? "<td class=\"k\">" : "<td>", f);
            html_text(f, tab_at(t, r, c));
            fputs("</td>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("</tbody>\n</table>\n<p class=\"note\">", f);
    if (t->note[0]) {
        html_text(f, t->note);
        fputc(' ', f);
    }
    if (self_contained) {   /* named, not linked: the one file refers to nothing outside */
        fputs("LaTeX: <code>", f);
        html_text(f, texrel);
        fputs("</code></p></div>\n", f);
    } else {
        fputs("<a href=\"", f);
        html_text(f, texrel);
        fputs("\">LaTeX</a></p></div>\n", f);
    }
}

static void md_table(FILE *f, const struct sl_report_tab *t, const char *texrel)
{
    fputs("**", f);
    md_text(f, t->title);
    fputs("**\n\n|", f);
    /* Markdown has no spanning cells: the group goes in front of its columns' heads */
    int g = 0, left = t->ngroups ? t->span[0] : 0;
    for (int c = 0; c < t->ncols; c++) {
        fputc(' ', f);
        if (t->ngroups && g < t->ngroups && t->group[g][0]) {
            md_text(f, t->group[g]);
            fputc(' ', f);
        }
        md_text(f, t->head[c] ? t->head[c] : "");
        fputs(" |", f);
        if (t->ngroups && --left == 0 && ++g < t->ngroups)
            left = t->span[g];
    }
    fputs("\n|", f);
    for (int c = 0; c < t->ncols; c++)
        fputs(c < t->nkeys ? "---|" : "---:|", f);
    fputc('\n', f);
    for (int r = 0; r < t->nrows; r++) {
        fputc('|', f);
        for (int c = 0; c < t->ncols; c++) {
            fputc(' ', f);
            md_text(f, tab_at(t, r, c));
            fputs(" |", f);
        }
        fputc('\n', f);
    }
    fputc('\n', f);
    if (t->note[0]) {
        md_text(f, t->note);
        fputc(' ', f);
    }
    fprintf(f, "[LaTeX](%s)\n\n", texrel);
}

/* Lines of a table per float (a stacked or wrapped row takes more than one):
 * a longer one is split into parts, each a float of its own that fits a
 * page. */
#define TEX_LINES 44

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
static double col_pt(const struct sl_report_tab *t, int c, int stack, int word)
{
    double w = t->head[c] ? cell_pt(t->head[c], stack ? 2 : 0, word) : 0;
    for (int r = 0; r < t->nrows; r++) {
        double x = cell_pt(tab_at(t, r, c), stack, word);
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
    int    wraps[SL_REPORT_MAXCOLS];    /* may be set in a \parbox */
    double w[SL_REPORT_MAXCOLS];        /* as printed */
    double minw[SL_REPORT_MAXCOLS];     /* wrapped as far as it goes */
    int    cut[SL_REPORT_MAXCOLS + 1];  /* columns [cut[k], cut[k+1]) per column part */
    int    ncut;
};

static int in_part(const struct tex_layout *lo, int cp, int c)
{
    return c < lo->nfixed || (c >= lo->cut[cp] && c < lo->cut[cp + 1]);
}

/* a group's heading wider than its columns widens them evenly */
static void group_spread(const struct sl_report_tab *t, double *w)
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
static void part_boxes(const struct tex_layout *lo, const struct sl_report_tab *t, int cp, double *box)
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

static void tex_part(FILE *f, const struct sl_report_tab *t, const struct tex_layout *lo, int cp, int from, int to,
                     int part, int parts)
{
    double box[SL_REPORT_MAXCOLS];
    part_boxes(lo, t, cp, box);
    fputs("\\begin{table}[htbp]\n\\centering\n\\footnotesize\n\\setlength{\\tabcolsep}{4pt}\n\\caption{", f);
    sl_tex_text(f, t->title);
    if (parts > 1)
        fprintf(f, " (part %d of %d)", part + 1, parts);
    fputc('}', f);
    if (part == 0)
        fprintf(f, "\n\\label{tab:%s}", t->id);
    fputs("\n\\begin{tabular}{", f);
    for (int c = 0; c < t->ncols; c++)
        if (in_part(lo, cp, c))
            fputc(c < t->nkeys || box[c] > 0 ? 'l' : 'r', f);
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
        tex_cell(f, t->head[c] ? t->head[c] : "", lo->stack && !lo->wraps[c] ? 2 : 0, c < t->nkeys ? 'l' : 'r',
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
            tex_cell(f, tab_at(t, r, c), lo->stack && !lo->wraps[c], c < t->nkeys ? 'l' : 'r', box[c]);
        }
        fputs(" \\\\\n", f);
    }
    fputs("\\bottomrule\n\\end{tabular}\n", f);
    if (t->note[0] && part == parts - 1) {
        fputs("\n\\smallskip\n\\parbox{\\linewidth}{\\scriptsize\\raggedright ", f);
        sl_tex_text(f, t->note);
        fputs("\\par}\n", f);
    }
    fputs("\\end{table}\n", f);
}

static void tex_fit(const struct sl_report_tab *t, struct tex_layout *lo)
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
    unsigned char edge[SL_REPORT_MAXCOLS + 1] = {0};
    for (int g = 0, gs = 0; g < t->ngroups && gs + t->span[g] <= SL_REPORT_MAXCOLS; g++)
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
static double row_lines(const struct sl_report_tab *t, const struct tex_layout *lo, int cp, const double *box, int r)
{
    double lines = 1;
    for (int c = 0; c < t->ncols; c++) {
        if (!in_part(lo, cp, c))
            continue;
        const char *v = tab_at(t, r, c);
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
static int row_cuts(const struct sl_report_tab *t, const struct tex_layout *lo, int cp, int *cut)
{
    double box[SL_REPORT_MAXCOLS];
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

/* returns the floats written since its last \\clearpage */
static int tex_table(FILE *f, const struct sl_report_tab *t)
{
    fputs("% shadowlab report table; needs \\usepackage{booktabs}; a wide one is split, never scaled\n", f);
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

enum sl_err sl_report_doc_table(struct sl_report_doc *doc, const struct sl_report_tab *t, struct sl_diag *d)
{
    if (t->oom)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, t->id, "report table");
    char rel[200], path[1400];
    snprintf(rel, sizeof rel, "tex/%s.tex", t->id);
    /* two tables may share an id (slugs fold names): number the later ones */
    for (int k = 2; sl_report_out_has(doc->out, rel); k++)
        snprintf(rel, sizeof rel, "tex/%s-%d.tex", t->id, k);
    enum sl_err e = sl_report_out_path(doc->out, rel, 1, path, sizeof path, d);
    if (e)
        return e;
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    int floats = tex_table(f, t);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
    html_table(doc->html, t, rel, doc->self_contained);
    md_table(doc->md, t, rel);
    doc->ntables++;
    if (doc->tex) {
        fprintf(doc->tex, "\\input{%s}\n", rel);
        /* a float per table part: flushed every few so LaTeX never holds
         * more than its 18 unprocessed floats */
        doc->tex_floats += floats;
        if (doc->tex_floats >= 8) {
            fputs("\\clearpage\n", doc->tex);
            doc->tex_floats = 0;
        }
    }
    return SL_OK;
}

