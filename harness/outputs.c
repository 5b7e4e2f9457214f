/*
 * outputs.c — see outputs.h.
 *
 * Every file is written from the cells in memory in sweep order; the tables
 * and the store get the same record of a cell (sl_out_record), so table.md
 * and `shadowlab table` on the store can never disagree. costs.csv is
 * generated from the column list of cellcols.h: its header and its rows
 * cannot drift apart.
 */
#define _XOPEN_SOURCE 700
#include "outputs.h"
#include <stdlib.h>
#include <string.h>
#include "util.h"

static void machine_of(const struct sl_provenance *p, char *out, size_t n)
{
    snprintf(out, n, "%s/%s/%s", p->host, p->cpu, p->isa);
}

void sl_out_overlay_name(const struct sl_config *c, const struct sl_cell *cl, char *out, size_t n)
{
    snprintf(out, n, "%s-%s-%dx%d-%d-%s.png", cl->scene, cl->viewpoint, c->viewport_w[cl->key.viewport],
             c->viewport_h[cl->key.viewport], c->maps[cl->key.map], c->methods[cl->key.method].label);
}

void sl_out_record(const struct sl_config *c, const struct sl_cell *cl, struct sl_cell_record *r)
{
    const struct sl_config_method *cm = &c->methods[cl->key.method];
    const struct sl_stage_ms *s = &cl->ms;
    memset(r, 0, sizeof *r);
    snprintf(r->scene, sizeof r->scene, "%s", cl->scene);
    snprintf(r->viewpoint, sizeof r->viewpoint, "%s", cl->viewpoint);
    snprintf(r->method, sizeof r->method, "%s", cm->method->name);
    snprintf(r->label, sizeof r->label, "%s", cm->label);
    r->vw = c->viewport_w[cl->key.viewport];
    r->vh = c->viewport_h[cl->key.viewport];
    r->map_size = c->maps[cl->key.map];
    r->cell_index = cl->index;
    r->n_pfl = cl->n_pfl;
    r->n_pnfl = cl->n_pnfl;
    r->n_background = cl->n_background;
    r->n_truth_lit = cl->n_truth_lit;
    r->n_truth_shadow = cl->n_truth_shadow;
    r->truth_rays = cl->truth_rays;
    r->runs = c->runs;
    r->lookups = cl->cost.lookups;
    r->rays = cl->cost.rays;
    r->tri_tests = cl->cost.tri_tests;
    r->gs_prims = cl->gs_prims;
    r->fragments = cl->fragments;
    r->violations = cl->violations;
    r->ms_gbuffer_render = s->gbuffer_render[SL_MED];
    r->ms_gbuffer_render_min = s->gbuffer_render[SL_MIN];
    r->ms_gbuffer_render_max = s->gbuffer_render[SL_MAX];
    r->ms_gbuffer_readback = s->gbuffer_readback;
    r->ms_truth = s->truth[SL_MED];
    r->ms_truth_min = s->truth[SL_MIN];
    r->ms_truth_max = s->truth[SL_MAX];
    r->ms_fit = s->fit;
    r->ms_map_render = s->map_render[SL_MED];
    r->ms_map_render_min = s->map_render[SL_MIN];
    r->ms_map_render_max = s->map_render[SL_MAX];
    r->ms_map_readback = s->map_readback;
    r->ms_method = s->method[SL_MED];
    r->ms_method_min = s->method[SL_MIN];
    r->ms_method_max = s->method[SL_MAX];
    r->ms_ray_step = cl->cost.ms_trace;
    r->ms_step1 = cl->cost.ms_step[0];
    r->ms_step2 = cl->cost.ms_step[1];
    r->ms_step3 = cl->cost.ms_step[2];
    r->ms_step4 = cl->cost.ms_step[3];
    r->ms_contours = s->contours;
    r->ms_figures = s->figures;
    r->ms_overlay = s->overlay;
    r->truth_cached = cl->truth_cached;
    r->fig = cl->fig;
    r->has_soft = cl->has_soft;
    r->soft = cl->soft;
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
    }
}

