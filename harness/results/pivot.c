/*
 * pivot.c — see pivot.h.
 *
 * Invariants: a pivot is built in one pass over (cell, region) points: each
 * point has a string for every key of SL_PIVOT_KEYS and one value (NaN when
 * its base is 0: it enters no aggregate, its keys still make a row or
 * column). Keys are ordered as the tables order them: map sizes ascending,
 * regions by thickness with the image last, everything else by first
 * appearance. LaTeX widths are estimated from the plain text of each cell at
 * \small in a plain article (10 pt, \columnwidth 345 pt); what does not fit
 * is transposed or split, never scaled. Nothing here prints to a terminal.
 */
#include "pivot.h"
#include "emit.h"
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "provenance.h"
#include "tex.h"   /* the width estimates: the writer lays out its floats */
#include "util.h"

const char *sl_pivot_key_name(enum sl_pivot_key k)
{
    static const char *const names[] = {
        "default",
#define SL_PK_NAME(name) #name,
        SL_PIVOT_KEYS(SL_PK_NAME)
#undef SL_PK_NAME
    };
    return k > 0 && k < SL_PK_COUNT ? names[k] : "?";
}

int sl_pivot_key_parse(const char *name)
{
    for (int k = 1; name && k < SL_PK_COUNT; k++)
        if (strcmp(name, sl_pivot_key_name((enum sl_pivot_key)k)) == 0)
            return k;
    return -1;
}

static const char *const agg_names[] = {"mean", "median", "sum", "min", "max", NULL};

int sl_pivot_agg_parse(const char *name)
{
    for (int k = 0; name && agg_names[k]; k++)
        if (strcmp(name, agg_names[k]) == 0)
            return k;
    return -1;
}

enum sl_err sl_pivot_where_parse(struct sl_pivot_desc *p, const char *kv, struct sl_diag *d)
{
    const char *eq = strchr(kv, '=');
    char key[32];
    if (!eq || (size_t)(eq - kv) >= sizeof key)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--where", "'%s' is not KEY=VALUE", kv);
    memcpy(key, kv, (size_t)(eq - kv));
    key[eq - kv] = '\0';
    int k = sl_pivot_key_parse(key);
    if (k < 0)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--where",
                       "unknown key '%s' (label, method, scene, viewpoint, viewport, map_size, region)", key);
    if (p->nwhere >= SL_PIVOT_MAX_WHERE)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--where", "at most %d", SL_PIVOT_MAX_WHERE);
    p->where[p->nwhere].key = (enum sl_pivot_key)k;
    p->where[p->nwhere].value = eq + 1;
    p->nwhere++;
    return SL_OK;
}

/* ---- numbers ---- */

/* the same without markup, for Markdown and for the width estimate */
static void plain_number(char *out, size_t n, double v, int dec)
{
    if (isnan(v)) {
        snprintf(out, n, "-");
        return;
    }
    snprintf(out, n, "%.*f", dec, v);
}

/* ---- width estimate (pt): tex.h ---- */

#define TEX_BUDGET      SL_TEX_BUDGET
#define TEX_COLSEP      12.0
#define TEX_MAXNUM      8
#define TEX_LABELMAX    130.0      /* a wider row name is wrapped in a \parbox of this width */

static double text_pt(const char *s) { return sl_tex_text_pt(s); }
static double number_pt(const char *plain) { return sl_tex_number_pt(plain); }

/* A \label key: letters and digits, anything else '-' (appended to out) */
static void label_key(char *out, size_t n, const char *s)
{
    size_t o = strlen(out);
    for (; *s && o + 1 < n; s++) {
        char ch = *s;
        int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9');
        out[o++] = ok ? ch : '-';
    }
    out[o] = '\0';
}

/* ---- the figure ---- */

enum src { SRC_HARD, SRC_SOFT, SRC_COL };

/* the counters and times of cellcols.h, by name */
struct colref {
    const char *name;
    size_t      off;
    int         is_ms;
};
#define PV_COL_text(name)
#define PV_COL_path(name)
#define PV_COL_dim(name)
#define PV_COL_index(name)
#define PV_COL_runs(name)
#define PV_COL_viewport(name)
#define PV_COL_wrong(name)
#define PV_COL_flag(name)
#define PV_COL_count(name) {#name, offsetof(struct sl_cell_record, name), 0},
#define PV_COL_ms(name)    {#name, offsetof(struct sl_cell_record, name), 1},
static const struct colref cols[] = {
#define PV_COL(name, kind, size, csv, head, check, key, from) PV_COL_##kind(name)
    SL_CELL_COLUMNS(PV_COL)
#undef PV_COL
};

const char *sl_pivot_counter_name(int i)
{
    return i >= 0 && (size_t)i < sizeof cols / sizeof cols[0] ? cols[i].name : NULL;
}

struct fig {
    enum src src;
    int      k;              /* figure or column */
    int      base;           /* SRC_HARD with --of FIGURE: that figure, else -1 */
    int      count;          /* a count, not a percentage */
    int      per_pfl;        /* SRC_COL with --of pfl: a counter as a share of the cell's PFL pixels */
    char     unit[64];       /* plain: "% of pixels", "count", "ms" */
    int      is_int;         /* values are whole numbers (a count, not averaged) */
};

static enum sl_err fig_resolve(const struct sl_pivot_desc *p, struct fig *g, struct sl_diag *d)
{
    const char *name = p->figure ? p->figure : "wrong";
    memset(g, 0, sizeof *g);
    g->k = -1;
    g->base = -1;
    const char *own = "";
    for (int k = 0; k < SL_FIG_COUNT && g->k < 0; k++)
        if (!strcmp(name, sl_figure_name((enum sl_figure)k)))
            g->src = SRC_HARD, g->k = k, own = sl_figure_of((enum sl_figure)k);
    for (int k = 0; k < SL_SFIG_COUNT && g->k < 0; k++)
        if (!strcmp(name, sl_soft_figure_name((enum sl_soft_figure)k)))
            g->src = SRC_SOFT, g->k = k, own = sl_soft_figure_of((enum sl_soft_figure)k);
    for (size_t k = 0; k < sizeof cols / sizeof cols[0] && g->k < 0; k++)
        if (!strcmp(name, cols[k].name))
            g->src = SRC_COL, g->k = (int)k;
    if (g->k < 0)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--figure",
                       "unknown figure '%s' (a name of figures.h or softfig.h, e.g. wrong, uncertain, soft_mae, "
                       "leaking, over_dark; or a counter or time: ms_method, rays, lookups, nonfinite, ...)", name);
    const char *of = p->of;
    if (g->src == SRC_COL) {
        /* a counter per PFL pixel: rays as a share of raytrace's, which
         * traces one ray a PFL pixel */
        if (of && !strcmp(of, "pfl") && !cols[g->k].is_ms) {
            g->per_pfl = 1;
            snprintf(g->unit, sizeof g->unit, "%% of PFL pixels");
            return SL_OK;
        }
        if (of && strcmp(of, "count"))
            return sl_fail(d, SL_E_USAGE, NULL, 0, "--of", "%s is a %s: only --of count%s", name,
                           cols[g->k].is_ms ? "time" : "counter", cols[g->k].is_ms ? "" : " or --of pfl");
        g->count = 1;
        snprintf(g->unit, sizeof g->unit, "%s", cols[g->k].is_ms ? "ms" : "count");
        g->is_int = !cols[g->k].is_ms;
        return SL_OK;
    }
    if ((of && !strcmp(of, "count")) || (!of && !own[0])) {
        g->count = 1;
        g->is_int = 1;
        snprintf(g->unit, sizeof g->unit, "count");
        return SL_OK;
    }
    if (of) {
        for (int k = 0; k < SL_FIG_COUNT && g->src == SRC_HARD && g->base < 0; k++)
            if (!strcmp(of, sl_figure_name((enum sl_figure)k)))
                g->base = k;
        if (g->base < 0)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "--of",
                           "'%s' is no base of %s (count, or a figure of figures.h of a figures.h figure)", of,
                           name);
        own = of;
    }
    if (g->src == SRC_SOFT && !strcmp(own, "visibility"))
        snprintf(g->unit, sizeof g->unit, "%% of full visibility");
    else
        snprintf(g->unit, sizeof g->unit, "%% of %s", own);
    return SL_OK;
}

/* the value of point (cell c, region r): NaN when it has no base */
static double fig_value(const struct fig *g, const struct sl_cell_record *c, int r)
{
    switch (g->src) {
    case SRC_COL: {
        if (cols[g->k].is_ms)
            return *(const double *)(const void *)((const char *)c + cols[g->k].off);
        double x = (double)*(const uint64_t *)(const void *)((const char *)c + cols[g->k].off);
        if (g->per_pfl)
            return c->n_pfl ? 100.0 * x / (double)c->n_pfl : NAN;
        return x;
    }
    case SRC_SOFT:
        return g->count ? (double)c->soft.n[g->k] : c->soft.pct[g->k];
    case SRC_HARD:
        if (g->count)
            return (double)c->fig.r[r].n[g->k];
        if (g->base >= 0)
            return c->fig.r[r].n[g->base] ? 100.0 * (double)c->fig.r[r].n[g->k] / (double)c->fig.r[r].n[g->base]
                                          : NAN;
        return c->fig.r[r].pct[g->k];
    }
    return NAN;
}

