/*
 * cellsink.c — see cellsink.h.
 *
 * Invariant: a cell's row is written only after every sheet handed to the
 * writer so far is on disk (a kill between the two would lose the sheet of
 * a cell `--resume` then skips).
 */
#include "cellsink.h"
#include "motion_run.h"

enum sl_err sl_sink_open_overlays(struct sl_cell_sink *s, struct sl_diag *d)
{
    enum sl_err e = sl_ovw_open(2, &s->ovw, d);
    s->sheets = sl_ovw_sink(s->ovw);
    return e;
}

const struct sl_sheet_sink *sl_sink_sheets(const struct sl_cell_sink *s)
{
    return s->ovw ? &s->sheets : NULL;
}

enum sl_err sl_sink_open_store(struct sl_cell_sink *s, const struct sl_provenance *p, struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    if (s->store_path[0] && !(e = sl_store_open(s->store_path, &s->st, d)))
        e = sl_out_begin_run(s->st, s->config, p, &s->run_id, d);
    return e;
}

enum sl_err sl_sink_put(struct sl_cell_sink *s, const struct sl_cell *cell, struct sl_diag *d)
{
    enum sl_err e = SL_OK;
    if (s->st && !(e = sl_ovw_wait(s->ovw, d)))
        e = sl_out_store_cell(s->st, s->run_id, s->config, cell, s->store_path, s->write_files ? &s->dirs : NULL, d);
    return e;
}

enum sl_err sl_sink_drain(struct sl_cell_sink *s, struct sl_diag *d)
{
    return sl_ovw_wait(s->ovw, d);
}

enum sl_err sl_sink_finish(struct sl_cell_sink *s, struct sl_run_result *res, int resume, FILE *table_out,
                           struct sl_diag *d)
{
    const struct sl_config *c = s->config;
    enum sl_err e;
    if (!s->write_files)
        return s->st ? sl_store_seal(s->st, d) : SL_OK;
    if ((e = sl_out_stage_finish(c, res, &s->dirs, resume, d)))
        return e;
    res->stored_total = -1;
    if (s->st && c->tables)
        e = sl_out_rebuild_from_store(s->st, c, res->ncells, s->dirs.final, &res->stored_total, d);
    if (!e && c->tables)   /* a config naming paths: the temporal tables, plots, overlay sequences */
        e = sl_motion_outputs(s->st, c, res, s->dirs.final, d);
    if (!e && table_out && c->tables) {
        e = sl_out_print_tables(table_out, c, res, d);
        sl_out_write_costs_md(table_out, c, res);
        sl_out_write_patterns_md(table_out, c, res);
    }
    if (!e && s->st)
        e = sl_out_record_run_files(s->st, s->run_id, s->store_path, &s->dirs, d);
    /* last: the .db alone holds the whole store before "written to" */
    if (!e && s->st)
        e = sl_store_seal(s->st, d);
    return e;
}

void sl_sink_close(struct sl_cell_sink *s, struct sl_run_result *res, int failed)
{
    if (s->ovw) {
        sl_ovw_wait(s->ovw, NULL);
        sl_ovw_stats(s->ovw, &res->overlays_written, &res->ms_overlay_writer, &res->ms_overlay_writer_cpu);
    }
    sl_ovw_close(s->ovw);   /* no sheet is written into a folder being dropped */
    s->ovw = NULL;
    if (failed)
        sl_out_stage_drop(&s->dirs);
    sl_store_close(s->st);
    s->st = NULL;
}
