/*
 * fuzz_common.h — libFuzzer entries read files by path, so each input is
 * written to a private temporary file first (the loaders resolve relative
 * paths against the file's folder; /tmp holds no scenes, which is fine).
 */
#ifndef SL_FUZZ_COMMON_H
#define SL_FUZZ_COMMON_H
#define _DEFAULT_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Writes data to /tmp/sl-fuzz-PID<suffix>; returns the path (static). */
static const char *fuzz_file(const uint8_t *data, size_t size, const char *suffix)
{
    static char path[128];
    snprintf(path, sizeof path, "/tmp/sl-fuzz-%ld%s", (long)getpid(), suffix);
    FILE *f = fopen(path, "wb");
    if (!f)
        abort();
    if (size && fwrite(data, 1, size, f) != size)
        abort();
    fclose(f);
    return path;
}
#endif