/* the regions a cell has for this figure: hard figures per region; the
 * rest once, for the whole image (r = -1) */
static int fig_regions(const struct fig *g, const struct sl_cell_record *c)
{
    if (g->src == SRC_HARD)
        return c->fig.nregions;
    if (g->src == SRC_SOFT)
        return c->has_soft ? 1 : 0;
    return 1;
}

/* ---- keys ---- */

#define KEYLEN 80

struct keyset {
    char (*v)[KEYLEN];
    double *ord;
    int     n, cap;
};

static int keyset_add(struct keyset *k, const char *s, double ord)
{
    for (int i = 0; i < k->n; i++)
        if (!strcmp(k->v[i], s))
            return i;
    if (k->n == k->cap) {
        int cap = k->cap ? 2 * k->cap : 16;
        char (*v)[KEYLEN] = realloc(k->v, (size_t)cap * sizeof *v);
        if (v)
            k->v = v;
        double *o = realloc(k->ord, (size_t)cap * sizeof *o);
        if (o)
            k->ord = o;
        if (!v || !o)
            return -1;
        k->cap = cap;
    }
    snprintf(k->v[k->n], KEYLEN, "%s", s);
    k->ord[k->n] = ord;
    return k->n++;
}

static void keyset_free(struct keyset *k)
{
    free(k->v);
    free(k->ord);
}

static void point_key(const struct sl_cell_record *c, int r, enum sl_pivot_key k, char *out, double *ord)
{
    *ord = 0;
    switch (k) {
    case SL_PK_label: snprintf(out, KEYLEN, "%s", c->label); break;
    case SL_PK_method: snprintf(out, KEYLEN, "%s", c->method); break;
    case SL_PK_scene: snprintf(out, KEYLEN, "%s", c->scene); break;
    case SL_PK_viewpoint: snprintf(out, KEYLEN, "%s", c->viewpoint); break;
    case SL_PK_viewport:
        snprintf(out, KEYLEN, "%dx%d", c->vw, c->vh);
        *ord = (double)c->vw * 1e6 + c->vh;
        break;
    case SL_PK_map_size:
        snprintf(out, KEYLEN, "%d", c->map_size);
        *ord = c->map_size;
        break;
    case SL_PK_region: {
        int t = r >= 0 ? c->fig.r[r].thickness : 0;
        sl_region_name(t, out, KEYLEN);
        *ord = t ? t : 1e9;
        break;
    }
    default: out[0] = '\0';
    }
}

/* a key's name for people: a column's or row's head, a caption's word */
static const char *key_head(enum sl_pivot_key k)
{
    switch (k) {
    case SL_PK_label: return "method";
    case SL_PK_method: return "algorithm";
    case SL_PK_map_size: return "shadow-map size";
    default: return sl_pivot_key_name(k);
    }
}

/* keys ordered by first appearance unless they have a numeric order */
static int by_order(enum sl_pivot_key k) { return k == SL_PK_viewport || k == SL_PK_map_size || k == SL_PK_region; }

/* ---- the pivot ---- */

struct pivot {
    struct fig    g;
    enum sl_pivot_key rk, ck;
    struct keyset key[SL_PK_COUNT];    /* every key's values among the points */
    int          *rperm, *cperm;       /* display order -> key index */
    double       *val;                 /* nrows x ncols (key index), NaN: none */
    int          *cnt;                 /* values aggregated */
    unsigned char *once;               /* a time: a cell of the entry was timed once (runs 1) */
    int           any_once;
    int           nr, nc, maxn, minn, region_default;
    int           varies[SL_PK_COUNT];  /* the key has two values inside one entry */
    char        (*ldisp)[KEYLEN];       /* per label key: its display name (cells.display) */
    int           nf_cells;            /* cells of the table with values not finite (cells.nonfinite) */
    int           any_frac, any_area;  /* soft cells of the table: a hard light's (frac), an area light's */
    char          lights[256];         /* and the lights their truths were computed for, each once */
    char          all_lights[256];     /* every kept cell's light in words, each once ("directional light") */
    char          studies[256];        /* the studies of the kept cells, each once */
    uint64_t      nonfinite;           /* and their sum */
    char          renderer[128];       /* a time: the GL renderer of its cells ("" unknown; "several") */
};

static void pivot_free(struct pivot *pv)
{
    for (int k = 0; k < SL_PK_COUNT; k++)
        keyset_free(&pv->key[k]);
    free(pv->rperm);
    free(pv->cperm);
    free(pv->val);
    free(pv->cnt);
    free(pv->once);
    free(pv->ldisp);
}

/* display order of a key's values: by first appearance, or by their numeric
 * order (insertion sort: stable, a few hundred values at most) */
static int *perm_of(const struct keyset *k, enum sl_pivot_key key)
{
    int *p = malloc((size_t)(k->n ? k->n : 1) * sizeof *p);
    if (!p)
        return NULL;
    for (int i = 0; i < k->n; i++) {
        int j = i;
        while (by_order(key) && j > 0 && k->ord[p[j - 1]] > k->ord[i]) {
            p[j] = p[j - 1];
            j--;
        }
        p[j] = i;
    }
    return p;
}

static int dbl_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double aggregate(enum sl_pivot_agg a, double *v, int n)
{
    if (n == 0)
        return NAN;
    double s = 0, lo = v[0], hi = v[0];
    for (int i = 0; i < n; i++) {
        s += v[i];
        lo = v[i] < lo ? v[i] : lo;
        hi = v[i] > hi ? v[i] : hi;
    }
    switch (a) {
    case SL_AGG_SUM: return s;
    case SL_AGG_MIN: return lo;
    case SL_AGG_MAX: return hi;
    case SL_AGG_MEDIAN:
        qsort(v, (size_t)n, sizeof *v, dbl_cmp);
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    default: return s / n;
    }
}

/* w appended to the list "a and b" unless there: light words
 * (sl_light_heading) never hold " and " */
static void add_light(char *list, size_t n, const char *w)
{
    for (const char *p = list; *p;) {
        const char *e = strstr(p, " and ");
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == strlen(w) && !strncmp(p, w, len))
            return;
        p += len + (e ? 5 : 0);
    }
    size_t o = strlen(list);
    if (o + strlen(w) + 6 < n)
        snprintf(list + o, n - o, "%s%s", o ? " and " : "", w);
}

