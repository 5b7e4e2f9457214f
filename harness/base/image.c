/*
 * image.c — image.h's functions, forwarded to the OpenImageIO module
 * (image_oiio.cpp, shadowlab-oiio.so), which is loaded on the first image
 * read or written, and the overlay sheets to the sheet module
 * (image_sheet.cpp, shadowlab-sheet.so: FreeType and libdeflate), loaded on
 * the first sheet. OpenImageIO pulls ~260 shared libraries and ~130 MB into
 * a process (0.4 s of start-up on a quiet machine here, 0.5 s of CPU); `version`,
 * `validate`, `table` and `check` write no image and so never pay for it,
 * and a run that writes sheets but no EXR does not either (issue 20).
 *
 * Where each module is looked for, first found wins:
 *   1. $SHADOWLAB_MODULE_DIR (a relocated or hand-built module);
 *   2. beside the running executable (the build tree: build/shadowlab);
 *   3. SL_MODULE_REL from the executable's folder (an installed tree:
 *      bin/../lib/shadowlab, computed from the install dirs at configure);
 *   4. SL_MODULE_BUILD_DIR, the build tree that compiled this file (tests
 *      and fuzz entries live in subfolders of it).
 * A missing or stale module is an SL_E_IMAGE failure naming every path tried.
 */
#define _GNU_SOURCE   /* readlink, PATH_MAX, dlopen flags */
#include "image_ops.h"
#include "provenance.h"
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef SL_MODULE_REL
#define SL_MODULE_REL "../lib/shadowlab"
#endif
#ifndef SL_MODULE_BUILD_DIR
#define SL_MODULE_BUILD_DIR "."
#endif

static pthread_once_t load_once = PTHREAD_ONCE_INIT, sheet_once = PTHREAD_ONCE_INIT;
static const struct sl_image_ops *ops;
static const struct sl_sheet_ops *sheet_ops;
static char load_why[768], sheet_why[768];

/* A module's file and entry point, and what its entry is called with. */
struct module {
    const char *file, *symbol;
    char *why;                         /* "path: reason; ..." of the paths tried */
    size_t nwhy;
    const void *(*enter)(void *entry);   /* the module's table, or NULL */
};

static int oiio_glyph_loaded(int fs, uint32_t c, struct sl_image_glyph *g);

static const void *enter_oiio(void *entry)
{
    return ((sl_image_module_fn)entry)(SL_IMAGE_ABI, sl_git_sha());
}

static const void *enter_sheet(void *entry)
{
    return ((sl_sheet_module_fn)entry)(SL_IMAGE_ABI, sl_git_sha(), oiio_glyph_loaded);
}

/* Append "path: reason; " to m->why; returns the table when path loads. */
static const void *try_dir(const struct module *m, const char *dir)
{
    char path[PATH_MAX];
    size_t used = strlen(m->why);
    if (snprintf(path, sizeof path, "%s/%s", dir, m->file) >= (int)sizeof path)
        return NULL;
    if (access(path, R_OK) != 0) {
        snprintf(m->why + used, m->nwhy - used, "%s%s (absent)", used ? "; " : "", path);
        return NULL;
    }
    /* NODELETE: the module (and OpenImageIO) stays until exit, like a linked
     * library; its static state is shared by every later call. */
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    void *entry = h ? dlsym(h, m->symbol) : NULL;
    const void *t = entry ? m->enter(entry) : NULL;
    if (!t)
        snprintf(m->why + used, m->nwhy - used, "%s%s (%s%s)", used ? "; " : "", path,
                 !h ? dlerror() : !entry ? "no " : "built for another version", !h || entry ? "" : m->symbol);
    return t;
}

static const void *load(const struct module *m)
{
    const void *t;
    const char *env = getenv("SHADOWLAB_MODULE_DIR");
    if (env && *env && (t = try_dir(m, env)))
        return t;
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;
            if ((t = try_dir(m, exe)))
                return t;
            char rel[PATH_MAX];
            if (snprintf(rel, sizeof rel, "%s/%s", exe, SL_MODULE_REL) < (int)sizeof rel && (t = try_dir(m, rel)))
                return t;
        }
    }
    return try_dir(m, SL_MODULE_BUILD_DIR);
}

