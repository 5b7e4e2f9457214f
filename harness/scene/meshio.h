/*
 * meshio.h — triangle meshes from model files, through assimp's C API
 * (OBJ, PLY, glTF/GLB, COLLADA, STL, ... whatever the installed assimp reads).
 *
 * A file's meshes (all nodes, with their node transforms) are triangulated,
 * transformed by `xform` (column-major 4x4, cglm layout; NULL = identity) and
 * appended to `m` as one welded indexed mesh: vertices with bit-identical
 * positions after the transform become one vertex, so edge and vertex
 * adjacency see the real connectivity. Points and lines are skipped.
 * Zero-area triangles (after welding) are dropped and counted.
 *
 * Errors (SL_E_SCENE, with d->file = path and a one-line reason): missing or
 * unreadable file, a format assimp does not read, a truncated or corrupt
 * file, a non-finite coordinate, a file with no triangle, a file whose
 * triangles all have zero area. On error `m` is left as it was.
 * Does not: touch GL or Embree, or know about scenes.
 */
#ifndef SL_MESHIO_H
#define SL_MESHIO_H
#include <stddef.h>
#include <stdint.h>
#include "scene.h"
#include "sl_error.h"

struct sl_mesh_load_stats {
    uint32_t meshes;            /* assimp meshes read */
    uint32_t triangles;         /* appended */
    uint32_t vertices;          /* appended, after welding */
    uint32_t degenerate;        /* zero-area triangles dropped */
    uint32_t skipped_prims;     /* points and lines skipped */
};

enum sl_err sl_mesh_load_file(struct sl_mesh *m, const char *path, const float xform[16],
                              struct sl_mesh_load_stats *st, struct sl_diag *d);
/* The same reader in this process, without the child: no isolation (a
 * crash or a loop in assimp is this process's) and no limits. For the fuzz
 * entries, where each input's fork of a sanitized process cost ~0.5 s and
 * the reader's coverage and sanitizer reports stayed in the child; never
 * for files a user gives. */
enum sl_err sl_mesh_load_file_here(struct sl_mesh *m, const char *path, const float xform[16],
                                   struct sl_mesh_load_stats *st, struct sl_diag *d);
/* The same, in this process, on size bytes at data: `name` stands for the
 * file in messages and gives assimp its format hint (its extension). For
 * the fuzz entries (no temporary file per input). */
enum sl_err sl_mesh_load_mem_here(struct sl_mesh *m, const void *data, size_t size, const char *name,
                                  const float xform[16], struct sl_mesh_load_stats *st,
                                  struct sl_diag *d);

/* Weld vertices of m with bit-identical positions (all of m, in place) and
 * drop triangles that become degenerate (two equal indices) or have zero
 * area; returns the number of triangles dropped. Order of the remaining
 * triangles is kept. */
uint32_t sl_mesh_weld(struct sl_mesh *m);

#endif
