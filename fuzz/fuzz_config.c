/* fuzz_config.c — libFuzzer entry for the config loader (sl_config_load). */
#include "fuzz_common.h"
#include "config.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size, ".yaml");
    struct sl_config *c = calloc(1, sizeof *c);
    struct sl_diag d;
    if (c)
        (void)sl_config_load(path, c, &d);
    free(c);
    unlink(path);
    return 0;
}
