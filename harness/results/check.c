/*
 * check.c — see check.h.
 *
 * The baseline's counters are the checked columns of cellcols.h and its
 * figure lists come from the X-macro of figures.h, so a
 * baseline written before a figure was added or renamed is refused with the
 * line of the cell that lacks it (refresh the baseline deliberately, see the
 * README). Every comparison is of integers or of shares computed the same
 * way on both sides, so a store compared with its own baseline moves nothing.
 */
#define _XOPEN_SOURCE 700
#include "check.h"
#include "emit.h"
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cyaml/cyaml.h>
#include "figrec.h"
#include "store.h"
#include "table.h"
#include "util.h"
#include "yamlfile.h"

#define SL_BASELINE_VERSION 1

/* baselines are written by shadowlab (tests/baselines/ci.yaml: 300 KiB);
 * 64 MiB leaves room for big sweeps and still refuses a runaway file unread */
#define SL_BASELINE_MAX_BYTES ((size_t)64 << 20)

static const char *const class_name[SL_CC_COUNT] = {
#define SL_CC_NAME(name, tol, text) #name,
    SL_CHECK_CLASSES(SL_CC_NAME)
#undef SL_CC_NAME
};
static const double class_tol[SL_CC_COUNT] = {
#define SL_CC_TOL(name, tol, text) tol,
    SL_CHECK_CLASSES(SL_CC_TOL)
#undef SL_CC_TOL
};
static const char *const class_text[SL_CC_COUNT] = {
#define SL_CC_TEXT(name, tol, text) text,
    SL_CHECK_CLASSES(SL_CC_TEXT)
#undef SL_CC_TEXT
};

/* The class of each figure of figures.h. */
static enum sl_check_class figure_class(enum sl_figure f)
{
    switch (f) {
    case SL_FIG_pixels: case SL_FIG_pfl: case SL_FIG_pnfl:
        return SL_CC_view;
    case SL_FIG_light_incorrect: case SL_FIG_shadow_incorrect: case SL_FIG_wrong: case SL_FIG_wrong_caught:
    case SL_FIG_kept_wrong: case SL_FIG_broken_ls: case SL_FIG_broken_sl: case SL_FIG_hinted_wrong:
    case SL_FIG_hinted_light_wrong: case SL_FIG_hinted_shadow_wrong:
        return SL_CC_error;
    case SL_FIG_ray_tri_tests:
        return SL_CC_cost;
    default:
        return SL_CC_decision;
    }
}

/* The counters of a cell a baseline holds: the columns of cellcols.h with a
 * check class, under their baseline key, in the order of the list.
 * BL_IF_<class>(...) keeps its arguments for a compared column. */
#define BL_IF_none(...)
#define BL_IF_view(...) __VA_ARGS__
#define BL_IF_error(...) __VA_ARGS__
#define BL_IF_decision(...) __VA_ARGS__
#define BL_IF_cost(...) __VA_ARGS__
#define BL_IF_invariant(...) __VA_ARGS__
#define BL_IF_soft(...) __VA_ARGS__

enum {
#define BL_CNT_ENUM(name, kind, size, csv, head, cls, key, from) BL_IF_##cls(BL_C_##key,)
    SL_CELL_COLUMNS(BL_CNT_ENUM)
#undef BL_CNT_ENUM
    BL_C_COUNT
};

/* ---- the baseline file's schema ---- */

struct bl_machine { char *cpu, *isa, *gl_renderer, *gl_version, *embree; };
struct bl_tol {
#define BL_TOL_MEMBER(name, tol, text) double *name;
    SL_CHECK_CLASSES(BL_TOL_MEMBER)
#undef BL_TOL_MEMBER
};
struct bl_counters {
#define BL_CNT_MEMBER(name, kind, size, csv, head, cls, key, from) BL_IF_##cls(uint64_t key;)
    SL_CELL_COLUMNS(BL_CNT_MEMBER)
#undef BL_CNT_MEMBER
};
struct bl_figs {
#define BL_FIG_MEMBER(name, text, of) uint64_t *name; unsigned name##_count;
    SL_FIGURES(BL_FIG_MEMBER)
#undef BL_FIG_MEMBER
};
/* a soft-shadow cell: counts, and the means (percent of visibility) */
struct bl_soft_n {
#define BL_SOFT_N_MEMBER(name, text, of) uint64_t name;
    SL_SOFT_FIGURES(BL_SOFT_N_MEMBER)
#undef BL_SOFT_N_MEMBER
};
struct bl_soft_mean { double *soft_mae, *soft_rmse, *soft_bias, *soft_truth_stderr; };
struct bl_cell {
    char *cell;
    struct bl_counters *counters;
    char **regions;
    unsigned regions_count;
    struct bl_figs *figures;
    struct bl_soft_n *soft;
    struct bl_soft_mean *soft_mean;
};
struct bl_file {
    unsigned version;
    char *study, *config, *config_hash, *git_sha, *measured, *counts;
    struct bl_machine *machine;
    struct bl_tol *tolerances;
    struct bl_cell *cells;
    unsigned cells_count;
};

static const cyaml_schema_value_t str_schema = {CYAML_VALUE_STRING(CYAML_FLAG_POINTER, char, 1, 255)};
static const cyaml_schema_value_t u64_schema = {CYAML_VALUE_UINT(CYAML_FLAG_DEFAULT, uint64_t)};

