/*
 * meshio_check.h — checks of a model file's bytes before assimp reads it:
 * PLY (ASCII: element lines present vs declared; binary little and big
 * endian: bytes present vs declared, face vertex indices vs the declared
 * vertex count; headers assimp crashes or loops on: a NUL byte, no
 * end_header token, a property before any element or of no PLY type), OBJ
 * (face corners naming a vertex, texture coordinate or normal that does
 * not exist) and glTF JSON (a skin without inverseBindMatrices, which
 * assimp 5.2 reads through a NULL pointer). Other formats pass unchecked.
 * Returns SL_OK or SL_E_SCENE with d->file = path and a one-line reason.
 * Does not: read geometry, or refuse what it does not understand.
 */
#ifndef SL_MESHIO_CHECK_H
#define SL_MESHIO_CHECK_H
#include <stddef.h>
#include "sl_error.h"

enum sl_err sl_mesh_precheck(const char *path, struct sl_diag *d);
/* The same checks of bytes in memory; `name` gives the format (by its
 * extension) and is what messages name (the fuzz entries). */
enum sl_err sl_mesh_precheck_mem(const void *data, size_t size, const char *name, struct sl_diag *d);
#endif
