/*
 * lightfit.h — the light frustum, fitted per view: orthographic for a
 * directional light, perspective from a spot light's position along its
 * direction or from the centre of an area light taken as a point
 * (lightfit.c, fit_point). For a directional light, as the seeds
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
#include <math.h>
#include "fitopts.h"
#include "frame.h"
#include "scene.h"
#include "view.h"

void sl_light_fit(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out);

/* Threads (issue 20): the fits below with _mt run their loops over pixels
 * and triangles on `threads` OpenMP threads (<= 0: omp_get_max_threads()),
 * in blocks fixed by the input's size and combined in block order, so the
 * box (bounds, counts, the unmapped list and its order) is bit for bit the
 * one-thread fit's whatever the count (lightfit.c, "blocks";
 * lightfit::threads_bit_identical checks it). The names without _mt are
 * these on one thread. */
void sl_light_fit_mt(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out, int threads);

/* The perspective frame of a light at `eye` looking along the unit `axis`,
 * fitted as an area light's centre is (lightfit.c, fit_point: receivers'
 * tangents up to atan(8) off the axis, the rest counted in n_outside; its
 * casters, near and far planes, unmapped triangles), to the PFL pixels i
 * with mask[i] == value (mask NULL: every one). A spot light's frame is
 * this along its direction (sl_light_fit); a point light's cube faces are
 * this along each face's axis, over the pixels that face selects. */
void sl_light_fit_persp(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const float axis[3],
                        const uint8_t *mask, uint8_t value, struct sl_light_box *out);
/* The same with a guard band of `guard` texels of a size x size map on each
 * side beyond the receivers' tangents (a point light's cube face,
 * harness/render/lightframe.h): lookups up to `guard` texels across the receivers' edge
 * read the scene there. The band is added before the casters are chosen,
 * so the near plane holds the band's casters too. guard 0, or a map of at
 * most 2 guard texels: sl_light_fit_persp's frame. */
void sl_light_fit_face(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const float axis[3],
                       const uint8_t *mask, uint8_t value, int size, int guard, struct sl_light_box *out);
void sl_light_fit_face_mt(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const float axis[3],
                          const uint8_t *mask, uint8_t value, int size, int guard, struct sl_light_box *out,
                          int threads);

/* A point light's cube: face 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z (GL's
 * cube-map order). A point p belongs to the face of the major axis of
 * p - eye; ties go to the lower axis (x before y before z), so every point
 * has one face whatever its direction; p = eye goes to +x (and is left
 * outside its frame by the fit: no direction). */
static inline int sl_cube_face_of(const float eye[3], const float p[3])
{
    const float d[3] = {p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]};
    int a = 0;
    if (fabsf(d[1]) > fabsf(d[a]))
        a = 1;
    if (fabsf(d[2]) > fabsf(d[a]))
        a = 2;
    return 2 * a + (d[a] < 0.0f);
}
/* The six faces' frames at once: out[f] is sl_light_fit_face_mt's box for
 * face f (axis sl_cube_axis(f), the pixels with face[i] == f) bit for bit,
 * each pass over the pixels and triangles made once for the six. */
void sl_light_fit_cube_mt(const struct sl_scene *s, const struct sl_view *v, const float eye[3], const uint8_t *face,
                          int size, int guard, struct sl_light_box out[6], int threads);
/* face[i] = sl_cube_face_of(eye, pixel i's position) for every pixel of
 * v, on `threads` threads as above */
void sl_cube_faces(const float eye[3], const struct sl_view *v, uint8_t *face, int threads);
static inline void sl_cube_axis(int face, float axis[3])
{
    axis[0] = axis[1] = axis[2] = 0.0f;
    axis[face / 2] = face % 2 ? -1.0f : 1.0f;
}

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
void sl_light_fit_stable(const struct sl_scene *s, const struct sl_view *v, const struct sl_fit_opts *o, int size,
                         struct sl_light_box *out);
void sl_light_fit_stable_mt(const struct sl_scene *s, const struct sl_view *v, const struct sl_fit_opts *o, int size,
                            struct sl_light_box *out, int threads);

/* A directional light's box fitted as sl_light_fit does, to the PFL pixels
 * i with mask[i] == value only (a depth slice's receivers, zpart); its
 * casters are chosen against those receivers' cross-section as above.
 * Returns 0 (box zeroed) under an area light: slices are for directional
 * lights. With every PFL pixel marked it is sl_light_fit's box exactly. */
int sl_light_fit_slice(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                       struct sl_light_box *out);
int sl_light_fit_slice_mt(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                          struct sl_light_box *out, int threads);

/* LiSPSM (Wimmer et al. 2004): a light-space perspective frame for a
 * directional light, fitted to the PFL pixels i with mask[i] == value
 * (mask NULL: all) and their casters, with the warp's near distance
 * n_opt = (zn + sqrt(zn zf)) / sin gamma (zn, zf: the view depths the
 * receivers span; gamma: the angle between view and light directions),
 * written to *nopt. Returns 1 with out->vp the warped frame (out->lo/hi its
 * warped bounds, persp 0), or 0 with out the uniform box of
 * sl_light_fit_slice where LiSPSM falls back to it: gamma -> 0 (n_opt ->
 * infinity, as the paper does), a body without depth, or an area light
 * (0 with n_receivers 0). */
int sl_light_fit_lispsm(const struct sl_scene *s, const struct sl_view *v, const uint8_t *mask, uint8_t value,
                        double zn, double zf, struct sl_light_box *out, double *nopt);

/* Split planes of z-partitioning (seed 004): planes[0..k] from n to f.
 * Closed form, eq. 50/63 (logarithmic): n_i = n (f/n)^((i-1)/k). Iterative,
 * eq. 62, blending the log and the uniform split by lambda in [0, 1]; equal
 * to the closed form at lambda = 1 (the seed's appendix B proves it,
 * tests/test_zpart.c checks it). */
void sl_zsplit_closed(double n, double f, int k, double *planes);
void sl_zsplit_iterative(double n, double f, int k, double lambda, double *planes);

/* A world point's view depth (distance in front of the camera along its
 * axis): -z in the camera's view space. */
static inline float sl_view_depth(const struct sl_view *v, const float p[3])
{
    return -(v->view[0][2] * p[0] + v->view[1][2] * p[1] + v->view[2][2] * p[2] + v->view[3][2]);
}

/* The view depths of the visible (non-background) pixels: their least and
 * greatest; 1 and 2 when none is visible. */
void sl_view_depth_range(const struct sl_view *v, float *zmin, float *zmax);

/* The light view basis for a direction (shared by the fit and the tests). */
void sl_light_view(const float dir[3], mat4 view);

#endif
