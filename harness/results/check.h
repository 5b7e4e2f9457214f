/*
 * check.h — a results store against a committed baseline, for CI.
 *
 * A baseline (YAML, written by sl_check_write_baseline) holds, per cell key
 * (scene/viewpoint/WxH/map/label), the counters of the cell and every figure
 * of every region, plus the machine it was measured on and a tolerance per
 * class of figure. sl_check compares the store's latest cell of each key:
 *
 * - invariant (violations of a method's declared exactness): always exact;
 * - every count, exactly, when the store's runs were measured on the
 *   baseline's machine (same CPU model, ISA, GL renderer and version, Embree:
 *   a deterministic run there gives the same counts) or when the baseline
 *   says `counts: exact`;
 * - otherwise each class within its tolerance: figures as a share of their
 *   region's pixels (view figures: of the image's pixels), in percentage
 *   points; cost counters relative to the baseline value, in percent.
 *   (llvmpipe and Embree pick code paths by instruction set, so another CPU
 *   may move a pixel or two: the tolerances absorb that, not a regression.)
 *
 * Times are never compared: they belong to the machine. Does not: run
 * anything, or write the store.
 */
#ifndef SL_CHECK_H
#define SL_CHECK_H
#include <stdio.h>
#include "sl_error.h"

/* name, default tolerance, what it holds */
#define SL_CHECK_CLASSES(X)                                                                         \
    X(invariant, 0.0,  "violations of a method's declared exactness (always exact)")                \
    X(view,      0.01, "the view: pixels, PFL, PnFL, truth counts (pp of the image's pixels)")      \
    X(error,     0.05, "wrong pixels: incorrect light or shadow, wrong, caught, kept wrong, turned bad, wrong hints (pp of the region)") \
    X(decision,  0.10, "how pixels were decided: light, shadow, uncertain, traced, hinted, confirmed, corrected, changes vs NSM (pp of the region)") \
    X(cost,      0.5,  "machine-independent counters: rays, ray-triangle tests, lookups, GS primitives, fragments (percent of the baseline value)") \
    X(soft,      0.1,  "soft shadows: MAE, RMSE, bias of the visible fraction (pp of visibility) and the soft counts (pp of the pixels)")

enum sl_check_class {
#define SL_CC_ENUM(name, tol, text) SL_CC_##name,
    SL_CHECK_CLASSES(SL_CC_ENUM)
#undef SL_CC_ENUM
    SL_CC_COUNT
};

enum sl_check_format {
    SL_CHECK_TEXT = 0,          /* a plain table for a terminal */
    SL_CHECK_MD = 1,            /* Markdown */
};

struct sl_check_opts {
    const char *study;          /* only cells of this config name; NULL = every cell */
    int         max_rows;       /* rows of the "what moved" table; 0 = 200 */
    int         format;         /* enum sl_check_format */
    int         color;          /* text only: ok green, FAIL red (ANSI); the caller decides (a TTY,
                                 * no NO_COLOR) */
    FILE       *json;           /* also every compared cell and class with its verdict, as JSON */
    FILE       *junit;          /* also JUnit XML: one testcase per (baseline cell, class) */
    int         exact;          /* every count exactly, whatever machine and whatever the baseline's
                                 * counts: mode (CI's platform matrix: another ISA or llvmpipe width
                                 * must give the same counts) */
};

struct sl_check_result {
    int cells;                  /* baseline cells */
    int missing;                /* baseline cells the store lacks (each a failure) */
    int extra;                  /* store cells the baseline lacks (listed, not a failure) */
    long compared;              /* values compared */
    long moved;                 /* values that differ at all */
    long failed;                /* values outside tolerance */
    int exact_counts;           /* counts were compared exactly */
    int config_differs;         /* some store cell's config hash is not the baseline's */
    int sha_differs;            /* some run's git SHA is not the baseline's */
};

/* Compare; prints the table of what moved and a summary to out. SL_OK when
 * the comparison ran (r->failed + r->missing say whether it passed); an
 * unreadable store or a bad baseline (file, line, key) is an error. */
enum sl_err sl_check(const char *db, const char *baseline, const struct sl_check_opts *o, FILE *out,
                     struct sl_check_result *r, struct sl_diag *d);

/* Write the store's latest cells (of `study`, NULL = all) as a baseline,
 * keeping the tolerances and count mode of an existing file at that path.
 * Atomic: a failure leaves the old file. */
enum sl_err sl_check_write_baseline(const char *db, const char *baseline, const char *study,
                                    struct sl_diag *d);

#endif