static enum sl_err pivot_build(const struct sl_cell_record *cells, int ncells, const struct sl_pivot_desc *p,
                               struct pivot *pv, struct sl_diag *d)
{
    memset(pv, 0, sizeof *pv);
    enum sl_err e = fig_resolve(p, &pv->g, d);
    if (e)
        return e;
    pv->rk = p->rows ? p->rows : SL_PK_label;
    pv->ck = p->cols ? p->cols : SL_PK_map_size;
    if (pv->rk == pv->ck)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--cols", "rows and columns are both %s", sl_pivot_key_name(pv->rk));
    pv->region_default = pv->rk != SL_PK_region && pv->ck != SL_PK_region;
    for (int w = 0; w < p->nwhere; w++)
        if (p->where[w].key == SL_PK_region)
            pv->region_default = 0;
    /* points: (row key, column key, value) */
    int cap = 0, np = 0;
    for (int i = 0; i < ncells; i++)
        cap += fig_regions(&pv->g, &cells[i]);
    int *pr = malloc((size_t)(cap ? cap : 1) * sizeof *pr), *pc = malloc((size_t)(cap ? cap : 1) * sizeof *pc);
    double *pval = malloc((size_t)(cap ? cap : 1) * sizeof *pval);
    int (*pk)[SL_PK_COUNT] = malloc((size_t)(cap ? cap : 1) * sizeof *pk);
    unsigned char *ponce = malloc((size_t)(cap ? cap : 1));
    if (!pr || !pc || !pval || !pk || !ponce) {
        free(pr), free(pc), free(pval), free(pk), free(ponce);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "pivot of %d cells", ncells);
    }
    for (int i = 0; i < ncells && !e; i++) {
        const struct sl_cell_record *c = &cells[i];
        int nreg = fig_regions(&pv->g, c), kept = 0;
        for (int r = 0; r < nreg && !e; r++) {
            int reg = pv->g.src == SRC_HARD ? r : -1;
            char ks[SL_PK_COUNT][KEYLEN];
            double ord[SL_PK_COUNT];
            for (int k = 1; k < SL_PK_COUNT; k++)
                point_key(c, reg, (enum sl_pivot_key)k, ks[k], &ord[k]);
            int keep = !pv->region_default || !strcmp(ks[SL_PK_region], "image");
            /* a key given twice is either value; different keys all hold */
            for (int k = 1; k < SL_PK_COUNT && keep; k++) {
                int asked = 0, hit = 0;
                for (int w = 0; w < p->nwhere; w++)
                    if ((int)p->where[w].key == k)
                        asked = 1, hit |= !strcmp(ks[k], p->where[w].value);
                keep = !asked || hit;
            }
            if (!keep)
                continue;
            int idx[SL_PK_COUNT] = {0};
            for (int k = 1; k < SL_PK_COUNT && !e; k++)
                if ((idx[k] = keyset_add(&pv->key[k], ks[k], ord[k])) < 0)
                    e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "pivot keys");
            memcpy(pk[np], idx, sizeof idx);
            pr[np] = idx[pv->rk];
            pc[np] = idx[pv->ck];
            pval[np] = fig_value(&pv->g, c, reg);
            ponce[np] = pv->g.src == SRC_COL && cols[pv->g.k].is_ms && c->runs == 1;
            np++;
            kept = 1;
        }
        if (kept) {
            if (c->light[0])
                add_light(pv->all_lights, sizeof pv->all_lights, c->light);
            if (c->study[0])
                add_light(pv->studies, sizeof pv->studies, c->study);
        }
        if (kept && pv->g.src == SRC_SOFT) {
            pv->any_frac |= c->frac;
            pv->any_area |= !c->frac;
            add_light(pv->lights, sizeof pv->lights, c->light[0] ? c->light : c->frac ? "hard light" : "area light");
        }
        if (kept && pv->g.src == SRC_COL && cols[pv->g.k].is_ms) {
            if (!pv->renderer[0])
                snprintf(pv->renderer, sizeof pv->renderer, "%s", c->gl_renderer);
            else if (strcmp(pv->renderer, c->gl_renderer))
                snprintf(pv->renderer, sizeof pv->renderer, "several GL renderers (see the store's runs)");
        }
        if (kept && c->nonfinite) {
            pv->nf_cells++;
            pv->nonfinite += c->nonfinite;
        }
    }
    if (!e) {
        pv->nr = pv->key[pv->rk].n;
        pv->nc = pv->key[pv->ck].n;
        size_t ne = (size_t)pv->nr * (size_t)pv->nc + 1;
        pv->val = malloc(ne * sizeof *pv->val);
        pv->cnt = calloc(ne, sizeof *pv->cnt);
        pv->once = calloc(ne, 1);
        pv->rperm = perm_of(&pv->key[pv->rk], pv->rk);
        pv->cperm = perm_of(&pv->key[pv->ck], pv->ck);
        double *tmp = malloc((size_t)(np ? np : 1) * sizeof *tmp);
        if (!pv->val || !pv->cnt || !pv->once || !pv->rperm || !pv->cperm || !tmp)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "pivot of %d cells", ncells);
        for (int r = 0; r < pv->nr && !e; r++)
            for (int c = 0; c < pv->nc; c++) {
                int n = 0;
                for (int i = 0; i < np; i++)
                    if (pr[i] == r && pc[i] == c && !isnan(pval[i])) {
                        tmp[n++] = pval[i];
                        pv->once[r * pv->nc + c] |= ponce[i];
                        pv->any_once |= ponce[i];
                    }
                pv->val[r * pv->nc + c] = aggregate(p->agg, tmp, n);
                pv->cnt[r * pv->nc + c] = n;
                pv->maxn = n > pv->maxn ? n : pv->maxn;
                if (n > 0 && (pv->minn == 0 || n < pv->minn))
                    pv->minn = n;
            }
        free(tmp);
        /* what the entries aggregate over: keys with two values in one entry */
        int *first = malloc((size_t)pv->nr * (size_t)pv->nc * sizeof *first + 1);
        for (int k = 1; k < SL_PK_COUNT && first && !e; k++) {
            for (int i = 0; i < pv->nr * pv->nc; i++)
                first[i] = -1;
            for (int i = 0; i < np && !pv->varies[k]; i++) {
                int *f0 = &first[pr[i] * pv->nc + pc[i]];
                if (*f0 < 0)
                    *f0 = pk[i][k];
                else if (*f0 != pk[i][k])
                    pv->varies[k] = 1;
            }
        }
        free(first);
        /* each label's display name: the first of its cells that has one */
        const struct keyset *lk = &pv->key[SL_PK_label];
        pv->ldisp = calloc((size_t)lk->n + 1, sizeof *pv->ldisp);
        if (!pv->ldisp)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "pivot labels");
        for (int i = 0; i < lk->n && !e; i++)
            for (int j = 0; j < ncells; j++)
                if (cells[j].display[0] && !strcmp(cells[j].label, lk->v[i])) {
                    snprintf(pv->ldisp[i], KEYLEN, "%s", cells[j].display);
                    break;
                }
    }
    free(pr), free(pc), free(pval), free(pk), free(ponce);
    if (e)
        pivot_free(pv);
    return e;
}

/* decimals of an entry: percentages and times 2, whole counts 0, a mean of counts 1 */
static int decimals(const struct pivot *pv, enum sl_pivot_agg a)
{
    if (!pv->g.count || !pv->g.is_int)
        return 2;
    return a == SL_AGG_MEAN || a == SL_AGG_MEDIAN ? 1 : 0;
}

/* ---- captions: in words, no internal ids (issue 47) ---- */

/* A key in words, singular and plural (a caption's "per method and
 * shadow-map size", "over 2 scenes"). */
static const char *key_word(enum sl_pivot_key k, int plural)
{
    if (!plural)
        return key_head(k);
    switch (k) {
    case SL_PK_label: return "methods";
    case SL_PK_method: return "algorithms";
    case SL_PK_scene: return "scenes";
    case SL_PK_viewpoint: return "viewpoints";
    case SL_PK_viewport: return "viewports";
    case SL_PK_map_size: return "shadow-map sizes";
    case SL_PK_region: return "regions";
    default: return "";
    }
}

/* The counters and times of cellcols.h a pivot takes, in words; a name not
 * here is written with its underscores as spaces (no table of them all:
 * the cost columns are the cost model's, and change with it). */
static const struct {
    const char *name, *words;
} col_words[] = {
    {"ms_method", "time of the method's per-pixel step: lookup and rays (median over the timed runs)"},
    {"ms_cost", "total time of the cell's stages summed: map pass, post, lookup, readback, rays "
                "(medians over the timed runs)"},
    {"ms_map", "time of the shadow-map pass (median over the timed runs)"},
    {"ms_post", "time of the post passes: blur, mipmaps (median over the timed runs)"},
    {"ms_lookup", "time of the per-pixel lookup (median over the timed runs)"},
    {"ms_readback", "time of the readback (median over the timed runs)"},
    {"ms_map_render", "time of the shadow-map render of the layers the method reads (median over the timed runs)"},
    {"ms_gbuffer_render", "time of the G-buffer render (median over the timed runs)"},
    {"ms_truth", "time of the ray-traced truth (median over the timed runs)"},
    {"ms_ray_step", "time of the method's shadow rays"},
    {"rays", "shadow rays traced"},
    {"lookups", "shadow-map lookups"},
    {"tri_tests", "ray-triangle tests"},
    {"fragments", "fragments shaded"},
    {"truth_rays", "rays of the truth"},
    {"texels", "texels read"},
    {"nonfinite", "values not finite"},
    {NULL, NULL},
};

/* the figure in words, its first letter a capital */
static void figure_words(const struct pivot *pv, const struct sl_pivot_desc *p, char *out, size_t n)
{
    const char *name = p->figure ? p->figure : "wrong";
    const char *text = pv->g.src == SRC_HARD   ? sl_figure_text((enum sl_figure)pv->g.k)
                       : pv->g.src == SRC_SOFT ? sl_soft_figure_text((enum sl_soft_figure)pv->g.k)
                                               : NULL;
    for (int k = 0; !text && col_words[k].name; k++)
        if (!strcmp(col_words[k].name, name))
            text = col_words[k].words;
    if (text)
        snprintf(out, n, "%s", text);
    else {
        snprintf(out, n, "%s", name);
        for (char *q = out; *q; q++)
            *q = *q == '_' ? ' ' : *q;
    }
    if (out[0] >= 'a' && out[0] <= 'z')
        out[0] = (char)(out[0] - 'a' + 'A');
}

/* the unit in words: "% of the image's pixels", "% of the pixels the
 * method puts in light", "ms", "count" */
static void unit_words(const struct pivot *pv, const struct sl_pivot_desc *p, char *out, size_t n)
{
    if (pv->g.src == SRC_HARD && !pv->g.count) {
        int base = pv->g.base;
        if (base < 0)
            for (int k = 0; k < SL_FIG_COUNT && base < 0; k++)
                if (!strcmp(sl_figure_of((enum sl_figure)pv->g.k), sl_figure_name((enum sl_figure)k)))
                    base = k;
        if (base >= 0 && !strcmp(sl_figure_name((enum sl_figure)base), "pixels"))
            snprintf(out, n, "%% of the %s pixels (background excluded)",
                     pv->region_default ? "image's" : "region's");
        else if (base >= 0)
            snprintf(out, n, "%% of the %s", sl_figure_text((enum sl_figure)base));
        else
            snprintf(out, n, "%s", pv->g.unit);
        return;
    }
    (void)p;
    snprintf(out, n, "%s", !strcmp(pv->g.unit, "count") ? "a count" : pv->g.unit);
}

/* value i of key k for people: a label's display name, a map size squared,
 * a viewport's "x" a times sign */
