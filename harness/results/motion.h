/*
 * motion.h — the temporal tables: per (scene, path, viewport, map size,
 * label), over a path's frames (pathfile.h) as the store or a run holds
 * them, the mean and worst per-frame wrong pixels (the whole image), the
 * flicker between consecutive frames (temporal.h) in all, per compared pair
 * and at worst, and per 1,000 contour pixels (the thinnest contour of the
 * later frame of each compared pair, drawn as the config says). Also the
 * per-frame series a plot draws.
 *
 * A cell is a path's frame when its viewpoint is named "<path>.<NNN>" (a
 * path's frames are so named, and a named viewpoint of that form would be
 * refused by the scene file where a path shares the name). A pair not
 * compared (flicker_compared 0: a path's first frame, or one whose previous
 * frame another process or run computed) counts toward the wrong pixels but
 * not toward flicker: `pairs` says how many were compared.
 *
 * Owns: the rows it returns (free()). Does not: read the store or print.
 */
#ifndef SL_MOTION_H
#define SL_MOTION_H
#include <stdio.h>
#include "cellcols.h"
#include "sl_error.h"
#include "table.h"

struct sl_motion_row {
    char     scene[64], path[24], label[48];
    int      vw, vh, map_size;
    int      frames, pairs;             /* frames held; pairs compared */
    double   mean_wrong;
    uint64_t worst_wrong;
    int      worst_frame;
    uint64_t flicker, worst_flicker, compared, contour_px;
    int      worst_flicker_frame;
    double   mean_flicker;              /* per compared pair */
    double   per_1000;                  /* flicker per 1,000 contour pixels; NAN when none */
};

/* Frame number of a viewpoint name "<path>.<NNN>" with the path's name in
 * path (n bytes), -1 when it is not a frame's. */
int sl_motion_frame_of(const char *viewpoint, char *path, size_t n);

/* The rows of cells (any order), sorted by scene, path, viewport, map size
 * and label's first appearance; *nrows 0 when no cell is a frame. */
enum sl_err sl_motion_rows(const struct sl_cell_record *cells, int ncells, struct sl_motion_row **rows,
                           int *nrows, struct sl_diag *d);

/* The tables, built as the table model (tabmodel.h) and written by its
 * emitter: Markdown, a table per (scene, path, viewport, map size); CSV, one
 * data table of every row; LaTeX, per group two booktabs tables paged by
 * rows (the model's paged mode: floats, so a two-column class takes them),
 * the wrong pixels and the flicker, each fitting \columnwidth. SL_E_NOMEM
 * when the model cannot be built. */
enum sl_err sl_motion_write(FILE *f, enum sl_table_format fmt, const struct sl_motion_row *rows, int n,
                            struct sl_diag *d);

/* The per-frame series of one (scene, path, viewport, map size) for a plot:
 * one line per frame "frame wrong_1 flicker_1 wrong_2 flicker_2 ..." in the
 * order of labels[] (flicker "NaN" where not compared, "-" where no cell);
 * returns the frames written. */
int sl_motion_series(FILE *f, const struct sl_cell_record *cells, int ncells, const struct sl_motion_row *row,
                     char (*labels)[48], int nlabels);

#endif
