/*
 * outputs.c — see outputs.h.
 *
 * Every file is written from the cells in memory in sweep order; the tables
 * and the store get the same record of a cell (sl_out_record), so table.md
 * and `shadowlab table` on the store can never disagree. costs.csv is
 * generated from the column list of cellcols.h: its header and its rows
 * cannot drift apart.
 *
 * A staging folder is claimed by its run for the run's life: an flock on
 * its lock file SL_OUT_CLAIM, taken before the folder gets its .partial
 * name. Whoever would carry or delete another run's staging folder takes
 * that lock first (LOCK_NB): held means the run is alive. A process id
 * cannot say so (a dead run's pid may be reused, a killed one not yet
 * reaped), a lock dies with its holder.
 */
#define _GNU_SOURCE   /* O_CLOEXEC, O_NOFOLLOW, flock */
#include "outputs.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <string.h>
#include "util.h"
#include "emit.h"

static void machine_of(const struct sl_provenance *p, char *out, size_t n)
{
    snprintf(out, n, "%s/%s/%s", p->host, p->cpu, p->isa);
}

/* A cell's file name from its key: "scene-viewpoint-WxH-map-label.ext" (the
 * scene's own name, as the cell's record keeps it). */
static void key_file_name(const struct sl_config *c, const struct sl_cell_key *k, const char *ext, char *out,
                          size_t n)
{
    const struct sl_config_scene *cs = &c->scenes[k->scene];
    snprintf(out, n, "%s-%s-%dx%d-%d-%s.%s", cs->name, cs->viewpoints[k->vp], c->viewport_w[k->viewport],
             c->viewport_h[k->viewport], c->maps[k->map], c->methods[k->method].label, ext);
}

void sl_out_overlay_name(const struct sl_config *c, const struct sl_cell *cl, char *out, size_t n)
{
    key_file_name(c, &cl->key, "png", out, n);
}

void sl_out_exr_name(const struct sl_config *c, const struct sl_cell *cl, char *out, size_t n)
{
    key_file_name(c, &cl->key, "exr", out, n);
}

/* The record's columns come from the list (cellcols.h, its `from`); the
 * figures, the study and the config hash are the record's own, not columns. */
void sl_out_record(const struct sl_config *c, const struct sl_cell *cl, struct sl_cell_record *r)
{
    const struct sl_config_method *cm = &c->methods[cl->key.method];
    const struct sl_cell_key *k = &cl->key;
    const struct sl_stage_ms *s = &cl->ms;
    memset(r, 0, sizeof *r);
#define SL_FROM_text(name, from)     snprintf(r->name, sizeof r->name, "%s", from);
#define SL_FROM_path(name, from)
#define SL_FROM_dim(name, from)      r->name = from;
#define SL_FROM_index(name, from)    r->name = from;
#define SL_FROM_runs(name, from)     r->name = from;
#define SL_FROM_count(name, from)    r->name = from;
#define SL_FROM_ms(name, from)       r->name = from;
#define SL_FROM_viewport(name, from)
#define SL_FROM_wrong(name, from)
#define SL_FROM_flag(name, from)     r->name = from;
#define SL_FROM(name, kind, size, csv, head, check, key, from) SL_FROM_##kind(name, from)
    SL_CELL_COLUMNS(SL_FROM)
#undef SL_FROM
    r->fig = cl->fig;
    r->has_soft = cl->has_soft;
    r->soft = cl->soft;
    r->has_alias = cl->has_alias;
    r->alias = cl->alias;
    snprintf(r->study, sizeof r->study, "%s", c->name);
    snprintf(r->config_hash, sizeof r->config_hash, "%016llx", c->hash);
}

static void table_cells_of(const struct sl_config *c, const struct sl_run_result *res,
                           struct sl_cell_record *tc)
{
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        struct sl_cell_record *t = &tc[i];
        sl_out_record(c, cl, t);
        if (c->overlays) {
            char name[400];
            sl_out_overlay_name(c, cl, name, sizeof name);
            snprintf(t->overlay, sizeof t->overlay, "overlays/%s", name);
        }
        snprintf(t->git_sha, sizeof t->git_sha, "%s", res->prov.git_sha);
        machine_of(&res->prov, t->machine, sizeof t->machine);
        snprintf(t->gl_renderer, sizeof t->gl_renderer, "%s", res->prov.gl_renderer);
    }
}

static enum sl_err write_tables(FILE *f, enum sl_table_format fmt, const struct sl_config *c,
                                const struct sl_run_result *res, const struct sl_table_rows *rows,
                                struct sl_diag *d)
{
    struct sl_cell_record *tc = sl_calloc((size_t)(res->ncells ? res->ncells : 1), sizeof *tc);
    if (!tc)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "table cells");
    table_cells_of(c, res, tc);
    char title[256];
    snprintf(title, sizeof title, "shadowlab: %s", c->name);
    enum sl_err e = rows ? sl_table_write_rows(f, fmt, title, tc, res->ncells, rows, d)
                         : sl_table_write(f, fmt, title, tc, res->ncells, d);
    free(tc);
    return e;
}

enum sl_err sl_out_write_tables(FILE *f, enum sl_table_format fmt, const struct sl_config *c,
                                const struct sl_run_result *res, struct sl_diag *d)
{
    return write_tables(f, fmt, c, res, NULL, d);
}

/* The terminal gets only the figures each method produces (about 20 rows of
 * NSM's are 0: hints, confirmations, changes against itself); table.md keeps
 * every row. */
enum sl_err sl_out_print_tables(FILE *f, const struct sl_config *c, const struct sl_run_result *res,
                                struct sl_diag *d)
{
    struct sl_table_rows rows = {.produced = 1};
    return write_tables(f, SL_TABLE_MD, c, res, &rows, d);
}