static void key_words(const struct pivot *pv, enum sl_pivot_key k, int i, char *out, size_t n)
{
    const char *v = pv->key[k].v[i];
    if (k == SL_PK_label && pv->ldisp && pv->ldisp[i][0])
        snprintf(out, n, "%s", pv->ldisp[i]);
    else if (k == SL_PK_map_size)
        snprintf(out, n, "%s\xC2\xB2", v);
    else if (k == SL_PK_viewport) {
        int w = 0, h = 0;
        sscanf(v, "%dx%d", &w, &h);
        snprintf(out, n, "%d\xC3\x97%d", w, h);
    } else
        snprintf(out, n, "%s", v);
}

/* "a", "a and b", "a, b and c" of the values of key k in display order;
 * more than five: their count only */
static size_t key_list(const struct pivot *pv, enum sl_pivot_key k, char *out, size_t n)
{
    const struct keyset *ks = &pv->key[k];
    size_t o = 0;
    out[0] = '\0';
    if (ks->n > 5)
        return (size_t)snprintf(out, n, "%d %s", ks->n, key_word(k, 1));
    int *perm = perm_of(ks, k);
    for (int i = 0; perm && i < ks->n; i++) {
        char w[KEYLEN + 8];
        key_words(pv, k, perm[i], w, sizeof w);
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, "%s%s", i == 0 ? "" : i == ks->n - 1 ? " and " : ", ", w);
    }
    free(perm);
    return o;
}

/* The caption's words (escaped by the emitter): what the entries are, per
 * which keys, what each aggregates (over which keys, how many values), what
 * every entry shares (the scene, viewport, map size, light when there is
 * one of it), the --where, the study. zero: the sentence that stands for a
 * table whose every entry is 0 ("... is 0 for every method and ..."). */
static void caption_words(const struct pivot *pv, const struct sl_pivot_desc *p, char *out, size_t n, int zero)
{
    char fig[256], unit[128], list[512];
    figure_words(pv, p, fig, sizeof fig);
    unit_words(pv, p, unit, sizeof unit);
    size_t o = (size_t)snprintf(out, n, "%s, %s, %s every %s and %s", fig, unit, zero ? "is 0 for" : "for",
                                key_word(pv->rk, 0), key_word(pv->ck, 0));
    /* what an entry aggregates over: the keys with two values in one entry */
    char over[1024];
    size_t ov = 0;
    int said = 0;
    over[0] = '\0';
    for (int k = 1; k < SL_PK_COUNT; k++) {
        if (k == (int)pv->rk || k == (int)pv->ck || !pv->varies[k])
            continue;
        key_list(pv, (enum sl_pivot_key)k, list, sizeof list);
        if (pv->key[k].n > 5)
            ov += (size_t)snprintf(over + ov, ov < sizeof over ? sizeof over - ov : 0, "%s%s", said ? " and " : "",
                                   list);
        else
            ov += (size_t)snprintf(over + ov, ov < sizeof over ? sizeof over - ov : 0, "%s%d %s (%s)",
                                   said ? " and " : "", pv->key[k].n, key_word((enum sl_pivot_key)k, pv->key[k].n > 1),
                                   list);
        said++;
    }
    if (said && pv->minn == pv->maxn)
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, ": the %s over %s, %d values an entry", agg_names[p->agg],
                              over, pv->maxn);
    else if (said)
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, ": the %s over %s, %d to %d values an entry",
                              agg_names[p->agg], over, pv->minn, pv->maxn);
    /* what every entry shares: a key of one value that is no row or column */
    static const enum sl_pivot_key shared[] = {SL_PK_label,    SL_PK_scene,    SL_PK_viewpoint,
                                               SL_PK_viewport, SL_PK_map_size, SL_PK_region};
    for (size_t s = 0; s < sizeof shared / sizeof shared[0]; s++) {
        enum sl_pivot_key k = shared[s];
        if (k == pv->rk || k == pv->ck || pv->varies[k] || pv->key[k].n != 1 ||
            (k == SL_PK_region && pv->region_default))
            continue;
        key_list(pv, k, list, sizeof list);
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, "; %s %s", key_word(k, 0), list);
    }
    if (pv->all_lights[0])
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, "; %s", pv->all_lights);
    if (pv->region_default && pv->g.src == SRC_HARD)
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, "; the whole image");
    /* a soft figure: the lights its cells' truths were computed for */
    if (pv->lights[0])
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, "; against the truth of the %s", pv->lights);
    /* a class figure of a hard light's cells: its tolerance (softfig.h) */
    int cls = pv->g.src == SRC_SOFT && (pv->g.k == SL_SFIG_soft_lit_right || pv->g.k == SL_SFIG_soft_umbra_right ||
                                        pv->g.k == SL_SFIG_soft_penumbra_right || pv->g.k == SL_SFIG_soft_class_right);
    if (cls && pv->any_frac)
        o += (size_t)snprintf(out + o, o < n ? n - o : 0,
                              "; %sunder a hard light lit within \xCE\xB5 = %.2f of 1 and umbra within \xCE\xB5 of 0 "
                              "(a class right when |v \xE2\x88\x92 truth| \xE2\x89\xA4 \xCE\xB5)",
                              pv->any_area ? "exact under an area light, " : "", (double)SL_SOFT_HARD_TOL);
    /* --where: the kept values, a label by its display name */
    for (int k = 1; k < SL_PK_COUNT; k++) {
        int first = 1;
        /* a key of one value is said above as what every entry shares */
        if (k != (int)pv->rk && k != (int)pv->ck && !pv->varies[k] && pv->key[k].n == 1)
            continue;
        for (int w = 0; w < p->nwhere; w++) {
            if ((int)p->where[w].key != k)
                continue;
            char v[KEYLEN + 8];
            int i = -1;
            for (int j = 0; j < pv->key[k].n && i < 0; j++)
                if (!strcmp(pv->key[k].v[j], p->where[w].value))
                    i = j;
            if (i >= 0)
                key_words(pv, (enum sl_pivot_key)k, i, v, sizeof v);
            else
                snprintf(v, sizeof v, "%s", p->where[w].value);
            o += (size_t)snprintf(out + o, o < n ? n - o : 0, "%s%s%s", first ? "; only " : " or ",
                                  first ? key_word((enum sl_pivot_key)k, 0) : "", first ? " " : "");
            o += (size_t)snprintf(out + o, o < n ? n - o : 0, "%s", v);
            first = 0;
        }
    }
    if (pv->studies[0])
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, " (%s %s)", strstr(pv->studies, " and ") ? "studies" : "study",
                              pv->studies);
    o += (size_t)snprintf(out + o, o < n ? n - o : 0, ".");
    if (pv->any_once)
        o += (size_t)snprintf(out + o, o < n ? n - o : 0,
                              " \xE2\x80\xA0 timed once (repetitions runs: 1): one measurement, no median.");
    /* a time: what it was measured on (provenance.h) */
    if (pv->g.src == SRC_COL && cols[pv->g.k].is_ms) {
        char gl[400];
        sl_gl_times_note(pv->renderer, gl, sizeof gl);
        snprintf(out + o, o < n ? n - o : 0, " %s", gl);
    }
}

/* The NON-FINITE note of table.md under a pivot whose cells hold values
 * not finite: their pixels are out of every figure the entries aggregate. */
static void nonfinite_note(struct sl_tab *t, const struct pivot *pv)
{
    if (pv->nf_cells)
        sl_tab_notef(t, "NON-FINITE: %d cell(s) of the table hold %llu value(s) not finite (NaN, \xC2\xB1inf) or "
                        "out of range; their pixels are left out of the figures (a package's verdict there: "
                        "uncertain).",
                     pv->nf_cells, (unsigned long long)pv->nonfinite);
}

/* a key's value for people: map sizes squared */
static void key_plain(enum sl_pivot_key k, const char *v, char *out, size_t n)
{
    snprintf(out, n, k == SL_PK_map_size ? "%s\xC2\xB2" : "%s", v);
}

/* a key's value in a LaTeX table's model: map sizes squared with their
 * thousands split ("1 024²"), a viewport's "x" a times sign */
static void key_cell(enum sl_pivot_key k, const char *v, char *out, size_t n)
{
    if (k == SL_PK_map_size) {
        char num[64];
        sl_tab_number(num, sizeof num, atof(v), 0);
        snprintf(out, n, "%s\xC2\xB2", num);
    } else if (k == SL_PK_viewport) {
        int w = 0, h = 0;
        sscanf(v, "%dx%d", &w, &h);
        snprintf(out, n, "%d\xC3\x97%d", w, h);
    } else
        snprintf(out, n, "%s", v);
}

/* ---- Markdown, CSV, JSON ---- */

/* The reading table (Markdown): the caption as a paragraph above it, the
 * row key's values down the first column (map sizes squared), an entry per
 * column, a dagger on an entry timed once. */
