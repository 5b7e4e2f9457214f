/*
 * fitopts.h — how a label's own light frame is fitted (config
 * 'light_frame: {fit: tight|sphere, snap: bool}'): the options alone, so a
 * config holds them without the fitting (lightfit.h, sl_light_fit_stable,
 * says what each does).
 *
 * Owns: nothing. Does not: fit anything.
 */
#ifndef SL_FITOPTS_H
#define SL_FITOPTS_H

enum sl_fit_kind { SL_FIT_TIGHT = 0, SL_FIT_SPHERE = 1 };
struct sl_fit_opts {
    int fit;     /* enum sl_fit_kind */
    int snap;    /* 1: whole texels (SL_FIT_SPHERE) */
};

#endif