static const cyaml_schema_field_t machine_fields[] = {
    CYAML_FIELD_STRING_PTR("cpu", CYAML_FLAG_POINTER, struct bl_machine, cpu, 0, 255),
    CYAML_FIELD_STRING_PTR("isa", CYAML_FLAG_POINTER, struct bl_machine, isa, 0, 255),
    CYAML_FIELD_STRING_PTR("gl_renderer", CYAML_FLAG_POINTER, struct bl_machine, gl_renderer, 0, 255),
    CYAML_FIELD_STRING_PTR("gl_version", CYAML_FLAG_POINTER, struct bl_machine, gl_version, 0, 255),
    CYAML_FIELD_STRING_PTR("embree", CYAML_FLAG_POINTER, struct bl_machine, embree, 0, 255),
    CYAML_FIELD_END
};
static const cyaml_schema_field_t tol_fields[] = {
#define BL_TOL_FIELD(name, tol, text) \
    CYAML_FIELD_FLOAT_PTR(#name, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_tol, name),
    SL_CHECK_CLASSES(BL_TOL_FIELD)
#undef BL_TOL_FIELD
    CYAML_FIELD_END
};
/* An invariant may be absent (0: a baseline written before it held none,
 * so a cell that has some fails); every other counter is required. */
#define BL_FLAG_invariant CYAML_FLAG_OPTIONAL
#define BL_FLAG_view CYAML_FLAG_DEFAULT
#define BL_FLAG_error CYAML_FLAG_DEFAULT
#define BL_FLAG_decision CYAML_FLAG_DEFAULT
#define BL_FLAG_cost CYAML_FLAG_DEFAULT
#define BL_FLAG_soft CYAML_FLAG_DEFAULT
static const cyaml_schema_field_t counter_fields[] = {
#define BL_CNT_FIELD(name, kind, size, csv, head, cls, key, from) \
    BL_IF_##cls(CYAML_FIELD_UINT(#key, BL_FLAG_##cls, struct bl_counters, key),)
    SL_CELL_COLUMNS(BL_CNT_FIELD)
#undef BL_CNT_FIELD
    CYAML_FIELD_END
};
static const cyaml_schema_field_t fig_fields[] = {
#define BL_FIG_FIELD(name, text, of) \
    CYAML_FIELD_SEQUENCE(#name, CYAML_FLAG_POINTER | CYAML_FLAG_FLOW, struct bl_figs, name, &u64_schema, 1, SL_MAX_REGIONS),
    SL_FIGURES(BL_FIG_FIELD)
#undef BL_FIG_FIELD
    CYAML_FIELD_END
};
static const cyaml_schema_field_t soft_n_fields[] = {
#define BL_SOFT_N_FIELD(name, text, of) CYAML_FIELD_UINT(#name, CYAML_FLAG_DEFAULT, struct bl_soft_n, name),
#define BL_SOFT_N_OPT(name, text, of) CYAML_FIELD_UINT(#name, CYAML_FLAG_OPTIONAL, struct bl_soft_n, name),
    /* the split of the mean error by sign: optional (baselines before it lack
     * it) and not compared, as mae and bias, which it follows from, are */
    SL_SOFT_BASE_FIGURES(BL_SOFT_N_FIELD)
    SL_SOFT_SPLIT_FIGURES(BL_SOFT_N_OPT)
#undef BL_SOFT_N_FIELD
#undef BL_SOFT_N_OPT
    CYAML_FIELD_END
};
static const cyaml_schema_field_t soft_mean_fields[] = {
    CYAML_FIELD_FLOAT_PTR("soft_mae", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_soft_mean, soft_mae),
    CYAML_FIELD_FLOAT_PTR("soft_rmse", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_soft_mean, soft_rmse),
    CYAML_FIELD_FLOAT_PTR("soft_bias", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_soft_mean, soft_bias),
    CYAML_FIELD_FLOAT_PTR("soft_truth_stderr", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_soft_mean,
                          soft_truth_stderr),
    CYAML_FIELD_END
};
/* a hard cell has regions and figures; a soft method's cell (area light) soft and
 * soft_mean; a hard method's cell under an area light all four */
static const cyaml_schema_field_t cell_fields[] = {
    CYAML_FIELD_STRING_PTR("cell", CYAML_FLAG_POINTER, struct bl_cell, cell, 1, 255),
    CYAML_FIELD_MAPPING_PTR("counters", CYAML_FLAG_POINTER, struct bl_cell, counters, counter_fields),
    CYAML_FIELD_SEQUENCE("regions", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_cell, regions, &str_schema,
                         1, SL_MAX_REGIONS),
    CYAML_FIELD_MAPPING_PTR("figures", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_cell, figures, fig_fields),
    CYAML_FIELD_MAPPING_PTR("soft", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_cell, soft, soft_n_fields),
    CYAML_FIELD_MAPPING_PTR("soft_mean", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_cell, soft_mean,
                            soft_mean_fields),
    CYAML_FIELD_END
};
static const cyaml_schema_value_t cell_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct bl_cell, cell_fields),
};
static const cyaml_schema_field_t file_fields[] = {
    CYAML_FIELD_UINT("shadowlab_baseline", CYAML_FLAG_DEFAULT, struct bl_file, version),
    CYAML_FIELD_STRING_PTR("study", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, study, 0, 255),
    CYAML_FIELD_STRING_PTR("config", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, config, 0, 1023),
    CYAML_FIELD_STRING_PTR("config_hash", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, config_hash, 0, 63),
    CYAML_FIELD_STRING_PTR("git_sha", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, git_sha, 0, 63),
    CYAML_FIELD_STRING_PTR("measured", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, measured, 0, 63),
    CYAML_FIELD_MAPPING_PTR("machine", CYAML_FLAG_POINTER, struct bl_file, machine, machine_fields),
    CYAML_FIELD_MAPPING_PTR("tolerances", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, tolerances,
                            tol_fields),
    CYAML_FIELD_STRING_PTR("counts", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct bl_file, counts, 1, 31),
    CYAML_FIELD_SEQUENCE("cells", CYAML_FLAG_POINTER, struct bl_file, cells, &cell_schema, 0, CYAML_UNLIMITED),
    CYAML_FIELD_END
};
static const cyaml_schema_value_t file_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, struct bl_file, file_fields),
};

