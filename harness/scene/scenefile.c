/*
 * scenefile.c — see scenefile.h.
 * Invariants: a loaded scene has at least one triangle, finite coordinates,
 * unit light and view directions, and each mesh entry as one welded range;
 * on any error the output scene is empty and the message names file, line and
 * key (the model file itself for errors inside a model).
 */
#define _DEFAULT_SOURCE
#include "scenefile.h"
#include <cglm/cglm.h>
#include <dirent.h>
#include <errno.h>
#include <ctype.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "gen.h"
#include "meshio.h"
#include "pathfile.h"
#include "util.h"
#include "yamlfile.h"

#ifndef SL_SCENES_DIR
#define SL_SCENES_DIR "scenes"
#endif

/* ---- raw schema ---- */

struct raw_xform {
    float *translate; unsigned translate_count;
    float *rotate;    unsigned rotate_count;
    float *scale;     unsigned scale_count;
};
struct raw_mesh {
    char *name, *generator, *file;
    float *center; unsigned center_count;
    float *min;    unsigned min_count;
    float *max;    unsigned max_count;
    float *size, *radius, *height, *major_radius, *minor_radius, *base, *width, *depth, *length;
    unsigned *segments, *rings, *grid, *count, *seed;
    struct raw_xform *transform;
    bool *two_sided;
    bool *receiver;
};
struct raw_light {
    char *type;
    float *direction; unsigned direction_count;
    float *position;  unsigned position_count;
    float *fov;
    float *penumbra;
    float *normal;    unsigned normal_count;
    float *up;        unsigned up_count;
    float *size;      unsigned size_count;
};
struct raw_vp {
    char *name;
    float *position;  unsigned position_count;
    float *direction; unsigned direction_count;
    float *up;        unsigned up_count;
    float fov, near, far;
};
struct raw_scene {
    char *name, *description, *base;
    struct raw_light *light;
    struct raw_mesh *meshes; unsigned meshes_count;
    struct raw_vp *viewpoints; unsigned viewpoints_count;
    struct sl_raw_path *paths; unsigned paths_count;
};

static const cyaml_schema_value_t float_schema = {CYAML_VALUE_FLOAT(CYAML_FLAG_DEFAULT, float)};

#define VEC_FIELD(key, type, member, n) \
    CYAML_FIELD_SEQUENCE(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member, &float_schema, n, n)
#define OPT_FLOAT(key, type, member) CYAML_FIELD_FLOAT_PTR(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member)
#define OPT_UINT(key, type, member) CYAML_FIELD_UINT_PTR(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member)
#define OPT_STR(key, type, member, max) \
    CYAML_FIELD_STRING_PTR(key, CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, type, member, 1, max)

static const cyaml_schema_field_t xform_fields[] = {
    VEC_FIELD("translate", struct raw_xform, translate, 3),
    VEC_FIELD("rotate", struct raw_xform, rotate, 3),
    VEC_FIELD("scale", struct raw_xform, scale, 3),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t mesh_fields[] = {
    OPT_STR("name", struct raw_mesh, name, SL_MESH_NAME - 1),
    OPT_STR("generator", struct raw_mesh, generator, 31),
    OPT_STR("file", struct raw_mesh, file, 511),
    VEC_FIELD("center", struct raw_mesh, center, 3),
    VEC_FIELD("min", struct raw_mesh, min, 3),
    VEC_FIELD("max", struct raw_mesh, max, 3),
    OPT_FLOAT("size", struct raw_mesh, size),
    OPT_FLOAT("radius", struct raw_mesh, radius),
    OPT_FLOAT("height", struct raw_mesh, height),
    OPT_FLOAT("major_radius", struct raw_mesh, major_radius),
    OPT_FLOAT("minor_radius", struct raw_mesh, minor_radius),
    OPT_FLOAT("base", struct raw_mesh, base),
    OPT_FLOAT("width", struct raw_mesh, width),
    OPT_FLOAT("depth", struct raw_mesh, depth),
    OPT_FLOAT("length", struct raw_mesh, length),
    OPT_UINT("segments", struct raw_mesh, segments),
    OPT_UINT("rings", struct raw_mesh, rings),
    OPT_UINT("grid", struct raw_mesh, grid),
    OPT_UINT("count", struct raw_mesh, count),
    OPT_UINT("seed", struct raw_mesh, seed),
    CYAML_FIELD_MAPPING_PTR("transform", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_mesh,
                            transform, xform_fields),
    CYAML_FIELD_BOOL_PTR("two_sided", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_mesh, two_sided),
    CYAML_FIELD_BOOL_PTR("receiver", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_mesh, receiver),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t mesh_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_mesh, mesh_fields),
};
static const cyaml_schema_field_t light_fields[] = {
    CYAML_FIELD_STRING_PTR("type", CYAML_FLAG_POINTER, struct raw_light, type, 1, 31),
    VEC_FIELD("direction", struct raw_light, direction, 3),
    VEC_FIELD("position", struct raw_light, position, 3),
    OPT_FLOAT("fov", struct raw_light, fov),
    OPT_FLOAT("penumbra", struct raw_light, penumbra),
    VEC_FIELD("normal", struct raw_light, normal, 3),
    VEC_FIELD("up", struct raw_light, up, 3),
    VEC_FIELD("size", struct raw_light, size, 2),
    CYAML_FIELD_END,
};
static const cyaml_schema_field_t vp_fields[] = {
    CYAML_FIELD_STRING_PTR("name", CYAML_FLAG_POINTER, struct raw_vp, name, 1, 31),
    CYAML_FIELD_SEQUENCE("position", CYAML_FLAG_POINTER, struct raw_vp, position, &float_schema, 3, 3),
    CYAML_FIELD_SEQUENCE("direction", CYAML_FLAG_POINTER, struct raw_vp, direction, &float_schema, 3, 3),
    VEC_FIELD("up", struct raw_vp, up, 3),
    CYAML_FIELD_FLOAT("fov", CYAML_FLAG_DEFAULT, struct raw_vp, fov),
    CYAML_FIELD_FLOAT("near", CYAML_FLAG_DEFAULT, struct raw_vp, near),
    CYAML_FIELD_FLOAT("far", CYAML_FLAG_DEFAULT, struct raw_vp, far),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t vp_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct raw_vp, vp_fields),
};
static const cyaml_schema_field_t scene_fields[] = {
    OPT_STR("name", struct raw_scene, name, 63),
    OPT_STR("description", struct raw_scene, description, 159),
    OPT_STR("base", struct raw_scene, base, 255),
    CYAML_FIELD_MAPPING_PTR("light", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene, light,
                            light_fields),
    CYAML_FIELD_SEQUENCE("meshes", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene, meshes,
                         &mesh_schema, 1, 4096),
    CYAML_FIELD_SEQUENCE("viewpoints", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene,
                         viewpoints, &vp_schema, 1, SL_MAX_VIEWPOINTS),
    CYAML_FIELD_SEQUENCE("paths", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct raw_scene, paths,
                         &sl_raw_path_schema, 1, SL_MAX_PATHS),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t scene_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, struct raw_scene, scene_fields),
};

