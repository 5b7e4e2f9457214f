/*
 * theses.h — the theses' printed numbers, read at run time from the data
 * files of report/theses/ (one CSV per thesis, README.md there gives the
 * columns) into the arrays the report's sections compare with the study's
 * cells: Moderno 2011's Primitives appendix, its appendix on the Bench,
 * Trees and Flowers scenes and its Table 15 (fidelity.c) and Morais 2015's
 * Tables 4-24 and their times, Tables 25-30 (morais.c).
 *
 * Where the files are: SHADOWLAB_THESES when set, else the installed share
 * folder of an installed binary (<prefix>/bin/shadowlab ->
 * <prefix>/share/shadowlab/theses), else the source tree's report/theses/
 * (a binary that is not installed), as scenes are found.
 * A file is read whole on first use and checked before any row is kept:
 * its header row exactly, each field's type and range, each enum by the
 * name the code has for it (SL_FIGURES, SL_MORAIS_ROWS), and one page per
 * table (the page the thesis prints it on; 0 where its text does not
 * say). A damaged file is
 * an SL_E_DATA naming the file, its line and the column; nothing is kept
 * of it. The rows stay until sl_theses_free (the report calls it when it
 * is done), their strings pointing into the file's own buffer.
 * Owns: the loaded files (static, one copy per process; not thread-safe:
 * the report is single-threaded). Does not: print, or judge a value
 * against the thesis's own sums (tests/test_morais.c, test_fidelity.c do).
 */
#ifndef SL_THESES_H
#define SL_THESES_H
#include <stddef.h>
#include <stdint.h>
#include "sl_error.h"
#include "figrec.h"

/* ---- Moderno 2011 (moderno-2011.csv; fidelity.c) ---- */

/* One datum of the Primitives appendix: table, viewpoint, map size,
 * contour, the cell's label, the figure of figrec.h and the value. */
struct sl_thesis_datum {
    int         table;
    int         page;           /* the table's printed page; 0 = not known */
    const char *viewpoint;
    int         map_size;
    int         contour;        /* px; 0 = whole image */
    const char *label;          /* the cell's label in configs/moderno-2011.yaml */
    enum sl_figure fig;
    uint64_t    value;
    const char *note;           /* a typo or an OCR garble and how it was resolved; NULL = none */
};

/* One view of the appendix on the Bench, Trees and Flowers scenes at
 * 1024 x 1024 (moderno-2011-scenes.csv): NSM's wrongly lit of its lit and
 * wrongly shadowed of its shadowed, in the 2 px contour (c2_) and the whole
 * image (img_), with one map size. The loaded array ends in a row whose
 * scene is NULL. */
struct sl_thesis_scene_view {
    int         table;
    int         page;                /* 0 = not known */
    const char *scene, *viewpoint;   /* as scenes/ names them */
    int         map_size;
    uint64_t    c2_lit_wrong, c2_lit, c2_shadow_wrong, c2_shadow;
    uint64_t    img_lit_wrong, img_lit, img_shadow_wrong, img_shadow;
    const char *note;
};

/* One case of Table 15 (moderno-2011-table15.csv): the cell's label (the
 * chain with the uncertain pixels left lit), its wrong pixels as a % of the
 * contour's, in the thesis's best, average or worst case. The loaded array
 * ends in a row whose scene is NULL. */
struct sl_thesis_table15 {
    int         table;
    int         page;                /* 0 = not known */
    const char *kase;                /* "best", "average", "worst" */
    const char *scene, *viewpoint;
    int         map_size, contour;
    const char *label;
    double      pct;                 /* as printed */
    const char *note;
};

/* ---- Morais 2015 (morais-2015.csv, morais-2015-times.csv; morais.c) ---- */

/* The rows of Morais's tables: the name the data files use, the name the
 * thesis prints. light .. shadow_uncertain are counted as he counts them,
 * over the pixels facing the light (PFL) only: light + shadow + undecided =
 * PFL, PnFL left out (Tables 7-24); pfl .. truth_shadow are the truth's
 * (Tables 4-6). One list, so the enum, the files' names and the printed
 * names cannot drift apart. */
#define SL_MORAIS_ROWS(X)                              \
    X(light,             "Pixels in Light")            \
    X(shadow,            "Pixels in Shadow")           \
    X(light_correct,     "Light – Correct")            \
    X(light_incorrect,   "Light – Incorrect")          \
    X(shadow_correct,    "Shadow – Correct")           \
    X(shadow_incorrect,  "Shadow – Incorrect")         \
    X(light_uncertain,   "Light – Uncertain")          \
    X(shadow_uncertain,  "Shadow – Uncertain")         \
    X(pfl,               "PFL")                        \
    X(pnfl,              "PnFL")                       \
    X(truth_light,       "PFL – in Light")             \
    X(truth_shadow,      "PFL – in Shadow")