/* The baseline's tolerances by class, NULL where the file gives none. */
static void tol_ptrs(const struct bl_tol *t, const double *out[SL_CC_COUNT])
{
    const double *p[SL_CC_COUNT] = {
#define BL_TOL_PTR(name, tol, text) t ? t->name : NULL,
        SL_CHECK_CLASSES(BL_TOL_PTR)
#undef BL_TOL_PTR
    };
    memcpy(out, p, sizeof p);
}

static const uint64_t *bl_fig(const struct bl_figs *f, int k, unsigned *n)
{
    switch ((enum sl_figure)k) {
#define BL_FIG_CASE(name, text, of) case SL_FIG_##name: *n = f->name##_count; return f->name;
        SL_FIGURES(BL_FIG_CASE)
#undef BL_FIG_CASE
    case SL_FIG_COUNT:
        break;
    }
    *n = 0;
    return NULL;
}

static uint64_t bl_counter(const struct bl_counters *c, int k)
{
    const uint64_t v[BL_C_COUNT] = {
#define BL_CNT_VAL(name, kind, size, csv, head, cls, key, from) BL_IF_##cls(c->key,)
        SL_CELL_COLUMNS(BL_CNT_VAL)
#undef BL_CNT_VAL
    };
    return v[k];
}

static const char *const counter_name[BL_C_COUNT] = {
#define BL_CNT_NAME(name, kind, size, csv, head, cls, key, from) BL_IF_##cls(#key,)
    SL_CELL_COLUMNS(BL_CNT_NAME)
#undef BL_CNT_NAME
};
static const enum sl_check_class counter_class[BL_C_COUNT] = {
#define BL_CNT_CLS(name, kind, size, csv, head, cls, key, from) BL_IF_##cls(SL_CC_##cls,)
    SL_CELL_COLUMNS(BL_CNT_CLS)
#undef BL_CNT_CLS
};

/* The same counters of a stored cell. */
static uint64_t cell_counter(const struct sl_cell_record *c, int k)
{
    const uint64_t v[BL_C_COUNT] = {
#define BL_CNT_CELL(name, kind, size, csv, head, cls, key, from) \
        BL_IF_##cls([BL_C_##key] = SL_CELL_U64_##kind(c, name),)
        SL_CELL_COLUMNS(BL_CNT_CELL)
#undef BL_CNT_CELL
    };
    return v[k];
}

static void cell_key(const struct sl_cell_record *c, char *out, size_t n)
{
    snprintf(out, n, "%s/%s/%dx%d/%d/%s", c->scene, c->viewpoint, c->vw, c->vh, c->map_size, c->label);
}

/* ---- comparing ---- */

/* What one baseline cell did per class, for --json and --junit. */
struct cell_stats {
    const char *cell;
    int  missing;
    long compared[SL_CC_COUNT], moved[SL_CC_COUNT], failed[SL_CC_COUNT];
    double worst[SL_CC_COUNT];            /* the largest |moved| */
    char first_fail[SL_CC_COUNT][200];    /* the first value outside tolerance */
};

struct cmp {
    FILE *out;
    const struct sl_check_opts *o;
    struct sl_check_result *r;
    double tol[SL_CC_COUNT];
    int exact;
    int rows, max_rows;
    long hidden;
    struct cell_stats *cur;               /* the baseline cell being compared */
    struct sl_tab tab;                    /* what moved: its rows */
};

/* The table of what moved, in the model: a row per moved value or missing
 * cell, its last column the verdict (FAIL: an alert row). Written once the
 * cells are compared: Markdown, or columns of fixed widths for a terminal
 * (FAIL in red, ok in green when asked). */
static void moved_table(struct sl_tab *t)
{
    static const char *const heads[] = {"cell", "region", "figure", "class", "baseline",
                                        "now",  "moved",  "tolerance", ""};
    static const int width[] = {40, 6, 24, 9, 12, 12, 14, 10, 0};
    sl_tab_init(t, "moved", 9, 4, "%s", "");
    t->plain = 1;
    t->padded = 1;
    t->verdict = 1;
    for (int k = 0; k < 9; k++) {
        sl_tab_head(t, k, "%s", heads[k]);
        t->termw[k] = width[k];
    }
    sl_tab_align(t, 8, 'l');
}

static void table_row(struct cmp *m, const char *cell, const char *region, const char *what, const char *cls,
                      const char *a, const char *b, const char *moved, const char *tol, int bad)
{
    const char *v[] = {cell, region, what, cls, a, b, moved, tol, bad ? "FAIL" : "ok"};
    m->rows++;
    sl_tab_row(&m->tab, 0);
    if (bad)
        sl_tab_alert(&m->tab);
    for (int k = 0; k < 9; k++)
        sl_tab_cell(&m->tab, k, "%s", v[k]);
}

static void stat_fail(struct cmp *m, enum sl_check_class cls, double moved, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void stat_fail(struct cmp *m, enum sl_check_class cls, double moved, const char *fmt, ...)
{
    struct cell_stats *s = m->cur;
    if (!s)
        return;
    s->moved[cls]++;
    if (fabs(moved) > s->worst[cls])
        s->worst[cls] = fabs(moved);
    if (!fmt)
        return;
    s->failed[cls]++;
    if (!s->first_fail[cls][0]) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(s->first_fail[cls], sizeof s->first_fail[cls], fmt, ap);
        va_end(ap);
    }
}

static void moved_row(struct cmp *m, const char *key, const char *region, const char *what,
                      enum sl_check_class cls, const char *a, const char *b, double moved, const char *unit);

/* One value: baseline a, now b; `share_of` the denominators that turn counts
 * into percentage points (0: relative to a, the cost rule). */