/* ---- generators ---- */

enum {
    P_CENTER = 1 << 0, P_MIN = 1 << 1, P_MAX = 1 << 2, P_SIZE = 1 << 3, P_RADIUS = 1 << 4,
    P_HEIGHT = 1 << 5, P_MAJOR = 1 << 6, P_MINOR = 1 << 7, P_BASE = 1 << 8, P_WIDTH = 1 << 9,
    P_DEPTH = 1 << 10, P_LENGTH = 1 << 11, P_SEGMENTS = 1 << 12, P_RINGS = 1 << 13,
    P_GRID = 1 << 14, P_COUNT = 1 << 15, P_SEED = 1 << 16,
};
static const char *const param_names[] = {
    "center", "min", "max", "size", "radius", "height", "major_radius", "minor_radius", "base",
    "width", "depth", "length", "segments", "rings", "grid", "count", "seed",
};
#define NPARAMS ((int)(sizeof param_names / sizeof param_names[0]))

struct gen_args {
    float c[3], lo[3], hi[3];
    float size, radius, height, major, minor, base, width, depth, length;
    unsigned segments, rings, grid, count, seed;
};

static void g_plane(struct sl_mesh *m, const struct gen_args *a) { sl_gen_plane(m, a->c[0], a->c[1], a->c[2], a->size, (int)a->grid); }
static void g_box(struct sl_mesh *m, const struct gen_args *a) { sl_gen_box(m, a->lo, a->hi); }
static void g_sphere(struct sl_mesh *m, const struct gen_args *a) { sl_gen_sphere(m, a->c[0], a->c[1], a->c[2], a->radius, (int)a->segments, (int)a->rings); }
static void g_torus(struct sl_mesh *m, const struct gen_args *a) { sl_gen_torus(m, a->c[0], a->c[1], a->c[2], a->major, a->minor, (int)a->segments, (int)a->rings); }
static void g_cylinder(struct sl_mesh *m, const struct gen_args *a) { sl_gen_cylinder(m, a->c[0], a->c[1], a->c[2], a->radius, a->height, (int)a->segments); }
static void g_pyramid(struct sl_mesh *m, const struct gen_args *a) { sl_gen_pyramid(m, a->c[0], a->c[1], a->c[2], a->base, a->height); }
static void g_cone(struct sl_mesh *m, const struct gen_args *a) { sl_gen_cone(m, a->c[0], a->c[1], a->c[2], a->radius, a->height, (int)a->segments); }
static void g_tree(struct sl_mesh *m, const struct gen_args *a) { sl_gen_tree(m, a->c[0], a->c[1], a->c[2], a->height, a->seed); }
static void g_flowers(struct sl_mesh *m, const struct gen_args *a) { sl_gen_flowers(m, a->c[0], a->c[1], a->c[2], a->width, a->depth, (int)a->count, a->seed); }
static void g_bench(struct sl_mesh *m, const struct gen_args *a) { sl_gen_bench(m, a->c[0], a->c[1], a->c[2], a->length, a->seed); }
static void g_lamp(struct sl_mesh *m, const struct gen_args *a) { sl_gen_lamp(m, a->c[0], a->c[1], a->c[2], a->height); }
/* the soil height it returns is y0 + 0.8 height: place flowers there */
static void g_flower_box(struct sl_mesh *m, const struct gen_args *a) { (void)sl_gen_flower_box(m, a->c[0], a->c[1], a->c[2], a->width, a->depth, a->height); }

/* required params, optional params (with their defaults in gen_defaults) */
static const struct generator {
    const char *name;
    unsigned required, optional;
    void (*build)(struct sl_mesh *, const struct gen_args *);
} generators[] = {
    {"plane", P_SIZE, P_CENTER | P_GRID, g_plane},
    {"box", P_MIN | P_MAX, 0, g_box},
    {"sphere", P_RADIUS, P_CENTER | P_SEGMENTS | P_RINGS, g_sphere},
    {"torus", P_MAJOR | P_MINOR, P_CENTER | P_SEGMENTS | P_RINGS, g_torus},
    {"cylinder", P_RADIUS | P_HEIGHT, P_CENTER | P_SEGMENTS, g_cylinder},
    {"pyramid", P_BASE | P_HEIGHT, P_CENTER, g_pyramid},
    {"cone", P_RADIUS | P_HEIGHT, P_CENTER | P_SEGMENTS, g_cone},
    {"tree", P_HEIGHT, P_CENTER | P_SEED, g_tree},
    {"flowers", P_WIDTH | P_DEPTH | P_COUNT, P_CENTER | P_SEED, g_flowers},
    {"bench", P_LENGTH, P_CENTER | P_SEED, g_bench},
    {"lamp", P_HEIGHT, P_CENTER, g_lamp},
    {"flower_box", P_WIDTH | P_DEPTH | P_HEIGHT, P_CENTER, g_flower_box},
    {NULL, 0, 0, NULL},
};

/* ---- helpers ---- */

