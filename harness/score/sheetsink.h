/*
 * sheetsink.h — where scoring hands a drawn overlay sheet: a place that
 * lends the buffers to draw a sheet into and writes it once handed back
 * (results' overlay writer is one: ovwriter.h, sl_ovw_sink, whose worker
 * thread composes and compresses the PNG off the cell's path).
 *
 * Owns: nothing (an interface: the context is the provider's). Does not:
 * draw (cell.c and overlay.h do), or know how or when a sheet is written.
 */
#ifndef SL_SHEETSINK_H
#define SL_SHEETSINK_H
#include "image.h"
#include "sl_error.h"

struct sl_sheet_sink {
    void *ctx;
    /* Buffers for a width x height sheet (contents undefined): rgb 3 * w * h
     * bytes, keep w * h; *slot the handle to submit or release them with. */
    enum sl_err (*acquire)(void *ctx, int width, int height, void **slot, unsigned char **rgb, unsigned char **keep,
                           struct sl_diag *d);
    /* The sheet s drawn in slot's buffers, to be written to path (copied). */
    enum sl_err (*submit)(void *ctx, void *slot, const char *path, const struct sl_image_sheet *s,
                          struct sl_diag *d);
    /* An acquired slot back unwritten (the cell failed before submitting). */
    void (*release)(void *ctx, void *slot);
};

#endif
