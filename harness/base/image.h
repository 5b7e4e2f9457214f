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

/* Write per-pixel integer layers (e.g. truth, verdict, how, contour) as the
 * UINT channels of one OpenEXR file, named as given; rows bottom-up. */
enum sl_err sl_image_write_layers(const char *path, int w, int h, int nlayers, const char *const *names,
                                  const unsigned char *const *layers, struct sl_diag *d);

/* Read back channel `name` of such a file as 32-bit integers, rows bottom-up
 * (tests); *out malloc'ed. */
enum sl_err sl_image_read_layer(const char *path, const char *name, int *w, int *h, unsigned **out,
                                struct sl_diag *d);

/* Read back an 8-bit RGB image (for tests); *rgb malloc'ed, rows top-down. */
enum sl_err sl_image_read_rgb8(const char *path, int *w, int *h, unsigned char **rgb,
                               struct sl_diag *d);

#ifdef __cplusplus
}
#endif
#endif
