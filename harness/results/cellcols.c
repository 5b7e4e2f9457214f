/*
 * cellcols.c — see cellcols.h.
 */
#include "cellcols.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

void sl_cell_record_init(struct sl_cell_record *r)
{
    memset(r, 0, sizeof *r);
#define SL_NAN_OF(name, kind, size, csv, head, check, key, from) SL_NAN_IF_##kind(name)
#define SL_NAN_IF_ms(name) r->name = NAN;
#define SL_NAN_IF_text(name)
#define SL_NAN_IF_path(name)
#define SL_NAN_IF_dim(name)
#define SL_NAN_IF_index(name)
#define SL_NAN_IF_runs(name)
#define SL_NAN_IF_count(name)
#define SL_NAN_IF_viewport(name)
#define SL_NAN_IF_wrong(name)
#define SL_NAN_IF_flag(name)
    SL_CELL_COLUMNS(SL_NAN_OF)
}

void sl_region_name(int thickness, char *out, size_t n)
{
    if (thickness == 0)
        snprintf(out, n, "image");
    else
        snprintf(out, n, "%dpx", thickness);
}

int sl_region_thickness(const char *name)
{
    if (!name)
        return -1;
    if (strcmp(name, "image") == 0)
        return 0;
    int t = 0, k = 0;
    while (name[k] >= '0' && name[k] <= '9' && t < 100000)
        t = 10 * t + (name[k++] - '0');
    return (k > 0 && t > 0 && strcmp(name + k, "px") == 0) ? t : -1;
}