static void compare(struct cmp *m, const char *key, const char *region, const char *what,
                    enum sl_check_class cls, uint64_t a, uint64_t b, double den_a, double den_b)
{
    m->r->compared++;
    if (m->cur)
        m->cur->compared[cls]++;
    if (a == b)
        return;
    m->r->moved++;
    double moved;
    const char *unit;
    if (cls == SL_CC_cost) {
        moved = 100.0 * ((double)b - (double)a) / (a ? (double)a : 1.0);
        unit = "%";
    } else {
        double pa = den_a > 0 ? 100.0 * (double)a / den_a : 0.0;
        double pb = den_b > 0 ? 100.0 * (double)b / den_b : 0.0;
        moved = pb - pa;
        unit = "pp";
    }
    char va[32], vb[32];
    snprintf(va, sizeof va, "%llu", (unsigned long long)a);
    snprintf(vb, sizeof vb, "%llu", (unsigned long long)b);
    moved_row(m, key, region, what, cls, va, vb, moved, unit);
}

/* Count a moved value, failed when beyond its class's tolerance (or counts
 * are exact), and list it while rows remain. */
static void moved_row(struct cmp *m, const char *key, const char *region, const char *what,
                      enum sl_check_class cls, const char *a, const char *b, double moved, const char *unit)
{
    double tol = m->tol[cls];
    int bad = m->exact || cls == SL_CC_invariant || !(fabs(moved) <= tol + 1e-12);
    char tolbuf[32];
    if (m->exact || cls == SL_CC_invariant)
        snprintf(tolbuf, sizeof tolbuf, "exact");
    else
        snprintf(tolbuf, sizeof tolbuf, "%g %s", tol, unit);
    if (bad)
        m->r->failed++;
    stat_fail(m, cls, moved, bad ? "%s %s: baseline %s, now %s, moved %+.4f %s (tolerance %s)" : NULL, region, what,
              a, b, moved, unit, tolbuf);
    if (m->rows >= m->max_rows) {
        m->hidden++;
        return;
    }
    char mv[48];
    snprintf(mv, sizeof mv, "%+.4f %s", moved, unit);
    table_row(m, key, region, what, class_name[cls], a, b, mv, tolbuf, bad);
}

/* A mean already in percent (a soft cell's MAE, ...): moved by the difference,
 * in percentage points; exact on the baseline's machine. */
static void compare_mean(struct cmp *m, const char *key, const char *what, double a, double b)
{
    m->r->compared++;
    if (m->cur)
        m->cur->compared[SL_CC_soft]++;
    if (a == b || (isnan(a) && isnan(b)))
        return;
    m->r->moved++;
    char va[32], vb[32];
    snprintf(va, sizeof va, "%.6g", a);
    snprintf(vb, sizeof vb, "%.6g", b);
    moved_row(m, key, "image", what, SL_CC_soft, va, vb, b - a, "pp");
}

static enum sl_err compare_cell(struct cmp *m, const char *file, const struct sl_yaml_pos *pos, unsigned ci,
                                const struct bl_cell *b, const struct sl_cell_record *c, struct sl_diag *d)
{
    char key[64];
    double img_b = (double)c->vw * (double)c->vh;
    double img_a = (double)(b->counters->n_pfl + b->counters->n_pnfl + b->counters->n_background);
    for (int k = 0; k < BL_C_COUNT; k++)
        compare(m, b->cell, "cell", counter_name[k], counter_class[k], bl_counter(b->counters, k),
                cell_counter(c, k), img_a, img_b);
    /* a soft method's cell has soft figures, a directional light's hard
     * ones, a hard method's under an area light both */
    if (!b->soft && !b->figures) {
        snprintf(key, sizeof key, "cells[%u]", ci);
        return sl_yaml_bad(d, SL_E_BASELINE, file, pos, key, "a cell needs 'figures', 'soft' or both");
    }
    int has_hard = c->fig.nregions > 0;
    if (!!b->soft != !!c->has_soft || !!b->figures != has_hard) {
        static const char *const kind[] = {"none", "hard", "soft", "soft + hard"};
        m->r->failed++;
        const char *ka = kind[(b->soft ? 2 : 0) + (b->figures ? 1 : 0)], *kb = kind[(c->has_soft ? 2 : 0) + has_hard];
        stat_fail(m, SL_CC_view, 0.0, "kind of cell: baseline %s, now %s", ka, kb);
        table_row(m, b->cell, "image", "(kind)", "view", ka, kb, "", "exact", 1);
        return SL_OK;
    }
    if (b->soft) {
        /* counts as shares of the pixels, means in percentage points of visibility */
        const uint64_t bn[SL_SFIG_COUNT] = {
#define BL_SOFT_N_VAL(name, text, of) b->soft->name,
            SL_SOFT_FIGURES(BL_SOFT_N_VAL)
#undef BL_SOFT_N_VAL
        };
        double pa = (double)bn[SL_SFIG_soft_pixels], pb = (double)c->soft.n[SL_SFIG_soft_pixels];
        for (int k = 0; k < SL_SFIG_COUNT; k++)
            if (k != SL_SFIG_leaking && k != SL_SFIG_over_dark)
                compare(m, b->cell, "image", sl_soft_figure_name((enum sl_soft_figure)k), SL_CC_soft, bn[k],
                        c->soft.n[k], pa, pb);
        const struct { const double *v; int k; } means[] = {
            {b->soft_mean ? b->soft_mean->soft_mae : NULL, SL_SFIG_soft_mae},
            {b->soft_mean ? b->soft_mean->soft_rmse : NULL, SL_SFIG_soft_rmse},
            {b->soft_mean ? b->soft_mean->soft_bias : NULL, SL_SFIG_soft_bias},
            {b->soft_mean ? b->soft_mean->soft_truth_stderr : NULL, SL_SFIG_soft_truth_stderr},
        };
        for (size_t j = 0; j < sizeof means / sizeof means[0]; j++)
            if (means[j].v)
                compare_mean(m, b->cell, sl_soft_figure_name((enum sl_soft_figure)means[j].k), *means[j].v,
                             c->soft.pct[means[j].k]);
        if (!b->figures)
            return SL_OK;
    }
    /* regions, matched by name */
    for (unsigned r = 0; r < b->regions_count; r++) {
        int found = -1;
        char name[16];
        for (int j = 0; j < c->fig.nregions && found < 0; j++) {
            sl_region_name(c->fig.r[j].thickness, name, sizeof name);
            if (strcmp(name, b->regions[r]) == 0)
                found = j;
        }
        if (found < 0) {
            m->r->failed++;
            stat_fail(m, SL_CC_view, 0.0, "region %s missing", b->regions[r]);
            table_row(m, b->cell, b->regions[r], "(region)", "view", "present", "missing", "", "exact", 1);
            continue;
        }
        const struct sl_region_figures *g = &c->fig.r[found];
        unsigned n;
        const uint64_t *pix = bl_fig(b->figures, SL_FIG_pixels, &n);
        double den_a = r < n ? (double)pix[r] : 0.0, den_b = (double)g->n[SL_FIG_pixels];
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            const uint64_t *v = bl_fig(b->figures, k, &n);
            if (n != b->regions_count) {
                snprintf(key, sizeof key, "cells[%u].figures.%s", ci, sl_figure_name((enum sl_figure)k));
                return sl_yaml_bad(d, SL_E_BASELINE, file, pos, key, "%u values for %u regions", n,
                                   b->regions_count);
            }
            enum sl_check_class cls = figure_class((enum sl_figure)k);
            if (cls == SL_CC_view)
                compare(m, b->cell, b->regions[r], sl_figure_name((enum sl_figure)k), cls, v[r], g->n[k], img_a,
                        img_b);
            else
                compare(m, b->cell, b->regions[r], sl_figure_name((enum sl_figure)k), cls, v[r], g->n[k], den_a,
                        den_b);
        }
    }
    return SL_OK;
}