static void read_table(struct sl_tab *t, const struct pivot *pv, const struct sl_pivot_desc *p)
{
    char cap[2048];
    caption_words(pv, p, cap, sizeof cap, 0);
    sl_tab_init(t, "pivot", 1 + pv->nc, 1, "%s", "");
    t->level = 1;   /* no heading: the caption is the intro */
    t->plain = 1;
    sl_tab_intro(t, cap);
    sl_tab_head(t, 0, "%s \\ %s", sl_pivot_key_name(pv->rk), sl_pivot_key_name(pv->ck));
    for (int c = 0; c < pv->nc; c++) {
        char k[KEYLEN + 4];
        key_plain(pv->ck, pv->key[pv->ck].v[pv->cperm[c]], k, sizeof k);
        sl_tab_head(t, 1 + c, "%s", k);
    }
    int dec = decimals(pv, p->agg);
    for (int r = 0; r < pv->nr; r++) {
        char k[KEYLEN + 4];
        key_plain(pv->rk, pv->key[pv->rk].v[pv->rperm[r]], k, sizeof k);
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", k);
        for (int c = 0; c < pv->nc; c++) {
            char v[64];
            plain_number(v, sizeof v, pv->val[pv->rperm[r] * pv->nc + pv->cperm[c]], dec);
            sl_tab_cell(t, 1 + c, "%s%s", v, pv->once[pv->rperm[r] * pv->nc + pv->cperm[c]] ? "\xE2\x80\xA0" : "");
        }
    }
    nonfinite_note(t, pv);
}

/* The data table (CSV): the keys as they are stored, the entries with 10
 * significant digits, an entry with no value empty. */
static void data_table(struct sl_tab *t, const struct pivot *pv)
{
    sl_tab_init(t, "pivot", 1 + pv->nc, 1, "pivot");
    sl_tab_head(t, 0, "%s", sl_pivot_key_name(pv->rk));
    for (int c = 0; c < pv->nc; c++)
        sl_tab_head(t, 1 + c, "%s", pv->key[pv->ck].v[pv->cperm[c]]);
    for (int r = 0; r < pv->nr; r++) {
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%s", pv->key[pv->rk].v[pv->rperm[r]]);
        for (int c = 0; c < pv->nc; c++) {
            double v = pv->val[pv->rperm[r] * pv->nc + pv->cperm[c]];
            if (!isnan(v))
                sl_tab_cell(t, 1 + c, "%.10g", v);
        }
    }
}

/* md or csv through the model; -1 out of memory */
static int write_model(FILE *f, enum sl_table_format fmt, const struct pivot *pv, const struct sl_pivot_desc *p)
{
    struct sl_tab t;
    const struct sl_emit_opts o = {.first = 1};
    if (fmt == SL_TABLE_CSV)
        data_table(&t, pv);
    else
        read_table(&t, pv, p);
    int k = (fmt == SL_TABLE_CSV ? sl_emit_csv : sl_emit_md)(f, &t, &o);
    sl_tab_free(&t);
    return k;
}

/* JSON keeps its own schema (the figure, its unit, the aggregate, the keys
 * and the where, then per row the values, the counts and which were timed
 * once): scripts read it. */
static void write_json(FILE *f, const struct pivot *pv, const struct sl_pivot_desc *p)
{
    fputs("{\"figure\": ", f);
    sl_emit_json_text(f, p->figure ? p->figure : "wrong");
    fputs(", \"unit\": ", f);
    sl_emit_json_text(f, pv->g.unit);
    fprintf(f, ", \"agg\": \"%s\", \"rows\": \"%s\", \"cols\": \"%s\", \"where\": {", agg_names[p->agg],
            sl_pivot_key_name(pv->rk), sl_pivot_key_name(pv->ck));
    int nw = 0;
    if (pv->region_default && pv->g.src == SRC_HARD)
        fprintf(f, "\"region\": \"image\""), nw++;
    for (int w = 0; w < p->nwhere; w++, nw++) {
        fprintf(f, "%s\"%s\": ", nw ? ", " : "", sl_pivot_key_name(p->where[w].key));
        sl_emit_json_text(f, p->where[w].value);
    }
    fputs("},\n \"columns\": [", f);
    for (int c = 0; c < pv->nc; c++) {
        if (c)
            fputs(", ", f);
        sl_emit_json_text(f, pv->key[pv->ck].v[pv->cperm[c]]);
    }
    fputs("],\n \"table\": [", f);
    for (int r = 0; r < pv->nr; r++) {
        fputs(r ? ",\n  {\"row\": " : "\n  {\"row\": ", f);
        sl_emit_json_text(f, pv->key[pv->rk].v[pv->rperm[r]]);
        fputs(", \"values\": [", f);
        for (int c = 0; c < pv->nc; c++) {
            double v = pv->val[pv->rperm[r] * pv->nc + pv->cperm[c]];
            if (isnan(v))
                fprintf(f, "%snull", c ? ", " : "");
            else
                fprintf(f, "%s%.17g", c ? ", " : "", v);
        }
        fputs("], \"n\": [", f);
        for (int c = 0; c < pv->nc; c++)
            fprintf(f, "%s%d", c ? ", " : "", pv->cnt[pv->rperm[r] * pv->nc + pv->cperm[c]]);
        /* a time: which entries hold a cell timed once (repetitions runs: 1) */
        if (pv->any_once) {
            fputs("], \"timed_once\": [", f);
            for (int c = 0; c < pv->nc; c++)
                fprintf(f, "%s%s", c ? ", " : "", pv->once[pv->rperm[r] * pv->nc + pv->cperm[c]] ? "true" : "false");
        }
        fputs("]}", f);
    }
    fputs("\n]}\n", f);
}

/* ---- LaTeX ---- */

/* One orientation of the table: rows x cols of entry (i, j) of the pivot. */
struct view {
    const struct pivot *pv;
    int                 t;          /* transposed */
    enum sl_pivot_key   rk, ck;
    int                 nr, nc;
};

static struct view view_of(const struct pivot *pv, int t)
{
    struct view v = {pv, t, t ? pv->ck : pv->rk, t ? pv->rk : pv->ck, t ? pv->nc : pv->nr, t ? pv->nr : pv->nc};
    return v;
}
/* A key's text in LaTeX: a label's display name (`display:` in the config,
 * else its method's own), every other key's value. */
static const char *tex_key_text(const struct pivot *pv, enum sl_pivot_key k, int i)
{
    return k == SL_PK_label && pv->ldisp && pv->ldisp[i][0] ? pv->ldisp[i] : pv->key[k].v[i];
}
static const char *view_rkey(const struct view *v, int r)
{
    const struct pivot *pv = v->pv;
    return v->t ? tex_key_text(pv, pv->ck, pv->cperm[r]) : tex_key_text(pv, pv->rk, pv->rperm[r]);
}
static const char *view_ckey(const struct view *v, int c)
{
    const struct pivot *pv = v->pv;
    return v->t ? tex_key_text(pv, pv->rk, pv->rperm[c]) : tex_key_text(pv, pv->ck, pv->cperm[c]);
}
static double view_val(const struct view *v, int r, int c)
{
    const struct pivot *pv = v->pv;
    int pr = v->t ? pv->rperm[c] : pv->rperm[r], pc = v->t ? pv->cperm[r] : pv->cperm[c];
    return pv->val[pr * pv->nc + pc];
}
static int view_once(const struct view *v, int r, int c)
{
    const struct pivot *pv = v->pv;
    int pr = v->t ? pv->rperm[c] : pv->rperm[r], pc = v->t ? pv->cperm[r] : pv->cperm[c];
    return pv->once[pr * pv->nc + pc];
}

static double rowname_pt(const struct view *v)
{
    double w = text_pt(key_head(v->rk));
    for (int r = 0; r < v->nr; r++) {
        char k[KEYLEN + 4];
        key_plain(v->rk, view_rkey(v, r), k, sizeof k);
        double x = text_pt(k);
        w = x > w ? x : w;
    }
    return w > TEX_LABELMAX ? TEX_LABELMAX : w;
}

static double col_pt(const struct view *v, int c, int dec)
{
    char k[KEYLEN + 4];
    key_plain(v->ck, view_ckey(v, c), k, sizeof k);
    double w = text_pt(k);
    for (int r = 0; r < v->nr; r++) {
        char s[64];
        double x = view_val(v, r, c);
        plain_number(s, sizeof s, x, sl_tab_sig_decimals(x, dec));
        x = number_pt(s) + (view_once(v, r, c) ? 4.0 : 0.0);   /* the dagger */
        w = x > w ? x : w;
    }
    return w;
}

/* Columns [c0, c1) with the row names fit the budget? */
static int fits(const struct view *v, int c0, int c1, int dec)
{
    if (c1 - c0 > TEX_MAXNUM)
        return 0;
    double w = rowname_pt(v) + TEX_COLSEP, heads = 0;
    for (int c = c0; c < c1; c++) {
        double x = col_pt(v, c, dec) + TEX_COLSEP;
        w += x;
        heads += x;
    }
    /* the spanning heading is no wider than the columns under it */
    double span = text_pt(key_head(v->ck)) + TEX_COLSEP;
    if (span > heads)
        w += span - heads;
    return w <= TEX_BUDGET;
}

/* The \label of a pivot: its study (when it has one), figure, base, aggregate,
 * rows, columns and every --where, so two pivots of one document never share
 * one; the parts that are the defaults (the figure's own base, the mean)
 * are left out. */
