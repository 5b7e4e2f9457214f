/*
 * image_ops.h — the table between image.c (in every binary) and the
 * OpenImageIO module (image_oiio.cpp, built as shadowlab-oiio.so and loaded
 * on first use). Each entry has the signature of its image.h function.
 * SL_IMAGE_ABI changes whenever this table or image.h's structs change, so a
 * stale module from another build is refused instead of called wrongly.
 */
#ifndef SL_IMAGE_OPS_H
#define SL_IMAGE_OPS_H
#include "image.h"
#ifdef __cplusplus
extern "C" {
#endif

#define SL_IMAGE_ABI 1

struct sl_image_ops {
    enum sl_err (*write_rgb8)(const char *, int, int, const unsigned char *, struct sl_diag *);
    enum sl_err (*write_layers)(const char *, int, int, int, const char *const *, const unsigned char *const *,
                                int, const struct sl_image_attr *, struct sl_diag *);
    enum sl_err (*read_layer)(const char *, const char *, int *, int *, unsigned **, struct sl_diag *);
    enum sl_err (*read_rgb8)(const char *, int *, int *, unsigned char **, struct sl_diag *);
    enum sl_err (*read_attr)(const char *, const char *, char *, int, struct sl_diag *);
    enum sl_err (*write_sheet)(const char *, const struct sl_image_sheet *, struct sl_diag *);
};

/* The module's one exported symbol: its table, or NULL when abi differs. */
typedef const struct sl_image_ops *(*sl_image_module_fn)(int abi, const char *git_sha);
#define SL_IMAGE_MODULE_SYMBOL "sl_image_module"
#define SL_IMAGE_MODULE_FILE "shadowlab-oiio.so"

#ifdef __cplusplus
}
#endif
#endif
