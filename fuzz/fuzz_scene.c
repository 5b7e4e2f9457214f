/*
 * fuzz_scene.c — libFuzzer entry for the scene-file loader (sl_scene_load).
 * A `base:` naming a scene resolves in fuzz/scenes/ (SHADOWLAB_SCENES,
 * unless set; see fuzz_config.c), so a base costs a small plane, while the
 * input's own generators still run at the sizes it asks for.
 */
#include "fuzz_common.h"
#include "scenefile.h"

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
    struct sl_scene s;
    struct sl_diag d;
    memset(&s, 0, sizeof s);
    if (sl_scene_load(path, &s, &d) == SL_OK)
        sl_scene_free(&s);
    unlink(path);
    return 0;
}
