/*
 * ovwriter.h — the overlay sheets written by a worker thread while the next
 * cell runs (issue 20: composing and compressing a sheet's PNG was 22% of
 * the Moderno study, all of it on the cell's critical path).
 *
 * The writer owns a few slots (depth, at most SL_OVW_MAX_DEPTH), each with
 * its own RGB and keep-mask buffers, allocated once per frame size and
 * reused. A cell takes a free slot (sl_ovw_acquire: waits while every slot
 * is queued or being written, so at most `depth` sheets are in flight and
 * memory stays bounded), draws its overlay straight into the slot's buffers
 * and hands the slot back with the sheet's description (sl_ovw_submit); the
 * worker composes and writes it (sl_image_write_sheet, the very call a cell
 * makes without a writer, so the file is byte for byte the same). Nothing
 * the worker reads points into the run's scratch: the next cell may
 * overwrite its own buffers at once.
 *
 * Errors: the first failed write is kept with its diagnostic (the file
 * named, as sl_image_write_sheet gives it) and returned by every later
 * acquire, submit and wait, so the run fails with the same error id and
 * message as when the cell wrote the sheet itself; the sheets still queued
 * then are dropped. The run waits (sl_ovw_wait) before its staging folder is
 * renamed into place, and closes the writer (sl_ovw_close, which waits too)
 * before the folder is dropped on an error or an interrupt.
 *
 * Owns: the worker thread and the slots' buffers. Does not: draw overlays
 * (score/overlay.h) or compose sheets (image.h). The worker blocks every
 * signal, so SIGINT and SIGTERM reach the run's thread, whose handler asks
 * the loop to stop.
 */
#ifndef SL_OVWRITER_H
#define SL_OVWRITER_H
#include "image.h"
#include "sheetsink.h"
#include "sl_error.h"

#define SL_OVW_MAX_DEPTH 4

struct sl_ovw;

/* A slot's buffers, w * h pixels: rgb 3 * w * h bytes (bottom-up rows), keep
 * w * h bytes (the sheet's keep mask, also free scratch for the cell). */
struct sl_ovw_slot {
    unsigned char *rgb, *keep;
    int w, h;
};

/* A writer with `depth` slots (1 .. SL_OVW_MAX_DEPTH; 0 means 2) and its
 * worker thread started. */
enum sl_err sl_ovw_open(int depth, struct sl_ovw **out, struct sl_diag *d);

/* A free slot whose buffers hold w * h pixels (contents undefined), waiting
 * while every slot is in flight. Returns an earlier sheet's write error
 * instead (*slot NULL). */
enum sl_err sl_ovw_acquire(struct sl_ovw *w, int width, int height, struct sl_ovw_slot **slot,
                           struct sl_diag *d);

/* Queue the slot's sheet for path (copied). s->rgb must be slot->rgb, s->keep
 * slot->keep or NULL, s->w and s->h the slot's; header attributes are not
 * carried (s->nattrs must be 0). The slot belongs to the writer from here. */
enum sl_err sl_ovw_submit(struct sl_ovw *w, struct sl_ovw_slot *slot, const char *path,
                          const struct sl_image_sheet *s, struct sl_diag *d);

/* Give an acquired slot back unwritten (the cell failed before submitting). */
void sl_ovw_release(struct sl_ovw *w, struct sl_ovw_slot *slot);

/* Wait until every queued sheet is written. SL_OK, or the first write error
 * with its diagnostic. */
enum sl_err sl_ovw_wait(struct sl_ovw *w, struct sl_diag *d);

/* Sheets written so far and the worker's time on them, ms: wall, and its
 * thread's CPU time (ms_cpu may be NULL): what the cells no longer pay. */
void sl_ovw_stats(const struct sl_ovw *w, int *written, double *ms, double *ms_cpu);

/* Wait, stop the worker, free everything. NULL-safe. */
void sl_ovw_close(struct sl_ovw *w);

/* The writer as the sink scoring hands its sheets to (sheetsink.h):
 * acquire, submit and release of this writer. */
struct sl_sheet_sink sl_ovw_sink(struct sl_ovw *w);

#endif