static int finite3(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

static int unit3(const float *in, float *out)
{
    double l = sqrt((double)in[0] * in[0] + (double)in[1] * in[1] + (double)in[2] * in[2]);
    if (!finite3(in) || !(l > 1e-12) || !isfinite(l))
        return 0;
    for (int k = 0; k < 3; k++)
        out[k] = (float)(in[k] / l);
    return 1;
}

/* The installed share folder (util.h, sl_share_dir), once. */
static const char *installed_dir(void)
{
    static char dir[1024];
    static int done;
    if (!done) {
        done = 1;
        sl_share_dir("scenes", dir, sizeof dir);
    }
    return dir;
}

int sl_scene_dirs(const char *rel_dir, char (*dirs)[1024], const char **origin, int max)
{
    int n = 0;
    if (rel_dir && n < max) {
        snprintf(dirs[n], 1024, "%s", rel_dir);
        origin[n++] = "config folder";
    }
    const char *e = getenv("SHADOWLAB_SCENES");
    for (const char *p = e; p && *p && n < max;) {
        size_t k = strcspn(p, ":");
        if (k) {
            snprintf(dirs[n], 1024, "%.*s", (int)k, p);
            origin[n++] = "SHADOWLAB_SCENES";
        }
        p += k + (p[k] == ':');
    }
    /* an installed binary never looks into the tree it was built from: the
     * source tree's scenes/ stands in only for a binary that is not installed */
    const char *inst = installed_dir();
    if (n < max) {
        snprintf(dirs[n], 1024, "%s", inst[0] ? inst : SL_SCENES_DIR);
        origin[n++] = inst[0] ? "installed" : "source tree";
    }
    return n;
}

const char *sl_scenes_dir(void)
{
    const char *inst = installed_dir();
    return inst[0] ? inst : SL_SCENES_DIR;
}

enum sl_err sl_scene_resolve(const char *ref, const char *rel_dir, char *path, size_t n,
                             struct sl_diag *d)
{
    size_t len = strlen(ref);
    /* a path ends in .yaml or starts with / or .; anything else is a name in
     * the scenes folder, which may have sub-folders (hard/grazing_89) */
    int is_path = ref[0] == '/' || ref[0] == '.' || (len > 5 && strcmp(ref + len - 5, ".yaml") == 0);
    if (is_path) {
        if (ref[0] == '/' || !rel_dir)
            snprintf(path, n, "%s", ref);
        else
            snprintf(path, n, "%s/%s", rel_dir, ref);
    } else {
        for (const char *p = ref; *p; p++)
            if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
                  *p == '-' || *p == '_' || (*p == '/' && p[1] && p[1] != '/' && p[1] != '.')))
                return sl_fail(d, SL_E_SCENE, NULL, 0, "scene", "'%s' is neither a scene name nor a path", ref);
        /* the first folder of the search path that has it */
        char dirs[16][1024];
        const char *origin[16];
        int nd = sl_scene_dirs(rel_dir, dirs, origin, 16);
        for (int i = 0; i < nd; i++) {
            snprintf(path, n, "%s/%s.yaml", dirs[i], ref);
            if (access(path, R_OK) == 0)
                return SL_OK;
        }
        char where[600] = "";
        for (int i = 0; i < nd; i++)
            snprintf(where + strlen(where), sizeof where - strlen(where), "%s%s", i ? ", " : "", dirs[i]);
        return sl_fail(d, SL_E_SCENE, NULL, 0, "scene", "no scene '%s' in %s", ref, where);
    }
    if (access(path, R_OK) != 0)
        return sl_fail(d, SL_E_SCENE, NULL, 0, "scene", "no scene '%s' (%s: %s)", ref, path, strerror(errno));
    return SL_OK;
}

/* The transform of a mesh entry: T * Rz * Ry * Rx * S (column vectors). */
static enum sl_err entry_xform(const struct raw_xform *x, const char *file, const struct sl_yaml_pos *pos,
                               unsigned i, mat4 out, struct sl_diag *d)
{
    char key[96];
    glm_mat4_identity(out);
    if (!x)
        return SL_OK;
    if (x->translate) {
        snprintf(key, sizeof key, "meshes[%u].transform.translate", i);
        if (!finite3(x->translate))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "non-finite translation");
        vec3 t = {x->translate[0], x->translate[1], x->translate[2]};
        glm_translate(out, t);
    }
    if (x->rotate) {
        snprintf(key, sizeof key, "meshes[%u].transform.rotate", i);
        if (!finite3(x->rotate))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "non-finite rotation");
        glm_rotate_z(out, glm_rad(x->rotate[2]), out);
        glm_rotate_y(out, glm_rad(x->rotate[1]), out);
        glm_rotate_x(out, glm_rad(x->rotate[0]), out);
    }
    if (x->scale) {
        snprintf(key, sizeof key, "meshes[%u].transform.scale", i);
        /* a negative scale would turn the mesh inside out (front faces flip) */
        if (!finite3(x->scale) || !(x->scale[0] > 0 && x->scale[1] > 0 && x->scale[2] > 0))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "scale factors must be finite and > 0");
        vec3 s = {x->scale[0], x->scale[1], x->scale[2]};
        glm_scale(out, s);
    }
    return SL_OK;
}

static void apply_xform(struct sl_mesh *m, uint32_t first_vertex, const mat4 x)
{
    for (uint32_t v = first_vertex; v < m->nv; v++) {
        float *p = m->pos + 3 * (size_t)v;
        vec4 w = {p[0], p[1], p[2], 1.0f}, r;
        glm_mat4_mulv((vec4 *)x, w, r);
        p[0] = r[0]; p[1] = r[1]; p[2] = r[2];
    }
}

