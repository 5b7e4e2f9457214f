/*
 * motion_run.h — a run's outputs over paths (pathfile.h), written into the
 * run folder when its config names a path: motion.md, motion.csv and
 * motion.tex (the temporal tables of motion.h, from every stored cell of the
 * config, or from the run's cells without a store), and per (scene, path,
 * viewport, map size) under motion/:
 *   NAME.dat, NAME.gp   wrong pixels and flicker per frame per label (gnuplot;
 *                       `gnuplot NAME.gp` there draws NAME.png)
 *   NAME.png            drawn when gnuplot is in PATH (else the note says so)
 *   NAME-LABEL/frame-NNN.png  the frames' error overlays as a numbered
 *                       sequence (links to overlays/, when overlays are on)
 *   NAME-LABEL.mp4      that sequence through ffmpeg, when ffmpeg is in PATH
 * motion.md ends with a note of what was skipped and why.
 *
 * Owns: nothing. Does not: print (the caller gets SL_OK or an error).
 */
#ifndef SL_MOTION_RUN_H
#define SL_MOTION_RUN_H
#include "config.h"
#include "runresult.h"
#include "store.h"

/* 1 when any scene entry of the config names a path. */
int sl_motion_config_has_paths(const struct sl_config *c);

enum sl_err sl_motion_outputs(struct sl_store *st, const struct sl_config *c, const struct sl_run_result *res,
                              const char *dir, struct sl_diag *d);

#endif
