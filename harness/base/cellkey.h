/*
 * cellkey.h — the key of one cell of a sweep: which scene, viewport,
 * viewpoint, map size and method label, as indices into the config's
 * lists (config.h). A plain value every stage may hold (plan.h makes them,
 * scoring and the results carry them), so it sits below them all.
 *
 * Owns: nothing. Does not: know the config's lists (plan.h maps a key to
 * its index in the sweep and back).
 */
#ifndef SL_CELLKEY_H
#define SL_CELLKEY_H

struct sl_cell_key {
    int scene;      /* index into config scenes */
    int viewport;   /* index into config viewports */
    int vp;         /* index into that scene's config viewpoints */
    int map;        /* index into config map sizes */
    int method;     /* index into config methods */
};

#endif