/* ---- costs.csv: the columns of cellcols.h with a csv position ---- */

static const int csv_pos[SL_COL_COUNT] = {
#define SL_CSV_POS(name, kind, size, csv, head, check, key, from) [SL_COL_##name] = csv,
    SL_CELL_COLUMNS(SL_CSV_POS)
#undef SL_CSV_POS
};
static const char *const csv_head[SL_COL_COUNT] = {
#define SL_CSV_HEAD(name, kind, size, csv, head, check, key, from) [SL_COL_##name] = head,
    SL_CELL_COLUMNS(SL_CSV_HEAD)
#undef SL_CSV_HEAD
};

/* The columns of costs.csv in order; their number. */
static int csv_order(enum sl_cell_col order[SL_COL_COUNT])
{
    int n = 0;
    for (int p = 1; n < SL_COL_COUNT; p++) {
        int found = -1;
        for (int k = 0; k < SL_COL_COUNT && found < 0; k++)
            if (csv_pos[k] == p)
                found = k;
        if (found < 0)
            break;
        order[n++] = (enum sl_cell_col)found;
    }
    return n;
}

/* cell j of the last row: the column's value as costs.csv has always written it */
static void csv_cell(struct sl_tab *t, int j, const struct sl_cell_record *r, enum sl_cell_col col)
{
#define SL_CSV_text(name)     sl_tab_cell(t, j, "%s", r->name);
#define SL_CSV_path(name)     sl_tab_cell(t, j, "%s", r->name);
#define SL_CSV_dim(name)      sl_tab_cell(t, j, "%d", r->name);
#define SL_CSV_index(name)    sl_tab_cell(t, j, "%d", r->name);
#define SL_CSV_runs(name)     sl_tab_cell(t, j, "%d", r->name);
#define SL_CSV_flag(name)     sl_tab_cell(t, j, "%d", r->name);
#define SL_CSV_count(name)    sl_tab_cell(t, j, "%llu", (unsigned long long)SL_CELL_U64_count(r, name));
#define SL_CSV_wrong(name)    sl_tab_cell(t, j, "%llu", (unsigned long long)SL_CELL_U64_wrong(r, name));
#define SL_CSV_ms(name)       sl_tab_cell(t, j, "%.3f", r->name);
#define SL_CSV_viewport(name) sl_tab_cell(t, j, "%dx%d", r->vw, r->vh);
    switch (col) {
#define SL_CSV_CASE(name, kind, size, csv, head, check, key, from) \
    case SL_COL_##name: SL_CSV_##kind(name) break;
    SL_CELL_COLUMNS(SL_CSV_CASE)
#undef SL_CSV_CASE
    case SL_COL_COUNT:
        break;
    }
}

/* costs.csv in the model: a row per cell, the columns of cellcols.h with a
 * csv position, then the provenance (the machine always quoted: the file
 * has always quoted it, and scripts that split on commas expect it so),
 * then the GL renderer the times were measured on, quoted too (CSV has no
 * caption: what a time is travels with each row) */
static void costs_csv_model(struct sl_tab *t, const struct sl_config *c, const struct sl_run_result *res)
{
    char machine[300];
    machine_of(&res->prov, machine, sizeof machine);
    enum sl_cell_col order[SL_COL_COUNT];
    int ncols = csv_order(order);
    sl_tab_init(t, "costs", ncols + 4, 0, "costs");
    for (int j = 0; j < ncols; j++)
        sl_tab_head(t, j, "%s", csv_head[order[j]]);
    sl_tab_head(t, ncols, "git_sha");
    sl_tab_head(t, ncols + 1, "config_hash");
    sl_tab_head(t, ncols + 2, "machine");
    sl_tab_head(t, ncols + 3, "gl_renderer");
    sl_tab_quote(t, ncols + 2);
    sl_tab_quote(t, ncols + 3);
    for (int i = 0; i < res->ncells; i++) {
        struct sl_cell_record r;
        sl_out_record(c, &res->cells[i], &r);
        sl_tab_row(t, 0);
        for (int j = 0; j < ncols; j++)
            csv_cell(t, j, &r, order[j]);
        sl_tab_cell(t, ncols, "%s", res->prov.git_sha);
        sl_tab_cell(t, ncols + 1, "%016llx", c->hash);
        sl_tab_cell(t, ncols + 2, "%s", machine);
        sl_tab_cell(t, ncols + 3, "%s", res->prov.gl_renderer);
    }
}

void sl_out_write_costs_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    struct sl_tab t;
    const struct sl_emit_opts o = {.first = 1};
    costs_csv_model(&t, c, res);
    sl_emit_csv(f, &t, &o);
    sl_tab_free(&t);
}

/* A time in the cost table: "-" where not measured (NAN), else 0.1 ms. */
static void ms_cell(struct sl_tab *t, int col, double ms)
{
    if (isnan(ms))
        sl_tab_cell(t, col, "-");
    else
        sl_tab_cell(t, col, "%.1f", ms);
}

/* The cost table in the model: a row per cell computed, its stages (one
 * definition for every method, C or package: cellcols.h's cost model),
 * their whole with its spread and the runs timed, the GPU times of the GL
 * stages, the counters; under it the renderer the times were measured on
 * and the run's total. */