static void pivot_id(const struct pivot *pv, const struct sl_pivot_desc *p, char *id, size_t n)
{
    snprintf(id, n, "pivot-");
    if (pv->studies[0] && !strstr(pv->studies, " and ")) {
        label_key(id, n, pv->studies);
        label_key(id, n, "-");
    }
    label_key(id, n, p->figure ? p->figure : "wrong");
    if (p->of) {
        label_key(id, n, "-of-");
        label_key(id, n, p->of);
    }
    if (p->agg != SL_AGG_MEAN) {
        label_key(id, n, "-");
        label_key(id, n, agg_names[p->agg]);
    }
    label_key(id, n, "-");
    label_key(id, n, sl_pivot_key_name(pv->rk));
    label_key(id, n, "-by-");
    label_key(id, n, sl_pivot_key_name(pv->ck));
    for (int w = 0; w < p->nwhere; w++) {
        label_key(id, n, "-");
        label_key(id, n, sl_pivot_key_name(p->where[w].key));
        label_key(id, n, "-");
        label_key(id, n, p->where[w].value);
    }
}

/* every entry that has a value is 0 (and one has) */
static int all_zero(const struct pivot *pv)
{
    int any = 0;
    for (int i = 0; i < pv->nr * pv->nc; i++) {
        if (isnan(pv->val[i]))
            continue;
        if (pv->val[i] != 0.0)
            return 0;
        any = 1;
    }
    return any;
}

/* One table of columns [c0, c1) in the model: a float, or (rows more than
 * a page holds) a float per page, the heads on each; the column key's name
 * spans the columns, a long row name is wrapped. */
static int tex_part(FILE *f, const struct view *v, const struct sl_pivot_desc *p, const char *cap, int c0,
                    int c1, int part, int parts, int dec)
{
    const struct pivot *pv = v->pv;
    char id[256] = "";
    if (p->tex_label)
        label_key(id, sizeof id, p->tex_label);
    else
        pivot_id(pv, p, id, sizeof id);
    if (parts > 1)
        snprintf(id + strlen(id), sizeof id - strlen(id), "-%d", part + 1);
    struct sl_tab t;
    if (parts > 1)
        sl_tab_init(&t, id, 1 + c1 - c0, 1, "%s (Part %d of %d.)", cap, part + 1, parts);
    else
        sl_tab_init(&t, id, 1 + c1 - c0, 1, "%s", cap);
    t.small = 1;
    t.paged = 1;   /* rows more than a page holds: a float per page (emit_tex.c) */
    if (v->rk != SL_PK_map_size && v->rk != SL_PK_viewport)
        t.fold[0] = TEX_LABELMAX;
    sl_tab_group(&t, 1, "%s", "");
    sl_tab_group(&t, c1 - c0, "%s", key_head(v->ck));
    sl_tab_head(&t, 0, "%s", key_head(v->rk));
    char k[KEYLEN + 16];
    for (int c = c0; c < c1; c++) {
        key_cell(v->ck, view_ckey(v, c), k, sizeof k);
        sl_tab_head(&t, 1 + c - c0, "%s", k);
    }
    for (int r = 0; r < v->nr; r++) {
        sl_tab_row(&t, 0);
        key_cell(v->rk, view_rkey(v, r), k, sizeof k);
        sl_tab_cell(&t, 0, "%s", k);
        for (int c = c0; c < c1; c++) {
            char s[96];
            sl_tab_sig(s, sizeof s, view_val(v, r, c), dec);
            sl_tab_cell(&t, 1 + c - c0, "%s%s", s, view_once(v, r, c) ? "\xE2\x80\xA0" : "");
        }
    }
    if (part == parts - 1)
        nonfinite_note(&t, pv);
    const struct sl_emit_opts o = {.blank = 1};
    int e = sl_emit_tex(f, &t, &o) < 0 ? -1 : 0;
    sl_tab_free(&t);
    return e;
}

static int write_tex(FILE *f, const struct pivot *pv, const struct sl_pivot_desc *p, struct sl_pivot_info *info)
{
    int dec = decimals(pv, p->agg);
    char cap[2048];
    /* a table of zeros says one thing: a sentence says it (issue 47) */
    if (all_zero(pv)) {
        char id[256] = "";
        if (p->tex_label)
            label_key(id, sizeof id, p->tex_label);
        else
            pivot_id(pv, p, id, sizeof id);
        caption_words(pv, p, cap, sizeof cap, 1);
        fprintf(f, "%% %s: every entry is 0, a sentence instead of a table\n\\par\\noindent ", id);
        sl_tex_text(f, cap);
        fputs("\\par\n\n", f);
        info->zero = 1;
        return 0;
    }
    caption_words(pv, p, cap, sizeof cap, 0);
    struct view v = view_of(pv, 0);
    if (!fits(&v, 0, v.nc, dec)) {
        struct view t = view_of(pv, 1);
        if (fits(&t, 0, t.nc, dec)) {
            v = t;
            info->transposed = 1;
        }
    }
    /* parts: greedy runs of columns that fit, at least one column each */
    int *starts = malloc(((size_t)v.nc + 1) * sizeof *starts), parts = 0;
    if (!starts)
        return -1;
    for (int c = 0; c < v.nc;) {
        int e = c + 1;
        while (e < v.nc && fits(&v, c, e + 1, dec))
            e++;
        starts[parts++] = c;
        c = e;
    }
    starts[parts] = v.nc;
    char line[256];
    if (parts > 1)
        snprintf(line, sizeof line, "%d columns do not fit \\columnwidth: split into %d tables", v.nc, parts);
    else if (info->transposed)
        snprintf(line, sizeof line, "%s as columns did not fit \\columnwidth: transposed", sl_pivot_key_name(pv->ck));
    if (parts > 1 || info->transposed)
        sl_emit_tex_comment(f, line, 0);
    int e = 0;
    for (int k = 0; k < parts && !e; k++)
        e = tex_part(f, &v, p, cap, starts[k], starts[k + 1], k, parts, dec);
    info->parts = parts;
    free(starts);
    return e;
}

enum sl_err sl_pivot_write(FILE *out, enum sl_table_format fmt, const struct sl_cell_record *cells, int ncells,
                           const struct sl_pivot_desc *p, struct sl_pivot_info *info, struct sl_diag *d)
{
    struct sl_pivot_info none;
    if (!info)
        info = &none;
    memset(info, 0, sizeof *info);
    if (!out || !p || ncells < 0 || (ncells && !cells))
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_pivot_write: bad arguments");
    if ((unsigned)p->agg > SL_AGG_MAX || (unsigned)p->rows >= SL_PK_COUNT || (unsigned)p->cols >= SL_PK_COUNT)
        return sl_fail(d, SL_E_USAGE, NULL, 0, NULL, "sl_pivot_write: bad description");
    struct pivot pv;
    enum sl_err e = pivot_build(cells, ncells, p, &pv, d);
    if (e)
        return e;
    info->nrows = pv.nr;
    info->ncols = pv.nc;
    switch (fmt) {
    case SL_TABLE_MD:
    case SL_TABLE_CSV:
        if (write_model(out, fmt, &pv, p) < 0)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "pivot of %d columns", pv.nc);
        info->parts = pv.nr > 0;
        break;
    case SL_TABLE_JSON: write_json(out, &pv, p); info->parts = pv.nr > 0; break;
    case SL_TABLE_LATEX:
        if (pv.nr > 0 && write_tex(out, &pv, p, info) != 0)
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "pivot of %d columns", pv.nc);
        break;
    default: e = sl_fail(d, SL_E_USAGE, NULL, 0, "--format", "a pivot is md, csv, latex or json");
    }
    pivot_free(&pv);
    if (!e && (ferror(out) || fflush(out) != 0))
        e = sl_fail(d, SL_E_IO, NULL, 0, NULL, "writing the table failed");
    return e;
}

/* ---- the run's LaTeX ---- */

/* s with its line breaks as spaces, appended to out: a comment is one line */
static void one_line(char *out, size_t n, const char *s)
{
    size_t o = strlen(out);
    for (; *s && o + 1 < n; s++)
        out[o++] = *s == '\n' || *s == '\r' ? ' ' : *s;
    out[o] = '\0';
}

/* provenance as comments: each distinct git SHA, config hash and machine;
 * a blank line after them */
static void tex_head(FILE *f, const char *what, const char *title, const struct sl_cell_record *cells, int n)
{
    char line[1200];
    snprintf(line, sizeof line, "shadowlab %s; needs \\usepackage{booktabs}; table* floats: a one- or two-column "
             "class takes them", what);
    sl_emit_tex_comment(f, line, 0);
    if (title) {
        snprintf(line, sizeof line, "from: ");
        one_line(line, sizeof line, title);
        sl_emit_tex_comment(f, line, 0);
    }
    for (int i = 0; i < n; i++) {
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = !strcmp(cells[i].git_sha, cells[j].git_sha) && !strcmp(cells[i].config_hash, cells[j].config_hash) &&
                   !strcmp(cells[i].machine, cells[j].machine);
        if (seen)
            continue;
        snprintf(line, sizeof line, "git ");
        one_line(line, sizeof line, cells[i].git_sha);
        snprintf(line + strlen(line), sizeof line - strlen(line), ", config %s, machine ", cells[i].config_hash);
        one_line(line, sizeof line, cells[i].machine);
        sl_emit_tex_comment(f, line, 0);
    }
    fputc('\n', f);
}

