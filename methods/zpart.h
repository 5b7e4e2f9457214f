/*
 * zpart.h — what zpart.c shares with the tests: the slice of every pixel.
 * The method itself is sl_method_zpart in the registry (method.h).
 */
#ifndef SL_ZPART_H
#define SL_ZPART_H
#include <stdint.h>
#include "view.h"

/* The split planes (planes[0..k]: eq. 62 with lambda over the visible
 * pixels' view depths) and each pixel's slice 0..k-1 (255: background). */
void sl_zpart_slices(const struct sl_view *v, int k, double lambda, double *planes, uint8_t *slice);

#endif
