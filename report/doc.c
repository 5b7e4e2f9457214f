/*
 * doc.c — the staging folder and the two pages (see report_int.h); a
 * table goes into them through the emitters (emit.h).
 *
 * Invariants:
 * - Every file of the report is registered with sl_report_out_path before
 *   it is written, so commit moves exactly those files and abort removes
 *   exactly those (never anything it did not write: no recursive deletes).
 * - Registered paths are relative, made of [A-Za-z0-9._-] and '/', and never
 *   start with '.' or contain "..": a cell's names cannot escape the folder.
 * - Text reaches a page only through the emitters' escapers (emit.h:
 *   html_text, md_text; sl_tex_text in emit_tex.c), so a label or path can
 *   never break a page or a table.
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

/* ---- escapers ---- */

#define html_text sl_emit_html_text
#define md_text sl_emit_md_text

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
    char *text = sl_vformat(fmt, ap);
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

void sl_report_tab_once(struct sl_tab *t)
{
    static const char once[] = SL_REPORT_ONCE " timed once (repetitions runs: 1): one measurement, no median.";
    if (!t->note || !strstr(t->note, once))
        sl_tab_note_cat(t, "%s%s", t->note && t->note[0] ? " " : "", once);
}

enum sl_err sl_report_doc_table(struct sl_report_doc *doc, const struct sl_tab *t, struct sl_diag *d)
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
    const struct sl_emit_opts own = {.first = 1}, page = {.link = rel, .link_named = doc->self_contained};
    int floats = sl_emit_tex(f, t, &own);
    int bad = ferror(f) || floats < 0;
    if (fclose(f) != 0 || bad)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
    sl_emit_html(doc->html, t, &page);
    sl_emit_md(doc->md, t, &page);
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

