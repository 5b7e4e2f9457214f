/*
 * overlay.h — the error overlay of one (view, map size, method), and an area
 * light's error heat map (sl_overlay_soft).
 *
 * The classes are the seeds' (Moderno 2011, Figures 17 and 49-51: wrongly
 * lit and wrongly shadowed inside the contour, any wrong pixel outside it,
 * undecided pixels), each drawn in the Okabe–Ito colour nearest the seed's
 * own (red → vermillion, yellow → yellow, blue → blue, purple → reddish
 * purple, green → bluish green), so readers with a colour-vision deficiency
 * tell them apart. Errors are opaque and drawn last: nothing covers them.
 * The contour is only a faint tint of the grey (35% bluish green), so a
 * wrong pixel inside it keeps its full colour and the band itself does not
 * hide where errors sit (issue 16: a solid 2-px green band lay exactly over
 * them). The grey is kept dark (at most 0.62) so that every error colour
 * stands out from it by hue and by lightness.
 *
 * Also here, the two choices of the overlay sheet (the file, image.h): the
 * part of the frame worth showing (the scene's bounding box when it fills
 * little of the frame) and the windows with most errors (the zoomed insets).
 *
 * Owns: nothing (fills the caller's buffers). Does not: write files (image.h).
 */
#ifndef SL_OVERLAY_H
#define SL_OVERLAY_H
#include <stdint.h>
#include "method.h"
#include "view.h"

/* The overlay's classes, in the order the legend lists them. */
enum sl_ov_class {
    SL_OV_LIT_WRONG = 0,    /* said lit, shadowed in truth, inside the contour */
    SL_OV_SHADOW_WRONG,     /* said shadowed, lit in truth, inside the contour */
    SL_OV_WRONG_OUTSIDE,    /* either, outside the contour */
    SL_OV_UNCERTAIN,        /* left undecided */
    SL_OV_CONTOUR,          /* a right pixel inside the contour (faint tint) */
    SL_OV_OUTSIDE_CONE,     /* a right pixel outside a spot light's cone (view.h): unlit by
                             * definition, hatched dark grey, drawn over the contour's tint */
    SL_OV_CLASSES
};
/* Okabe–Ito colours of the classes (the contour's is blended at 35%); the
 * outside-cone class is no colour but grey: its legend swatch is the
 * hatching's light stripe. */
extern const uint8_t sl_overlay_colour[SL_OV_CLASSES][3];

/* rgb: 3 * w * h bytes, bottom-up rows. err (w * h, may be NULL): 255 where
 * the pixel is wrong or uncertain (the pixels the sheet never draws over),
 * else 0. count (may be NULL): pixels per class. Lit pixels are shaded by
 * n.l: l = -light_dir, or toward light_pos (3 floats) where it is given (a
 * spot, point or area light: a fixed direction would leave a point light's
 * image dark). */
void sl_overlay_build(const struct sl_view *v, const float light_dir[3], const float *light_pos,
                      const struct sl_verdicts *vd,
                      const uint8_t *band, int thickness, uint8_t *rgb, uint8_t *err,
                      uint64_t count[SL_OV_CLASSES]);

/* The lit colours of a view's pixels (n.l shading, the contour's tint),
 * which depend on the view, the light and the bands, not on the method:
 * drawn once and kept for the view's next cells. Zero it before first use. */
struct sl_overlay_shade {
    uint64_t serial;          /* the view's (view.h) */
    size_t   n;               /* pixels held */
    float    light_dir[3], light_pos[3];
    int      has_pos, thickness;
    uint8_t *band;            /* the bands they were drawn with (compared whole: cheap beside the drawing) */
    uint8_t *lit;             /* 3 bytes a pixel */
};
void sl_overlay_shade_free(struct sl_overlay_shade *sh);

/* sl_overlay_build, the lit colours taken from sh (drawn into it first when
 * it holds another view, light, bands or thickness); the same bytes and
 * counts. sh NULL, or no memory: as sl_overlay_build. */
void sl_overlay_build_shaded(struct sl_overlay_shade *sh, const struct sl_view *v, const float light_dir[3],
                             const float *light_pos, const struct sl_verdicts *vd, const uint8_t *band,
                             int thickness, uint8_t *rgb, uint8_t *err, uint64_t count[SL_OV_CLASSES]);

/* A rectangle of pixels, y = 0 the bottom row. */
struct sl_ov_box { int x, y, w, h; };

/* The part of the frame worth showing: the scene's bounding box (pixels
 * whose truth is not background) when it covers less than half the frame;
 * else, given the contour bands (band, and err: nonzero where wrong or
 * uncertain; either may be NULL), the box of the contours and the errors
 * padded by 1/16 of the frame's shorter side, when that covers less than half
 * (a ground plane filling the frame around small casters: Bench, Trees).
 * Boxes are padded by at least pad and clamped to the frame. Returns 1 when
 * *out is such a crop, 0 when it is the whole frame. */
int sl_overlay_crop(const struct sl_view *v, const uint8_t *band, const uint8_t *err, int pad,
                    struct sl_ov_box *out);

/* Up to n windows of s x s pixels holding the most nonzero pixels of err,
 * chosen greedily: the first holds the most of any window (ties: the lowest,
 * then leftmost), each next one the most of any window overlapping none
 * chosen before; windows holding none are not chosen. count[k]: nonzero
 * pixels in window k. Returns the number chosen, or -1 when out of memory.
 * Cost: one summed-area table and n scans of every window position. */
int sl_overlay_insets(int w, int h, const uint8_t *err, int s, int n, struct sl_ov_box *out, uint64_t *count);

/* An area light's error heat map: the visible fraction vis as grey; where it
 * is off the truth by more than 0.05, vermillion where too dark and blue
 * where too light (Okabe–Ito), stronger with the error; background
 * (tri == 0) black. */
void sl_overlay_soft(int w, int h, const uint32_t *tri, const float *vis, const float *truth, uint8_t *rgb);

#endif
