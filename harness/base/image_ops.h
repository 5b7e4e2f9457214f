/*
 * image_ops.h — the tables between image.c (in every binary) and its two
 * modules, each loaded on first use: OpenImageIO's (image_oiio.cpp, built as
 * shadowlab-oiio.so) and the sheet's (image_sheet.cpp, shadowlab-sheet.so,
 * which loads no OpenImageIO: FreeType and libdeflate). Each entry has the
 * signature of its image.h function.
 * SL_IMAGE_ABI changes whenever this table or image.h's structs change, so a
 * stale module from another build is refused instead of called wrongly.
 */
#ifndef SL_IMAGE_OPS_H
#define SL_IMAGE_OPS_H
#include "image.h"
#ifdef __cplusplus
extern "C" {
#endif

#define SL_IMAGE_ABI 3

struct sl_image_ops {
    enum sl_err (*write_rgb8)(const char *, int, int, const unsigned char *, struct sl_diag *);
    enum sl_err (*write_layers)(const char *, int, int, int, const char *const *, const unsigned char *const *,
                                int, const struct sl_image_attr *, struct sl_diag *);
    enum sl_err (*read_layer)(const char *, const char *, int *, int *, unsigned **, struct sl_diag *);
    enum sl_err (*read_rgb8)(const char *, int *, int *, unsigned char **, struct sl_diag *);
    enum sl_err (*read_attr)(const char *, const char *, char *, int, struct sl_diag *);
    enum sl_err (*write_floats)(const char *, int, int, int, const char *const *, const float *const *, int,
                                const struct sl_image_attr *, struct sl_diag *);
    enum sl_err (*read_floats)(const char *, struct sl_image_floats *, struct sl_diag *);
    /* a glyph through render_text and OpenImageIO's font search: the
     * sheet module's source when its font file is missing, and the tests'
     * reference (1 drawn, 0 none, -1 no font) */
    int (*glyph)(int fs, uint32_t c, struct sl_image_glyph *g);
};

/* A glyph source (sl_image_ops.glyph, or image.c's loader in front of it). */
typedef int (*sl_image_glyph_fn)(int fs, uint32_t c, struct sl_image_glyph *g);

struct sl_sheet_ops {
    enum sl_err (*write_sheet)(const char *, const struct sl_image_sheet *, struct sl_diag *);
    /* a glyph as the sheets draw it, rendered afresh */
    int (*glyph)(int fs, uint32_t c, struct sl_image_glyph *g);
};

/* The module's one exported symbol: its table, or NULL when abi differs. */
typedef const struct sl_image_ops *(*sl_image_module_fn)(int abi, const char *git_sha);
#define SL_IMAGE_MODULE_SYMBOL "sl_image_module"
#define SL_IMAGE_MODULE_FILE "shadowlab-oiio.so"

/* The sheet module's one exported symbol: its table, or NULL when abi
 * differs; glyph: where it asks for glyphs when its font file is missing. */
typedef const struct sl_sheet_ops *(*sl_sheet_module_fn)(int abi, const char *git_sha, sl_image_glyph_fn glyph);
#define SL_SHEET_MODULE_SYMBOL "sl_sheet_module"
#define SL_SHEET_MODULE_FILE "shadowlab-sheet.so"

#ifdef __cplusplus
}
#endif
#endif