static void costs_model(struct sl_tab *t, const struct sl_config *c, const struct sl_run_result *res)
{
    enum { NCOL = 25 };
    static const char lr[] = "rllrlrrrrrrrrrrrrrrrrrrrr";
    sl_tab_init(t, "costs", NCOL, 5,
                "Cost per cell by stages (ms, medians of the timed runs; G-buffer and truth are shared by the "
                "cells of a view)");
    t->level = 2;
    t->plain = 1;
    static const char *const heads[NCOL] = {
        "cell", "scene", "viewpoint", "map", "label", "G-buffer", "truth", "fit", "map pass", "post",
        "lookup", "readback", "rays ms", "total", "total min-max", "n", "GPU map", "GPU post", "GPU lookup",
        "rays", "lookups", "ray-tri tests", "fragments", "figures", "overlay"};
    for (int k = 0; k < NCOL; k++) {
        sl_tab_head(t, k, "%s", heads[k]);
        sl_tab_align(t, k, lr[k]);
    }
    int once = 0;
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        const struct sl_stage_ms *s = &cl->ms;
        sl_tab_row(t, 0);
        sl_tab_cell(t, 0, "%d", cl->index);
        sl_tab_cell(t, 1, "%s", cl->scene);
        sl_tab_cell(t, 2, "%s", cl->viewpoint);
        sl_tab_cell(t, 3, "%d", c->maps[cl->key.map]);
        sl_tab_cell(t, 4, "%s", c->methods[cl->key.method].label);
        sl_tab_cell(t, 5, "%.1f", s->gbuffer_render[SL_MED] + s->gbuffer_readback);
        sl_tab_cell(t, 6, "%.1f%s", s->truth[SL_MED], cl->truth_cached ? " (cached)" : "");
        sl_tab_cell(t, 7, "%.1f", s->fit);
        ms_cell(t, 8, s->st_map);
        ms_cell(t, 9, s->st_post);
        ms_cell(t, 10, s->st_lookup);
        ms_cell(t, 11, s->st_readback);
        ms_cell(t, 12, s->st_rays);
        sl_tab_cell(t, 13, "%.1f%s", s->total[SL_MED], s->runs_method == 1 ? "\xE2\x80\xA0" : "");
        sl_tab_cell(t, 14, "%.1f-%.1f", s->total[SL_MIN], s->total[SL_MAX]);
        sl_tab_cell(t, 15, "%d", s->runs_method);
        ms_cell(t, 16, s->gpu_map[SL_MED]);
        ms_cell(t, 17, s->gpu_post);
        ms_cell(t, 18, s->gpu_lookup);
        sl_tab_cell(t, 19, "%llu", (unsigned long long)cl->cost.rays);
        sl_tab_cell(t, 20, "%llu", (unsigned long long)cl->cost.lookups);
        sl_tab_cell(t, 21, "%llu", (unsigned long long)cl->cost.tri_tests);
        sl_tab_cell(t, 22, "%llu", (unsigned long long)cl->fragments);
        sl_tab_cell(t, 23, "%.1f", s->contours + s->figures);
        sl_tab_cell(t, 24, "%.1f", s->overlay);
        once |= s->runs_method == 1;
    }
    char gl[400];
    sl_gl_times_note(res->prov.gl_renderer, gl, sizeof gl);
    sl_tab_notef(t, "%s Stages, one definition for every method: map pass (the shadow maps it reads, the "
                    "driver's layers or its own), post (blur, mipmaps), lookup (its per-pixel step without "
                    "rays), readback (maps or visibility back to the CPU), rays; total = their sum, with the "
                    "min-max of n timed runs of the method (repetitions: %s). GPU: GL_TIME_ELAPSED of the GL "
                    "stages, - where none ran.%s\n\n",
                 gl, c->rep_mode == SL_REP_OFF ? "off" : c->rep_mode == SL_REP_FIXED ? "fixed" : "adaptive",
                 once ? " \xE2\x80\xA0 timed once: one measurement, no median." : "");
    sl_tab_note_cat(t, "Total %.0f ms (scenes %.1f ms, BVH %.1f ms); %d cell(s) computed, %d already stored.",
                    res->ms_total, res->ms_scene, res->ms_bvh, res->ncells, res->skipped);
}

static int any_patterns(const struct sl_run_result *res)
{
    int any = 0;
    for (int i = 0; i < res->ncells; i++)
        any |= res->cells[i].has_patterns;
    return any;
}

void sl_out_write_costs_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    struct sl_tab t;
    /* after the figures' tables, which end with a blank line: one more; the
     * texel patterns follow it when there are any, else the file ends */
    const struct sl_emit_opts o = {.first = 1, .gap = 1, .tight = !any_patterns(res)};
    costs_model(&t, c, res);
    sl_emit_md(f, &t, &o);
    sl_tab_free(&t);
}

/* The texel-coherence patterns in the model: per cell and region of a
 * coherence method, the undecided pixels by how many of its texels say
 * shadow. data: the long form (CSV: a line per count, from 0), else a row
 * per region with a column per count from 1 to 8. */
