/*
 * report.h — `shadowlab report RESULTS_DB`: one offline page (report.html,
 * inline CSS and one inline script, no network; it links the files beside
 * it, or with self_contained embeds them as data: URIs) and its Markdown twin
 * (report.md), with latex also report.tex, from the results store: a
 * contents tree, a summary (what was run, headline table, plots), then:
 *   - per study (config name): thesis-style tables in the layout of the
 *     thesis whose methods the cells ran (Moderno 2011 Tables 5-23, Morais
 *     2015 Table 7 and Tables 25/26), each also as a booktabs .tex file;
 *   - the chain's steps per scene as stacked bars (Moderno Figures 31/32) and
 *     wrong and undecided pixels against method time and rays per pixel with
 *     the Pareto front marked, drawn by gnuplot (SVG and PDF, each kept as
 *     .dat + .gp);
 *   - a cost section (times, rays, ray-triangle tests, GS primitives,
 *     fragments), the error overlays the runs wrote (copied), and the
 *     provenance of every run (git SHA, config and its hash, machine).
 *
 * Output is staged in DIR/.staging-<pid>/ and moved into DIR file by file
 * (each rename atomic) only when everything was written, report.md and
 * report.html last; a failure removes what it staged and leaves DIR as it was.
 *
 * Owns: nothing after return. Does not: run experiments, write to the store,
 * print (errors come back as an id and an sl_diag), or fetch anything from
 * the network. gnuplot is the one outside program it runs (system(), in the
 * staging folder's plots/).
 */
#ifndef SL_REPORT_H
#define SL_REPORT_H
#include <stddef.h>
#include <stdint.h>
#include "sl_error.h"
#include "store.h"
#include "table.h"

/* Zero means the default. */
struct sl_report_opts {
    const char *db;        /* the results store (required) */
    const char *out_dir;   /* NULL: <db folder>/report */
    const char *gnuplot;   /* NULL: "gnuplot" searched in PATH */
    int self_contained;    /* report.html embeds its images and plots (data: URIs): one file */
    int latex;             /* also report.tex, a pdflatex document \input-ing the tables and plot PDFs */
};

/* What a report holds, read from the store or given by a test. Overlay paths
 * of the cells are relative to source_dir. */
struct sl_report_input {
    const struct sl_cell_record *cells;
    int                         ncells;
    const struct sl_store_run  *runs;
    int                         nruns;
    const char                 *source;       /* shown as the report's source ("" allowed) */
    const char                 *source_dir;   /* folder overlay paths are relative to */
    struct sl_store            *store;        /* the store read (its plan and recorded files), or NULL */
};

/* Read the store and write the report; the folder written goes to dir (n
 * bytes, may be NULL). SL_E_IO for a missing, empty or foreign database;
 * SL_E_USAGE when it holds no results or gnuplot is not installed (key
 * "gnuplot"); SL_E_OUTPUT when the folder cannot be written. */
enum sl_err sl_report_write(const struct sl_report_opts *o, char *dir, size_t n, struct sl_diag *d);

/* Write the report of cells already in memory into out_dir. */
enum sl_err sl_report_build(const struct sl_report_input *in, const char *out_dir, const char *gnuplot,
                            struct sl_diag *d);
/* The same with sl_report_opts's self_contained and latex. */
enum sl_err sl_report_build_with(const struct sl_report_input *in, const char *out_dir, const char *gnuplot,
                                 int self_contained, int latex, struct sl_diag *d);

/* ---- the accuracy-vs-cost data, exposed for its unit test ---- */

/* One point per (study, label, map size): means over the label's cells of
 * that map size (scenes, viewpoints, viewports). */
struct sl_report_point {
    char   label[48], method[32];
    char   display[64];    /* the label's name for people (`display:`, else its method's); legends use it */
    int    map_size;
    int    ncells;
    double wrong_pct;      /* wrong pixels, % of the non-background pixels (whole image) */
    double uncertain_pct;  /* pixels the method leaves undecided, % of the same */
    double ms;             /* the method's time per cell, ms: ms_layers + ms_step */
    double ms_layers;      /* rendering the shadow-map layers it reads (median of repetitions) */
    double ms_step;        /* its per-pixel step, ray step included (median of repetitions) */
    double ms_min, ms_max; /* the same from the repetitions' minima and maxima; = ms with one run */
    int    reps;           /* fewest timed repetitions of its cells */
    double rays_per_px;    /* shadow rays per non-background pixel */
    int    front_ms;       /* on the Pareto front of (ms, wrong_pct + uncertain_pct) */
    int    front_rays;     /* on the Pareto front of (rays_per_px, wrong_pct + uncertain_pct) */
};

