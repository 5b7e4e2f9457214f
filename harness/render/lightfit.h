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

/* The light view basis for a direction (shared by the fit and the tests). */
void sl_light_view(const float dir[3], mat4 view);

#endif