/* Check a generator's parameters and fill args with them and the defaults. */
static enum sl_err gen_args_of(const struct generator *g, const struct raw_mesh *r, const char *file,
                               const struct sl_yaml_pos *pos, unsigned i, struct gen_args *a,
                               struct sl_diag *d)
{
    char key[96];
    unsigned given = (r->center ? P_CENTER : 0u) | (r->min ? P_MIN : 0u) | (r->max ? P_MAX : 0u) |
                     (r->size ? P_SIZE : 0u) | (r->radius ? P_RADIUS : 0u) | (r->height ? P_HEIGHT : 0u) |
                     (r->major_radius ? P_MAJOR : 0u) | (r->minor_radius ? P_MINOR : 0u) |
                     (r->base ? P_BASE : 0u) | (r->width ? P_WIDTH : 0u) | (r->depth ? P_DEPTH : 0u) |
                     (r->length ? P_LENGTH : 0u) | (r->segments ? P_SEGMENTS : 0u) |
                     (r->rings ? P_RINGS : 0u) | (r->grid ? P_GRID : 0u) | (r->count ? P_COUNT : 0u) |
                     (r->seed ? P_SEED : 0u);
    for (int b = 0; b < NPARAMS; b++) {
        unsigned bit = 1u << b;
        snprintf(key, sizeof key, "meshes[%u].%s", i, param_names[b]);
        if ((given & bit) && !((g->required | g->optional) & bit))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "generator '%s' takes no '%s'", g->name,
                               param_names[b]);
        if (!(given & bit) && (g->required & bit)) {
            snprintf(key, sizeof key, "meshes[%u]", i);
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "generator '%s' needs '%s'", g->name,
                               param_names[b]);
        }
    }
    memset(a, 0, sizeof *a);
    a->segments = 32;
    a->rings = 16;
    a->grid = 1;
    a->count = 100;
    a->seed = 1;
    if (r->center) memcpy(a->c, r->center, sizeof a->c);
    if (r->min) memcpy(a->lo, r->min, sizeof a->lo);
    if (r->max) memcpy(a->hi, r->max, sizeof a->hi);
    const struct { float *v; float *dst; const char *name; } lens[] = {
        {r->size, &a->size, "size"}, {r->radius, &a->radius, "radius"}, {r->height, &a->height, "height"},
        {r->major_radius, &a->major, "major_radius"}, {r->minor_radius, &a->minor, "minor_radius"},
        {r->base, &a->base, "base"}, {r->width, &a->width, "width"}, {r->depth, &a->depth, "depth"},
        {r->length, &a->length, "length"},
    };
    for (size_t k = 0; k < sizeof lens / sizeof lens[0]; k++) {
        if (!lens[k].v)
            continue;
        snprintf(key, sizeof key, "meshes[%u].%s", i, lens[k].name);
        if (!isfinite(*lens[k].v) || !(*lens[k].v > 0.0f) || *lens[k].v > 1e7f)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "%s must be finite, > 0 and <= 1e7", lens[k].name);
        *lens[k].dst = *lens[k].v;
    }
    const struct { float *v; const char *name; } vecs[] = {{r->center, "center"}, {r->min, "min"}, {r->max, "max"}};
    for (size_t k = 0; k < 3; k++) {
        snprintf(key, sizeof key, "meshes[%u].%s", i, vecs[k].name);
        if (vecs[k].v && !finite3(vecs[k].v))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "non-finite %s", vecs[k].name);
    }
    if (r->min && r->max && !(a->lo[0] < a->hi[0] && a->lo[1] < a->hi[1] && a->lo[2] < a->hi[2])) {
        snprintf(key, sizeof key, "meshes[%u].max", i);
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "max must exceed min on every axis");
    }
    if (g->build == g_torus && !(a->minor < a->major)) {
        snprintf(key, sizeof key, "meshes[%u].minor_radius", i);
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "minor_radius must be below major_radius");
    }
    const struct { unsigned *v; unsigned *dst; unsigned lo, hi; const char *name; } ints[] = {
        {r->segments, &a->segments, 3, 4096, "segments"}, {r->rings, &a->rings, 2, 4096, "rings"},
        {r->grid, &a->grid, 1, 4096, "grid"}, {r->count, &a->count, 1, 1000000, "count"},
        {r->seed, &a->seed, 0, 0xffffffffu, "seed"},
    };
    for (size_t k = 0; k < sizeof ints / sizeof ints[0]; k++) {
        if (!ints[k].v)
            continue;
        snprintf(key, sizeof key, "meshes[%u].%s", i, ints[k].name);
        if (*ints[k].v < ints[k].lo || *ints[k].v > ints[k].hi)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "%s must be in %u..%u", ints[k].name,
                               ints[k].lo, ints[k].hi);
        *ints[k].dst = *ints[k].v;
    }
    return SL_OK;
}

/* ---- building ---- */

/* Meshes are appended with their entry's linear transform applied, but not
 * its translation: that is kept per range in double (shift) and added only
 * when the scene is moved to its local frame (rebase), so a scene placed 1e5
 * units from the origin loses no precision to float sums at 1e5. */
struct build {
    struct sl_mesh all;
    struct sl_mesh_range *ranges;
    struct shift { double t[3]; uint32_t v0, nv; } *shift;   /* per range: translation, its vertices */
    /* per range, for an error found only once the scene is put together (a
     * triangle that float precision collapses in the local frame): the
     * entry's reach (largest |world coordinate|) and where to blame it */
    struct blame { double reach; char file[512]; char key[96]; int line; } *blame;
    int nranges, cap;
};

/* Past this a coordinate is refused: float holds 3.4e38, but the products
 * of the projection and the truth's ray tests overflow long before. */
#define SL_MAX_COORD 1e30

/* What grew an entry's coordinates: its translation when that dominates,
 * else its scale when it has one, else the model's own coordinates (file)
 * or the generator's parameters (the entry). */
static void blame_key(const struct raw_mesh *r, unsigned i, double ext, double shift, char *key, size_t n)
{
    if (r->transform && r->transform->translate && shift >= ext)
        snprintf(key, n, "meshes[%u].transform.translate", i);
    else if (r->transform && r->transform->scale)
        snprintf(key, n, "meshes[%u].transform.scale", i);
    else if (r->file)
        snprintf(key, n, "meshes[%u].file", i);
    else
        snprintf(key, n, "meshes[%u]", i);
}