static void patterns_model(struct sl_tab *t, const struct sl_config *c, const struct sl_run_result *res, int data)
{
    static const char *const dheads[] = {"cell", "scene", "viewpoint", "viewport", "map_size", "label", "texels",
                                         "region", "shadowed_texels", "pixels", "shadowed_in_truth", "git_sha",
                                         "config_hash"};
    static const char *const heads[] = {"cell", "scene", "viewpoint", "map", "label", "region"};
    static const char lr[] = "rllrll";
    if (data) {
        sl_tab_init(t, "patterns", 13, 8, "patterns");
        for (int k = 0; k < 13; k++)
            sl_tab_head(t, k, "%s", dheads[k]);
    } else {
        sl_tab_init(t, "patterns", 14, 6, "Texel coherence: undecided pixels by how many texels say shadow "
                                          "(pixels, of which shadowed in truth)");
        t->level = 2;
        t->plain = 1;
        for (int k = 0; k < 14; k++) {
            if (k < 6)
                sl_tab_head(t, k, "%s", heads[k]);
            else
                sl_tab_head(t, k, "%d", k - 5);
            sl_tab_align(t, k, k < 6 ? lr[k] : 'r');
        }
    }
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        if (!cl->has_patterns)
            continue;
        int n = (int)sl_params_get(&c->methods[cl->key.method].params.values, "texels");
        for (int r = 0; r < cl->fig.nregions; r++) {
            char rn[16];
            if (data)
                sl_region_name(cl->fig.r[r].thickness, rn, sizeof rn);
            else if (cl->fig.r[r].thickness)
                snprintf(rn, sizeof rn, "%d px", cl->fig.r[r].thickness);
            else
                snprintf(rn, sizeof rn, "image");
            for (int k = 0; k <= (data ? n : 0); k++) {
                sl_tab_row(t, 0);
                sl_tab_cell(t, 0, "%d", cl->index);
                sl_tab_cell(t, 1, "%s", cl->scene);
                sl_tab_cell(t, 2, "%s", cl->viewpoint);
                if (!data) {
                    sl_tab_cell(t, 3, "%d", c->maps[cl->key.map]);
                    sl_tab_cell(t, 4, "%s", c->methods[cl->key.method].label);
                    sl_tab_cell(t, 5, "%s", rn);
                    for (int j = 1; j <= 8; j++)
                        if (j < n)
                            sl_tab_cell(t, 5 + j, "%llu (%llu)", (unsigned long long)cl->pattern[r][j][0],
                                        (unsigned long long)cl->pattern[r][j][1]);
                    continue;
                }
                sl_tab_cell(t, 3, "%dx%d", c->viewport_w[cl->key.viewport], c->viewport_h[cl->key.viewport]);
                sl_tab_cell(t, 4, "%d", c->maps[cl->key.map]);
                sl_tab_cell(t, 5, "%s", c->methods[cl->key.method].label);
                sl_tab_cell(t, 6, "%d", n);
                sl_tab_cell(t, 7, "%s", rn);
                sl_tab_cell(t, 8, "%d", k);
                sl_tab_cell(t, 9, "%llu", (unsigned long long)cl->pattern[r][k][0]);
                sl_tab_cell(t, 10, "%llu", (unsigned long long)cl->pattern[r][k][1]);
                sl_tab_cell(t, 11, "%s", res->prov.git_sha);
                sl_tab_cell(t, 12, "%016llx", c->hash);
            }
        }
    }
}

void sl_out_write_patterns_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    struct sl_tab t;
    patterns_model(&t, c, res, 1);
    sl_emit_csv(f, &t, NULL);
    sl_tab_free(&t);
}

void sl_out_write_patterns_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    if (!any_patterns(res))
        return;
    struct sl_tab t;
    patterns_model(&t, c, res, 0);
    sl_emit_md(f, &t, NULL);
    sl_tab_free(&t);
}

void sl_out_write_run_yaml(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "config: %s\nconfig_hash: %016llx\n", c->path, c->hash);
    sl_provenance_write(&res->prov, f, "");
    fprintf(f, "cells_computed: %d\ncells_skipped: %d\n", res->ncells, res->skipped);
    if (res->warmed)   /* path frames scored again for the next frame's flicker only (doc/guide.md, Errors over motion) */
        fprintf(f, "cells_warmed_up: %d\n", res->warmed);
    fprintf(f, "ms_total: %.1f\n", res->ms_total);
}

/* ---- the run's folder: staged, then swapped into place ---- */

static int rm_cb(const char *p, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb; (void)flag; (void)ftw;
    return remove(p);
}

static void rm_tree(const char *path)
{
    nftw(path, rm_cb, 16, FTW_DEPTH | FTW_PHYS);
}

/* The overlay's path as the store keeps it: relative to the database's
 * folder when the results folder lies under it (the usual layout,
 * results/shadowlab.db beside results/<name>/), else absolute. The file is in
 * place once the run ends (the staging folder is renamed then). */
static void overlay_store_path(const char *store_path, const char *final, const char *sub, const char *name,
                               char *out, size_t n)
{
    char dbdir[PATH_MAX], fin[PATH_MAX], tmp[1200];
    sl_path_dir(store_path, tmp, sizeof tmp);
    if (!realpath(tmp, dbdir) || !realpath(final, fin)) {
        /* the results folder does not exist yet on a first run: resolve its parent */
        char parent[1200];
        snprintf(parent, sizeof parent, "%s", final);
        char *ps = strrchr(parent, '/');
        const char *base = ps ? ps + 1 : final;
        if (ps)
            *ps = '\0';
        else
            snprintf(parent, sizeof parent, ".");
        char rp[PATH_MAX];
        if (!realpath(tmp, dbdir) || !realpath(parent, rp)) {
            snprintf(out, n, "%s/%s/%s", final, sub, name);
            return;
        }
        snprintf(fin, sizeof fin, "%.*s/%s", (int)(sizeof fin - 300), rp, base);
    }
    size_t k = strlen(dbdir);
    if (strncmp(fin, dbdir, k) == 0 && fin[k] == '/')
        snprintf(out, n, "%s/%s/%s", fin + k + 1, sub, name);
    else
        snprintf(out, n, "%s/%s/%s", fin, sub, name);
}

/* One file of the cell, in the staging folder now: its path as the store
 * will find it (in the results folder, once the staging folder is renamed),
 * its size and CRC-32. 0 when it is not there (nothing to record). */
