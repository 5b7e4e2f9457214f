/*
 * meshio_check.h — checks of a model file's bytes before assimp reads it:
 * PLY (ASCII: element lines present vs declared; binary little and big
 * endian: bytes present vs declared, face vertex indices vs the declared
 * vertex count) and OBJ (face corners naming a vertex, texture coordinate
 * or normal that does not exist). Other formats pass unchecked.
 * Returns SL_OK or SL_E_SCENE with d->file = path and a one-line reason.
 * Does not: read geometry, or refuse what it does not understand.
 */
#ifndef SL_MESHIO_CHECK_H
#define SL_MESHIO_CHECK_H
#include "sl_error.h"

enum sl_err sl_mesh_precheck(const char *path, struct sl_diag *d);
#endif