enum sl_err sl_pivot_tex_summary(FILE *out, const char *title, const struct sl_cell_record *cells, int ncells,
                                 struct sl_diag *d)
{
    tex_head(out, "summary tables (table-detail.tex has every view)", title, cells, ncells);
    /* one study at a time: the store may hold several */
    enum sl_err e = SL_OK;
    for (int i = 0; i < ncells && !e; i++) {
        int seen = 0;
        for (int j = 0; j < i && !seen; j++)
            seen = !strcmp(cells[i].study, cells[j].study);
        if (seen)
            continue;
        const char *study = cells[i].study;
        int nscenes = 0, soft = 0;
        for (int j = 0; j < ncells; j++) {
            if (strcmp(cells[j].study, study))
                continue;
            soft |= cells[j].has_soft;
            int dup = 0;
            for (int k = 0; k < j && !dup; k++)
                dup = !strcmp(cells[k].study, study) && !strcmp(cells[k].scene, cells[j].scene);
            nscenes += !dup;
        }
        static const struct {
            const char *figure;
            enum sl_pivot_key cols;
            int soft, scenes;
        } tabs[] = {
            {"wrong", SL_PK_map_size, 0, 0},   {"uncertain", SL_PK_map_size, 0, 0},
            {"ms_cost", SL_PK_map_size, 0, 0}, {"soft_mae", SL_PK_map_size, 1, 0},
            {"wrong", SL_PK_scene, 0, 1},
        };
        char key[160];
        for (size_t t = 0; t < sizeof tabs / sizeof tabs[0] && !e; t++) {
            if ((tabs[t].soft && !soft) || (tabs[t].scenes && nscenes < 2))
                continue;
            snprintf(key, sizeof key, "%s-%s-%s", study, tabs[t].figure, sl_pivot_key_name(tabs[t].cols));
            struct sl_pivot_desc p = {.rows = SL_PK_label, .cols = tabs[t].cols, .figure = tabs[t].figure,
                                      .tex_label = key};
            /* the study's cells only: a where on a field that is not a key */
            struct sl_cell_record *sub = malloc((size_t)ncells * sizeof *sub);
            if (!sub)
                return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "summary tables");
            int k = 0;
            for (int j = 0; j < ncells; j++)
                if (!strcmp(cells[j].study, study))
                    sub[k++] = cells[j];
            e = sl_pivot_write(out, SL_TABLE_LATEX, sub, k, &p, NULL, d);
            free(sub);
        }
    }
    if (!e && (ferror(out) || fflush(out) != 0))
        e = sl_fail(d, SL_E_IO, NULL, 0, NULL, "writing the tables failed");
    return e;
}

/* ---- the per-view detail ---- */

static int same_view(const struct sl_cell_record *a, const struct sl_cell_record *b)
{
    return a->vw == b->vw && a->vh == b->vh && !strcmp(a->scene, b->scene) && !strcmp(a->viewpoint, b->viewpoint) &&
           !strcmp(a->study, b->study);
}

/* one column of a detail table: heading, the value of a cell and the
 * caption's words for it */
struct dcol {
    char   head[48];           /* plain; escaped when written */
    int    dec;
    double (*get)(const struct sl_cell_record *c, int arg);
    int    arg;
    int    what;               /* its caption group: 0 none (the map size), 1 the pixels' classes in %, 2 a
                                * count, 3 the time, 4 a contour's share, 5 an area light's figures */
    char   word[48];           /* its words in the group's phrase ("in light", "2") */
};

static int image_region(const struct sl_cell_record *c)
{
    for (int r = 0; r < c->fig.nregions; r++)
        if (c->fig.r[r].thickness == 0)
            return r;
    return c->fig.nregions - 1;
}
static double get_pct(const struct sl_cell_record *c, int k) { return c->fig.r[image_region(c)].pct[k]; }
static double get_n(const struct sl_cell_record *c, int k) { return (double)c->fig.r[image_region(c)].n[k]; }
static double get_caught(const struct sl_cell_record *c, int t)
{
    for (int r = 0; r < c->fig.nregions; r++)
        if (c->fig.r[r].thickness == t)
            return c->fig.r[r].pct[SL_FIG_wrong_caught];
    return NAN;
}
static double get_soft(const struct sl_cell_record *c, int k) { return c->soft.pct[k]; }
static double get_ms(const struct sl_cell_record *c, int k) { (void)k; return c->ms_method; }
static double get_map(const struct sl_cell_record *c, int k) { (void)k; return c->map_size; }

static double dcol_pt(const struct dcol *col, const struct sl_cell_record *cells, const int *idx, int n)
{
    double w = text_pt(col->head);
    for (int i = 0; i < n; i++) {
        char s[64];
        double v = col->get(&cells[idx[i]], col->arg);
        plain_number(s, sizeof s, v, sl_tab_sig_decimals(v, col->dec));
        double x = number_pt(s) + (col->get == get_ms && cells[idx[i]].runs == 1 ? 4.0 : 0.0);
        w = x > w ? x : w;
    }
    return w;
}

/* "a", "a and b", "a, b and c" of the words of group g's columns, appended */
static size_t dcol_words(const struct dcol *dc, int nc, int g, char *out, size_t n)
{
    int k = 0, m = 0;
    for (int c = 0; c < nc; c++)
        m += dc[c].what == g;
    size_t o = strlen(out);
    for (int c = 0; c < nc; c++)
        if (dc[c].what == g) {
            o += (size_t)snprintf(out + o, o < n ? n - o : 0, "%s%s", k == 0 ? "" : k == m - 1 ? " and " : ", ",
                                  dc[c].word);
            k++;
        }
    return o;
}

/* The caption of a detail table: the view in words, then what each of its
 * columns holds (only the columns of this part), the light, the study. */
static void detail_caption(const struct sl_cell_record *v, const struct dcol *dc, int nc, const char *soft,
                           char *cap, size_t n)
{
    size_t o = (size_t)snprintf(cap, n, "Scene %s, viewpoint %s, viewport %d\xC3\x97%d", v->scene, v->viewpoint,
                                v->vw, v->vh);
    if (v->light[0])
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, ", %s", v->light);
    o += (size_t)snprintf(cap + o, o < n ? n - o : 0, ", per method and shadow-map size");
    int has[6] = {0};
    for (int c = 0; c < nc; c++)
        has[dc[c].what] = 1;
    const char *sep = ": ";
    if (has[2]) {
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, "%sthe wrong pixels as a count", sep);
        sep = "; ";
    }
    if (has[1]) {
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, "%sthe pixels ", sep);
        o = dcol_words(dc, nc, 1, cap, n);
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, " (%% of the image's pixels, background excluded)");
        sep = "; ";
    }
    if (has[4]) {
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, "%sthe share of the image's wrong pixels inside the ", sep);
        o = dcol_words(dc, nc, 4, cap, n);
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, " px contours (%%)");
        sep = "; ";
    }
    if (has[5]) {
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, "%s%s", sep, soft);
        sep = "; ";
    }
    if (has[3])
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0,
                              "%sthe time of the method's per-pixel step (ms, the median over its timed runs; "
                              "\xE2\x80\xA0: timed once, no median)", sep);
    if (v->study[0])
        o += (size_t)snprintf(cap + o, o < n ? n - o : 0, " (study %s)", v->study);
    snprintf(cap + o, o < n ? n - o : 0, ".");
}

/* A table of the view's cells idx[0..n) over columns dc[0..nc) (the
 * method's name first, implicit); its caption names what its columns hold.
 * A long name is wrapped; rows more than a page holds, a float per page.
 * Returns the floats it took since its last \clearpage, -1 out of memory. */
static int detail_table(FILE *f, const struct sl_cell_record *cells, const int *idx, int n, const struct dcol *dc,
                        int nc, const char *soft, const char *kind, int part, int clear)
{
    const struct sl_cell_record *v = &cells[idx[0]];
    char cap[1536];
    detail_caption(v, dc, nc, soft, cap, sizeof cap);
    char id[256] = "detail-";
    label_key(id, sizeof id, v->study);
    label_key(id, sizeof id, "-");
    label_key(id, sizeof id, v->scene);
    label_key(id, sizeof id, "-");
    label_key(id, sizeof id, v->viewpoint);
    snprintf(id + strlen(id), sizeof id - strlen(id), "-%dx%d-%s-%d", v->vw, v->vh, kind, part + 1);
    struct sl_tab t;
    sl_tab_init(&t, id, 1 + nc, 1, "%s", cap);
    t.small = 1;
    t.paged = 1;
    t.fold[0] = TEX_LABELMAX;
    sl_tab_head(&t, 0, "method");
    for (int c = 0; c < nc; c++)
        sl_tab_head(&t, 1 + c, "%s", dc[c].head);
    for (int i = 0; i < n; i++) {
        const struct sl_cell_record *c = &cells[idx[i]];
        sl_tab_row(&t, 0);
        sl_tab_cell(&t, 0, "%s", c->display[0] ? c->display : c->label);
        for (int k = 0; k < nc; k++) {
            char s[96];
            if (dc[k].get == get_map)
                snprintf(s, sizeof s, "%d\xC2\xB2", c->map_size);
            else
                sl_tab_sig(s, sizeof s, dc[k].get(c, dc[k].arg), dc[k].dec);
            sl_tab_cell(&t, 1 + k, "%s%s", s, dc[k].get == get_ms && c->runs == 1 ? "\xE2\x80\xA0" : "");
        }
    }
    t.squares = 1;
    const struct sl_emit_opts eo = {.clear = clear, .blank = 1};
    int e = sl_emit_tex(f, &t, &eo);
    sl_tab_free(&t);
    return e;
}