static int cell_file(const char *store_path, const struct sl_out_dirs *dirs, const char *sub, const char *staged,
                     const char *name, struct sl_store_file *f, struct sl_diag *d, enum sl_err *e)
{
    char at[1700];
    snprintf(at, sizeof at, "%s/%s", staged, name);
    if (access(at, F_OK) != 0)
        return 0;
    overlay_store_path(store_path, dirs->final, sub, name, f->path, sizeof f->path);
    *e = sl_store_file_digest(at, &f->size, &f->crc32, d);
    if (*e == SL_E_IO)
        *e = SL_E_OUTPUT;
    return 1;
}

enum sl_err sl_out_record_run_files(struct sl_store *st, int64_t run_id, const char *store_path,
                                    const struct sl_out_dirs *dirs, struct sl_diag *d)
{
    DIR *dp = opendir(dirs->final);
    if (!dp)
        return SL_OK;   /* a run that wrote no folder (--no-files) */
    struct sl_store_file *f = NULL;
    int n = 0;
    enum sl_err e = SL_OK;
    for (struct dirent *de; !e && (de = readdir(dp));) {
        char at[1400];
        struct stat sb;
        snprintf(at, sizeof at, "%s/%s", dirs->final, de->d_name);
        /* the run's own files: regular files at the folder's top (the
         * overlays and EXR files are the cells', recorded with them) */
        if (de->d_name[0] == '.' || lstat(at, &sb) != 0 || !S_ISREG(sb.st_mode))
            continue;
        struct sl_store_file *nf = realloc(f, (size_t)(n + 1) * sizeof *f);
        if (!nf) {
            e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "the run's files");
            break;
        }
        f = nf;
        overlay_store_path(store_path, dirs->final, "", de->d_name, f[n].path, sizeof f[n].path);
        /* "<final>//<name>" from an empty sub: one slash */
        char *dbl = strstr(f[n].path, "//");
        if (dbl)
            memmove(dbl, dbl + 1, strlen(dbl));
        if ((e = sl_store_file_digest(at, &f[n].size, &f[n].crc32, d)))
            e = SL_E_OUTPUT;
        n++;
    }
    closedir(dp);
    if (!e && n)
        e = sl_store_put_run_files(st, run_id, f, n, d);
    free(f);
    return e;
}

enum sl_err sl_out_store_cell(struct sl_store *st, int64_t run_id, const struct sl_config *c,
                              const struct sl_cell *cl, const char *store_path, const struct sl_out_dirs *dirs,
                              struct sl_diag *d)
{
    struct sl_cell_record sc;
    sl_out_record(c, cl, &sc);
    struct sl_store_file files[3];
    int nfiles = 0;
    enum sl_err e = SL_OK;
    if (dirs && dirs->final[0] && c->overlays) {
        char name[400];
        sl_out_overlay_name(c, cl, name, sizeof name);
        overlay_store_path(store_path, dirs->final, "overlays", name, sc.overlay, sizeof sc.overlay);
        /* the sheet is on disk (the sink waited for it): recorded with the cell */
        nfiles += cell_file(store_path, dirs, "overlays", dirs->overlays, name, &files[nfiles], d, &e);
    }
    if (!e && dirs && dirs->final[0] && c->exr) {
        char name[400];
        sl_out_exr_name(c, cl, name, sizeof name);
        nfiles += cell_file(store_path, dirs, "exr", dirs->exr, name, &files[nfiles], d, &e);
    }
    if (!e && dirs && dirs->final[0] && c->visibility) {
        char name[400];
        sl_out_visibility_name(c, cl, name, sizeof name);
        nfiles += cell_file(store_path, dirs, "visibility", dirs->visibility, name, &files[nfiles], d, &e);
    }
    return e ? e : sl_store_put_cell_files(st, run_id, c->hash, &sc, files, nfiles, d);
}

/* Move the files of <from>/<sub> into <to>/<sub> where <to> has no file of that name. */
static void carry_files(const char *from, const char *to, const char *sub)
{
    char src[1400], dst[1400];
    snprintf(src, sizeof src, "%s/%s", from, sub);
    DIR *dir = opendir(src);
    if (!dir)
        return;
    snprintf(dst, sizeof dst, "%s/%s", to, sub);
    mkdir(dst, 0777);
    struct dirent *e;
    while ((e = readdir(dir))) {
        /* a killed run may have left a half-written image under its
         * temporary name (image.cpp writes name.tmp.ext, then renames) */
        if (e->d_name[0] == '.' || strstr(e->d_name, ".tmp."))
            continue;
        char a[1800], b[1800];
        snprintf(a, sizeof a, "%s/%s", src, e->d_name);
        snprintf(b, sizeof b, "%s/%s", dst, e->d_name);
        if (access(b, F_OK) != 0)
            rename(a, b);
    }
    closedir(dir);
}

/* A dead run's staging folder claimed for us: the fd of its lock file,
 * locked, or -1 while its run is alive (or it is no folder of ours: a
 * symbolic link is never followed). A folder without the file is an older
 * build's, whose run is gone. */
