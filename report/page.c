/*
 * page.c — the report's pages as files (see report_int.h, doc): the
 * contents tree put in front of the bodies doc.c wrote, the LaTeX document
 * around its \\inputs, and the overlay gallery with its filters (its
 * thumbnails' src through doc.c's sl_report_doc_src, as every image's).
 *
 * Invariants:
 * - The pages are registered last-moved (SL_REPORT_PAGE), so the folder
 *   never holds a report.html whose images are not there yet.
 * - Only the ids doc.c made (slugs) and escaped text reach a page.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "report_int.h"
#include "table.h"

#define html_text sl_emit_html_text
#define md_text sl_emit_md_text
#define SL_REPORT_PAGE 2   /* keep value of the pages: moved after every other file */

/* the distinct values of one key of the thumbnails, in order of first appearance */
static void filter_select(FILE *f, const struct sl_report_thumb *t, int n, size_t off, const char *key,
                          const char *name)
{
    fprintf(f, "<label>%s <select data-k=\"%s\"><option value=\"\">all</option>", name, key);
    for (int i = 0; i < n; i++) {
        const char *v = *(const char *const *)((const char *)&t[i] + off);
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = strcmp(*(const char *const *)((const char *)&t[j] + off), v) == 0;
        if (seen)
            continue;
        fputs("<option>", f);
        html_text(f, v);
        fputs("</option>", f);
    }
    fputs("</select></label> ", f);
}

void sl_report_doc_filter_gallery(struct sl_report_doc *doc, const struct sl_report_thumb *t, int n)
{
    FILE *f = doc->html;
    char gid[32];   /* one gallery per study, each under its own heading */
    snprintf(gid, sizeof gid, "gal-%d", doc->nheads);
    fprintf(f, "<div class=\"filters\" data-for=\"%s\">Show: ", gid);
    filter_select(f, t, n, offsetof(struct sl_report_thumb, scene), "scene", "scene");
    filter_select(f, t, n, offsetof(struct sl_report_thumb, view), "view", "view");
    filter_select(f, t, n, offsetof(struct sl_report_thumb, map), "map", "map");
    filter_select(f, t, n, offsetof(struct sl_report_thumb, method), "method", "method");
    fprintf(f, "<span class=\"count\">%d overlays</span></div>\n<div class=\"gallery\" id=\"%s\">\n", n, gid);
    for (int i = 0; i < n; i++) {
        fputs("<figure id=\"", f);
        html_text(f, t[i].id);
        fputs("\" data-scene=\"", f);
        html_text(f, t[i].scene);
        fputs("\" data-view=\"", f);
        html_text(f, t[i].view);
        fputs("\" data-map=\"", f);
        html_text(f, t[i].map);
        fputs("\" data-method=\"", f);
        html_text(f, t[i].method);
        /* linked page: the thumbnail opens the full PNG; one file: it opens
         * in place (figure:target spans the grid at full size), so the image
         * is embedded once */
        fputs("\"><a href=\"", f);
        if (doc->self_contained) {
            fputc('#', f);
            html_text(f, t[i].id);
        } else {
            html_text(f, t[i].rel);
        }
        fputs("\"><img loading=\"lazy\" src=\"", f);
        sl_report_doc_src(doc, t[i].rel);
        fputs("\" alt=\"", f);
        html_text(f, t[i].caption);
        fputs("\"></a><figcaption>", f);
        html_text(f, t[i].caption);
        fputs("</figcaption></figure>\n", f);
        fputs("- ![", doc->md);
        md_text(doc->md, t[i].caption);
        fprintf(doc->md, "](%s) ", t[i].rel);
        md_text(doc->md, t[i].caption);
        fputc('\n', doc->md);
    }
    fputs("</div>\n", f);
    fputc('\n', doc->md);
}

/* ---- the pages ---- */

static enum sl_err write_page(struct sl_report_doc *doc, const char *rel, int keep, const char *a, const char *b,
                              size_t blen, const char *c, const char *e2, size_t e2len, const char *f2,
                              struct sl_diag *d)
{
    char path[1400];
    enum sl_err e = sl_report_out_path(doc->out, rel, keep, path, sizeof path, d);
    if (e)
        return e;
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write: %s", strerror(errno));
    fputs(a, f);
    fwrite(b, 1, blen, f);
    fputs(c, f);
    fwrite(e2, 1, e2len, f);
    fputs(f2, f);
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "write failed");
    return SL_OK;
}

/* The contents tree: nested lists of every heading below the title. */
static void toc_html(FILE *f, const struct sl_report_doc *doc)
{
    fputs("<nav class=\"toc\"><b>Contents</b>\n", f);
    int depth = 0;
    for (int i = 0; i < doc->nheads; i++) {
        const struct sl_report_heading *h = &doc->heads[i];
        if (h->level < 2)
            continue;
        int want = h->level - 1;
        if (depth >= want)
            fputs("</li>\n", f);
        while (depth > want) {
            fputs("</ul></li>\n", f);
            depth--;
        }
        while (depth < want) {
            fputs(depth + 1 < want ? "<ul><li>" : "<ul>", f);
            depth++;
        }
        fputs("<li><a href=\"#", f);
        html_text(f, h->id);
        fputs("\">", f);
        html_text(f, h->text);
        fputs("</a>", f);
    }
    while (depth > 0) {
        fputs("</li></ul>", f);
        depth--;
    }
    fputs("</nav>\n", f);
}

