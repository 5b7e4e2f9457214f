/*
 * view.c — see view.h.
 */
#include "view.h"
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