static int claim_dead(const char *dir)
{
    struct stat sb;
    if (lstat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return -1;
    char lk[1300];
    snprintf(lk, sizeof lk, "%s/%s", dir, SL_OUT_CLAIM);
    int fd = open(lk, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        return -1;
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

static enum sl_err kept_add(struct sl_out_kept *k, const char *dir, struct sl_diag *d)
{
    char (*p)[1200] = realloc(k->dir, (size_t)(k->n + 1) * sizeof *p);
    if (!p)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "folders to carry from");
    k->dir = p;
    snprintf(k->dir[k->n++], sizeof k->dir[0], "%s", dir);
    return SL_OK;
}

enum sl_err sl_out_kept_find(const struct sl_config *c, const char *root, const char *final, const char *own,
                             struct sl_out_kept *k, struct sl_diag *d)
{
    memset(k, 0, sizeof *k);
    enum sl_err e = kept_add(k, final, d);
    DIR *dir = root && !e ? opendir(root) : NULL;
    if (!dir)
        return e;
    char prefix[200], path[1200];
    snprintf(prefix, sizeof prefix, ".%s.partial-", c->name);
    struct dirent *de;
    while (!e && (de = readdir(dir))) {
        if (strncmp(de->d_name, prefix, strlen(prefix)) != 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", root, de->d_name);
        if (own && strcmp(path, own) == 0)
            continue;
        /* claimable now (its run is dead) is what carry_previous will find:
         * the claim is let go at once, carry_previous takes it again */
        int fd = claim_dead(path);
        if (fd < 0)
            continue;
        close(fd);
        e = kept_add(k, path, d);
    }
    closedir(dir);
    return e;
}

/* 1 when one of k's folders holds sub/name whole: there, and, when st
 * records the file (at its path in the results folder, k->dir[0]), of the
 * recorded size and CRC-32 (a damaged file is as good as a lost one: the
 * cell is computed again and writes it anew). */
static int kept_has(const struct sl_out_kept *k, const char *sub, const char *name, struct sl_store *st)
{
    long long want_size = 0;
    uint32_t want_crc = 0;
    int recorded = 0;
    if (st && k->n > 0) {
        char rec[1200];
        overlay_store_path(sl_store_path(st), k->dir[0], sub, name, rec, sizeof rec);
        recorded = sl_store_file_recorded(st, rec, &want_size, &want_crc) == 1;
    }
    for (int i = 0; i < k->n; i++) {
        char p[1700];
        snprintf(p, sizeof p, "%s/%s/%s", k->dir[i], sub, name);
        if (access(p, F_OK) != 0)
            continue;
        long long size = 0;
        uint32_t crc = 0;
        if (!recorded || (sl_store_file_digest(p, &size, &crc, NULL) == SL_OK && size == want_size && crc == want_crc))
            return 1;
    }
    return 0;
}

int sl_out_kept_whole(const struct sl_config *c, const struct sl_cell_key *key, const struct sl_out_kept *k,
                      struct sl_store *st)
{
    char png[400], exr[400];
    key_file_name(c, key, "png", png, sizeof png);
    key_file_name(c, key, "exr", exr, sizeof exr);
    return (!c->overlays || kept_has(k, "overlays", png, st)) && (!c->exr || kept_has(k, "exr", exr, st)) &&
           (!c->visibility || kept_has(k, "visibility", exr, st));
}

void sl_out_kept_free(struct sl_out_kept *k)
{
    free(k->dir);
    memset(k, 0, sizeof *k);
}

static void carry_previous(const char *root, const char *name, const char *final, const char *stage)
{
    carry_files(final, stage, "overlays");
    carry_files(final, stage, "exr");
    carry_files(final, stage, "visibility");
    DIR *dir = opendir(root);
    if (!dir)
        return;
    char prefix[200], own[1200];
    snprintf(prefix, sizeof prefix, ".%s.partial-", name);
    struct dirent *e;
    while ((e = readdir(dir))) {
        if (strncmp(e->d_name, prefix, strlen(prefix)) != 0)
            continue;
        snprintf(own, sizeof own, "%s/%s", root, e->d_name);
        if (strcmp(own, stage) == 0)
            continue;
        /* only a dead run's folder: another run of this config may be writing
         * its own right now (it holds its claim) */
        int fd = claim_dead(own);
        if (fd < 0)
            continue;
        carry_files(own, stage, "overlays");
        carry_files(own, stage, "exr");
        carry_files(own, stage, "visibility");
        rm_tree(own);   /* a killed run's leftovers: its cells are in the store */
        close(fd);
    }
    closedir(dir);
}

/* A run row carrying the filled-in config, so a number in the store can be
 * reproduced from the store alone. */
enum sl_err sl_out_begin_run(struct sl_store *st, const struct sl_config *c, const struct sl_provenance *p,
                             int64_t *run_id, struct sl_diag *d)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "config text");
    sl_config_write(c, f);
    fclose(f);
    enum sl_err e = sl_store_begin_run(st, p, c->name, c->path, c->hash, text, run_id, d);
    free(text);
    /* the whole sweep's keys, whatever slice this run computes: a store
     * then says how many of its cells it holds, and which it lacks */
    int n = sl_plan_count(c);
    struct sl_store_key *keys = e ? NULL : sl_calloc((size_t)n + 1, sizeof *keys);
    if (!e && !keys)
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "the plan's %d cells", n);
    for (int i = 0; !e && i < n; i++) {
        struct sl_cell_key k;
        sl_plan_cell(c, i, &k);
        const struct sl_config_scene *cs = &c->scenes[k.scene];
        keys[i] = (struct sl_store_key){.scene = cs->name, .viewpoint = cs->viewpoints[k.vp],
                                        .label = c->methods[k.method].label, .vw = c->viewport_w[k.viewport],
                                        .vh = c->viewport_h[k.viewport], .map_size = c->maps[k.map], .index = i};
    }
    if (!e)
        e = sl_store_put_plan(st, c->hash, keys, n, d);
    free(keys);
    return e;
}

enum sl_err sl_out_no_link(const char *path, struct sl_diag *d)
{
    struct stat sb;
    if (lstat(path, &sb) == 0 && S_ISLNK(sb.st_mode))
        return sl_fail(d, SL_E_USAGE, path, 0, NULL, "is a symbolic link where the run writes: a run never "
                       "writes through one (remove it, or name the folder it points at with --out/--db/--cache)");
    return SL_OK;
}