/* The columns in parts that each fit beside the name, as even as the
 * widest part allows (greedy cuts left a part of one column: 4 + 4 + 1
 * became 3 + 3 + 3); the first nkeep (the map size) repeat in every part.
 * *floats: floats since the last \clearpage (one is written before a table
 * when 6 or more are pending: LaTeX holds at most 18). */
static int detail_tables(FILE *f, const struct sl_cell_record *cells, const int *idx, int n, const struct dcol *dc,
                         int ndc, int nkeep, const char *soft, const char *kind, int *floats)
{
    double lw = text_pt("method");
    for (int i = 0; i < n; i++) {
        double x = text_pt(cells[idx[i]].display[0] ? cells[idx[i]].display : cells[idx[i]].label);
        lw = x > lw ? x : lw;
    }
    if (lw > TEX_LABELMAX)
        lw = TEX_LABELMAX;
    double keep = lw + TEX_COLSEP, w[SL_MAX_REGIONS + 16];
    for (int c = 0; c < nkeep; c++)
        keep += dcol_pt(&dc[c], cells, idx, n) + TEX_COLSEP;
    for (int c = nkeep; c < ndc; c++)
        w[c] = dcol_pt(&dc[c], cells, idx, n) + TEX_COLSEP;
    /* the fewest parts greedy cuts take, then the fewest columns a part
     * with which every part still fits */
    int parts = 0;
    for (int c = nkeep; c < ndc; parts++) {
        double x = keep;
        int e = c;
        while (e < ndc && (e == c || x + w[e] <= TEX_BUDGET))
            x += w[e++];
        c = e;
    }
    int per = parts ? (ndc - nkeep + parts - 1) / parts : 1, cut[SL_MAX_REGIONS + 17], ncut;
    for (;; per++) {
        ncut = 0;
        int ok = 1;
        for (int c = nkeep; c < ndc;) {
            int e = c + per < ndc ? c + per : ndc;
            double x = keep;
            for (int k = c; k < e; k++)
                x += w[k];
            ok &= x <= TEX_BUDGET || e - c == 1;
            cut[ncut++] = c;
            c = e;
        }
        cut[ncut] = ndc;
        if (ok || per >= ndc - nkeep)
            break;
    }
    int err = 0;
    for (int p = 0; p < ncut && !err; p++) {
        struct dcol sel[SL_MAX_REGIONS + 16];
        int ns = 0;
        for (int k = 0; k < nkeep; k++)
            sel[ns++] = dc[k];
        for (int k = cut[p]; k < cut[p + 1]; k++)
            sel[ns++] = dc[k];
        int clear = *floats >= 6;
        int k = detail_table(f, cells, idx, n, sel, ns, soft, kind, p, clear);
        err = k < 0;
        *floats = clear ? k : *floats + k;
    }
    return err ? -1 : 0;
}

/* -1: out of memory */
static int detail_view(FILE *f, const struct sl_cell_record *cells, const int *idx, int n, int *floats)
{
    /* the hard cells, then the area light's */
    int *h = malloc((size_t)n * sizeof *h), *s = malloc((size_t)n * sizeof *s), err = 0;
    if (!h || !s) {
        free(h), free(s);
        return -1;
    }
    int nh = 0, ns = 0;
    for (int i = 0; i < n; i++) {
        if (cells[idx[i]].fig.nregions > 0)
            h[nh++] = idx[i];
        if (cells[idx[i]].has_soft)
            s[ns++] = idx[i];
    }
    if (nh) {
        struct dcol dc[SL_MAX_REGIONS + 16];
        int k = 0;
        dc[k++] = (struct dcol){"map", 0, get_map, 0, 0, ""};
        /* the wrong pixels first, the count beside its percentage: a split
         * by columns keeps them in one table */
        dc[k++] = (struct dcol){"wrong", 0, get_n, SL_FIG_wrong, 2, ""};
        dc[k++] = (struct dcol){"wrong %", 2, get_pct, SL_FIG_wrong, 1, "wrong"};
        dc[k++] = (struct dcol){"light %", 2, get_pct, SL_FIG_light, 1, "in light"};
        dc[k++] = (struct dcol){"shadow %", 2, get_pct, SL_FIG_shadow, 1, "in shadow"};
        dc[k++] = (struct dcol){"undecided %", 2, get_pct, SL_FIG_uncertain, 1, "left undecided"};
        dc[k++] = (struct dcol){"step ms", 2, get_ms, 0, 3, ""};
        const struct sl_cell_record *c0 = &cells[h[0]];
        for (int r = 0; r < c0->fig.nregions; r++) {
            if (!c0->fig.r[r].thickness)
                continue;
            dc[k] = (struct dcol){"", 2, get_caught, c0->fig.r[r].thickness, 4, ""};
            snprintf(dc[k].head, sizeof dc[k].head, "in %dpx %%", c0->fig.r[r].thickness);
            snprintf(dc[k].word, sizeof dc[k].word, "%d", c0->fig.r[r].thickness);
            k++;
        }
        err = detail_tables(f, cells, h, nh, dc, k, 1, "", "hard", floats);
    }
    if (ns && !err) {
        /* the light the truth was computed for (a view has one); under a
         * hard light the classes take softfig.h's tolerance */
        const struct sl_cell_record *c0 = &cells[s[0]];
        char light[400];
        if (c0->frac)
            snprintf(light, sizeof light,
                     "the visibility against its 0/1 truth over the PFL pixels (MAE, RMSE, bias in %% of "
                     "full visibility; pixels within 0.05 and classed right, lit or umbra within "
                     "\xCE\xB5 = %.2f of 1 or 0, in %% of the pixels)", (double)SL_SOFT_HARD_TOL);
        else
            snprintf(light, sizeof light, "%s",
                     "the visible fraction against the area truth (MAE, RMSE, bias in % of full "
                     "visibility; pixels within 0.05 and classed right in % of the pixels)");
        struct dcol dc[8];
        int k = 0;
        dc[k++] = (struct dcol){"map", 0, get_map, 0, 0, ""};
        dc[k++] = (struct dcol){"MAE %", 3, get_soft, SL_SFIG_soft_mae, 5, ""};
        dc[k++] = (struct dcol){"RMSE %", 3, get_soft, SL_SFIG_soft_rmse, 5, ""};
        dc[k++] = (struct dcol){"bias %", 3, get_soft, SL_SFIG_soft_bias, 5, ""};
        dc[k++] = (struct dcol){"within 0.05 %", 2, get_soft, SL_SFIG_soft_within_005, 5, ""};
        dc[k++] = (struct dcol){"class right %", 2, get_soft, SL_SFIG_soft_class_right, 5, ""};
        dc[k++] = (struct dcol){"step ms", 2, get_ms, 0, 3, ""};
        err = detail_tables(f, cells, s, ns, dc, k, 1, light, "soft", floats);
    }
    free(h), free(s);
    return err;
}

enum sl_err sl_pivot_tex_detail(FILE *out, const char *title, const struct sl_cell_record *cells, int ncells,
                                struct sl_diag *d)
{
    tex_head(out, "detail tables, a float (or one a page) per view and group of columns", title, cells, ncells);
    int floats = 0;
    int *idx = malloc((size_t)(ncells ? ncells : 1) * sizeof *idx);
    char *done = calloc((size_t)(ncells ? ncells : 1), 1);
    if (!idx || !done) {
        free(idx), free(done);
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "detail tables");
    }
    for (int i = 0; i < ncells; i++) {
        if (done[i])
            continue;
        /* the view's cells: labels in order of appearance, map sizes ascending */
        int n = 0;
        for (int j = i; j < ncells; j++)
            if (!done[j] && same_view(&cells[i], &cells[j])) {
                int lab = -1;
                for (int k = 0; k < n && lab < 0; k++)
                    if (!strcmp(cells[idx[k]].label, cells[j].label))
                        lab = k;
                int at = n;
                if (lab >= 0) {
                    at = lab;
                    while (at < n && !strcmp(cells[idx[at]].label, cells[j].label) &&
                           cells[idx[at]].map_size <= cells[j].map_size)
                        at++;
                }
                memmove(idx + at + 1, idx + at, (size_t)(n - at) * sizeof *idx);
                idx[at] = j;
                n++;
                done[j] = 1;
            }
        if (detail_view(out, cells, idx, n, &floats) < 0) {
            free(idx), free(done);
            return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "detail tables");
        }
    }
    free(idx), free(done);
    if (ferror(out) || fflush(out) != 0)
        return sl_fail(d, SL_E_IO, NULL, 0, NULL, "writing the detail tables failed");
    return SL_OK;
}