static enum sl_err add_entry(struct build *b, const struct raw_mesh *r, const char *file,
                             const struct sl_yaml_pos *pos, unsigned i, struct sl_diag *d)
{
    char key[96];
    snprintf(key, sizeof key, "meshes[%u]", i);
    if (!!r->generator == !!r->file)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "a mesh needs exactly one of 'generator' and 'file'");
    mat4 x;
    enum sl_err e = entry_xform(r->transform, file, pos, i, x, d);
    if (e)
        return e;
    /* the translation waits for the rebase (struct build) */
    const double shift[3] = {x[3][0], x[3][1], x[3][2]};
    x[3][0] = x[3][1] = x[3][2] = 0.0f;
    struct sl_mesh m = {0};
    if (r->generator) {
        const struct generator *g = generators;
        while (g->name && strcmp(g->name, r->generator) != 0)
            g++;
        if (!g->name) {
            char known[256] = "";
            for (const struct generator *k = generators; k->name; k++)
                sl_known_add(known, sizeof known, k->name);
            snprintf(key, sizeof key, "meshes[%u].generator", i);
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "unknown generator '%s' (known: %s)",
                               r->generator, known);
        }
        struct gen_args a;
        if ((e = gen_args_of(g, r, file, pos, i, &a, d)))
            return e;
        g->build(&m, &a);
        if (m.oom) {
            sl_mesh_free(&m);
            return sl_fail(d, SL_E_NOMEM, file, sl_yaml_line(pos, key), key, "generator '%s'", g->name);
        }
        apply_xform(&m, 0, x);
        sl_mesh_weld(&m);
    } else {
        const char *params[] = {"center", "min", "max", "size", "radius", "height", "major_radius",
                                "minor_radius", "base", "width", "depth", "length", "segments",
                                "rings", "grid", "count", "seed"};
        const void *given[] = {r->center, r->min, r->max, r->size, r->radius, r->height, r->major_radius,
                               r->minor_radius, r->base, r->width, r->depth, r->length, r->segments,
                               r->rings, r->grid, r->count, r->seed};
        for (size_t k = 0; k < sizeof params / sizeof params[0]; k++)
            if (given[k]) {
                snprintf(key, sizeof key, "meshes[%u].%s", i, params[k]);
                return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "'%s' is a generator parameter; "
                                   "place a model file with 'transform'", params[k]);
            }
        char dir[512], path[1024];
        sl_path_dir(file, dir, sizeof dir);
        if (r->file[0] == '/')
            snprintf(path, sizeof path, "%s", r->file);
        else
            snprintf(path, sizeof path, "%s/%s", dir, r->file);
        struct sl_mesh_load_stats st;
        struct sl_diag md;
        snprintf(key, sizeof key, "meshes[%u].file", i);
        if ((e = sl_yaml_ref_check(d, SL_E_SCENE, file, pos, key, path)))
            return e;
        if ((e = sl_mesh_load_file(&m, path, (const float *)x, &st, &md))) {
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "%s: %s", md.file[0] ? md.file : path, md.msg);
        }
    }
    if (m.nt == 0) {
        sl_mesh_free(&m);
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "mesh has no triangle");
    }
    /* overflow is the entry's: non-finite or past SL_MAX_COORD once placed */
    double ext = 0.0, sh = 0.0;
    for (uint32_t v = 0; v < 3 * m.nv; v++) {
        double a = fabs((double)m.pos[v]);
        ext = !(a <= ext) ? a : ext;   /* NaN sticks */
    }
    for (int k = 0; k < 3; k++)
        sh = fabs(shift[k]) > sh ? fabs(shift[k]) : sh;
    blame_key(r, i, ext, sh, key, sizeof key);
    if (!(ext + sh <= (double)(float)SL_MAX_COORD)) {   /* 1e30 as a float is 1.00000002e30 */
        sl_mesh_free(&m);
        int line = sl_yaml_line(pos, key);
        if (!line) {
            char ek[32];
            snprintf(ek, sizeof ek, "meshes[%u]", i);
            line = sl_yaml_line(pos, ek);
        }
        return sl_fail(d, SL_E_SCENE, file, line, key, "the mesh's coordinates reach %.3g once placed: at most "
                       "%g (float range; precision is lost long before)", ext + sh, SL_MAX_COORD);
    }
    /* append as one range */
    if (b->nranges == b->cap) {
        int cap = b->cap ? 2 * b->cap : 16;
        void *p = realloc(b->ranges, (size_t)cap * sizeof *b->ranges);
        if (p)
            b->ranges = p;
        void *q = p ? realloc(b->shift, (size_t)cap * sizeof *b->shift) : NULL;
        if (q)
            b->shift = q;
        void *w = q ? realloc(b->blame, (size_t)cap * sizeof *b->blame) : NULL;
        if (!w) {
            sl_mesh_free(&m);
            return sl_fail(d, SL_E_NOMEM, file, 0, NULL, "mesh ranges");
        }
        b->blame = w;
        b->cap = cap;
    }
    struct blame *bl = &b->blame[b->nranges];
    bl->reach = ext + sh;
    snprintf(bl->file, sizeof bl->file, "%s", file);
    snprintf(bl->key, sizeof bl->key, "%s", key);
    bl->line = sl_yaml_line(pos, key);
    if (!bl->line) {
        char ek[32];
        snprintf(ek, sizeof ek, "meshes[%u]", i);
        bl->line = sl_yaml_line(pos, ek);
    }
    memcpy(b->shift[b->nranges].t, shift, sizeof shift);
    b->shift[b->nranges].v0 = b->all.nv;
    b->shift[b->nranges].nv = m.nv;
    struct sl_mesh_range *rg = &b->ranges[b->nranges++];
    memset(rg, 0, sizeof *rg);
    if (r->name)
        snprintf(rg->name, sizeof rg->name, "%s", r->name);
    else
        snprintf(rg->name, sizeof rg->name, "%s%u", r->generator ? r->generator : "model", i);
    rg->first = b->all.nt;
    rg->count = m.nt;
    rg->two_sided = r->two_sided ? *r->two_sided : 0;
    rg->receiver = r->receiver ? *r->receiver : 0;
    uint32_t base = b->all.nv;
    for (uint32_t v = 0; v < m.nv; v++)
        sl_mesh_vertex(&b->all, m.pos[3 * v], m.pos[3 * v + 1], m.pos[3 * v + 2]);
    for (uint32_t t = 0; t < m.nt; t++)
        sl_mesh_tri(&b->all, base + m.idx[3 * t], base + m.idx[3 * t + 1], base + m.idx[3 * t + 2]);
    sl_mesh_free(&m);
    if (b->all.oom)
        return sl_fail(d, SL_E_NOMEM, file, 0, NULL, "scene too large");
    return SL_OK;
}

