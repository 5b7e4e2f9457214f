/*
 * report_int.h — the report's parts, shared by the files of report/ only:
 *   out    the staging folder and the list of files to move into place
 *   tab    the tables: the one table model (results/tabmodel.h), written by
 *          the emitters (emit.h) in HTML, Markdown and LaTeX, so the three
 *          can never disagree
 *   doc    the two pages written in step (HTML and Markdown)
 *   study  one config's cells and the keys they span
 * and the sections: layouts.c (Moderno's and Curtis's thesis tables, costs),
 * morais.c (Morais's tables), plots.c (gnuplot); the theses' numbers are
 * data files read by theses.c (theses.h).
 * Nothing here prints; every fallible call returns an sl_err.
 */
#ifndef SL_REPORT_INT_H
#define SL_REPORT_INT_H
#include <math.h>
#include <stdio.h>
#include "emit.h"
#include "report.h"
#include "tabmodel.h"
#include "theses.h"

/* ---- out ---- */

struct sl_report_file {
    char *rel;      /* path inside the report folder */
    int   keep;     /* 0: scratch, removed at commit; 1: moved into place; 2: moved after every 1 */
};

struct sl_report_out {
    char  dir[1024];
    char  stage[1100];
    struct sl_report_file *files;
    int   n, cap;
};

enum sl_err sl_report_out_begin(struct sl_report_out *o, const char *dir, struct sl_diag *d);
/* Register rel (made of [A-Za-z0-9._-] and '/') and give its staging path,
 * making its folders. Registering a rel twice is SL_E_INTERNAL. */
enum sl_err sl_report_out_path(struct sl_report_out *o, const char *rel, int keep, char *path, size_t n,
                               struct sl_diag *d);
/* 1 if rel is registered. */
int         sl_report_out_has(const struct sl_report_out *o, const char *rel);
enum sl_err sl_report_out_commit(struct sl_report_out *o, struct sl_diag *d);
void        sl_report_out_abort(struct sl_report_out *o);   /* also frees */

/* The report's tables are the one table model (tabmodel.h), written by the
 * emitters (emit.h): HTML and Markdown into the pages, LaTeX into tex/.
 * SL_REPORT_MAXCOLS: the columns a table of Morais's layout holds at most
 * (its map sizes and labels past that are left out), as when the report's
 * tables had at most 24. */
#define SL_REPORT_MAXCOLS 24

/* A time measured once (repetitions runs: 1) is marked in every table that
 * prints it: SL_REPORT_ONCE after the value, and the table's note says what
 * the mark means (sl_report_tab_once, after the note is written). */
#define SL_REPORT_ONCE "\xE2\x80\xA0"   /* † */
void sl_report_tab_once(struct sl_tab *t);

/* ---- doc ---- */

/* A heading as the contents tree lists it. */
struct sl_report_heading {
    int  level;
    char id[96];
    char text[160];
};

/* html, md and tex are the pages' bodies (memory streams, see
 * sl_report_doc_open): the contents tree goes in front of them when the
 * pages are finished, since it lists every heading. tex is NULL without
 * --latex. */
struct sl_report_doc {
    FILE *html, *md, *tex;
    char *html_buf, *md_buf, *tex_buf;
    size_t html_len, md_len, tex_len;
    struct sl_report_out *out;
    int   ntables;
    int   tex_floats;   /* floats since the last \\clearpage */
    int   self_contained;   /* images and plots as data: URIs */
    int   gp_pdf;           /* gnuplot's pdfcairo terminal: 0 not asked yet, 1 there, -1 not */
    struct sl_report_heading *heads;
    int   nheads, capheads;
    int   oom;
};

enum sl_err sl_report_doc_open(struct sl_report_doc *doc, int latex, struct sl_diag *d);
/* Close the body streams and write the pages: HTML (head, contents tree,
 * body), Markdown (contents list, body), and with --latex the document
 * report.tex. `head` is the HTML up to <body>, `tail` after the body. */
