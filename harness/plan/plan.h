/*
 * plan.h — the sweep a config expands to: a list of independent cells,
 * scene x viewport x viewpoint x map size x method label, each with an
 * index (so `--cells A:B` can split a sweep across machines and processes),
 * and what each group of cells sharing a view and a map size needs rendered.
 *
 * Owns: nothing (pure functions of the config). Does not: run a cell
 * (run.c), score it (cell.c) or write it anywhere.
 */
#ifndef SL_PLAN_H
#define SL_PLAN_H
#include <stdint.h>
#include "cellkey.h"
#include "config.h"

/* Number of cells of the sweep, and the key of the cell at `index`. */
int  sl_plan_count(const struct sl_config *c);
void sl_plan_cell(const struct sl_config *c, int index, struct sl_cell_key *k);

/* The index of the cell of key k (the inverse of sl_plan_cell). */
int  sl_plan_index(const struct sl_config *c, const struct sl_cell_key *k);

/* The layers (SL_NEED bits of frame.h and method.h) wanted by the selected
 * cells of the (view, map size) group that starts at cell `from` (a group's
 * cells are contiguous in sweep order), leaving out the cells a resumed run
 * will skip: skip[i] set for cell i (indexed by cell; NULL: none). */
unsigned sl_plan_group_needs(const struct sl_config *c, int from, int last, const uint8_t *skip);

/* Of those layers, the ones every selected cell of the group that reads
 * them reads only at each pixel's own texel (method.h: at_pixel): the run
 * may hold them gathered per pixel (frame.h, sl_frame_gather). */
unsigned sl_plan_group_at_pixel(const struct sl_config *c, int from, int last, const uint8_t *skip);

/* Of those layers, the ones that selected cells of the group read through
 * the lookups the run makes per view (method.h: looks; frame.h:
 * sl_frame_look): looks[0] read so by one cell or more, looks[1] by two or
 * more (worth a pass of their own). */
void sl_plan_group_looks(const struct sl_config *c, int from, int last, const uint8_t *skip, unsigned looks[2]);

/* Split the sweep into at most n slices [b[i], b[i+1]) (b holds n + 1
 * ints) for tasks or worker processes: balanced by cell count, each cut moved
 * to a view boundary (scene, viewport, viewpoint) when one lies within a
 * quarter of a slice, so a view's G-buffer and truth are computed in one task. Returns
 * the number of slices (no empty one). */
int sl_plan_slices(const struct sl_config *c, int n, int *b);
/* How much sharing a split loses: the views that start a second time
 * (a slice beginning inside a view renders its G-buffer and traces or reads
 * its truth again); *nviews: the sweep's views. */
int sl_plan_split_views(const struct sl_config *c, const int *b, int n, int *nviews);

#endif