/* Every run behind the compared cells was measured on the baseline's machine. */
static int same_machine(const struct bl_machine *bm, const struct sl_store_run *runs, int nruns,
                        const struct sl_cell_record *cells, int ncells)
{
    for (int i = 0; i < ncells; i++) {
        const struct sl_store_run *run = NULL;
        for (int j = 0; j < nruns && !run; j++)
            if (runs[j].run_id == cells[i].run_id)
                run = &runs[j];
        if (!run || strcmp(run->prov.cpu, bm->cpu) || strcmp(run->prov.isa, bm->isa) ||
            strcmp(run->prov.gl_renderer, bm->gl_renderer) || strcmp(run->prov.gl_version, bm->gl_version) ||
            strcmp(run->prov.embree, bm->embree))
            return 0;
    }
    return 1;
}

static enum sl_err load_store(const char *db, const char *study, struct sl_cell_record **cells, int *n,
                              struct sl_store_run **runs, int *nruns, struct sl_diag *d)
{
    struct sl_store *s = NULL;
    enum sl_err e = sl_store_open_existing(db, &s, d);
    struct sl_store_filter f = {.study = study};
    if (!e)
        e = sl_store_query(s, &f, cells, n, d);
    if (!e && (e = sl_store_runs(s, runs, nruns, d))) {
        free(*cells);
        *cells = NULL;
    }
    sl_store_close(s);
    if (!e && *n == 0) {
        free(*cells);
        sl_store_runs_free(*runs, *nruns);
        *cells = NULL;
        *runs = NULL;
        e = sl_fail(d, SL_E_USAGE, db, 0, study ? "--study" : NULL, "no cells%s%s in the store",
                    study ? " of study " : "", study ? study : "");
    }
    return e;
}

/* ---- --json and --junit ---- */

static void xml_str(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        case '"': fputs("&quot;", f); break;
        default:
            if ((unsigned char)*s >= 0x20 || *s == '\t' || *s == '\n')
                fputc(*s, f);
        }
    }
}

/* Does the class apply to the cell (anything compared, or a failure)? A hard
 * cell has no soft class and a soft cell no figures of the hard classes. */
static int class_applies(const struct cell_stats *s, int k)
{
    return s->missing || s->compared[k] || s->failed[k];
}

static void write_json(FILE *f, const char *db, const char *baseline, const struct cmp *m,
                       const struct cell_stats *st, unsigned n)
{
    fprintf(f, "{\n  \"db\": ");
    sl_emit_json_text(f, db);
    fprintf(f, ",\n  \"baseline\": ");
    sl_emit_json_text(f, baseline);
    fprintf(f, ",\n  \"exact_counts\": %s,\n  \"cells\": %d,\n  \"missing\": %d,\n  \"extra\": %d,\n"
               "  \"compared\": %ld,\n  \"moved\": %ld,\n  \"failed\": %ld,\n  \"passed\": %s,\n",
            m->exact ? "true" : "false", m->r->cells, m->r->missing, m->r->extra, m->r->compared, m->r->moved,
            m->r->failed, m->r->failed || m->r->missing ? "false" : "true");
    fprintf(f, "  \"tolerances\": {");
    for (int k = 0; k < SL_CC_COUNT; k++)
        fprintf(f, "%s\"%s\": %g", k ? ", " : "", class_name[k], m->tol[k]);
    fprintf(f, "},\n  \"results\": [");
    for (unsigned i = 0; i < n; i++) {
        const struct cell_stats *s = &st[i];
        fprintf(f, "%s\n    {\"cell\": ", i ? "," : "");
        sl_emit_json_text(f, s->cell ? s->cell : "");
        fprintf(f, ", \"missing\": %s, \"classes\": {", s->missing ? "true" : "false");
        for (int k = 0, w = 0; k < SL_CC_COUNT; k++) {
            if (!class_applies(s, k))
                continue;
            fprintf(f, "%s\n      \"%s\": {\"compared\": %ld, \"moved\": %ld, \"failed\": %ld, "
                       "\"worst_moved\": %.6g, \"passed\": %s",
                    w++ ? "," : "", class_name[k], s->compared[k], s->moved[k], s->failed[k], s->worst[k],
                    s->missing || s->failed[k] ? "false" : "true");
            if (s->failed[k]) {
                fprintf(f, ", \"first_failure\": ");
                sl_emit_json_text(f, s->first_fail[k]);
            }
            fputc('}', f);
        }
        fprintf(f, "}}");
    }
    fprintf(f, "\n  ]\n}\n");
}

