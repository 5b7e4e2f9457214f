/*
 * image.h — the C face of the OpenImageIO wrapper (image.cpp, the only C++ in
 * shadowlab). Writes 8-bit RGB images; the format follows the extension.
 * Rows are given bottom-up (GL order) and written top-down. The file appears
 * under its name only when complete (written to a temporary, then renamed).
 *
 * The overlay sheet (sl_image_write_sheet) is composed in plain memory,
 * reproducing ImageBufAlgo's drawing byte for byte (each glyph drawn once
 * per size and process, by FreeType as render_text calls it, then blitted),
 * and encoded as a PNG by libdeflate in one call (the pixels and header keys
 * OpenImageIO wrote), in a module of its own that does not load OpenImageIO:
 * the frame (or a crop of it) at 1:1, zoomed insets beside it (nearest
 * neighbour) whose windows are marked on the frame, a title and a legend.
 * Text needs a TrueType font (DejaVu Sans, Debian's fonts-dejavu-core, or,
 * when that file is missing, what OpenImageIO's font search finds, through
 * its module); without one the sheet is drawn without text and
 * the legend and captions are still in the file's metadata.
 */
#ifndef SL_IMAGE_H
#define SL_IMAGE_H
#include <stdint.h>
#include "sl_error.h"
#ifdef __cplusplus
extern "C" {
#endif

enum sl_err sl_image_write_rgb8(const char *path, int w, int h, const unsigned char *rgb_bottom_up,
                                struct sl_diag *d);

/* Header attributes: name = value strings. */
struct sl_image_attr { const char *name, *value; };

/* Per-pixel integer layers (truth, verdict, ...) as one OpenEXR file. Each
 * layer is written twice: as a HALF channel under its name holding the code
 * itself (0, 1, 2, ... exact in half; what viewers and `oiiotool --stats`
 * show), and as a UINT channel "code.<name>" (the integer as it is, for
 * tools that want integers). attrs (may be 0) go in the header, e.g.
 * "shadowlab:verdict" = "0 background, 1 lit, ...". Rows bottom-up. */
enum sl_err sl_image_write_layers(const char *path, int w, int h, int nlayers, const char *const *names,
                                  const unsigned char *const *layers, int nattrs,
                                  const struct sl_image_attr *attrs, struct sl_diag *d);

/* Read back channel `name` of such a file as 32-bit integers, rows bottom-up
 * (tests): a UINT channel as it is, a HALF or FLOAT one rounded; *out malloc'ed. */
enum sl_err sl_image_read_layer(const char *path, const char *name, int *w, int *h, unsigned **out,
                                struct sl_diag *d);

/* Read back an 8-bit RGB image (for tests); *rgb malloc'ed, rows top-down. */
enum sl_err sl_image_read_rgb8(const char *path, int *w, int *h, unsigned char **rgb,
                               struct sl_diag *d);

/* A string attribute of an image file's header into out (n bytes);
 * SL_E_IO when the file or the attribute is missing. */
enum sl_err sl_image_read_attr(const char *path, const char *name, char *out, int n, struct sl_diag *d);

/* Float channels as one OpenEXR file (FLOAT, zip), rows bottom-up: chans[c]
 * holds w * h values of the channel names[c]; attrs (may be 0) go in the
 * header. What `outputs.visibility: exr` writes (a cell's visibility, V, and
 * its coverage, A) and what `shadowlab grade` reads back. */
enum sl_err sl_image_write_floats(const char *path, int w, int h, int nch, const char *const *names,
                                  const float *const *chans, int nattrs, const struct sl_image_attr *attrs,
                                  struct sl_diag *d);

/* An image read as floats, every channel, rows bottom-up: px holds nch
 * values a pixel; names[c] the file's channel names ("R", "Y", "A", ...);
 * bits the file's bits per value (8, 16, 32; half: 16, float: 32) and
 * is_float whether they are floating point. Values as stored: integers
 * scaled to 0..1, alpha not multiplied in or out (a PNG's alpha is read as
 * it is stored, unassociated), no colour-space conversion. */
#define SL_IMAGE_MAX_CH 8
struct sl_image_floats {
    int    w, h, nch, bits, is_float;
    char   names[SL_IMAGE_MAX_CH][32];
    char   format[16];   /* the reader's name: "openexr", "png", ... */
    float *px;
};
/* SL_E_IO when the file cannot be read (named), SL_E_USAGE when it has more
 * than SL_IMAGE_MAX_CH channels or more than 2^28 pixels. *out zeroed on
 * failure; free with sl_image_floats_free (NULL-safe). */
enum sl_err sl_image_read_floats(const char *path, struct sl_image_floats *out, struct sl_diag *d);
void        sl_image_floats_free(struct sl_image_floats *im);

#define SL_SHEET_MAX_INSETS 4
#define SL_SHEET_MAX_LEGEND 8

/* The overlay sheet. Rectangles are in the frame's pixels, y = 0 its bottom
 * row. Zero fields mean: no crop (whole frame), no insets, no legend. */
struct sl_image_sheet {
    int w, h;
    const unsigned char *rgb;        /* 3 * w * h, bottom-up */
    const unsigned char *keep;       /* w * h or NULL: nonzero where nothing may be drawn over (errors) */
    int view[4];                     /* x, y, w, h shown at 1:1; w == 0: the whole frame */
    int ninsets, zoom;
    int inset[SL_SHEET_MAX_INSETS][4];
    char inset_caption[SL_SHEET_MAX_INSETS][96];
    int nlegend;
    unsigned char legend_rgb[SL_SHEET_MAX_LEGEND][3];
    char legend_text[SL_SHEET_MAX_LEGEND][96];
    char title[200];
    int nattrs;
    const struct sl_image_attr *attrs;
};

/* Compose and write the sheet (PNG: the format follows the extension). Its
 * header says where each part landed, in the file's top-down pixels:
 * "shadowlab:view" = "x y w h X Y" (the frame's rectangle, top-down, and its
 * top-left corner in the sheet), "shadowlab:insetK" (K = 1, 2, ...) =
 * "x y s s X Y zoom", "shadowlab:legend" (the legend's lines) and
 * "shadowlab:text" = "1" when a font was found. */
enum sl_err sl_image_write_sheet(const char *path, const struct sl_image_sheet *s, struct sl_diag *d);

/* One glyph of the sheet's font at pixel size fs, as FreeType renders it:
 * the bitmap's placement from the pen (left, and top above the baseline),
 * its size, the pen's advance, and its coverage / 255 (w * h floats, top
 * row first, malloc'ed; NULL when empty). */
struct sl_image_glyph { int left, top, w, h, adv; float *a; };

/* Code point c at size fs as the sheets draw it (oiio 0: the sheet module's
 * own source, FreeType on the font file when it is there) or as OpenImageIO's
 * render_text draws it (oiio 1), each rendered afresh; for tests comparing
 * the two. 1 drawn, 0 the font has no such glyph, -1 no font or no module
 * (d says which module). */
int sl_image_glyph(int oiio, int fs, uint32_t c, struct sl_image_glyph *g, struct sl_diag *d);

#ifdef __cplusplus
}
#endif
#endif
