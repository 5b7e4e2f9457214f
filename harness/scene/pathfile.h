/*
 * pathfile.h — paths in scene files: a camera that moves (keyframes of
 * position and direction, an orbit around a point, a dolly along a line, or
 * a named viewpoint held still) and, optionally, a directional light that
 * sweeps its elevation and azimuth, over a number of frames. Each frame
 * becomes a viewpoint of the scene named "<path>.<frame>" (orbit.007),
 * held after the named viewpoints, so a config that names the path sweeps
 * its frames as views and everything per view (G-buffer, truth, its cache,
 * the store's keys, resume, slices) applies unchanged.
 *
 *   paths:
 *     - name: orbit
 *       frames: 60
 *       camera:
 *         orbit: {center: [0, 0, 0], radius: 80, height: 45, degrees: [0, 354]}
 *         # or keyframes: [{position: [..], direction: [..]}, ...]   (1 or more)
 *         # or dolly: {from: [..], to: [..], direction: [..]}
 *         # or viewpoint: side            (held still; fov, near, far and up from it)
 *         up: [0, 1, 0]                   # default [0, 1, 0]
 *         fov: 60                         # default 60 (or the viewpoint's)
 *         near: 20                        # required unless viewpoint: is given
 *         far: 250
 *     - name: sun
 *       frames: 60
 *       camera: {viewpoint: side}
 *       light: {elevation: [25, 65], azimuth: [30, 120]}   # degrees; one value = held
 *
 * Frame t of n sits at s = t / (n - 1) along the path (s = 0 when n = 1),
 * both ends included (a closed orbit therefore stops one step short of its
 * start: [0, 354] for 60 frames). Keyframes are spaced evenly in s; position
 * and direction are interpolated linearly between neighbours (the direction
 * renormalised). Orbit: the camera at center + (radius sin a, height,
 * radius cos a), looking at the center. Light: elevation above the x-z plane
 * and azimuth from +z toward +x of the direction TOWARD the light; the light
 * travels the opposite way.
 *
 * Does not: render, or know configs. Errors name file, line and key.
 */
#ifndef SL_PATHFILE_H
#define SL_PATHFILE_H
#include <cyaml/cyaml.h>
#include "scene.h"
#include "sl_error.h"

struct sl_yaml_pos;

/* The parsed YAML of one entry (scenefile.c holds a sequence of them). */
struct raw_key {
    float *position; unsigned position_count;
    float *direction; unsigned direction_count;
};
struct raw_orbit {
    float *center; unsigned center_count;
    float radius;
    float *height;
    float *degrees; unsigned degrees_count;
};
struct raw_dolly {
    float *from; unsigned from_count;
    float *to; unsigned to_count;
    float *direction; unsigned direction_count;
};
struct raw_camera {
    char *viewpoint;
    struct raw_key *keyframes; unsigned keyframes_count;
    struct raw_orbit *orbit;
    struct raw_dolly *dolly;
    float *up; unsigned up_count;
    float *fov, *near, *far;
};
struct raw_sweep {
    float *elevation; unsigned elevation_count;
    float *azimuth; unsigned azimuth_count;
};
struct sl_raw_path {
    char *name;
    unsigned frames;
    struct raw_camera *camera;
    struct raw_sweep *light;
};


/* The schema of one entry of `paths:` (scenefile.c's top-level key). */
extern const cyaml_schema_value_t sl_raw_path_schema;

/* Expand the paths into frames appended to s->vp after the named
 * viewpoints (s->nvp already set, the light already read): fills
 * s->paths, s->npaths, s->nframes. */
enum sl_err sl_paths_expand(const struct sl_raw_path *raw, unsigned n, const char *file,
                            const struct sl_yaml_pos *pos, const struct sl_light *light, struct sl_scene *s,
                            struct sl_diag *d);

/* The camera and light of frame t of a path at s in [0, 1], pure (tests). */
void sl_path_orbit(const float center[3], float radius, float height, float deg, float pos[3], float dir[3]);
void sl_path_sun(float elevation_deg, float azimuth_deg, float dir[3]);

#endif
