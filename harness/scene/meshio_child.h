/*
 * meshio_child.h — run a model reader in a forked child with CPU, memory and
 * wall-clock limits, and take back its mesh through a pipe, checked.
 *
 * The reader runs in the child only; a crash, a hang or an exhausted limit
 * there becomes an SL_E_SCENE error naming `path` and the cause (signal,
 * CPU seconds, wall seconds, memory limit). On success `out` (which must be
 * empty) holds the reader's mesh: every index below nv, every coordinate
 * finite, nv and nt in 1..MESHIO_MAX_ELEMS; the caller frees it. On error
 * `out` and `st` are left as they were.
 * Does not: read the file itself, or know what format it is.
 */
#ifndef SL_MESHIO_CHILD_H
#define SL_MESHIO_CHILD_H
#include "meshio.h"

/* uint32 indices and counts everywhere; keep well clear of the top values,
 * which adjacency uses as markers. */
#define MESHIO_MAX_ELEMS 0x3fffffffu

/* Reads path into the empty mesh m (in the child). */
typedef enum sl_err (*sl_mesh_reader_fn)(struct sl_mesh *m, const char *path,
                                         const float xform[16],
                                         struct sl_mesh_load_stats *st, struct sl_diag *d);

enum sl_err sl_mesh_read_in_child(sl_mesh_reader_fn read, const char *path,
                                  const float xform[16], struct sl_mesh *out,
                                  struct sl_mesh_load_stats *st, struct sl_diag *d);
#endif
