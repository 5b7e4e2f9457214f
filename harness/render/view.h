/*
 * view.h — what the camera sees, once per scene x viewpoint x viewport:
 * the G-buffer read back from GL and, per pixel, its class and its truth.
 *
 * Pixel (x, y) is at index y * w + x with y = 0 the bottom row (GL's order);
 * images are flipped only when written to files.
 *
 * Owns: the per-pixel arrays (sl_view_free). Does not: render (gbuffer.c) or
 * trace (truth.c); nothing here depends on a method.
 */
#ifndef SL_VIEW_H
#define SL_VIEW_H
#include <stdint.h>
#include <cglm/cglm.h>
#include "scene.h"

/* The truth of one pixel. PnFL pixels (dot(n, l) <= 0 with n the face normal
 * turned toward the camera and l toward the light) are shadowed by definition
 * and counted apart from the PFL ones, as in Morais 2015. Under an area
 * light, l points to its centre and a PFL pixel also lies on the side the
 * light emits (sl_point_faces): the classes and this truth are those of the
 * point the hard-shadow methods take the light for. */
enum sl_truth {
    SL_T_BACKGROUND = 0,
    SL_T_PNFL       = 1,
    SL_T_LIT        = 2,   /* PFL, no occluder toward the light */
    SL_T_SHADOW     = 3,   /* PFL, occluded */
};

/* What a method may know of a pixel: its class. */
enum sl_class {
    SL_C_BACKGROUND = 0,
    SL_C_PNFL       = 1,
    SL_C_PFL        = 2,
};

struct sl_view {
    int       w, h;
    int       vp;          /* viewpoint index in the scene */
    mat4      view, proj;  /* camera matrices (cglm, column-major) */
    float    *pos;         /* 3 per pixel, world position (GL-interpolated) */
    float    *nrm;         /* 3 per pixel, unit face normal turned toward the camera */
    uint32_t *tri;         /* triangle index + 1; 0 marks background */
    uint8_t  *cls;         /* enum sl_class */
    uint8_t  *truth;       /* enum sl_truth; NULL in the copy methods get */
    uint64_t  n_background, n_pnfl, n_pfl, n_lit, n_shadow;
    /* Under a spot light: 1 where the pixel lies outside the cone
     * (sl_spot_inside false), else 0; NULL under any other light. Such a
     * pixel is unlit by definition: its class and truth stay PnFL (methods
     * never look it up, the figures count it as PnFL), and n_outside_cone
     * counts it apart, a part of n_pnfl (the tables print n_pnfl -
     * n_outside_cone as "facing away"). A pixel both facing away and
     * outside the cone counts as outside the cone (gbuffer.c says why). */
    uint8_t  *outside;
    uint64_t  n_outside_cone;
    /* Unique per G-buffer render in this process (gbuffer.c), never 0: the
     * key of what is computed from the view alone and kept across its cells
     * (the aliasing error m, aliasing.h). A copy keeps it: copies are the
     * same pixels. */
    uint64_t  serial;
};

void sl_view_free(struct sl_view *v);

/* G-buffer values that are not finite (positions, normals of non-background
 * pixels). A hard case must never produce one (tests/test_hard.c). */
uint64_t sl_view_bad(const struct sl_view *v);

#endif
