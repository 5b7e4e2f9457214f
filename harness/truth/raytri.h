/*
 * raytri.h — ray-triangle tests outside Embree: the double-precision reference
 * the truth is checked against, and the sure/unsure shadow-ray test methods
 * use to confirm a shadow against a stored triangle (one "ray-triangle test"
 * in the cost counters).
 */
#ifndef SL_RAYTRI_H
#define SL_RAYTRI_H

/* Möller-Trumbore in double. Returns 1 and *t when the ray o + t*dir hits the
 * closed triangle abc (edges included) with t > tmin; culls no side. */
int sl_ray_tri_d(const double o[3], const double dir[3], const double a[3], const double b[3],
                 const double c[3], double tmin, double *t);

/* Distance from point p to the closed triangle abc (0 inside), in double. */
double sl_point_tri_dist_d(const double p[3], const double a[3], const double b[3],
                           const double c[3]);

/* Distance from p to the boundary (the three edges) of triangle abc. */
double sl_point_tri_edge_dist_d(const double p[3], const double a[3], const double b[3],
                                const double c[3]);

/* Does the shadow ray from p (along the unit `toward`, the direction to the
 * light, from tnear up to tmax, as the truth traces it: sl_frame_toward)
 * surely meet triangle abc (+1), surely miss it (-1), or is it too close to
 * call (0)? Decided in double with a margin of 1e-5 of the coordinates' size
 * (far above float rounding): +1 needs the crossing inside the triangle by
 * the margin, beyond 2 tnear and short of tmax by the margin; -1 needs it
 * outside by the margin, before tnear / 2, where Embree does not look, or
 * beyond tmax by the margin (behind a point light). A grazing ray is
 * always 0. */
int sl_shadow_ray_tri_sure(const float p[3], const float toward[3], float tmax, float tnear, const float a[3],
                           const float b[3], const float c[3]);

/* sl_shadow_ray_tri_sure(...) > 0, to the bit (the same tests in a cheaper
 * order): for callers that act on a sure hit only. */
int sl_shadow_ray_tri_hit(const float p[3], const float toward[3], float tmax, float tnear, const float a[3],
                          const float b[3], const float c[3]);

#endif
