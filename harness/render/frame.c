/*
 * frame.c — see frame.h: a frame's rays toward the light and the frees.
 */
#include "frame.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "arealight.h"

void sl_frame_toward(const struct sl_light_frame *f, const float p[3], float dir[3], float *tmax)
{
    if (!f->box.persp) {
        for (int k = 0; k < 3; k++)
            dir[k] = -f->dir[k];
        *tmax = INFINITY;
    } else if (!sl_point_ray(f->box.eye, p, dir, tmax)) {
        dir[0] = dir[1] = 0.0f;   /* at the light itself: no ray */
        dir[2] = 1.0f;
        *tmax = 0.0f;
    }
}

void sl_frame_free(struct sl_light_frame *f)
{
    if (!f)
        return;
    for (int i = 0; i < SL_LAYER_COUNT; i++) {
        free(f->layer[i].depth);
        free(f->layer[i].id);
    }
    memset(f, 0, sizeof *f);
}

void sl_light_box_free(struct sl_light_box *b)
{
    free(b->unmapped);
    b->unmapped = NULL;
    b->n_unmapped = 0;
}
