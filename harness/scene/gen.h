/*
 * gen.h — procedural meshes: the growing mesh the generators append to, and
 * the generators of the built-in scenes' shapes and props.
 *
 * Owns: nothing beyond the sl_mesh it is handed (sl_mesh_free). Does not:
 * read files (meshio.h, scenefile.h) or make a scene of a mesh (scene.h).
 */
#ifndef SL_GEN_H
#define SL_GEN_H
#include "scene.h"

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
/* Props of the Bench, Trees and Flowers scenes (metres; gen.c says each
 * one's shape). Triangle counts: cone 2n; tree 1024 (64 trunk + 960 open
 * leaves, two-sided); flowers 64 * count (12 closed solids a flower: a
 * prism stem, and petals, leaves and a blossom cone as thin solids 1.5 mm
 * thick, one-sided: front-face culling keeps the faces behind the lit
 * ones); bench 240 (20 closed boxes); lamp 172; flower box 28 (one closed
 * hollow solid; returns the soil height y0 + 0.8 h). Seeded ones give the
 * same mesh for the same seed. */
void  sl_gen_cone(struct sl_mesh *m, float cx, float y0, float cz, float r, float h, int n);
void  sl_gen_tree(struct sl_mesh *m, float cx, float y0, float cz, float height, uint32_t seed);
void  sl_gen_flowers(struct sl_mesh *m, float cx, float y0, float cz, float width, float depth,
                     int count, uint32_t seed);
void  sl_gen_bench(struct sl_mesh *m, float cx, float y0, float cz, float length, uint32_t seed);
void  sl_gen_lamp(struct sl_mesh *m, float cx, float y0, float cz, float height);
float sl_gen_flower_box(struct sl_mesh *m, float cx, float y0, float cz, float w, float d, float h);

#endif
