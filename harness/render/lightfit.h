/*
 * lightfit.h — the light frustum, fitted per view: orthographic for a
 * directional light, perspective from the centre of an area light taken as
 * a point (lightfit.c, fit_point). For a directional light, as the seeds
 * did: "the minimum size needed to contain the objects seen
 * by the camera, including all geometry that could influence lighting".
 *
 * Receivers are the PFL pixels of the view (the only points whose shadow is
 * looked up); across the light the box is their light-space bounds, and along
 * the light it runs from the nearest triangle that overlaps those bounds
 * (every possible caster: a directional light's shadow rays are parallel, so
 * nothing outside the receivers' cross-section can shadow them) to the
 * farthest receiver. Small relative margins keep the boundary points inside.
 * Does not: render or read GL.
 */
#ifndef SL_LIGHTFIT_H
#define SL_LIGHTFIT_H
#include "frame.h"
#include "scene.h"
#include "view.h"

void sl_light_fit(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out);

/* Stabilised frames for a directional light (issue 23: shadows under
 * motion), the options engines use so a shadow map does not crawl as the
 * camera moves. `fit`:
 *   SL_FIT_TIGHT   sl_light_fit above (the seeds'; changes size and place
 *                  with every view);
 *   SL_FIT_SPHERE  a fixed size: across the light the square around the
 *                  bounding sphere of the camera's frustum (near to far; its
 *                  radius depends on fov, aspect, near and far only, so it
 *                  does not change as the camera turns or moves), rounded up
 *                  to 1/16 unit, with one texel of slack on each side; along
 *                  the light the scene's whole depth (fixed for a fixed light).
 * `snap` (SL_FIT_SPHERE only): the square's corner moves in whole texels of
 * the fixed light view (sl_light_view), so a camera moving across the light
 * shifts the map by whole texels instead of resampling it. The box holds
 * every PFL pixel of the view (they lie in the frustum, so in the sphere);
 * n_receivers counts them. Area lights are refused by config.c. */
enum sl_fit_kind { SL_FIT_TIGHT = 0, SL_FIT_SPHERE = 1 };
struct sl_fit_opts {
    int fit;     /* enum sl_fit_kind */
    int snap;    /* 1: whole texels (SL_FIT_SPHERE) */
};
void sl_light_fit_stable(const struct sl_scene *s, const struct sl_view *v, const struct sl_fit_opts *o, int size,
                         struct sl_light_box *out);

/* The light view basis for a direction (shared by the fit and the tests). */
void sl_light_view(const float dir[3], mat4 view);

#endif
