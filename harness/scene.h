/*
 * scene.h — a scene in memory: one indexed triangle soup (all meshes welded
 * into shared vertex/index arrays, triangle i = primitive i in GL and in
 * Embree), per-triangle unit face normals, the bounding box, one directional
 * light and the named viewpoints.
 *
 * Owns: its arrays (sl_scene_free releases everything; NULL-safe).
 * Does not: touch GL or Embree (gl buffers and BVHs are built from it by
 * glctx.c and truth.c), read files (the YAML scene loader is a later module;
 * for now scenes are built by name from procedural generators, see gen.c).
 */
#ifndef SL_SCENE_H
#define SL_SCENE_H
#include <stdint.h>
#include "sl_error.h"

#define SL_MAX_VIEWPOINTS 16

struct sl_viewpoint {
    char  name[32];
    float pos[3];
    float dir[3];     /* unit */
    float up[3];      /* unit */
    float fov_deg;    /* vertical */
    float znear, zfar;
};

struct sl_scene {
    char      name[64];
    float    *pos;    /* 3 * nv */
    uint32_t  nv;
    uint32_t *idx;    /* 3 * nt */
    uint32_t  nt;
    float    *fn;     /* 3 * nt, unit face normals (counter-clockwise front) */
    float     lo[3], hi[3];
    float     light_dir[3];   /* unit direction the light travels */
    struct sl_viewpoint vp[SL_MAX_VIEWPOINTS];
    int       nvp;
};

/* Growing mesh used by the generators; appended into a scene. */
struct sl_mesh {
    float    *pos; uint32_t nv, cap_v;
    uint32_t *idx; uint32_t nt, cap_t;
    int       oom;   /* set when an append failed; checked once at the end */
};

uint32_t sl_mesh_vertex(struct sl_mesh *m, float x, float y, float z);
void     sl_mesh_tri(struct sl_mesh *m, uint32_t a, uint32_t b, uint32_t c);
void     sl_mesh_free(struct sl_mesh *m);

/* Procedural generators (gen.c). Every mesh is closed unless it is a plane;
 * front faces are counter-clockwise seen from outside. */
void sl_gen_plane(struct sl_mesh *m, float cx, float y, float cz, float size, int grid);
void sl_gen_sphere(struct sl_mesh *m, float cx, float cy, float cz, float r, int slices, int stacks);
void sl_gen_torus(struct sl_mesh *m, float cx, float cy, float cz, float R, float r, int nu, int nv);
void sl_gen_cylinder(struct sl_mesh *m, float cx, float y0, float cz, float r, float h, int n);
void sl_gen_pyramid(struct sl_mesh *m, float cx, float y0, float cz, float base, float h);
void sl_gen_box(struct sl_mesh *m, const float lo[3], const float hi[3]);

/* Scene from a mesh: copies arrays, computes face normals and bounds;
 * degenerate (zero-area) triangles are rejected with SL_E_SCENE. */
enum sl_err sl_scene_from_mesh(struct sl_scene *s, const struct sl_mesh *m, struct sl_diag *d);

/* Built-in scenes by name ("primitives", "quad-test", ...). */
enum sl_err sl_scene_build(const char *name, struct sl_scene *out, struct sl_diag *d);
int         sl_scene_count(void);
const char *sl_scene_name(int i);
const char *sl_scene_summary(int i);
int         sl_scene_find_viewpoint(const struct sl_scene *s, const char *name);

void sl_scene_free(struct sl_scene *s);

#endif