static void write_junit(FILE *f, const char *db, const char *baseline, const struct cell_stats *st, unsigned n)
{
    long tests = 0, failures = 0;
    for (unsigned i = 0; i < n; i++)
        for (int k = 0; k < SL_CC_COUNT; k++)
            if (class_applies(&st[i], k)) {
                tests++;
                failures += st[i].missing || st[i].failed[k];
            }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites tests=\"%ld\" failures=\"%ld\">\n"
               "  <testsuite name=\"shadowlab check ", tests, failures);
    xml_str(f, db);
    fprintf(f, " against ");
    xml_str(f, baseline);
    fprintf(f, "\" tests=\"%ld\" failures=\"%ld\" errors=\"0\">\n", tests, failures);
    for (unsigned i = 0; i < n; i++) {
        const struct cell_stats *s = &st[i];
        for (int k = 0; k < SL_CC_COUNT; k++) {
            if (!class_applies(s, k))
                continue;
            fprintf(f, "    <testcase classname=\"");
            xml_str(f, s->cell ? s->cell : "");
            fprintf(f, "\" name=\"%s\"", class_name[k]);
            if (!s->missing && !s->failed[k]) {
                fprintf(f, "/>\n");
                continue;
            }
            fprintf(f, ">\n      <failure message=\"");
            if (s->missing)
                fprintf(f, "the cell is missing from the store");
            else
                xml_str(f, s->first_fail[k]);
            fprintf(f, "\">%ld of %ld value(s) outside tolerance</failure>\n    </testcase>\n", s->failed[k],
                    s->compared[k]);
        }
    }
    fprintf(f, "  </testsuite>\n</testsuites>\n");
}

/* What differs before any figure is compared, first: a config hash other
 * than the baseline's (another config, other -D overrides: every figure may
 * move for that reason alone) and a git SHA other than the baseline's (other
 * code). Said, not failed: the exit status is the figures'. */
static void say_provenance(FILE *out, const struct bl_file *b, const struct sl_cell_record *cells, int n,
                           const struct sl_store_run *runs, int nruns, struct sl_check_result *r)
{
    int other_hash = 0, other_sha = 0;
    const char *hash = NULL, *sha = NULL;
    for (int j = 0; b->config_hash && b->config_hash[0] && j < n; j++)
        if (strcmp(cells[j].config_hash, b->config_hash)) {
            other_hash++;
            hash = cells[j].config_hash;
        }
    for (int j = 0; b->git_sha && b->git_sha[0] && j < nruns; j++)
        if (strcmp(runs[j].prov.git_sha, b->git_sha)) {
            other_sha++;
            sha = runs[j].prov.git_sha;
        }
    /* said when none matches: a store that mixes configs or builds (the
     * baseline itself written from such a store holds both) is not a store
     * of another config */
    r->config_differs = n > 0 && other_hash == n;
    r->sha_differs = nruns > 0 && other_sha == nruns;
    if (!r->config_differs && !r->sha_differs)
        return;
    fprintf(out, "Before the figures, what differs from the baseline:\n");
    if (r->config_differs)
        fprintf(out, "- config hash: the store's %d cell(s) have %s, the baseline %s: another config or other -D "
                     "overrides, so figures may move for that reason alone\n",
                n, hash, b->config_hash);
    if (r->sha_differs)
        fprintf(out, "- git SHA: the store's %d run(s) at %s, the baseline at %s: other code\n", nruns, sha,
                b->git_sha);
    fprintf(out, "\n");
}

