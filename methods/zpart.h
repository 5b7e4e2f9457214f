/*
 * zpart.h — what zpart.c shares with the tests: the slice of every pixel.
 * The method itself is sl_method_zpart in the registry (method.h).
 */
#ifndef SL_ZPART_H
#define SL_ZPART_H
#include <stdint.h>
#include "method.h"
#include "view.h"

/* The split planes (planes[0..k]: eq. 62 with lambda over the visible
 * pixels' view depths) and each pixel's slice 0..k-1 (255: background). */
void sl_zpart_slices(const struct sl_view *v, int k, double lambda, double *planes, uint8_t *slice);

/* The method's run for k slices of the given lambda, each map uniform or
 * LiSPSM (lispsm.c runs it with k = 1). */
enum sl_err sl_zpart_run_k(const struct sl_method_args *a, int k, double lambda, int lispsm,
                           struct sl_verdicts *out, struct sl_cost *c, struct sl_diag *d);

#endif