static void load_module(void)
{
    const struct module m = {SL_IMAGE_MODULE_FILE, SL_IMAGE_MODULE_SYMBOL, load_why, sizeof load_why, enter_oiio};
    ops = load(&m);
}

static void load_sheet_module(void)
{
    const struct module m = {SL_SHEET_MODULE_FILE, SL_SHEET_MODULE_SYMBOL, sheet_why, sizeof sheet_why,
                             enter_sheet};
    sheet_ops = load(&m);
}

/* The table, or NULL with d filled. */
static const struct sl_image_ops *image_ops(const char *path, struct sl_diag *d)
{
    pthread_once(&load_once, load_module);
    if (!ops)
        sl_fail(d, SL_E_IMAGE, path, 0, NULL, "cannot load the image module: %s", load_why);
    return ops;
}

enum sl_err sl_image_write_rgb8(const char *path, int w, int h, const unsigned char *rgb, struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->write_rgb8(path, w, h, rgb, d) : SL_E_IMAGE;
}

enum sl_err sl_image_write_layers(const char *path, int w, int h, int nlayers, const char *const *names,
                                  const unsigned char *const *layers, int nattrs,
                                  const struct sl_image_attr *attrs, struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->write_layers(path, w, h, nlayers, names, layers, nattrs, attrs, d) : SL_E_IMAGE;
}

enum sl_err sl_image_read_layer(const char *path, const char *name, int *w, int *h, unsigned **out,
                                struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->read_layer(path, name, w, h, out, d) : SL_E_IMAGE;
}

enum sl_err sl_image_read_rgb8(const char *path, int *w, int *h, unsigned char **rgb, struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->read_rgb8(path, w, h, rgb, d) : SL_E_IMAGE;
}

enum sl_err sl_image_write_floats(const char *path, int w, int h, int nch, const char *const *names,
                                  const float *const *chans, int nattrs, const struct sl_image_attr *attrs,
                                  struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->write_floats(path, w, h, nch, names, chans, nattrs, attrs, d) : SL_E_IMAGE;
}

enum sl_err sl_image_read_floats(const char *path, struct sl_image_floats *out, struct sl_diag *d)
{
    memset(out, 0, sizeof *out);
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->read_floats(path, out, d) : SL_E_IMAGE;
}

void sl_image_floats_free(struct sl_image_floats *im)
{
    if (im) {
        free(im->px);
        im->px = NULL;
    }
}

enum sl_err sl_image_read_attr(const char *path, const char *name, char *out, int n, struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->read_attr(path, name, out, n, d) : SL_E_IMAGE;
}

/* The sheet module's table, or NULL with d filled. */
static const struct sl_sheet_ops *sheet_table(const char *path, struct sl_diag *d)
{
    pthread_once(&sheet_once, load_sheet_module);
    if (!sheet_ops)
        sl_fail(d, SL_E_IMAGE, path, 0, NULL, "cannot load the sheet module: %s", sheet_why);
    return sheet_ops;
}

enum sl_err sl_image_write_sheet(const char *path, const struct sl_image_sheet *s, struct sl_diag *d)
{
    const struct sl_sheet_ops *t = sheet_table(path, d);
    return t ? t->write_sheet(path, s, d) : SL_E_IMAGE;
}

/* The sheet module's glyphs when its font file is missing: OpenImageIO's
 * module loaded then, not before. -1 (no font) when it does not load. */
static int oiio_glyph_loaded(int fs, uint32_t c, struct sl_image_glyph *g)
{
    struct sl_diag d;
    const struct sl_image_ops *t = image_ops(NULL, &d);
    if (!t) {
        memset(g, 0, sizeof *g);
        return -1;
    }
    return t->glyph(fs, c, g);
}

int sl_image_glyph(int oiio, int fs, uint32_t c, struct sl_image_glyph *g, struct sl_diag *d)
{
    memset(g, 0, sizeof *g);
    if (oiio) {
        const struct sl_image_ops *t = image_ops(NULL, d);
        return t ? t->glyph(fs, c, g) : -1;
    }
    const struct sl_sheet_ops *t = sheet_table(NULL, d);
    return t ? t->glyph(fs, c, g) : -1;
}