enum sl_err sl_check(const char *db, const char *baseline, const struct sl_check_opts *o, FILE *out,
                     struct sl_check_result *r, struct sl_diag *d)
{
    static const struct sl_check_opts none;
    if (!o)
        o = &none;
    memset(r, 0, sizeof *r);
    struct bl_file *b = NULL;
    struct sl_yaml_pos *pos = NULL;
    enum sl_err e = sl_yaml_load(baseline, &file_schema, (void **)&b, &pos, SL_BASELINE_MAX_BYTES, SL_E_BASELINE, d);
    if (e)
        return e;
    struct sl_cell_record *cells = NULL;
    struct sl_store_run *runs = NULL;
    int n = 0, nruns = 0;
    struct cmp m = {.out = out, .o = o, .r = r, .max_rows = o->max_rows > 0 ? o->max_rows : 200};
    moved_table(&m.tab);
    if (b->version != SL_BASELINE_VERSION) {
        e = sl_yaml_bad(d, SL_E_BASELINE, baseline, pos, "shadowlab_baseline", "version %u: this build reads %d",
                        b->version, SL_BASELINE_VERSION);
        goto done;
    }
    for (int k = 0; k < SL_CC_COUNT; k++)
        m.tol[k] = class_tol[k];
    {
        const double *t[SL_CC_COUNT];
        tol_ptrs(b->tolerances, t);
        for (int k = 0; k < SL_CC_COUNT; k++)
            if (t[k]) {
                char key[64];
                snprintf(key, sizeof key, "tolerances.%s", class_name[k]);
                if (!(*t[k] >= 0.0 && *t[k] <= 100.0)) {
                    e = sl_yaml_bad(d, SL_E_BASELINE, baseline, pos, key, "%g: a tolerance is 0..100", *t[k]);
                    goto done;
                }
                if (k == SL_CC_invariant && *t[k] != 0.0) {
                    e = sl_yaml_bad(d, SL_E_BASELINE, baseline, pos, key, "invariants are exact: 0 only");
                    goto done;
                }
                m.tol[k] = *t[k];
            }
    }
    const char *counts = b->counts ? b->counts : "same_machine";
    if (strcmp(counts, "same_machine") && strcmp(counts, "exact") && strcmp(counts, "tolerance")) {
        e = sl_yaml_bad(d, SL_E_BASELINE, baseline, pos, "counts", "'%s': same_machine, exact or tolerance", counts);
        goto done;
    }
    if ((e = load_store(db, o->study, &cells, &n, &runs, &nruns, d)))
        goto done;
    m.exact = o->exact || strcmp(counts, "exact") == 0 ||
              (strcmp(counts, "same_machine") == 0 && same_machine(b->machine, runs, nruns, cells, n));
    r->exact_counts = m.exact;
    r->cells = (int)b->cells_count;

    char *seen = calloc((size_t)n + 1, 1);
    if (!seen) {
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "check");
        goto done;
    }
    struct cell_stats *stats = calloc(b->cells_count + 1, sizeof *stats);
    if (!stats) {
        free(seen);
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "check");
        goto done;
    }
    fprintf(out, o->format == SL_CHECK_MD ? "## shadowlab check: %s against %s\n\n" : "shadowlab check: %s against %s\n\n",
            db, baseline);
    say_provenance(out, b, cells, n, runs, nruns, r);
    for (unsigned i = 0; i < b->cells_count && !e; i++) {
        const struct bl_cell *bc = &b->cells[i];
        m.cur = &stats[i];
        m.cur->cell = bc->cell;
        int found = -1;
        char key[256];
        for (int j = 0; j < n && found < 0; j++) {
            cell_key(&cells[j], key, sizeof key);
            if (strcmp(key, bc->cell) == 0)
                found = j;
        }
        if (found < 0) {
            r->missing++;
            m.cur->missing = 1;
            table_row(&m, bc->cell, "", "(cell)", "", "present", "missing", "", "", 1);
            continue;
        }
        seen[found] = 1;
        e = compare_cell(&m, baseline, pos, i, bc, &cells[found], d);
    }
    if (m.rows) {
        const struct sl_emit_opts eo = {.first = 1, .color = o->color};
        if ((o->format == SL_CHECK_MD ? sl_emit_md : sl_emit_term)(out, &m.tab, &eo) < 0 && !e)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "check: the table of what moved");
    }
    if (!e) {
        if (m.hidden)
            fprintf(out, "\n... and %ld more moved values not shown\n", m.hidden);
        for (int j = 0; j < n; j++)
            if (!seen[j]) {
                char key[256];
                cell_key(&cells[j], key, sizeof key);
                if (r->extra++ == 0)
                    fprintf(out, "\nCells in the store that the baseline does not have (not compared):\n");
                fprintf(out, "- %s\n", key);
            }
        fprintf(out, "\n%ld values of %d cells compared: %ld moved, %ld outside tolerance, %d cell(s) missing.\n",
                r->compared, r->cells, r->moved, r->failed, r->missing);
        if (m.exact)
            fprintf(out, "Counts compared exactly (%s).\n",
                    o->exact                     ? "--exact"
                    : strcmp(counts, "exact") == 0 ? "the baseline says counts: exact"
                                                 : "same CPU, ISA, GL renderer and Embree as the baseline");
        else
            fprintf(out, "Counts compared within the tolerances (%s):\n",
                    strcmp(counts, "tolerance") == 0 ? "the baseline says counts: tolerance"
                                                     : "measured on another machine than the baseline");
        if (!m.exact)
            for (int k = 0; k < SL_CC_COUNT; k++)
                fprintf(out, "- %s: %g — %s\n", class_name[k], m.tol[k], class_text[k]);
    }
    if (!e && o->json)
        write_json(o->json, db, baseline, &m, stats, b->cells_count);
    if (!e && o->junit)
        write_junit(o->junit, db, baseline, stats, b->cells_count);
    free(stats);
    free(seen);
done:
    sl_tab_free(&m.tab);
    free(cells);
    sl_store_runs_free(runs, nruns);
    sl_yaml_free(&file_schema, b, pos);
    return e;
}

/* ---- writing a baseline ---- */

/* A YAML double-quoted scalar. */
static void yq(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fputc('\\', f);
        if ((unsigned char)*s >= 0x20)
            fputc(*s, f);
    }
    fputc('"', f);
}

enum sl_err sl_check_write_baseline(const char *db, const char *baseline, const char *study,
                                    struct sl_diag *d)
{
    /* keep the tolerances and count mode of the file being replaced */
    double tol[SL_CC_COUNT];
    int tol_set[SL_CC_COUNT] = {0};
    char counts[32] = "";
    for (int k = 0; k < SL_CC_COUNT; k++)
        tol[k] = class_tol[k];
    FILE *probe = fopen(baseline, "r");
    if (probe) {
        fclose(probe);
        struct bl_file *old = NULL;
        struct sl_yaml_pos *pos = NULL;
        enum sl_err e = sl_yaml_load(baseline, &file_schema, (void **)&old, &pos, SL_BASELINE_MAX_BYTES, SL_E_BASELINE, d);
        if (e)
            return e;
        {
            const double *t[SL_CC_COUNT];
            tol_ptrs(old->tolerances, t);
            for (int k = 0; k < SL_CC_COUNT; k++)
                if (t[k]) {
                    tol[k] = *t[k];
                    tol_set[k] = 1;
                }
        }
        if (old->counts)
            snprintf(counts, sizeof counts, "%s", old->counts);
        sl_yaml_free(&file_schema, old, pos);
    }

