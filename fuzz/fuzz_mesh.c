/*
 * fuzz_mesh.c — libFuzzer entry for the model reader (meshio.c).
 *
 * With SL_FUZZ_MESH_HERE (cmake -DSL_FUZZ_MESH_HERE=ON) the reader runs in
 * this process (sl_mesh_load_file_here): the byte checks of PLY and OBJ
 * (meshio_check.c), assimp, the checks of what assimp returns and the weld,
 * all guided by coverage and seen by the sanitizers, at 128 inputs/s and
 * more instead of 3 (each input forked a sanitized process). A crash, a
 * hang or a leak in assimp is then a finding of this process: one the
 * child contains at run time, which needs triage (a byte check in
 * meshio_check.c where one can tell, or an input in tests/bad/models/).
 * Such findings come within seconds today (issue 34: a glTF skin SEGV, an
 * ASCII PLY loop), so CI builds the default: the reader in its child, as at
 * run time, with the byte checks also run here in-process, where they are
 * guided and where ASan sees them. SL_FUZZ_EXT picks the file name's
 * extension (assimp, and the byte checks, go by it).
 */
#include "fuzz_common.h"
#include "gen.h"      /* sl_mesh_free */
#include "meshio.h"
#include "meshio_check.h"
#ifndef SL_FUZZ_EXT
#define SL_FUZZ_EXT ".obj"
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, SL_FUZZ_EXT);
    struct sl_mesh m = {0};
    struct sl_mesh_load_stats st;
    struct sl_diag d;
#ifdef SL_FUZZ_MESH_HERE
    (void)sl_mesh_load_file_here(&m, path, NULL, &st, &d);
#else
    (void)sl_mesh_precheck(path, &d);
    (void)sl_mesh_load_file(&m, path, NULL, &st, &d);
#endif
    sl_mesh_free(&m);
    unlink(path);
    return 0;
}
