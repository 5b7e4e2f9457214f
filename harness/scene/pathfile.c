/*
 * pathfile.c — see pathfile.h.
 * Invariants: every frame is a viewpoint that read_viewpoint (scenefile.c)
 * would accept — finite position, unit direction, up not parallel to it,
 * fov in (0.1, 179], 0 < near < far <= 1e7 near — and a moved light is a
 * unit direction; frames are memset before they are filled, since the truth
 * cache keys a view by the viewpoint's bytes.
 */
#define _DEFAULT_SOURCE
#include "pathfile.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "yamlfile.h"

static const cyaml_schema_value_t float_schema = {CYAML_VALUE_FLOAT(CYAML_FLAG_DEFAULT, float)};
#define VEC(key, type, member, lo, hi) \
    CYAML_FIELD_SEQUENCE(key, CYAML_FLAG_POINTER, type, member, &float_schema, lo, hi)
#define OPT_VEC(key, type, member, lo, hi) \
    CYAML_FIELD_SEQUENCE(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member, &float_schema, lo, hi)
#define OPT_FLOAT(key, type, member) CYAML_FIELD_FLOAT_PTR(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member)

static const cyaml_schema_field_t key_fields[] = {
    VEC("position", struct raw_key, position, 3, 3),
    VEC("direction", struct raw_key, direction, 3, 3),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t key_schema = {CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_key, key_fields)};
