/*
 * fuzz_mesh.c — libFuzzer entry for the mesh loader (sl_mesh_load_file).
 * assimp runs in the loader's child process, so a crash there is an error,
 * not a finding; what is fuzzed is our side: the byte checks of PLY and OBJ
 * (meshio_check.c), the checks of what assimp returns, the weld, and the
 * pipe protocol. The child's coverage and its sanitizer reports do not
 * reach libFuzzer (another process), so the byte checks, which only read,
 * are also run here in-process first: that is where they are guided and
 * where ASan sees them. SL_FUZZ_EXT picks the file name's extension
 * (assimp, and the byte checks, go by it).
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
    (void)sl_mesh_precheck(path, &d);
    (void)sl_mesh_load_file(&m, path, NULL, &st, &d);
    sl_mesh_free(&m);
    unlink(path);
    return 0;
}
