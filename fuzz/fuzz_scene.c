/* fuzz_scene.c — libFuzzer entry for the scene-file loader (sl_scene_load). */
#include "fuzz_common.h"
#include "scenefile.h"

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
