/*
 * cellcols.c — see cellcols.h.
 */
#include "cellcols.h"
#include <math.h>
#include <string.h>

void sl_cell_record_init(struct sl_cell_record *r)
{
    memset(r, 0, sizeof *r);
#define SL_NAN_OF(name, kind, size, csv, head, check, key) SL_NAN_IF_##kind(name)
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