enum sl_err sl_out_write_tables(FILE *f, enum sl_table_format fmt, const struct sl_config *c,
                                const struct sl_run_result *res, struct sl_diag *d)
{
    struct sl_cell_record *tc = sl_calloc((size_t)(res->ncells ? res->ncells : 1), sizeof *tc);
    if (!tc)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "table cells");
    table_cells_of(c, res, tc);
    char title[256];
    snprintf(title, sizeof title, "shadowlab: %s", c->name);
    enum sl_err e = sl_table_write(f, fmt, title, tc, res->ncells, d);
    free(tc);
    return e;
}

/* ---- costs.csv: the columns of cellcols.h with a csv position ---- */

static const int csv_pos[SL_COL_COUNT] = {
#define SL_CSV_POS(name, kind, size, csv, head, check, key) [SL_COL_##name] = csv,
    SL_CELL_COLUMNS(SL_CSV_POS)
#undef SL_CSV_POS
};
static const char *const csv_head[SL_COL_COUNT] = {
#define SL_CSV_HEAD(name, kind, size, csv, head, check, key) [SL_COL_##name] = head,
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

static void csv_value(FILE *f, const struct sl_cell_record *r, enum sl_cell_col col)
{
#define SL_CSV_text(name)     fprintf(f, "%s", r->name);
#define SL_CSV_path(name)     fprintf(f, "%s", r->name);
#define SL_CSV_dim(name)      fprintf(f, "%d", r->name);
#define SL_CSV_index(name)    fprintf(f, "%d", r->name);
#define SL_CSV_runs(name)     fprintf(f, "%d", r->name);
#define SL_CSV_flag(name)     fprintf(f, "%d", r->name);
#define SL_CSV_count(name)    fprintf(f, "%llu", (unsigned long long)SL_CELL_U64_count(r, name));
#define SL_CSV_wrong(name)    fprintf(f, "%llu", (unsigned long long)SL_CELL_U64_wrong(r, name));
#define SL_CSV_ms(name)       fprintf(f, "%.3f", r->name);
#define SL_CSV_viewport(name) fprintf(f, "%dx%d", r->vw, r->vh);
    switch (col) {
#define SL_CSV_CASE(name, kind, size, csv, head, check, key) \
    case SL_COL_##name: SL_CSV_##kind(name) break;
    SL_CELL_COLUMNS(SL_CSV_CASE)
#undef SL_CSV_CASE
    case SL_COL_COUNT:
        break;
    }
}

void sl_out_write_costs_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    char machine[300];
    machine_of(&res->prov, machine, sizeof machine);
    enum sl_cell_col order[SL_COL_COUNT];
    int ncols = csv_order(order);
    for (int j = 0; j < ncols; j++)
        fprintf(f, "%s%s", j ? "," : "", csv_head[order[j]]);
    fprintf(f, ",git_sha,config_hash,machine\n");
    for (int i = 0; i < res->ncells; i++) {
        struct sl_cell_record r;
        sl_out_record(c, &res->cells[i], &r);
        for (int j = 0; j < ncols; j++) {
            if (j)
                fputc(',', f);
            csv_value(f, &r, order[j]);
        }
        fprintf(f, ",%s,%016llx,\"%s\"\n", res->prov.git_sha, c->hash, machine);
    }
}

