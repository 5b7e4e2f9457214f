/*
 * fuzz_config.c — libFuzzer entry for the config loader (sl_config_load).
 * The loader loads every scene a config names; those resolve in fuzz/scenes/
 * (SHADOWLAB_SCENES, unless set): the real scenes with one small plane for
 * meshes (fuzz/tiny_scenes.py), so an input costs milliseconds, not the
 * seconds of generating Bench's 54,200 triangles under ASan.
 */
#include "fuzz_common.h"
#include "config.h"

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    setenv("SHADOWLAB_SCENES", SL_FUZZ_SCENES, 0);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, ".yaml");
    struct sl_config *c = calloc(1, sizeof *c);
    struct sl_diag d;
    if (c && sl_config_load(path, c, &d) == SL_OK)
        sl_config_free(c);
    free(c);
    unlink(path);
    return 0;
}
