/*
 * runhelp.c — see runhelp.h.
 */
#include "runhelp.h"
#include <math.h>

/* G-buffer values that are not finite (positions, normals of non-background
 * pixels). A hard case must never produce one (tests/test_hard.c). */
uint64_t sl_run_view_bad(const struct sl_view *v)
{
    uint64_t n = 0;
    size_t np = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < np; i++)
        if (v->cls[i] != SL_C_BACKGROUND)
            for (int k = 0; k < 3; k++)
                n += !isfinite(v->pos[3 * i + k]) + !isfinite(v->nrm[3 * i + k]);
    return n;
}

/* Shadow-map depths outside [0, 1] or not finite. */
uint64_t sl_run_layer_bad(const struct sl_depth_layer *l, int size)
{
    uint64_t n = 0;
    size_t nt = (size_t)size * (size_t)size;
    for (size_t i = 0; i < nt; i++)
        n += !(l->depth[i] >= 0.0f && l->depth[i] <= 1.0f);
    return n;
}
