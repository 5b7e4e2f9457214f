/*
 * adjacency.h — edge and vertex adjacency of a scene's triangles, built once
 * per scene (the adjacency-aware methods read it: Moderno 2011's adjacent
 * geometry, Morais 2015's SGSM with adjacency, GL_TRIANGLES_ADJACENCY).
 *
 * Edge k of triangle t runs from idx[3t+k] to idx[3t+(k+1)%3].
 * - edge[3t+k]: the one other triangle sharing that edge (either winding);
 *   SL_ADJ_NONE when the edge is open (no other triangle) and SL_ADJ_MULTI
 *   when it is non-manifold (three or more triangles on it).
 * - opposite[3t+k]: the vertex of that neighbour not on the edge (for
 *   GL_TRIANGLES_ADJACENCY index buffers); SL_ADJ_NONE when edge[] is not a
 *   triangle.
 * - vertex neighbours in CSR form: the triangles sharing at least one vertex
 *   with t, t itself excluded, each once, ascending:
 *   vtx_tris[vtx_off[t] .. vtx_off[t+1]).
 * Connectivity is by vertex index, so the scene's vertices must be welded
 * (sl_mesh_weld) for it to mean geometry.
 */
#ifndef SL_ADJACENCY_H
#define SL_ADJACENCY_H
#include <stdint.h>
#include "scene.h"
#include "sl_error.h"

#define SL_ADJ_NONE  0xffffffffu
#define SL_ADJ_MULTI 0xfffffffeu

struct sl_adjacency {
    uint32_t  nt;
    uint32_t *edge;          /* 3 * nt */
    uint32_t *opposite;      /* 3 * nt */
    uint32_t *vtx_off;       /* nt + 1 */
    uint32_t *vtx_tris;      /* vtx_off[nt] */
    uint32_t  open_edges, nonmanifold_edges;
};

enum sl_err sl_adjacency_build(const struct sl_scene *s, struct sl_adjacency *a, struct sl_diag *d);
void        sl_adjacency_free(struct sl_adjacency *a);

#endif