enum sl_err sl_out_no_store_link(const char *path, struct sl_diag *d)
{
    static const char *const with[] = {"", "-wal", "-shm", "-journal", ".lock"};
    enum sl_err e = SL_OK;
    for (size_t i = 0; i < sizeof with / sizeof with[0] && !e; i++) {
        char p[1300];
        snprintf(p, sizeof p, "%s%s", path, with[i]);
        e = sl_out_no_link(p, d);
    }
    return e;
}

/* The staging folder made under a name no other run looks at, claimed,
 * then renamed to its .partial name: no run ever sees it unclaimed. */
static enum sl_err stage_make(struct sl_out_dirs *o, const char *root, const char *name, struct sl_diag *d)
{
    char tmp[1200], lk[1300];
    snprintf(o->stage, sizeof o->stage, "%s/.%s.partial-%ld", root, name, (long)getpid());
    snprintf(tmp, sizeof tmp, "%s/.%s.claiming-%ld", root, name, (long)getpid());
    rm_tree(o->stage);   /* this pid's: a run long gone (nftw does not follow a link) */
    rm_tree(tmp);
    int fd = -1;
    if (mkdir(tmp, 0777) != 0)
        goto fail;
    snprintf(lk, sizeof lk, "%s/%s", tmp, SL_OUT_CLAIM);
    if ((fd = open(lk, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644)) < 0 || flock(fd, LOCK_EX) != 0 ||
        rename(tmp, o->stage) != 0)
        goto fail;
    o->claim = fd + 1;
    return SL_OK;
fail:;
    int en = errno;
    if (fd >= 0)
        close(fd);
    rm_tree(tmp);
    char shown[1200];
    snprintf(shown, sizeof shown, "%s", o->stage);
    o->stage[0] = '\0';
    return sl_fail(d, SL_E_OUTPUT, shown, 0, NULL, "cannot make the staging folder: %s", strerror(en));
}

static void claim_release(struct sl_out_dirs *o)
{
    if (o->claim > 0)
        close(o->claim - 1);
    o->claim = 0;
}

enum sl_err sl_out_stage_begin(const struct sl_config *c, const char *root, struct sl_out_dirs *o,
                               struct sl_diag *d)
{
    enum sl_err e;
    snprintf(o->root, sizeof o->root, "%s", root);
    snprintf(o->final, sizeof o->final, "%s/%s", root, c->name);
    o->claim = 0;
    if ((e = sl_out_no_link(o->final, d)) || (e = stage_make(o, root, c->name, d)))
        return e;
    snprintf(o->overlays, sizeof o->overlays, "%s/overlays", o->stage);
    snprintf(o->exr, sizeof o->exr, "%s/exr", o->stage);
    snprintf(o->visibility, sizeof o->visibility, "%s/visibility", o->stage);
    if ((c->overlays && (e = sl_mkdirs(o->overlays, d))) || (c->exr && (e = sl_mkdirs(o->exr, d))) ||
        (c->visibility && (e = sl_mkdirs(o->visibility, d)))) {
        sl_out_stage_drop(o);
        return e;
    }
    return SL_OK;
}

static int has_entries(const char *dir)
{
    DIR *dp = opendir(dir);
    if (!dp)
        return 0;
    struct dirent *e;
    int n = 0;
    while (!n && (e = readdir(dp)))
        n = strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    closedir(dp);
    return n;
}

/* A run that failed after cells went into the store (a table that could
 * not be written, a full disk) keeps its staging folder when it holds
 * overlays or EXR files: the store points at them, and the next `--resume`
 * carries them over from this (then dead) run's folder (carry_previous). */
void sl_out_stage_drop(struct sl_out_dirs *o)
{
    if (o->stage[0] && !has_entries(o->overlays) && !has_entries(o->exr) && !has_entries(o->visibility))
        rm_tree(o->stage);
    o->stage[0] = '\0';
    claim_release(o);   /* kept or not, it is a dead run's folder from now on */
}

/* The run's cells and result, for sl_out_write_formats: table.md also
 * gets the costs and the texel patterns. */
struct run_tables {
    const struct sl_config     *c;
    const struct sl_run_result *res;
};

static enum sl_err write_run_table(FILE *f, enum sl_table_format fmt, const void *arg, struct sl_diag *d)
{
    const struct run_tables *t = arg;
    enum sl_err e = sl_out_write_tables(f, fmt, t->c, t->res, d);
    if (fmt == SL_TABLE_MD) {
        sl_out_write_costs_md(f, t->c, t->res);
        sl_out_write_patterns_md(f, t->c, t->res);
    }
    return e;
}

