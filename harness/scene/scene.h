/*
 * scene.h — a scene in memory: one indexed triangle soup (all meshes welded
 * into shared vertex/index arrays, triangle i = primitive i in GL and in
 * Embree), per-triangle unit face normals, the bounding box, one directional
 * light and the named viewpoints.
 *
 * Each mesh of the scene file is one contiguous range of triangles, welded
 * on its own (so adjacency follows each object's real connectivity and never
 * joins two objects that merely touch), and is one- or two-sided.
 *
 * Owns: its arrays (sl_scene_free releases everything; NULL-safe).
 * Does not: touch GL or Embree (gl buffers and BVHs are built from it by
 * glctx.c and truth.c). Scene files are read by scenefile.c.
 */
#ifndef SL_SCENE_H
#define SL_SCENE_H
#include <stdint.h>
#include "scenelimits.h"
#include "sl_error.h"


struct sl_viewpoint {
    char  name[32];
    float pos[3];
    float dir[3];     /* unit */
    float up[3];      /* unit */
    float fov_deg;    /* vertical */
    float znear, zfar;
    /* a path's frame (pathfile.h): its path (index into sl_scene.paths) and
     * frame number; path = -1 for a named viewpoint */
    int   path, frame;
    int   has_light;        /* the frame moves the directional light: light_dir replaces the scene's */
    float light_dir[3];     /* unit direction the light travels */
};

enum sl_light_type {
    SL_LIGHT_DIRECTIONAL = 0,
    SL_LIGHT_SPOT,
    SL_LIGHT_POINT,
    SL_LIGHT_AREA,     /* rectangle: centre, normal, up, size */
};

struct sl_light {
    int   type;        /* enum sl_light_type */
    float dir[3];      /* directional, spot: unit direction the light travels */
    float pos[3];      /* spot, point; area: centre */
    float fov_deg;     /* spot: full cone angle */
    float penumbra_deg;/* spot, optional: the soft rim's angular width inside the cone's edge; the
                        * hard methods and the truth ignore it (the cone's edge stays at fov / 2) */
    float normal[3];   /* area: unit, the side that emits */
    float up[3];       /* area: unit, in the light's plane */
    float size[2];     /* area: width (across up x normal), height (along up) */
};

#define SL_MESH_NAME 48
struct sl_mesh_range {
    char     name[SL_MESH_NAME];
    uint32_t first, count;    /* triangles [first, first + count) */
    int      two_sided;       /* leaves: never culled, shadowed from both sides */
    int      receiver;        /* a pure receiver (the ground): left out of soft_mc's layers (Curtis 3.3) */
};

struct sl_scene {
    char      name[64];
    char      path[512];      /* scene file, "" for scenes made in code */
    char      description[160];
    struct sl_light light;
    struct sl_mesh_range *ranges;
    int       nranges;
    float    *pos;    /* 3 * nv */
    uint32_t  nv;
    uint32_t *idx;    /* 3 * nt */
    uint32_t  nt;
    float    *fn;     /* 3 * nt, unit face normals (counter-clockwise front) */
    float     lo[3], hi[3];
    float     light_dir[3];   /* = light.dir: unit direction the light travels */
    struct sl_viewpoint vp[SL_MAX_VIEWS];
    int       nvp;            /* named viewpoints; the paths' frames follow them */
    int       nframes;        /* frames of every path, vp[nvp .. nvp + nframes) */
    struct sl_path_info {
        char name[24];
        int  first, count;    /* its frames: vp[first .. first + count) */
        int  moves_camera, moves_light;
    } paths[SL_MAX_PATHS];
    int       npaths;
    float     base_light_dir[3];  /* the scene file's light direction (a frame's may replace light_dir) */
    double    origin[3];      /* world position of the scene's local origin: scene files are
                               * moved there (scenefile.c, rebase), positions above are local */
};

/* Growing mesh used by the generators; appended into a scene. */
struct sl_mesh {
    float    *pos; uint32_t nv, cap_v;
    uint32_t *idx; uint32_t nt, cap_t;
    int       oom;   /* set when an append failed; checked once at the end */
};

/* The unnormalised normal (b - a) x (c - a) of a triangle in double; returns
 * its length (twice the area), 0 for a zero-area triangle. The scene and the
 * weld share it, so the weld drops exactly the triangles a scene rejects. */
double sl_tri_normal_d(const float a[3], const float b[3], const float c[3], double n[3]);

/* Scene from a mesh: copies arrays, computes face normals and bounds;
 * degenerate (zero-area) triangles are rejected with SL_E_SCENE. */
enum sl_err sl_scene_from_mesh(struct sl_scene *s, const struct sl_mesh *m, struct sl_diag *d);

/* A named viewpoint or a path's frame ("orbit.007") by name, -1 none. */
int         sl_scene_find_viewpoint(const struct sl_scene *s, const char *name);
/* A path by name, -1 none. */
int         sl_scene_find_path(const struct sl_scene *s, const char *name);

/* Make viewpoint vp's light the scene's: a light path's frame sets
 * light.dir and light_dir to its own direction, any other viewpoint puts
 * back the scene file's (base_light_dir). Directional lights only move. */
void        sl_scene_use_view_light(struct sl_scene *s, int vp);

void sl_scene_free(struct sl_scene *s);

/* The mesh (index into ranges) holding triangle t (0-based), or -1: the
 * ranges follow one another in the scene file's order, so a binary search
 * over their first triangles. */
static inline int sl_scene_mesh_of(const struct sl_scene *s, uint32_t t)
{
    int lo = 0, hi = s->nranges - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (s->ranges[mid].first <= t)
            lo = mid;
        else
            hi = mid - 1;
    }
    return s->nranges > 0 && t >= s->ranges[lo].first && t - s->ranges[lo].first < s->ranges[lo].count ? lo : -1;
}

#endif
