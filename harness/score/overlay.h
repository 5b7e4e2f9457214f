/*
 * overlay.h — the error overlay of one (view, map size, method), in the
 * seeds' colours (Moderno 2011, Figures 17 and 49-51) over a grey render
 * shaded by the method's own verdicts: contour green, wrongly lit red and
 * wrongly shadowed yellow inside the contour, any wrong pixel outside it blue;
 * undecided pixels purple (Moderno's colour for uncertain pixels). And an
 * area light's error heat map (sl_overlay_soft).
 *
 * Owns: nothing (fills the caller's rgb). Does not: write files (image.h).
 */
#ifndef SL_OVERLAY_H
#define SL_OVERLAY_H
#include <stdint.h>
#include "method.h"
#include "view.h"

/* rgb: 3 * w * h bytes, bottom-up rows. */
void sl_overlay_build(const struct sl_view *v, const float light_dir[3], const struct sl_verdicts *vd,
                      const uint8_t *band, int thickness, uint8_t *rgb);

/* An area light's error heat map: the visible fraction vis as grey; where it
 * is off the truth by more than 0.05, red where too dark and blue where too
 * light, stronger with the error; background (tri == 0) black. */
void sl_overlay_soft(int w, int h, const uint32_t *tri, const float *vis, const float *truth, uint8_t *rgb);

#endif