void sl_out_write_costs_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "\n## Cost per cell (ms; G-buffer and truth are shared by the cells of a view)\n\n");
    fprintf(f, "| cell | scene | viewpoint | map | label | G-buffer | truth | fit | map render | readback "
               "| method (median of %d) | of which rays | rays | lookups | ray-tri tests | GS prims | contours | figures | overlay |\n", c->runs);
    fprintf(f, "|---:|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        const struct sl_stage_ms *s = &cl->ms;
        fprintf(f, "| %d | %s | %s | %d | %s | %.1f | %.1f%s | %.1f | %.1f | %.1f | %.1f | %.1f | %llu | %llu | %llu | %llu | %.1f | %.1f | %.1f |\n",
                cl->index, cl->scene, cl->viewpoint, c->maps[cl->key.map], c->methods[cl->key.method].label,
                s->gbuffer_render[SL_MED] + s->gbuffer_readback, s->truth[SL_MED], cl->truth_cached ? " (cached)" : "",
                s->fit, s->map_render[SL_MED], s->map_readback, s->method[SL_MED], cl->cost.ms_trace,
                (unsigned long long)cl->cost.rays,
                (unsigned long long)cl->cost.lookups, (unsigned long long)cl->cost.tri_tests,
                (unsigned long long)cl->gs_prims, s->contours, s->figures, s->overlay);
    }
    fprintf(f, "\nTotal %.0f ms (scenes %.1f ms, BVH %.1f ms); %d cell(s) computed, %d already stored.\n",
            res->ms_total, res->ms_scene, res->ms_bvh, res->ncells, res->skipped);
}

void sl_out_write_patterns_csv(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "cell,scene,viewpoint,viewport,map_size,label,texels,region,shadowed_texels,pixels,"
               "shadowed_in_truth,git_sha,config_hash\n");
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        if (!cl->has_patterns)
            continue;
        int n = c->methods[cl->key.method].params.texels;
        for (int r = 0; r < cl->fig.nregions; r++)
            for (int k = 0; k <= n; k++) {
                char rn[16];
                if (cl->fig.r[r].thickness)
                    snprintf(rn, sizeof rn, "%dpx", cl->fig.r[r].thickness);
                else
                    snprintf(rn, sizeof rn, "image");
                fprintf(f, "%d,%s,%s,%dx%d,%d,%s,%d,%s,%d,%llu,%llu,%s,%016llx\n", cl->index, cl->scene,
                        cl->viewpoint, c->viewport_w[cl->key.viewport], c->viewport_h[cl->key.viewport],
                        c->maps[cl->key.map], c->methods[cl->key.method].label, n, rn, k,
                        (unsigned long long)cl->pattern[r][k][0], (unsigned long long)cl->pattern[r][k][1],
                        res->prov.git_sha, c->hash);
            }
    }
}

void sl_out_write_patterns_md(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    int any = 0;
    for (int i = 0; i < res->ncells; i++)
        any |= res->cells[i].has_patterns;
    if (!any)
        return;
    fprintf(f, "\n## Texel coherence: undecided pixels by how many texels say shadow "
               "(pixels, of which shadowed in truth)\n\n");
    fprintf(f, "| cell | scene | viewpoint | map | label | region | 1 | 2 | 3 | 4 | 5 | 6 | 7 | 8 |\n");
    fprintf(f, "|---:|---|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < res->ncells; i++) {
        const struct sl_cell *cl = &res->cells[i];
        if (!cl->has_patterns)
            continue;
        int n = c->methods[cl->key.method].params.texels;
        for (int r = 0; r < cl->fig.nregions; r++) {
            char rn[16];
            if (cl->fig.r[r].thickness)
                snprintf(rn, sizeof rn, "%d px", cl->fig.r[r].thickness);
            else
                snprintf(rn, sizeof rn, "image");
            fprintf(f, "| %d | %s | %s | %d | %s | %s |", cl->index, cl->scene, cl->viewpoint,
                    c->maps[cl->key.map], c->methods[cl->key.method].label, rn);
            for (int k = 1; k <= 8; k++) {
                if (k < n)
                    fprintf(f, " %llu (%llu) |", (unsigned long long)cl->pattern[r][k][0],
                            (unsigned long long)cl->pattern[r][k][1]);
                else
                    fprintf(f, " |");
            }
            fprintf(f, "\n");
        }
    }
}

void sl_out_write_run_yaml(FILE *f, const struct sl_config *c, const struct sl_run_result *res)
{
    fprintf(f, "config: %s\nconfig_hash: %016llx\n", c->path, c->hash);
    sl_provenance_write(&res->prov, f, "");
    fprintf(f, "cells_computed: %d\ncells_skipped: %d\nms_total: %.1f\n", res->ncells, res->skipped,
            res->ms_total);
}
