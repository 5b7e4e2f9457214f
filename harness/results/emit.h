/*
 * emit.h — one emitter per table format, each in its own file, each owning
 * its format's escaping and number formatting: emit_md.c (Markdown),
 * emit_csv.c (CSV, RFC 4180), emit_tex.c (LaTeX booktabs floats, table* so that
 * a two-column class takes them, fitted to the line and never scaled; also tex.h's text and numbers), emit_html.c (an
 * HTML table) and emit_json.c (an object per table). Each writes one table
 * of the model (tabmodel.h) to a stream.
 *
 * Adding a format: a file emit_<name>.c with one function of the sl_emit_fn
 * type, its declaration here, and its line in sl_emitters (emit.c). The
 * writers build models and never change for a new format.
 *
 * Does not: open files, decide what a table holds.
 */
#ifndef SL_EMIT_H
#define SL_EMIT_H
#include <stdio.h>
#include "tabmodel.h"

/* Where a table sits in its stream, and what a page around it adds (the
 * report's: a companion file named under it). Zero: a table alone, nothing
 * around it. */
struct sl_emit_opts {
    const char *link;        /* a file beside the page (the table's .tex), linked under the table */
    int         link_named;  /* HTML: name it, do not link it (a page that refers to nothing outside) */
    int         first;       /* the first table of its stream: CSV writes its header, JSON no comma before it */
    int         gap;         /* Markdown: a blank line before it (after text that ends without one) */
    int         tight;       /* Markdown: the stream ends after its note: no blank line after it */
    const char *comment;     /* LaTeX: the first table's comment line, without "% " (NULL: the report's);
                              * before a paged table, a blank line follows it */
    int         clear;       /* LaTeX, fixed: a \clearpage and a blank line before it (the writer counts
                              * its floats: LaTeX holds at most 18 it has not placed) */
    int         blank;       /* LaTeX, fixed: a blank line after it */
    int         color;       /* terminal: a verdict column in colour (the caller decides: a TTY, no NO_COLOR) */
};

/* Writes t; returns the floats it took (LaTeX, since its last \clearpage;
 * 0 for a format without floats), or -1 when t cannot be written (out of
 * memory; LaTeX: wider than SL_TAB_MAXCOLS columns). */
typedef int (*sl_emit_fn)(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);

int sl_emit_md(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);
int sl_emit_csv(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);
int sl_emit_tex(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);
int sl_emit_html(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);
int sl_emit_json(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);
int sl_emit_term(FILE *f, const struct sl_tab *t, const struct sl_emit_opts *o);

/* The emitters by name ("md", "csv", "latex", "html", "json", "term"), a
 * sentinel-terminated table; sl_emit_find returns NULL for an unknown name. */
struct sl_emitter {
    const char *name;
    sl_emit_fn  emit;
};
extern const struct sl_emitter sl_emitters[];
sl_emit_fn sl_emit_find(const char *name);

/* A comment line of a stream of LaTeX tables (sl_emit_tex writes one before
 * the first table: o->comment, NULL: the report's; before a paged table a
 * blank line follows it); blank: a blank line after it. A writer calls it
 * for a stream with no table, or for a second line (what it is from). */
void sl_emit_tex_comment(FILE *f, const char *comment, int blank);
/* A \clearpage and a blank line, where a writer that counts its floats needs
 * one (LaTeX holds at most 18 it has not placed). */
void sl_emit_tex_clearpage(FILE *f);

/* Text escaped for HTML (& < > " ') and for CommonMark (markup punctuation);
 * a JSON string, quoted (" \ and the control characters escaped). */
void sl_emit_html_text(FILE *f, const char *s);
void sl_emit_md_text(FILE *f, const char *s);
void sl_emit_json_text(FILE *f, const char *s);

#endif