/* Points of the cells (callers pass one study), labels in order of first
 * appearance, map sizes ascending within a label; both fronts marked. The
 * fronts count an undecided pixel as an error: a method that leaves 1.2% of
 * the image undecided has not answered for it, however few it gets wrong.
 * *out is malloc'ed (free), NULL when *n is 0. */
enum sl_err sl_report_points(const struct sl_cell_record *cells, int ncells, struct sl_report_point **out,
                             int *n, struct sl_diag *d);

/* Pareto front of points (x[i], y[i]), both lower-is-better: front[i] = 1
 * when no other point is <= in both and < in one. Equal points are all on
 * the front; NaN points never are and dominate nothing. Returns the number
 * on the front. */
int sl_report_pareto(const double *x, const double *y, int n, unsigned char *front);

/* The font (px) of an SVG plot w px wide: 8.5 pt once the page prints on
 * A4 (a plot wider than the 703 px of its 186 mm line is shrunk to it), at
 * least 11 px on screen. The PDF plots use 9 pt at 12 cm. */
int sl_report_svg_font_px(int w);


/* ---- the fidelity section (fidelity.c), exposed for its unit test ---- */

/* One number of Moderno 2011's appendix (Primitives) beside shadowlab's. */
struct sl_report_fidelity_row {
    int            table;          /* the thesis's table number */
    int            page;           /* the table's printed page; 0 = not known */
    const char    *viewpoint;
    int            map_size, contour;   /* contour 0 = whole image */
    const char    *label;          /* the cell's label (configs/moderno-2011.yaml) */
    enum sl_figure fig;
    uint64_t       thesis;         /* as published (typos resolved: note) */
    int            measured;       /* 0: the store has no such cell or region ("not measured") */
    uint64_t       value;          /* shadowlab's, when measured */
    double         ratio;          /* value / thesis; NAN when not measured or the thesis's is 0 */
    const char    *note;           /* NULL or the typo / transcription note */
};
#define SL_REPORT_FIDELITY_MAXROWS 2048
#define SL_REPORT_FIDELITY_NCLAIMS 7
/* A claim's table datum agrees with the thesis's when ours / thesis lies in
 * [1/band, band]: a stated choice, printed beside every claim. Counts of the
 * same scene, view and approach within a factor of two; a thesis's 0 agrees
 * only with 0 (scenes/CALIBRATION.md says why Primitives' counts differ). */
#define SL_REPORT_FIDELITY_BAND 2.0

/* A qualitative claim of the thesis, measured on the cells, and the
 * appendix tables it rests on (Primitives, every viewpoint), each datum of
 * them against the study's within the claim's band. Verdict: 0 when a
 * measured datum falls outside the band or the claim's own test fails; -1
 * when neither failed but a datum or the test is not measured; 1 only when
 * the test holds and every datum is measured and within the band. */
struct sl_report_fidelity_claim {
    const char *claim, *thesis;
    int         verdict;           /* 1 reproduced, 0 not, -1 not measured */
    char        measured[200];
    double      band;              /* a datum agrees when ours / thesis lies in [1/band, band]; 0: no table datum */
    int         data, within, unmeasured;   /* the tables' data, those within the band, those not measured */
    char        tables[360];       /* the tables, the band and the datum furthest from the thesis's */
};

/* The theses whose sections a study can get, named as a method's family
 * names them (sl_report_family_id: "moderno-2011", ...). sl_report_family_of
 * reads a method's own metadata as a cell stores it (cells.family, beside:
 * method.h): 2 the method is the thesis's own (it brings the sections), 1 a
 * baseline its tables list beside its own (the thesis is a word of beside),
 * 0 none. */
enum sl_report_family { SL_REPORT_MODERNO, SL_REPORT_MORAIS, SL_REPORT_CURTIS, SL_REPORT_NFAMILIES };
const char *sl_report_family_id(enum sl_report_family f);
int sl_report_family_of(const char *family, const char *beside, enum sl_report_family f);

/* 1 if the cells hold hard-shadow cells of scene primitives. */
int sl_report_fidelity_applies(const struct sl_cell_record *c, int n);
/* Every transcribed datum (at most max) against the cells; returns the
 * count, -1 when report/theses/moderno-2011.csv cannot be read (theses.h:
 * sl_theses_moderno says why). */
int sl_report_fidelity_rows(const struct sl_cell_record *c, int n, struct sl_report_fidelity_row *out, int max);
/* The claims (max >= SL_REPORT_FIDELITY_NCLAIMS, else 0); returns the count. */
int sl_report_fidelity_claims(const struct sl_cell_record *c, int n, struct sl_report_fidelity_claim *out, int max);

#endif