static enum sl_err read_light(const struct raw_light *l, const char *file, const struct sl_yaml_pos *pos,
                              struct sl_light *out, struct sl_diag *d)
{
    static const char *const types[] = {"directional", "spot", "point", "area"};
    memset(out, 0, sizeof *out);
    int t = -1;
    for (int k = 0; k < 4; k++)
        if (strcmp(l->type, types[k]) == 0)
            t = k;
    if (t < 0)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.type",
                           "unknown light type '%s' (known: directional, spot, point, area)", l->type);
    out->type = t;
    /* which keys each type takes: direction, position, fov, normal, up, size */
    static const unsigned takes[4] = {0x01, 0x07, 0x02, 0x3a};
    const void *given[6] = {l->direction, l->position, l->fov, l->normal, l->up, l->size};
    static const char *const names[6] = {"direction", "position", "fov", "normal", "up", "size"};
    char key[64];
    for (int k = 0; k < 6; k++) {
        snprintf(key, sizeof key, "light.%s", names[k]);
        if (given[k] && !(takes[t] & (1u << k)))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "light type '%s' takes no '%s'", types[t], names[k]);
        if (!given[k] && (takes[t] & (1u << k)))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light", "light type '%s' needs '%s'", types[t], names[k]);
    }
    if (l->direction && !unit3(l->direction, out->dir))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.direction", "direction must be finite and non-zero");
    if (l->position) {
        if (!finite3(l->position))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.position", "non-finite position");
        memcpy(out->pos, l->position, sizeof out->pos);
    }
    if (l->fov) {
        if (!(*l->fov > 0.0f && *l->fov < 180.0f))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.fov", "fov must be in (0, 180) degrees");
        out->fov_deg = *l->fov;
    }
    /* penumbra (spot only, optional): degrees of a soft rim inside the
     * cone's edge, [0, fov / 2]. Parsed, checked and stated in the tables'
     * headings; the hard methods and the truth ignore it (they shadow
     * against the cone's edge, a hard boundary), so it changes no count. */
    if (l->penumbra) {
        if (t != SL_LIGHT_SPOT)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.penumbra", "light type '%s' takes no 'penumbra' "
                               "(spot lights only)", types[t]);
        if (!(*l->penumbra >= 0.0f && *l->penumbra <= 0.5f * out->fov_deg))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.penumbra",
                               "penumbra must be in [0, fov / 2] = [0, %g] degrees", 0.5 * (double)out->fov_deg);
        out->penumbra_deg = *l->penumbra;
    }
    if (l->normal && !unit3(l->normal, out->normal))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.normal", "normal must be finite and non-zero");
    if (l->up) {
        if (!unit3(l->up, out->up) || fabsf(glm_vec3_dot(out->up, out->normal)) > 0.999f)
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.up", "up must be finite and not along the normal");
    }
    if (l->size) {
        if (!(isfinite(l->size[0]) && isfinite(l->size[1]) && l->size[0] > 0 && l->size[1] > 0))
            return sl_yaml_bad(d, SL_E_SCENE, file, pos, "light.size", "size must be finite and > 0");
        out->size[0] = l->size[0];
        out->size[1] = l->size[1];
    }
    return SL_OK;
}

/* Scene and viewpoint names become parts of file names under --out: only
 * [A-Za-z0-9._-], no leading dot (no '..', no hidden file), 1..63 bytes. */
static int safe_name(const char *s)
{
    size_t n = strlen(s);
    if (n == 0 || n > 63 || s[0] == '.')
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '.' && *s != '_' && *s != '-')
            return 0;
    return 1;
}

static enum sl_err read_viewpoint(const struct raw_vp *r, const char *file, const struct sl_yaml_pos *pos,
                                  unsigned i, struct sl_viewpoint *v, struct sl_diag *d)
{
    char key[96];
    memset(v, 0, sizeof *v);
    snprintf(v->name, sizeof v->name, "%s", r->name);
    v->path = -1;
    snprintf(key, sizeof key, "viewpoints[%u].name", i);
    if (!safe_name(r->name))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "viewpoint name '%.64s': use 1..63 letters, "
                           "digits, '-', '_' and '.', not starting with '.' (it names files)", r->name);
    snprintf(key, sizeof key, "viewpoints[%u].position", i);
    if (!finite3(r->position))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "non-finite position");
    memcpy(v->pos, r->position, sizeof v->pos);
    snprintf(key, sizeof key, "viewpoints[%u].direction", i);
    if (!unit3(r->direction, v->dir))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "direction must be finite and non-zero");
    float up[3] = {0, 1, 0};
    snprintf(key, sizeof key, "viewpoints[%u].up", i);
    if (r->up && !unit3(r->up, up))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "up must be finite and non-zero");
    if (fabsf(glm_vec3_dot(up, v->dir)) > 0.9999f)
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "up is parallel to the view direction");
    memcpy(v->up, up, sizeof up);
    /* Degenerate views are refused: they render as all background, with no
     * word. fov in (0.1, 179] degrees: at 179.999 tan(fov/2) is 1.1e5 and the
     * whole scene shrinks to the image's centre pixel (at 179, 115); below
     * 0.1 a pixel spans under 1e-6 radians, at float's precision for the
     * view direction. far/near at most 1e7: the projection is float, and
     * past that (1e-30 with 1e30, say) depths at the far end all round to
     * the same value, or the matrix's terms under- and overflow. */
    snprintf(key, sizeof key, "viewpoints[%u].fov", i);
    if (!(r->fov > 0.0f && r->fov < 180.0f))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "fov must be in (0, 180) degrees");
    if (!(r->fov > 0.1f && r->fov <= 179.0f))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "viewpoint '%s': fov %g degrees is degenerate: use "
                           "(0.1, 179] (the image would be all background)", r->name, (double)r->fov);
    snprintf(key, sizeof key, "viewpoints[%u].near", i);
    if (!(r->near > 0.0f) || !isfinite(r->near))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "near must be > 0");
    snprintf(key, sizeof key, "viewpoints[%u].far", i);
    if (!(r->far > r->near) || !isfinite(r->far))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "far must exceed near");
    if (!((double)r->far / (double)r->near <= 1e7))
        return sl_yaml_bad(d, SL_E_SCENE, file, pos, key, "viewpoint '%s': near %g and far %g are degenerate: "
                           "far/near must be at most 1e7 (depth precision)", r->name, (double)r->near,
                           (double)r->far);
    v->fov_deg = r->fov;
    v->znear = r->near;
    v->zfar = r->far;
    return SL_OK;
}

/* The files of a chain of base: scenes, outermost first (cycle check). */
struct chain { int n; char real[5][1024]; const char *shown[5]; };

/* realpath into a fixed buffer (realpath itself may write PATH_MAX bytes) */
static void real_of(const char *path, char *buf, size_t n)
{
    char *r = realpath(path, NULL);
    snprintf(buf, n, "%s", r ? r : path);
    free(r);
}