static const cyaml_schema_field_t orbit_fields[] = {
    VEC("center", struct raw_orbit, center, 3, 3),
    CYAML_FIELD_FLOAT("radius", CYAML_FLAG_DEFAULT, struct raw_orbit, radius),
    OPT_FLOAT("height", struct raw_orbit, height),
    VEC("degrees", struct raw_orbit, degrees, 2, 2),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t dolly_fields[] = {
    VEC("from", struct raw_dolly, from, 3, 3),
    VEC("to", struct raw_dolly, to, 3, 3),
    VEC("direction", struct raw_dolly, direction, 3, 3),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t camera_fields[] = {
    CYAML_FIELD_STRING_PTR("viewpoint", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_camera, viewpoint, 1, 63),
    CYAML_FIELD_SEQUENCE("keyframes", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_camera, keyframes,
                         &key_schema, 1, 64),
    CYAML_FIELD_MAPPING_PTR("orbit", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_camera, orbit, orbit_fields),
    CYAML_FIELD_MAPPING_PTR("dolly", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_camera, dolly, dolly_fields),
    OPT_VEC("up", struct raw_camera, up, 3, 3),
    OPT_FLOAT("fov", struct raw_camera, fov),
    OPT_FLOAT("near", struct raw_camera, near),
    OPT_FLOAT("far", struct raw_camera, far),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t sweep_fields[] = {
    VEC("elevation", struct raw_sweep, elevation, 1, 2),
    VEC("azimuth", struct raw_sweep, azimuth, 1, 2),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t path_fields[] = {
    CYAML_FIELD_STRING_PTR("name", CYAML_FLAG_POINTER, struct sl_raw_path, name, 1, 63),
    CYAML_FIELD_UINT("frames", CYAML_FLAG_DEFAULT, struct sl_raw_path, frames),
    CYAML_FIELD_MAPPING_PTR("camera", CYAML_FLAG_POINTER, struct sl_raw_path, camera, camera_fields),
    CYAML_FIELD_MAPPING_PTR("light", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct sl_raw_path, light, sweep_fields),
    CYAML_FIELD_END,
};
const cyaml_schema_value_t sl_raw_path_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct sl_raw_path, path_fields),
};

void sl_path_orbit(const float center[3], float radius, float height, float deg, float pos[3], float dir[3])
{
    double a = (double)deg * M_PI / 180.0;
    pos[0] = (float)(center[0] + radius * sin(a));
    pos[1] = center[1] + height;
    pos[2] = (float)(center[2] + radius * cos(a));
    for (int k = 0; k < 3; k++)
        dir[k] = center[k] - pos[k];
}

void sl_path_sun(float elevation_deg, float azimuth_deg, float dir[3])
{
    double e = (double)elevation_deg * M_PI / 180.0, a = (double)azimuth_deg * M_PI / 180.0;
    dir[0] = (float)(-cos(e) * sin(a));
    dir[1] = (float)(-sin(e));
    dir[2] = (float)(-cos(e) * cos(a));
}

static int finite_n(const float *v, unsigned n)
{
    for (unsigned k = 0; k < n; k++)
        if (!isfinite(v[k]))
            return 0;
    return 1;
}

static int unit(const float in[3], float out[3])
{
    double l = sqrt((double)in[0] * in[0] + (double)in[1] * in[1] + (double)in[2] * in[2]);
    if (!finite_n(in, 3) || !(l > 1e-6) || !isfinite(l))
        return 0;
    for (int k = 0; k < 3; k++)
        out[k] = (float)(in[k] / l);
    return 1;
}

static float lerp(float a, float b, double s) { return (float)((1.0 - s) * a + s * b); }

/* Path names name frames and files: [A-Za-z0-9_-], 1..23 bytes (no '.',
 * which separates the frame number). */
static int path_name_ok(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > 23)
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-')
            return 0;
    return 1;
}

/* The camera of frame t (s along the path) into v; 0 with *why set when
 * its direction degenerates (keyframes turning by 180 degrees). */
static int camera_at(const struct raw_camera *c, const struct sl_viewpoint *held, double s, struct sl_viewpoint *v,
                     const char **why)
{
    float dir[3];
    if (held) {
        memcpy(v->pos, held->pos, sizeof v->pos);
        memcpy(dir, held->dir, sizeof dir);
    } else if (c->orbit) {
        const struct raw_orbit *o = c->orbit;
        sl_path_orbit(o->center, o->radius, o->height ? *o->height : 0.0f, lerp(o->degrees[0], o->degrees[1], s),
                      v->pos, dir);
    } else if (c->dolly) {
        for (int k = 0; k < 3; k++)
            v->pos[k] = lerp(c->dolly->from[k], c->dolly->to[k], s);
        memcpy(dir, c->dolly->direction, sizeof dir);
    } else {
        unsigned n = c->keyframes_count;
        double u = s * (double)(n - 1);
        unsigned i = n > 1 ? (unsigned)floor(u) : 0;
        if (i >= n - 1)
            i = n > 1 ? n - 2 : 0;
        const struct raw_key *a = &c->keyframes[i], *b = &c->keyframes[n > 1 ? i + 1 : 0];
        double f = n > 1 ? u - (double)i : 0.0;
        float da[3], db[3];
        if (!unit(a->direction, da) || !unit(b->direction, db)) {
            *why = "a keyframe's direction must be finite and non-zero";
            return 0;
        }
        for (int k = 0; k < 3; k++) {
            v->pos[k] = lerp(a->position[k], b->position[k], f);
            dir[k] = lerp(da[k], db[k], f);
        }
    }
    if (!finite_n(v->pos, 3)) {
        *why = "a frame's camera position is not finite";
        return 0;
    }
    if (!unit(dir, v->dir)) {
        *why = "a frame's view direction is zero or not finite (keyframes turning the camera by 180 degrees, "
               "or an orbit's camera at its center)";
        return 0;
    }
    return 1;
}

static enum sl_err expand_one(const struct sl_raw_path *r, unsigned pi, const char *file,
                              const struct sl_yaml_pos *pos, const struct sl_light *light, struct sl_scene *s,
                              struct sl_diag *d)
{
    char key[128];
    const struct raw_camera *c = r->camera;
    snprintf(key, sizeof key, "paths[%u].name", pi);
    if (!path_name_ok(r->name))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "path name '%.64s': use 1..23 letters, digits, '-' and "
                           "'_' (its frames are named <path>.<frame>)", r->name);
    if (sl_scene_find_path(s, r->name) >= 0)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "path '%s' named twice", r->name);
    snprintf(key, sizeof key, "paths[%u].frames", pi);
    if (r->frames < 1 || r->frames > 1000)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "frames must be 1 .. 1000");
    if (s->nframes + (int)r->frames > SL_MAX_FRAMES)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "the scene's paths hold more than %d frames together",
                           SL_MAX_FRAMES);
    int kinds = !!c->viewpoint + !!c->keyframes + !!c->orbit + !!c->dolly;
    snprintf(key, sizeof key, "paths[%u].camera", pi);
    if (kinds != 1)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "give exactly one of viewpoint, keyframes, orbit, dolly "
                           "(%d given)", kinds);
    const struct sl_viewpoint *held = NULL;
    if (c->viewpoint) {
        int v = -1;
        for (int i = 0; i < s->nvp; i++)
            if (strcmp(s->vp[i].name, c->viewpoint) == 0)
                v = i;
        snprintf(key, sizeof key, "paths[%u].camera.viewpoint", pi);
        if (v < 0)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "no viewpoint '%s' in this scene file", c->viewpoint);
        held = &s->vp[v];
    }
    if (c->orbit) {
        snprintf(key, sizeof key, "paths[%u].camera.orbit", pi);
        if (!(c->orbit->radius > 0.0f) || !isfinite(c->orbit->radius) || !finite_n(c->orbit->center, 3) ||
            !finite_n(c->orbit->degrees, 2) || (c->orbit->height && !isfinite(*c->orbit->height)))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "an orbit needs a finite center, degrees and height "
                               "and a radius > 0");
    }
    if (c->dolly) {
        snprintf(key, sizeof key, "paths[%u].camera.dolly", pi);
        if (!finite_n(c->dolly->from, 3) || !finite_n(c->dolly->to, 3))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "a dolly needs finite from and to");
    }
    float up[3] = {0, 1, 0};
    float fov = held ? held->fov_deg : 60.0f, znear = held ? held->znear : NAN, zfar = held ? held->zfar : NAN;
    if (held)
        memcpy(up, held->up, sizeof up);
    snprintf(key, sizeof key, "paths[%u].camera.up", pi);
    if (c->up && !unit(c->up, up))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "up must be finite and non-zero");
    if (c->fov)
        fov = *c->fov;
    if (c->near)
        znear = *c->near;
    if (c->far)
        zfar = *c->far;
    /* the bounds read_viewpoint (scenefile.c) puts on a named viewpoint */
    /* a key not in the file is named by the camera's line */
    snprintf(key, sizeof key, "paths[%u].camera%s", pi, c->fov ? ".fov" : "");
    if (!(fov > 0.1f && fov <= 179.0f))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "fov must be in (0.1, 179] degrees");
    snprintf(key, sizeof key, "paths[%u].camera%s", pi, c->near ? ".near" : "");
    if (!(znear > 0.0f) || !isfinite(znear))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "near must be given (or a viewpoint) and > 0");
    snprintf(key, sizeof key, "paths[%u].camera%s", pi, c->far ? ".far" : "");
    if (!(zfar > znear) || !isfinite(zfar) || !((double)zfar / (double)znear <= 1e7))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "far must be given (or a viewpoint), exceed near and be "
                           "at most 1e7 near");
    if (r->light) {
        snprintf(key, sizeof key, "paths[%u].light", pi);
        if (light->type != SL_LIGHT_DIRECTIONAL)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "a light path moves a directional light; this "
                               "scene's light is not one");
        const struct raw_sweep *w = r->light;
        if (!finite_n(w->elevation, w->elevation_count) || !finite_n(w->azimuth, w->azimuth_count))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "elevation and azimuth must be finite");
        for (unsigned k = 0; k < w->elevation_count; k++)
            if (!(fabsf(w->elevation[k]) < 90.0f || w->elevation[k] == 90.0f))
                return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "elevation must be in (-90, 90] degrees");
    }
    struct sl_path_info *info = &s->paths[s->npaths];
    memset(info, 0, sizeof *info);
    snprintf(info->name, sizeof info->name, "%s", r->name);
    info->first = s->nvp + s->nframes;
    info->count = (int)r->frames;
    info->moves_camera = !held;
    info->moves_light = r->light != NULL;
    for (unsigned t = 0; t < r->frames; t++) {
        double u = r->frames > 1 ? (double)t / (double)(r->frames - 1) : 0.0;
        struct sl_viewpoint *v = &s->vp[info->first + (int)t];
        memset(v, 0, sizeof *v);
        snprintf(v->name, sizeof v->name, "%s.%03u", r->name, t);
        const char *why = "";
        snprintf(key, sizeof key, "paths[%u].camera", pi);
        if (!camera_at(c, held, u, v, &why))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "frame %u: %s", t, why);
        if (fabsf(up[0] * v->dir[0] + up[1] * v->dir[1] + up[2] * v->dir[2]) > 0.9999f)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "frame %u: up is parallel to the view direction", t);
        memcpy(v->up, up, sizeof up);
        v->fov_deg = fov;
        v->znear = znear;
        v->zfar = zfar;
        v->path = s->npaths;
        v->frame = (int)t;
        if (r->light) {
            const struct raw_sweep *w = r->light;
            float el = w->elevation_count == 2 ? lerp(w->elevation[0], w->elevation[1], u) : w->elevation[0];
            float az = w->azimuth_count == 2 ? lerp(w->azimuth[0], w->azimuth[1], u) : w->azimuth[0];
            v->has_light = 1;
            sl_path_sun(el, az, v->light_dir);
        }
        for (int i = 0; i < s->nvp; i++)
            if (strcmp(s->vp[i].name, v->name) == 0)
                return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "frame %u's name '%s' is a viewpoint's", t,
                                   v->name);
    }
    s->nframes += (int)r->frames;
    s->npaths++;
    return SL_OK;
}

enum sl_err sl_paths_expand(const struct sl_raw_path *raw, unsigned n, const char *file,
                            const struct sl_yaml_pos *pos, const struct sl_light *light, struct sl_scene *s,
                            struct sl_diag *d)
{
    s->nframes = 0;
    s->npaths = 0;
    for (unsigned i = 0; i < n; i++) {
        enum sl_err e = expand_one(&raw[i], i, file, pos, light, s, d);
        if (e)
            return e;
    }
    return SL_OK;
}
