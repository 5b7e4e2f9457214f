/*
 * runhelp.h — small checks of the run loop (run.c), kept apart so run.c
 * stays within its size limit: values of a view and of a shadow-map layer
 * that are not finite or out of range.
 *
 * Owns: nothing. Does not: print or decide anything (the run counts them
 * into the cell's `nonfinite`).
 */
#ifndef SL_RUNHELP_H
#define SL_RUNHELP_H
#include <stdint.h>
#include "frame.h"
#include "view.h"

/* G-buffer values that are not finite (positions, normals of non-background
 * pixels). A hard case must never produce one (tests/test_hard.c). */
uint64_t sl_run_view_bad(const struct sl_view *v);

/* Shadow-map depths outside [0, 1] or not finite. */
uint64_t sl_run_layer_bad(const struct sl_depth_layer *l, int size);

#endif
