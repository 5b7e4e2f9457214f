/*
 * view.c — see view.h.
 */
#include "view.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

void sl_view_free(struct sl_view *v)
{
    if (!v)
        return;
    free(v->pos);
    free(v->nrm);
    free(v->tri);
    free(v->cls);
    free(v->truth);
    free(v->outside);
    memset(v, 0, sizeof *v);
}

uint64_t sl_view_bad(const struct sl_view *v)
{
    uint64_t n = 0;
    size_t np = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < np; i++)
        if (v->cls[i] != SL_C_BACKGROUND)
            for (int k = 0; k < 3; k++)
                n += !isfinite(v->pos[3 * i + k]) + !isfinite(v->nrm[3 * i + k]);
    return n;
}

