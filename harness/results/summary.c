/*
 * summary.c — see summary.h. Invariant: every value printed is one cell's
 * percentage (best, worst, average case) or the plain mean of those the
 * average runs over; ties keep the first cell in the caller's order.
 */
#include "summary.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "util.h"

struct pick { const struct sl_cell_record *cell; int region; double v; };

static int wanted(const struct sl_summary_opts *o, int thickness)
{
    return o->region < 0 ? thickness != 0 : thickness == o->region;
}

enum sl_err sl_summary_write(FILE *out, enum sl_table_format fmt, const struct sl_cell_record *cells, int n,
                             const struct sl_summary_opts *o, struct sl_diag *d)
{
    if (o->figure < 0 || o->figure >= SL_FIG_COUNT)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--summary", "unknown figure");
    if (!sl_figure_of((enum sl_figure)o->figure)[0])
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--summary", "'%s' is a count, not a percentage",
                       sl_figure_name((enum sl_figure)o->figure));
    for (int i = 1; i < n; i++)
        if (strcmp(cells[i].label, cells[0].label) != 0)
            return sl_fail(d, SL_E_USAGE, NULL, 0, "--label",
                           "cells of several labels ('%s', '%s'): summarise one at a time", cells[0].label,
                           cells[i].label);
    /* map sizes, ascending */
    int maps[64], nmaps = 0;
    for (int i = 0; i < n; i++) {
        int m = cells[i].map_size, k = 0;
        while (k < nmaps && maps[k] != m)
            k++;
        if (k == nmaps && nmaps < 64)
            maps[nmaps++] = m;
    }
    for (int a = 1; a < nmaps; a++)
        for (int b = a; b > 0 && maps[b - 1] > maps[b]; b--) {
            int t = maps[b]; maps[b] = maps[b - 1]; maps[b - 1] = t;
        }
    double sum = 0.0;
    long count = 0;
    struct pick best[64], worst[64], avgcase = {NULL, 0, NAN};
    for (int k = 0; k < nmaps; k++)
        best[k] = worst[k] = (struct pick){NULL, 0, NAN};
    for (int i = 0; i < n; i++) {
        const struct sl_cell_record *c = &cells[i];
        int k = 0;
        while (maps[k] != c->map_size)
            k++;
        for (int r = 0; r < c->fig.nregions; r++) {
            int t = c->fig.r[r].thickness;
            double v = c->fig.r[r].pct[o->figure];
            if (o->avg_scene && !strcmp(c->scene, o->avg_scene) && o->avg_viewpoint &&
                !strcmp(c->viewpoint, o->avg_viewpoint) && t == o->avg_region &&
                (!o->avg_map || o->avg_map == c->map_size) && !avgcase.cell)
                avgcase = (struct pick){c, t, v};
            if (!wanted(o, t) || isnan(v))
                continue;
            sum += v;
            count++;
            int better = o->lower_is_better ? v < best[k].v : v > best[k].v;
            int worse = o->lower_is_better ? v > worst[k].v : v < worst[k].v;
            if (!best[k].cell || better)
                best[k] = (struct pick){c, t, v};
            if (!worst[k].cell || worse)
                worst[k] = (struct pick){c, t, v};
        }
    }
    if (!count)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--summary", "no cell has a value for '%s' in that region",
                       sl_figure_name((enum sl_figure)o->figure));
    const char *name = sl_figure_name((enum sl_figure)o->figure);
    double avg = sum / (double)count;
    char rn[16];
    if (fmt == SL_TABLE_CSV) {
        fprintf(out, "figure,label,kind,map_size,scene,viewpoint,region,percent\n");
        fprintf(out, "%s,%s,average,,,,,%.4f\n", name, cells[0].label, avg);
        for (int k = 0; k < nmaps; k++) {
            const struct pick *p[2] = {&best[k], &worst[k]};
            for (int w = 0; w < 2; w++) {
                if (!p[w]->cell)
                    continue;
                sl_region_name(p[w]->region, rn, sizeof rn);
                fprintf(out, "%s,%s,%s,%d,%s,%s,%s,%.4f\n", name, cells[0].label, w ? "worst" : "best", maps[k],
                        p[w]->cell->scene, p[w]->cell->viewpoint, rn, p[w]->v);
            }
        }
        if (avgcase.cell) {
            sl_region_name(avgcase.region, rn, sizeof rn);
            fprintf(out, "%s,%s,average case,%d,%s,%s,%s,%.4f\n", name, cells[0].label, avgcase.cell->map_size,
                    avgcase.cell->scene, avgcase.cell->viewpoint, rn, avgcase.v);
        }
        return SL_OK;
    }
    if (fmt != SL_TABLE_MD)
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--format", "summaries come as md or csv");
    fprintf(out, "## Summary of %s (%% of %s), label %s\n\n", name, sl_figure_of((enum sl_figure)o->figure),
            cells[0].label);
    fprintf(out, "| | average |");
    for (int k = 0; k < nmaps; k++)
        fprintf(out, " %d² best | %d² worst |", maps[k], maps[k]);
    if (avgcase.cell)
        fprintf(out, " average case |");
    fprintf(out, "\n|---|---:|");
    for (int k = 0; k < nmaps; k++)
        fprintf(out, "---:|---:|");
    if (avgcase.cell)
        fprintf(out, "---:|");
    const char *rows[] = {"scene", "viewpoint", "contour", "map", "value"};
    for (int row = 0; row < 5; row++) {
        fprintf(out, "\n| %s |", rows[row]);
        if (row == 4)
            fprintf(out, " %.2f |", avg);
        else
            fprintf(out, " |");
        int cols = 2 * nmaps + (avgcase.cell ? 1 : 0);
        for (int col = 0; col < cols; col++) {
            const struct pick *p = col < 2 * nmaps ? (col % 2 ? &worst[col / 2] : &best[col / 2]) : &avgcase;
            if (!p->cell) {
                fprintf(out, " |");
                continue;
            }
            sl_region_name(p->region, rn, sizeof rn);
            switch (row) {
            case 0:   /* with its light, as every heading names it: "lamp (spot light, 70°)" */
                fprintf(out, p->cell->light[0] ? " %s (%s) |" : " %s |", p->cell->scene, p->cell->light);
                break;
            case 1: fprintf(out, " %s |", p->cell->viewpoint); break;
            case 2: fprintf(out, " %s |", rn); break;
            case 3: fprintf(out, " %d² |", p->cell->map_size); break;
            case 4: fprintf(out, " %.2f |", p->v); break;
            }
        }
    }
    fprintf(out, "\n\nAverage over %ld (cell, region) values.\n", count);
    return SL_OK;
}