    struct sl_cell_record *cells = NULL;
    struct sl_store_run *runs = NULL;
    int n = 0, nruns = 0;
    enum sl_err e = load_store(db, study, &cells, &n, &runs, &nruns, d);
    if (e)
        return e;
    /* the machine, SHA and config of the latest run behind these cells */
    const struct sl_store_run *run = NULL;
    for (int j = 0; j < nruns; j++)
        for (int i = 0; i < n; i++)
            if (runs[j].run_id == cells[i].run_id)
                run = &runs[j];
    struct sl_outfile of;
    if (!run) {
        e = sl_fail(d, SL_E_INTERNAL, db, 0, NULL, "cells without their run");
        goto done;
    }
    if ((e = sl_out_open(&of, baseline, d)))
        goto done;
    FILE *f = of.f;
    fprintf(f, "# shadowlab baseline: the figures and counters of every cell of a results store,\n"
               "# compared by `shadowlab check DB --baseline THIS_FILE`. Written by\n"
               "# `shadowlab check DB --baseline THIS_FILE --update`: refresh it deliberately\n"
               "# (doc/guide.md, \"Refreshing a baseline\"), never to make a failing check pass.\n");
    fprintf(f, "shadowlab_baseline: %d\n", SL_BASELINE_VERSION);
    fprintf(f, "study: ");
    yq(f, run->study);
    fprintf(f, "\nconfig: ");
    yq(f, run->config_path);
    fprintf(f, "\nconfig_hash: ");
    yq(f, run->config_hash);
    /* Not sl_provenance_write (run.yaml's and bench's writer): the baseline
     * keeps only what decides whether counts must be exact (the machine:
     * block its schema reads back, bl_machine), its values quoted, and its
     * bytes are the baseline format's. */
    fprintf(f, "\ngit_sha: ");
    yq(f, run->prov.git_sha);
    fprintf(f, "\nmeasured: ");
    yq(f, run->prov.time_utc);
    fprintf(f, "\nmachine:\n  cpu: ");
    yq(f, run->prov.cpu);
    fprintf(f, "\n  isa: ");
    yq(f, run->prov.isa);
    fprintf(f, "\n  gl_renderer: ");
    yq(f, run->prov.gl_renderer);
    fprintf(f, "\n  gl_version: ");
    yq(f, run->prov.gl_version);
    fprintf(f, "\n  embree: ");
    yq(f, run->prov.embree);
    fprintf(f, "\n# same_machine: counts exact on the machine above, else within the tolerances;\n"
               "# exact: always exact; tolerance: always within the tolerances\n");
    fprintf(f, "counts: %s\n", counts[0] ? counts : "same_machine");
    fprintf(f, "tolerances:\n");
    for (int k = 0; k < SL_CC_COUNT; k++)
        fprintf(f, "  %s: %g   # %s%s\n", class_name[k], tol[k], class_text[k], tol_set[k] ? "" : " [default]");
    fprintf(f, "cells:\n");
    for (int i = 0; i < n; i++) {
        const struct sl_cell_record *c = &cells[i];
        char key[256];
        cell_key(c, key, sizeof key);
        fprintf(f, "  - cell: ");
        yq(f, key);
        fprintf(f, "\n    counters: {");
        for (int k = 0; k < BL_C_COUNT; k++)
            fprintf(f, "%s%s: %llu", k ? ", " : "", counter_name[k], (unsigned long long)cell_counter(c, k));
        fprintf(f, "}\n");
        if (c->has_soft) {
            fprintf(f, "    soft: {");
            for (int k = 0; k < SL_SFIG_COUNT; k++)
                fprintf(f, "%s%s: %llu", k ? ", " : "", sl_soft_figure_name((enum sl_soft_figure)k),
                        (unsigned long long)c->soft.n[k]);
            fprintf(f, "}\n    soft_mean: {");
            static const int means[] = {SL_SFIG_soft_mae, SL_SFIG_soft_rmse, SL_SFIG_soft_bias,
                                        SL_SFIG_soft_truth_stderr};
            int w = 0;
            for (size_t j = 0; j < sizeof means / sizeof means[0]; j++)
                if (!isnan(c->soft.pct[means[j]]))   /* exact to the last bit: %.17g round-trips */
                    fprintf(f, "%s%s: %.17g", w++ ? ", " : "", sl_soft_figure_name((enum sl_soft_figure)means[j]),
                            c->soft.pct[means[j]]);
            fprintf(f, "}\n");
        }
        if (c->fig.nregions == 0)
            continue;
        fprintf(f, "    regions: [");
        for (int r = 0; r < c->fig.nregions; r++) {
            char name[16];
            sl_region_name(c->fig.r[r].thickness, name, sizeof name);
            fprintf(f, "%s%s", r ? ", " : "", name);
        }
        fprintf(f, "]\n    figures:\n");
        for (int k = 0; k < SL_FIG_COUNT; k++) {
            fprintf(f, "      %s: [", sl_figure_name((enum sl_figure)k));
            for (int r = 0; r < c->fig.nregions; r++)
                fprintf(f, "%s%llu", r ? ", " : "", (unsigned long long)c->fig.r[r].n[k]);
            fprintf(f, "]\n");
        }
    }
    e = sl_out_commit(&of, d);
done:
    free(cells);
    sl_store_runs_free(runs, nruns);
    return e;
}