static void chain_text(const struct chain *ch, const char *last, char *buf, size_t n)
{
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < ch->n && k < n; i++)
        k += (size_t)snprintf(buf + k, n - k, "%s -> ", ch->shown[i]);
    if (k < n)
        snprintf(buf + k, n - k, "%s", last);
}

static enum sl_err load_into(const char *path, struct build *b, struct sl_light *light, int *have_light,
                             struct sl_scene *out, struct chain *ch, struct sl_diag *d)
{
    int depth = ch->n;
    real_of(path, ch->real[depth], sizeof ch->real[depth]);
    ch->shown[depth] = path;
    ch->n++;
    struct raw_scene *r = NULL;
    struct sl_yaml_pos *pos = NULL;
    enum sl_err e = sl_yaml_load(path, &scene_schema, (void **)&r, &pos, SL_SCENE_MAX_BYTES, SL_E_SCENE, d);
    if (e)
        return e;
    if (r->base) {
        char dir[512], bpath[1024];
        sl_path_dir(path, dir, sizeof dir);
        struct sl_diag bd;
        char real[1024];
        int cycle = 0;
        if (sl_scene_resolve(r->base, dir, bpath, sizeof bpath, &bd))
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "base", "%s", bd.msg);
        else {
            for (char *q; (q = strstr(bpath, "/./")) != NULL;) /* dir/./x.yaml -> dir/x.yaml */
                memmove(q, q + 2, strlen(q + 2) + 1);
            real_of(bpath, real, sizeof real);
            for (int k = 0; k < ch->n; k++)
                cycle |= strcmp(ch->real[k], real) == 0;
        }
        if (!e && cycle) {
            char text[800];
            chain_text(ch, bpath, text, sizeof text);
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "base", "base '%s' makes a cycle: %s", r->base, text);
        } else if (!e && depth >= 4)
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "base", "scenes based on scenes more than 4 deep");
        else if (!e)
            e = sl_yaml_ref_check(d, SL_E_SCENE, path, pos, "base", bpath);
        if (!e)
            e = load_into(bpath, b, light, have_light, NULL, ch, d);
    }
    if (!e && r->light) {
        e = read_light(r->light, path, pos, light, d);
        *have_light = 1;
    }
    for (unsigned i = 0; !e && i < r->meshes_count; i++)
        e = add_entry(b, &r->meshes[i], path, pos, i, d);
    if (!e && out) {
        const char *slash = strrchr(path, '/');
        const char *base = slash ? slash + 1 : path;
        size_t n = strlen(base);
        if (r->name)
            snprintf(out->name, sizeof out->name, "%s", r->name);
        else
            snprintf(out->name, sizeof out->name, "%.*s", (int)(n > 5 ? n - 5 : n), base);
        if (!safe_name(out->name))
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "name", "scene name '%.64s': use 1..63 letters, "
                            "digits, '-', '_' and '.', not starting with '.' (it names files)", out->name);
        if (r->description)
            snprintf(out->description, sizeof out->description, "%s", r->description);
        for (unsigned i = 0; !e && i < r->viewpoints_count; i++) {
            e = read_viewpoint(&r->viewpoints[i], path, pos, i, &out->vp[i], d);
            for (unsigned k = 0; !e && k < i; k++)
                if (strcmp(out->vp[k].name, out->vp[i].name) == 0) {
                    char key[64];
                    snprintf(key, sizeof key, "viewpoints[%u].name", i);
                    e = sl_yaml_bad(d, SL_E_SCENE, path, pos, key, "viewpoint '%s' named twice", out->vp[i].name);
                }
        }
        out->nvp = (int)r->viewpoints_count;
        if (!e && !*have_light)
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "light", "the scene has no light");
        if (!e && r->paths)
            e = sl_paths_expand(r->paths, r->paths_count, path, pos, light, out, d);
        if (!e && b->all.nt == 0)
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "meshes", "the scene has no mesh");
        if (!e && out->nvp + out->nframes == 0)
            e = sl_yaml_bad(d, SL_E_SCENE, path, pos, "viewpoints", "the scene has no viewpoint");
    }
    sl_yaml_free(&scene_schema, r, pos);
    return e;
}

/* Move the scene to its local frame: the origin is the centre of its
 * bounds (in double, in world units), and every position — vertices (with
 * their entry's translation), viewpoints, the light's position — becomes
 * relative to it. Shadows do not depend on where the world's origin is, but
 * float precision does: 1e5 units out, floats are 0.0078 apart and a camera
 * matrix built there moves edges by a pixel; in the local frame the scene is
 * computed as if it were at the origin (tests/test_hard.c: a scene 1e5 away
 * gives the same counts as its twin at the origin). */
static void rebase(struct build *b, struct sl_scene *out, struct sl_light *light)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int r = 0; r < b->nranges; r++)
        for (uint32_t v = b->shift[r].v0; v < b->shift[r].v0 + b->shift[r].nv; v++)
            for (int k = 0; k < 3; k++) {
                double w = (double)b->all.pos[3 * v + k] + b->shift[r].t[k];
                lo[k] = w < lo[k] ? w : lo[k];
                hi[k] = w > hi[k] ? w : hi[k];
            }
    for (int k = 0; k < 3; k++)
        out->origin[k] = isfinite(lo[k]) ? 0.5 * (lo[k] + hi[k]) : 0.0;
    for (int r = 0; r < b->nranges; r++)
        for (uint32_t v = b->shift[r].v0; v < b->shift[r].v0 + b->shift[r].nv; v++)
            for (int k = 0; k < 3; k++)
                b->all.pos[3 * v + k] =
                    (float)((double)b->all.pos[3 * v + k] + b->shift[r].t[k] - out->origin[k]);
    for (int i = 0; i < out->nvp + out->nframes; i++)
        for (int k = 0; k < 3; k++)
            out->vp[i].pos[k] = (float)((double)out->vp[i].pos[k] - out->origin[k]);
    for (int k = 0; k < 3; k++)
        light->pos[k] = (float)((double)light->pos[k] - out->origin[k]);
}

/* Each entry's triangles have area on their own (generators make none
 * without, models are welded and checked); one that has none in the local
 * frame was collapsed by float precision, because the scene spans far more
 * than its detail: the entry that reaches farthest made the span, and is
 * named (its translation, scale or model file), with the collapsed one. */