enum sl_morais_row {
#define SL_MR_ENUM(id, text) SL_MR_##id,
    SL_MORAIS_ROWS(SL_MR_ENUM)
#undef SL_MR_ENUM
    SL_MR_COUNT
};

/* One printed value of Tables 4-24; the loaded array ends in a row whose
 * scene is NULL. */
struct sl_morais_datum {
    int         table;
    int         page;                /* the table's printed page; 0 = not known */
    const char *scene, *viewpoint;   /* as scenes/ names them (trees/side, flowers/against, bench/against) */
    int         vw, vh, map_size;    /* map_size 0: Tables 4-6 (the truth, no map) */
    const char *method;              /* configs/morais-2015.yaml's method; "raytrace" = OptiX Prime */
    enum sl_morais_row row;
    uint64_t    n;
    double      pct;                 /* as printed */
    const char *note;                /* a typo, OCR artefact or error of the thesis and how it was read */
};
/* One printed time of Tables 25-30; the loaded array ends in a row whose
 * scene is NULL. */
struct sl_morais_time {
    int         table;
    int         page;                /* the table's printed page; 0 = not known */
    const char *scene, *viewpoint;
    int         vw, vh, map_size;
    int         stage;               /* 0: shadow-map rendering (Tables 25/27/29), 1: ray-tracing step (26/28/30) */
    const char *method;              /* nsm, csm (CSMa), csm_adj (CSMA), raytrace (OptiX Prime) */
    double      ms;
    const char *note;
};

/* Hertel 2009's Table 2 (seed 002): his scenes, times on his GPU and the
 * rays traced; hertel-2009.csv. */
struct sl_hertel_row {
    int         table;
    int         page;                /* the table's printed page; 0 = not known */
    const char *scene;               /* his scene's name as printed */
    int         tris;
    double      rt_class, rt_insec, rt_opt;   /* ms: every ray, the uncertain only, cut at the stored depth */
    uint64_t    rays, insec;         /* "# rays", "# insec. rays" */
    const char *note;
};

/* ---- loading ---- */

enum sl_thesis_kind { SL_THESIS_MODERNO, SL_THESIS_MORAIS, SL_THESIS_MORAIS_TIMES, SL_THESIS_HERTEL,
                      SL_THESIS_MODERNO_SCENES, SL_THESIS_MODERNO_TABLE15, SL_THESIS_NKINDS };

/* One data file read: rows (struct sl_thesis_datum, sl_morais_datum,
 * sl_morais_time, sl_hertel_row, sl_thesis_scene_view or sl_thesis_table15
 * by kind) n of them and a zeroed row after them; their
 * strings point into buf. */
struct sl_thesis_file {
    enum sl_thesis_kind kind;
    void *rows;
    int   n;
    char *buf;
};

/* The file's name in the theses' folder ("moderno-2011.csv", ...). */
const char *sl_thesis_file_name(enum sl_thesis_kind k);
/* The folder the files are read from (see above), no trailing '/'. */
const char *sl_theses_dir(void);
/* Read and check path as a file of kind k into f (zeroed on failure):
 * SL_E_IO when it cannot be read, SL_E_DATA (file, line, column) when it
 * is not what the kind's schema says, SL_E_NOMEM. */
enum sl_err sl_thesis_file_load(enum sl_thesis_kind k, const char *path, struct sl_thesis_file *f,
                                struct sl_diag *d);
void        sl_thesis_file_free(struct sl_thesis_file *f);

/* The process's copy, read from sl_theses_dir() on first use: the rows and
 * their count (the arrays end in a zeroed row). d may be NULL. */
enum sl_err sl_theses_moderno(const struct sl_thesis_datum **rows, int *n, struct sl_diag *d);
enum sl_err sl_theses_morais(const struct sl_morais_datum **rows, int *n, struct sl_diag *d);
enum sl_err sl_theses_morais_times(const struct sl_morais_time **rows, int *n, struct sl_diag *d);
enum sl_err sl_theses_hertel(const struct sl_hertel_row **rows, int *n, struct sl_diag *d);
enum sl_err sl_theses_moderno_scenes(const struct sl_thesis_scene_view **rows, int *n, struct sl_diag *d);
enum sl_err sl_theses_moderno_table15(const struct sl_thesis_table15 **rows, int *n, struct sl_diag *d);
/* The page the thesis prints table `table` on, from the process's copy of
 * kind k's file (read on first use); 0 when its text does not say, the
 * file has no such table or cannot be read. */
int         sl_thesis_page(enum sl_thesis_kind k, int table);
/* "Table N, p. P" (or "Table N" when the page is not known) into buf, the
 * way the report cites a thesis's table; returns buf. */
const char *sl_thesis_cite(enum sl_thesis_kind k, int table, char *buf, size_t n);
/* Drop the process's copies (a later call reads the files again). */
void        sl_theses_free(void);

/* The data files' name of a row ("light", ...), NULL when out of range. */
const char *sl_morais_row_id(enum sl_morais_row r);

#endif
