/*
 * fuzz_mesh.c — libFuzzer entry for the model reader (meshio.c).
 *
 * With SL_FUZZ_MESH_HERE (cmake -DSL_FUZZ_MESH_HERE=ON) the reader runs in
 * this process on the input's bytes (sl_mesh_load_mem_here: no temporary
 * file, no fork; OBJ by path, see below): the byte checks of PLY and OBJ (meshio_check.c), assimp
 * (from memory, with the extension as its format hint), the checks of what
 * assimp returns and the weld, all guided by coverage and seen by the
 * sanitizers. A crash, a hang or a leak in assimp is then a finding of this
 * process: one the child contains at run time, which needs triage (a byte
 * check in meshio_check.c that refuses its class, and the input in
 * tests/bad/models/), or a crash fuzz/run.sh counts as assimp's own (fork
 * mode; its stack puts libassimp first, fuzz/classify.awk) once the
 * reader's child is seen to contain it (SL_FUZZ_CHILD below). CI builds
 * with it. Without it, the reader runs in its child, as at run
 * time, on a temporary file (~2 inputs/s: each input forks a sanitized
 * process whose coverage libFuzzer does not see), with the byte checks also
 * run here in-process. SL_FUZZ_EXT picks the format (assimp and the byte
 * checks go by the extension).
 */
#include "gen.h"      /* sl_mesh_free */
#include "meshio.h"
#include "meshio_check.h"
#ifndef SL_FUZZ_EXT
#define SL_FUZZ_EXT ".obj"
#endif
#include "fuzz_common.h"
#ifdef SL_FUZZ_MESH_HERE
/* OBJ names side files (mtllib): assimp opens them through the memory
 * reader's IO system, which crashes on some names (a write to a wild
 * address; the same file read by path loads), so OBJ inputs are read by
 * path, in this process. */
#define SL_FUZZ_BY_PATH (sizeof SL_FUZZ_EXT == 5 && !memcmp(SL_FUZZ_EXT, ".obj", 4))

/* SL_FUZZ_CHILD=1 in the environment: read the input as at run time, in
 * the reader's child (sl_mesh_load_file), and say how it ended on stderr.
 * fuzz/run.sh runs each input of a crash it blames on assimp this way
 * (-runs=1): the parent must come back with a result, not crash or hang. */
static int fuzz_child = -1;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct sl_mesh m = {0};
    struct sl_mesh_load_stats st;
    struct sl_diag d = {0};
    if (fuzz_child < 0)
        fuzz_child = getenv("SL_FUZZ_CHILD") != NULL;
    if (fuzz_child) {
        const char *path = fuzz_file(data, size, SL_FUZZ_EXT);
        int rc = (int)sl_mesh_load_file(&m, path, NULL, &st, &d);
        fprintf(stderr, "sl-fuzz-child: %s: rc %d%s%s\n", SL_FUZZ_EXT, rc,
                rc ? ": " : " (loaded)", rc ? d.msg : "");
        unlink(path);
    } else if (SL_FUZZ_BY_PATH) {
        const char *path = fuzz_file(data, size, SL_FUZZ_EXT);
        (void)sl_mesh_load_file_here(&m, path, NULL, &st, &d);
        unlink(path);
    } else {
        (void)sl_mesh_load_mem_here(&m, data, size, "input" SL_FUZZ_EXT, NULL, &st, &d);
    }
    sl_mesh_free(&m);
    return 0;
}
#else

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
#endif