static enum sl_err collapsed(const struct build *b, struct sl_diag *d)
{
    for (int r = 0; r < b->nranges; r++) {
        const struct sl_mesh_range *rg = &b->ranges[r];
        for (uint32_t t = rg->first; t < rg->first + rg->count; t++) {
            const uint32_t *ix = b->all.idx + 3 * (size_t)t;
            double n[3];
            if (sl_tri_normal_d(b->all.pos + 3 * (size_t)ix[0], b->all.pos + 3 * (size_t)ix[1],
                                b->all.pos + 3 * (size_t)ix[2], n) > 0.0)
                continue;
            int far = 0;
            for (int k = 1; k < b->nranges; k++)
                far = b->blame[k].reach > b->blame[far].reach ? k : far;
            const struct blame *bl = &b->blame[far];
            return sl_fail(d, SL_E_SCENE, bl->file, bl->line, bl->key, "mesh '%s' reaches %g units: so far out, "
                           "float precision collapses triangle %u of mesh '%s' to zero area (keep the scene's "
                           "extent within about 1e6 times its smallest detail)", b->ranges[far].name, bl->reach,
                           t - rg->first, rg->name);
        }
    }
    return SL_OK;
}

enum sl_err sl_scene_load(const char *path, struct sl_scene *out, struct sl_diag *d)
{
    memset(out, 0, sizeof *out);
    struct build b;
    memset(&b, 0, sizeof b);
    struct sl_light light;
    memset(&light, 0, sizeof light);
    int have_light = 0;
    struct chain ch = {0};
    enum sl_err e = load_into(path, &b, &light, &have_light, out, &ch, d);
    if (!e) {
        rebase(&b, out, &light);
        e = collapsed(&b, d);
    }
    if (!e)
        e = sl_scene_from_mesh(out, &b.all, d);
    free(b.shift);
    free(b.blame);
    sl_mesh_free(&b.all);
    if (e) {
        free(b.ranges);
        sl_scene_free(out);
        if (!d->file[0])
            snprintf(d->file, sizeof d->file, "%s", path);
        return e;
    }
    snprintf(out->path, sizeof out->path, "%s", path);
    out->ranges = b.ranges;
    out->nranges = b.nranges;
    out->light = light;
    memcpy(out->light_dir, light.dir, sizeof out->light_dir);
    if (light.type == SL_LIGHT_AREA)   /* the light travels from its emitting side: PFL faces it */
        memcpy(out->light_dir, light.normal, sizeof out->light_dir);
    memcpy(out->base_light_dir, out->light_dir, sizeof out->base_light_dir);
    return SL_OK;
}

int sl_scene_sniff(const char *path, char *descr, size_t n)
{
    if (descr && n)
        descr[0] = '\0';
    int fd;
    struct sl_diag d;
    if (sl_open_regular(path, &fd, NULL, &d))
        return 0;   /* not a regular file: not a scene (its loader says why) */
    FILE *f = fdopen(fd, "r");
    if (!f) {
        close(fd);
        return 0;
    }
    char line[512];
    int scene = 0;
    while ((!scene || (descr && !descr[0])) && ftell(f) < (long)SL_SCENE_MAX_BYTES && fgets(line, sizeof line, f)) {
        scene |= strncmp(line, "meshes:", 7) == 0 || strncmp(line, "light:", 6) == 0 ||
                 strncmp(line, "base:", 5) == 0;
        if (descr && n && strncmp(line, "description:", 12) == 0 && !descr[0]) {
            char *v = line + 12;
            while (*v == ' ' || *v == '"')
                v++;
            v[strcspn(v, "\"\n")] = '\0';
            snprintf(descr, n, "%s", v);
        }
    }
    fclose(f);
    return scene;
}

int sl_scene_list_where(char (*names)[64], char (*descr)[160], char (*paths)[1024], const char **origins,
                        int max)
{
    char dirs[16][1024];
    const char *origin[16];
    int nd = sl_scene_dirs(NULL, dirs, origin, 16), n = 0;
    for (int di = 0; di < nd; di++) {
        DIR *dir = opendir(dirs[di]);
        if (!dir)
            continue;
        struct dirent *de;
        while ((de = readdir(dir)) && n < max) {
            size_t len = strlen(de->d_name);
            if (len < 6 || len > 68 || strcmp(de->d_name + len - 5, ".yaml") != 0 || de->d_name[0] == '.')
                continue;
            char name[64];
            snprintf(name, sizeof name, "%.*s", (int)(len - 5), de->d_name);
            int dup = 0;   /* an earlier folder of the path has it: that one is used */
            for (int k = 0; k < n && !dup; k++)
                dup = strcmp(names[k], name) == 0;
            char path[1100];
            snprintf(path, sizeof path, "%s/%s", dirs[di], de->d_name);
            if (dup || !sl_scene_sniff(path, descr[n], 160))
                continue;   /* configs and other YAML files are not scenes */
            snprintf(names[n], 64, "%s", name);
            if (paths)
                snprintf(paths[n], 1024, "%s", path);
            if (origins)
                origins[n] = origin[di];
            n++;
        }
        closedir(dir);
    }
    /* sorted, so listings are stable */
    for (int i = 1; i < n; i++)
        for (int k = i; k > 0 && strcmp(names[k - 1], names[k]) > 0; k--) {
            char t[64], td[160], tp[1024];
            memcpy(t, names[k], 64); memcpy(names[k], names[k - 1], 64); memcpy(names[k - 1], t, 64);
            memcpy(td, descr[k], 160); memcpy(descr[k], descr[k - 1], 160); memcpy(descr[k - 1], td, 160);
            if (paths) {
                memcpy(tp, paths[k], 1024); memcpy(paths[k], paths[k - 1], 1024); memcpy(paths[k - 1], tp, 1024);
            }
            if (origins) {
                const char *to = origins[k];
                origins[k] = origins[k - 1];
                origins[k - 1] = to;
            }
        }
    return n;
}

int sl_scene_list(char (*names)[64], char (*descr)[160], int max)
{
    return sl_scene_list_where(names, descr, NULL, NULL, max);
}

enum sl_err sl_scene_build(const char *ref, struct sl_scene *out, struct sl_diag *d)
{
    char path[1024];
    memset(out, 0, sizeof *out);
    enum sl_err e = sl_scene_resolve(ref, NULL, path, sizeof path, d);
    return e ? e : sl_scene_load(path, out, d);
}
