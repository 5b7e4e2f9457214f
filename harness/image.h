/*
 * image.h — the C face of the OpenImageIO wrapper (image.cpp, the only C++ in
 * shadowlab). Writes 8-bit RGB images; the format follows the extension.
 * Rows are given bottom-up (GL order) and written top-down. The file appears
 * under its name only when complete (written to a temporary, then renamed).
 */
#ifndef SL_IMAGE_H
#define SL_IMAGE_H
#include "sl_error.h"
#ifdef __cplusplus
extern "C" {
#endif

enum sl_err sl_image_write_rgb8(const char *path, int w, int h, const unsigned char *rgb_bottom_up,
                                struct sl_diag *d);

/* Read back an 8-bit RGB image (for tests); *rgb malloc'ed, rows top-down. */
enum sl_err sl_image_read_rgb8(const char *path, int *w, int *h, unsigned char **rgb,
                               struct sl_diag *d);

#ifdef __cplusplus
}
#endif
#endif