static void toc_md(FILE *f, const struct sl_report_doc *doc)
{
    fputs("**Contents**\n\n", f);
    for (int i = 0; i < doc->nheads; i++) {
        const struct sl_report_heading *h = &doc->heads[i];
        if (h->level < 2)
            continue;
        for (int k = 2; k < h->level; k++)
            fputs("  ", f);
        fputs("- [", f);
        md_text(f, h->text);
        fprintf(f, "](#%s)\n", h->id);
    }
    fputc('\n', f);
}

enum sl_err sl_report_doc_finish(struct sl_report_doc *doc, const char *head, const char *tail,
                                 const char *tex_title, struct sl_diag *d)
{
    int bad = 0;
    FILE **f[3] = {&doc->html, &doc->md, &doc->tex};
    for (int k = 0; k < 3; k++)
        if (*f[k]) {
            bad |= ferror(*f[k]);
            bad |= fclose(*f[k]) != 0;
            *f[k] = NULL;
        }
    if (bad || doc->oom)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report pages");
    char *toch = NULL, *tocm = NULL;
    size_t tochn = 0, tocmn = 0;
    FILE *th = open_memstream(&toch, &tochn), *tm = open_memstream(&tocm, &tocmn);
    if (!th || !tm) {
        if (th)
            fclose(th);
        if (tm)
            fclose(tm);
        free(toch);
        free(tocm);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report contents");
    }
    toc_html(th, doc);
    toc_md(tm, doc);
    fclose(th);
    fclose(tm);
    enum sl_err e = SL_OK;
    if (doc->tex_buf) {
        static const char pre[] =
            "% shadowlab report: pdflatex report.tex (twice, for the contents)\n"
            "\\documentclass[a4paper,10pt]{article}\n\\usepackage[utf8]{inputenc}\n\\usepackage[T1]{fontenc}\n"
            "\\usepackage{lmodern}\n\\usepackage{booktabs}\n\\usepackage{graphicx}\n"
            "\\extrafloats{200}\n\\setcounter{topnumber}{4}\n\\setcounter{totalnumber}{6}\n"
            "\\renewcommand{\\topfraction}{0.95}\n\\renewcommand{\\textfraction}{0.05}\n"
            "\\renewcommand{\\floatpagefraction}{0.6}\n\\sloppy\n\\begin{document}\n\\title{";
        char *t = NULL;
        size_t tn = 0;
        FILE *tt = open_memstream(&t, &tn);
        if (!tt)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report.tex");
        if (!e) {
            sl_tex_text(tt, tex_title);
            fputs("}\n\\author{}\n\\date{}\n\\maketitle\n\\tableofcontents\n\n", tt);
            fclose(tt);
            char *a = malloc(sizeof pre + tn);
            if (!a) {
                e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report.tex");
            } else {
                memcpy(a, pre, sizeof pre - 1);
                memcpy(a + sizeof pre - 1, t, tn);
                a[sizeof pre - 1 + tn] = '\0';
                e = write_page(doc, "report.tex", 1, a, doc->tex_buf, doc->tex_len, "", "", 0,
                               "\n\\end{document}\n", d);
                free(a);
            }
            free(t);
        }
    }
    if (!e)
    {
        /* the contents go before the first heading below the title */
        const char *cut = doc->md_buf && doc->md_len > 1 ? strstr(doc->md_buf + 1, "<a id=") : NULL;
        size_t at = cut ? (size_t)(cut - doc->md_buf) : doc->md_len;
        e = write_page(doc, "report.md", SL_REPORT_PAGE, "", doc->md_buf, at, tocm, doc->md_buf + at,
                       doc->md_len - at, "", d);
    }
    if (!e) {
        /* head, the title block, the contents, the rest: the body's first
         * part (title and summary line) ends at the first "<h2" */
        const char *cut = doc->html_buf ? strstr(doc->html_buf, "<h2") : NULL;
        size_t at = cut ? (size_t)(cut - doc->html_buf) : 0;
        char *first = malloc(strlen(head) + at + tochn + 1);
        if (!first) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "report.html");
        } else {
            size_t k = strlen(head);
            memcpy(first, head, k);
            memcpy(first + k, doc->html_buf, at);
            memcpy(first + k + at, toch, tochn);
            first[k + at + tochn] = '\0';
            e = write_page(doc, "report.html", SL_REPORT_PAGE, first, doc->html_buf + at, doc->html_len - at, tail,
                           "", 0, "", d);
            free(first);
        }
    }
    free(toch);
    free(tocm);
    return e;
}