enum sl_err sl_report_doc_finish(struct sl_report_doc *doc, const char *head, const char *tail,
                                 const char *tex_title, struct sl_diag *d);
void        sl_report_doc_free(struct sl_report_doc *doc);
/* A collapsible section (<details>) headed at level, listed in the contents. */
void sl_report_doc_section_begin(struct sl_report_doc *doc, int level, const char *anchor, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
void sl_report_doc_section_end(struct sl_report_doc *doc);
/* Raw HTML into the page only (the caller escapes). */
void sl_report_doc_raw_html(struct sl_report_doc *doc, const char *html);
/* The page's value for a src/href of a report file: rel, or with
 * self_contained a data: URI of the staged file (malloc'ed; NULL if out of
 * memory or unreadable, then rel is used). */
char *sl_report_doc_uri(struct sl_report_doc *doc, const char *rel);
/* Write that value into the page, HTML-escaped. */
void  sl_report_doc_src(struct sl_report_doc *doc, const char *rel);
/* One gallery item with its filter keys (HTML data- attributes). */
struct sl_report_thumb {
    const char *rel, *caption, *scene, *view, *map, *method, *id;
};
void sl_report_doc_filter_gallery(struct sl_report_doc *doc, const struct sl_report_thumb *t, int n);
/* \includegraphics of a plot's PDF in the LaTeX document (nothing without --latex). */
void sl_report_doc_tex_figure(struct sl_report_doc *doc, const char *pdf_rel, const char *caption);

void sl_report_doc_heading(struct sl_report_doc *doc, int level, const char *anchor, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
void sl_report_doc_para(struct sl_report_doc *doc, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* "text" linking to rel, as a paragraph of its own */
void sl_report_doc_link(struct sl_report_doc *doc, const char *rel, const char *text);
/* Links in one paragraph: rel[i] named text[i]; prefix before them. */
void sl_report_doc_links(struct sl_report_doc *doc, const char *prefix, const char *const *rel,
                         const char *const *text, int n);
void sl_report_doc_image(struct sl_report_doc *doc, const char *rel, const char *caption);
void sl_report_doc_details(struct sl_report_doc *doc, const char *summary, const char *text);
void sl_report_doc_list(struct sl_report_doc *doc, const char *const *items, int n);
/* The table in both pages, its .tex in tex/<id>.tex linked under it. */
enum sl_err sl_report_doc_table(struct sl_report_doc *doc, const struct sl_tab *t, struct sl_diag *d);

/* ---- study ---- */

#define SL_REPORT_MAXKEYS 64

/* light: the scene's light in words (cellcols.h), "" when unknown; n_outside_cone
 * and n_image: a spot light's pixels outside its cone and the image's pixels */
struct sl_report_view { char scene[64], viewpoint[32], light[48]; int vw, vh; uint64_t n_outside_cone, n_image; };

struct sl_report_study {
    char  name[64], slug[64];
    const struct sl_cell_record *cells;   /* the study's cells (not owned) */
    int   n;
    struct sl_report_view views[256];    /* scene x viewpoint x viewport, in order of first appearance */
    int   nviews;
    char  scenes[SL_REPORT_MAXKEYS][64];
    int   nscenes;
    char  labels[SL_REPORT_MAXKEYS][48], methods[SL_REPORT_MAXKEYS][32];
    char  family[SL_REPORT_MAXKEYS][40], beside[SL_REPORT_MAXKEYS][64];   /* the label's method's (cells.family) */
    int   nlabels;
    int   maps[SL_REPORT_MAXKEYS], nmaps;          /* ascending */
    int   regions[SL_MAX_REGIONS], nregions;       /* contours ascending, whole image (0) last */
    int   moderno, morais;                         /* a thesis's own method ran: its sections (layouts.c) */
    int   area;                                    /* cells under an area light (has_soft, not frac) */
    int   curtis;                                  /* area cells and a Curtis 2009 method among the labels */
    int   frac;                                    /* cells with a hard light's fractional errors (frac) */
};

/* Fill the keys of s from its cells; SL_E_USAGE when they exceed the limits. */
enum sl_err sl_report_study_keys(struct sl_report_study *s, struct sl_diag *d);
/* The study's cell of a key, NULL if none. */
/* A label's display name (its cells'), else the label: every row and legend
 * names a method so. */
const char *sl_report_display(const struct sl_report_study *s, const char *label);
const struct sl_cell_record *sl_report_study_cell(const struct sl_report_study *s, const struct sl_report_view *v,
                                                 const char *label, int map_size);
/* Index of a region of thickness t in the cell, -1 if it has none. */
int sl_report_region(const struct sl_cell_record *c, int thickness);
void sl_report_region_name(int thickness, char *buf, size_t n);

/* plots.c: a plot of another section, drawn (plots/NAME.{dat,gp,svg,pdf}; body
 * reads the data as DATA) and shown with its caption */
enum sl_err sl_report_plot_draw(struct sl_report_doc *doc, const char *gnuplot, const char *name, int w, int h,
                                const char *data, const char *body, const char *caption, struct sl_diag *d);
/* motion.c: the study's paths (results/motion.h), when it has any */
enum sl_err sl_report_motion(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                             struct sl_diag *d);

/* layouts.c */
/* ms as the tables print it: "–" when not > 0, else 2, 1 or 0 decimals by size */
void sl_report_fmt_ms(char *buf, size_t n, double ms);
/* A view's title ("scene (light) / viewpoint / WxH") and a table id "slug-what-scene-viewpoint-WxH". */
void sl_report_view_title(const struct sl_report_view *v, char *buf, size_t n);
void sl_report_view_id(const struct sl_report_study *s, const struct sl_report_view *v, const char *what, char *buf,
                       size_t n);
enum sl_err sl_report_moderno(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d);
enum sl_err sl_report_costs(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d);
/* Soft shadows: per view, rows label x map size, the soft figures and their cost */
enum sl_err sl_report_curtis(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d);
/* family_of(method, MODERNO / MORAIS) > 0: the layout's tables list the method */
/* sl_report_family_of for label l of the study; is_*: > 0 */
int sl_report_label_in(const struct sl_report_study *s, int l, enum sl_report_family f);
int sl_report_is_moderno(const struct sl_report_study *s, int l);
int sl_report_is_morais(const struct sl_report_study *s, int l);

/* ---- Morais 2015 (morais.c; his numbers: theses.h) ---- */

const char *sl_morais_row_name(enum sl_morais_row r);   /* as the thesis names it */

/* One cell's (whole image's) rows on Morais's base: n[] the counts, base[]
 * the count each percentage is taken of (0: no percentage). From the stored
 * figures by figures.h's counting rules: PnFL pixels are always shadow and
 * never wrong, so shadow - pnfl and shadow_correct - pnfl are the PFL
 * counts; traced pixels are PFL pixels (a method traces no other), split by
 * the truth into traced_shadow and the rest, as shares of the final light
 * and shadow (the thesis's base). Returns 0 when the cell has no
 * whole-image region. */
struct sl_morais_counts { uint64_t n[SL_MR_COUNT], base[SL_MR_COUNT]; };
int sl_morais_counts(const struct sl_cell_record *c, struct sl_morais_counts *out);

/* Tables 4-30 for the thesis's three cases, beside the thesis's numbers;
 * Hertel 2009's classification (hertel, hertel_exact) per case; every other
 * view in the same rows without a thesis column. */
enum sl_err sl_report_morais(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d);

/* fractional.c: a hard light's fractional errors (frac cells) per label and map size */
enum sl_err sl_report_fractional(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                                 struct sl_diag *d);

/* fidelity.c: Moderno 2011's Primitives numbers and claims beside the study's */
enum sl_err sl_report_fidelity(struct sl_report_doc *doc, const struct sl_report_study *s, struct sl_diag *d);
/* The Bench scenes' validation against Morais's Tables 7-24 (scenes/CALIBRATION.md):
 * per viewport, the median of ours / thesis and the share within 2x. */
enum sl_err sl_report_fidelity_morais(struct sl_report_doc *doc, const struct sl_report_study *s,
                                      struct sl_diag *d);
/* The Bench scenes' validation against Moderno 2011 (scenes/CALIBRATION.md):
 * its appendix with the 2048² map (NSM's contour and wrong pixels, the
 * dominant error kind) and Table 15 (the chain, the rest lit); applies
 * only where the study has a cell of either (an unreadable file applies). */
int         sl_report_fidelity_scenes_applies(const struct sl_report_study *s);
enum sl_err sl_report_fidelity_scenes(struct sl_report_doc *doc, const struct sl_report_study *s,
                                      struct sl_diag *d);

/* plots.c */
enum sl_err sl_report_gnuplot_find(const char *want, char *path, size_t n, struct sl_diag *d);
enum sl_err sl_report_plot_chain(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                                 struct sl_diag *d);
enum sl_err sl_report_plot_accuracy(struct sl_report_doc *doc, const struct sl_report_study *s,
                                    const char *gnuplot, struct sl_diag *d);

/* A plot's gnuplot script (*m into *body) and its data (*dm into *data),
 * each built in memory; on failure neither is left open (what names the
 * plot's study in the message). */
enum sl_err sl_report_open_script(FILE **m, char **body, size_t *blen, FILE **dm, char **data, size_t *dlen,
                                  const char *what, struct sl_diag *d);
/* Close what sl_report_open_script opened: SL_OK with *body and *data the
 * script and its data, or (bad set by the caller, a write or close failed)
 * both freed, NULL, and an error naming what. */
enum sl_err sl_report_close_script(FILE *m, FILE *dm, char **body, char **data, int bad, const char *what,
                                   struct sl_diag *d);
/* The colour and gnuplot marker of the k-th label of a plot (Okabe-Ito, twelve
 * markers), the same in every plot. */
void sl_report_style(int k, const char **colour, int *pt);
/* `set {axis}range` (and logscale when the positive values span more than two
 * decades) from the values: padded, never below 0 for values >= 0, from 0
 * when from_zero and linear. Defines the gnuplot function XZERO_OF(c) (YZERO_OF
 * for y): column c, with a 0 moved onto a log axis's tick labelled 0 below its
 * smallest value. Returns 1 log, 0 linear, -1 when every value is 0 or none is
 * finite (nothing written: drop the panel). */
int  sl_report_axis(FILE *m, const char *axis, const double *v, int n, int from_zero);

/* For sections outside plots.c: a string quoted for gnuplot (the plot
 * itself: sl_report_plot_draw above). */
void        sl_report_gp_quote(FILE *f, const char *s);

/* A cell's whole cost, ms, with its min and max (which: 0 median, 1 min, 2
 * max): ms_cost, its stages summed (cellcols.h: map pass, post, lookup,
 * readback, rays), the one total every report table and plot shows; a
 * record without it (NAN: tests' hand-made cells) adds the layers' render
 * and the step. */
static inline double sl_report_cell_ms(const struct sl_cell_record *c, int which)
{
    const double tot[3] = {c->ms_cost, c->ms_cost_min, c->ms_cost_max};
    const double lay[3] = {c->ms_map_render, c->ms_map_render_min, c->ms_map_render_max};
    const double st[3] = {c->ms_method, c->ms_method_min, c->ms_method_max};
    if (!isnan(tot[which]) && tot[which] > 0.0)
        return tot[which];
    double a = isnan(lay[which]) || lay[which] <= 0.0 ? (isnan(lay[0]) ? 0.0 : lay[0]) : lay[which];
    double b = isnan(st[which]) || st[which] <= 0.0 ? (isnan(st[0]) ? 0.0 : st[0]) : st[which];
    return a + b;
}

/* aliasing.c: the aliasing error m (seed 004) per label: tables and the error rate against m */
int         sl_report_aliasing_applies(const struct sl_report_study *s);
enum sl_err sl_report_aliasing(struct sl_report_doc *doc, const struct sl_report_study *s, const char *gnuplot,
                               struct sl_diag *d);

#endif