enum sl_err sl_out_stage_finish(const struct sl_config *c, const struct sl_run_result *res,
                                struct sl_out_dirs *o, int resume, struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    if (c->tables) {
        static const struct sl_out_format_file tables[] = {
            {"figures.csv", SL_TABLE_CSV}, {"table.md", SL_TABLE_MD}, {"table.tex", SL_TABLE_LATEX_SUMMARY},
            {"table-detail.tex", SL_TABLE_LATEX_DETAIL},
        };
        const struct run_tables t = {c, res};
        if ((e = sl_out_write_formats(o->stage, tables, (int)(sizeof tables / sizeof tables[0]), write_run_table,
                                      &t, d)))
            return e;
    }
    {
        static const char *const files[] = {"costs.csv", "config.yaml", "run.yaml", "patterns.csv"};
        for (size_t f = 0; f < sizeof files / sizeof files[0] && !e; f++) {
            struct sl_outfile of;
            char path[1300];
            snprintf(path, sizeof path, "%s/%s", o->stage, files[f]);
            if ((e = sl_out_open(&of, path, d)))
                break;
            switch (f) {
            case 0: sl_out_write_costs_csv(of.f, c, res); break;
            case 1:
                fprintf(of.f, "# from %s (hash %016llx), git %s\n", c->path, c->hash, res->prov.git_sha);
                sl_config_write(c, of.f);
                break;
            case 2: sl_out_write_run_yaml(of.f, c, res); break;
            case 3: sl_out_write_patterns_csv(of.f, c, res); break;
            }
            e = sl_out_commit(&of, d);
        }
        if (e)
            return e;
    }
    /* a resumed run computed only the missing cells: the overlays and EXR
     * files of the cells it skipped come from the previous results folder, or
     * from the staging folder of a run that was killed, so what the store
     * points at is in place */
    if (resume)
        carry_previous(o->root, c->name, o->final, o->stage);
    /* swap the finished folder into place */
    {
        char old[1200];
        snprintf(old, sizeof old, "%s/.%s.old-%ld", o->root, c->name, (long)getpid());
        struct stat sb;
        int had = stat(o->final, &sb) == 0;
        if (had && rename(o->final, old) != 0) {
            return sl_fail(d, SL_E_OUTPUT, o->final, 0, NULL, "cannot replace the previous results: %s",
                           strerror(errno));
        }
        if (rename(o->stage, o->final) != 0) {
            if (had)
                rename(old, o->final);
            return sl_fail(d, SL_E_OUTPUT, o->final, 0, NULL, "cannot move results into place: %s",
                           strerror(errno));
        }
        if (had)
            rm_tree(old);
        /* in place under its final name, which no run takes for a staging
         * folder: the claim's file goes, then the claim */
        char lk[1300];
        snprintf(lk, sizeof lk, "%s/%s", o->final, SL_OUT_CLAIM);
        unlink(lk);
        claim_release(o);
        o->stage[0] = '\0';
    }
    return SL_OK;
}

enum sl_err sl_out_stored_cells(struct sl_store *st, const struct sl_config *c, struct sl_cell_record **cells,
                                int *n, struct sl_diag *d)
{
    struct sl_store_filter f = {.study = c->name};
    *cells = NULL;
    *n = 0;
    int all = 0;
    enum sl_err e = sl_store_query(st, &f, cells, &all, d);
    if (e)
        return e;
    char hash[24];
    snprintf(hash, sizeof hash, "%016llx", c->hash);
    for (int i = 0; i < all; i++)
        if (strcmp((*cells)[i].config_hash, hash) == 0)
            (*cells)[(*n)++] = (*cells)[i];
    return SL_OK;
}

enum sl_err sl_out_write_formats(const char *dir, const struct sl_out_format_file *files, int nfiles,
                                 sl_out_format_writer write, const void *arg, struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    for (int i = 0; i < nfiles && !e; i++) {
        struct sl_outfile of;
        char path[1300];
        snprintf(path, sizeof path, "%s/%s", dir, files[i].name);
        if ((e = sl_out_open(&of, path, d)))
            break;
        e = write(of.f, files[i].fmt, arg, d);
        if (e)
            sl_out_abort(&of);
        else
            e = sl_out_commit(&of, d);
    }
    return e;
}

/* The stored cells of a rebuild and their title, for sl_out_write_formats. */
struct stored_tables {
    const char                  *title;
    const struct sl_cell_record *cells;
    int                          n;
};

static enum sl_err write_stored_table(FILE *f, enum sl_table_format fmt, const void *arg, struct sl_diag *d)
{
    const struct stored_tables *t = arg;
    return sl_table_write(f, fmt, t->title, t->cells, t->n, d);
}

/* The run folder's figures.csv, table.md, table.tex and table-detail.tex from the store, when
 * it holds more cells of this config (same hash) than this run computed: a
 * resumed, split or interrupted run then still leaves tables of every
 * stored cell, as `shadowlab table DB` would print them. */
enum sl_err sl_out_rebuild_from_store(struct sl_store *st, const struct sl_config *c, int computed,
                                      const char *dir, int *stored, struct sl_diag *d)
{
    *stored = -1;
    struct sl_cell_record *cells = NULL;
    int k = 0;
    enum sl_err e = sl_out_stored_cells(st, c, &cells, &k, d);
    if (e)
        return e;
    *stored = k;
    if (k <= computed) {
        free(cells);
        return SL_OK;
    }
    static const struct sl_out_format_file files[] = {
        {"figures.csv", SL_TABLE_CSV}, {"table.md", SL_TABLE_MD}, {"table.tex", SL_TABLE_LATEX_SUMMARY},
            {"table-detail.tex", SL_TABLE_LATEX_DETAIL},
    };
    char title[256];
    snprintf(title, sizeof title, "shadowlab: %s (every stored cell of this config)", c->name);
    const struct stored_tables t = {title, cells, k};
    e = sl_out_write_formats(dir, files, (int)(sizeof files / sizeof files[0]), write_stored_table, &t, d);
    free(cells);
    return e;
}

int64_t sl_out_stored_id(const struct sl_config *c, const struct sl_cell_key *k, struct sl_store *st)
{
    const struct sl_config_scene *cs = &c->scenes[k->scene];
    return sl_store_cell_id(st, c->hash, cs->name, cs->viewpoints[k->vp], c->viewport_w[k->viewport],
                           c->viewport_h[k->viewport], c->maps[k->map], c->methods[k->method].label);
}

int sl_out_stored(const struct sl_config *c, const struct sl_cell_key *k, struct sl_store *st)
{
    return sl_out_stored_id(c, k, st) != 0;
}
