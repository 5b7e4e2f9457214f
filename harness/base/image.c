/*
 * image.c — image.h's functions, forwarded to the OpenImageIO module
 * (image_oiio.cpp, shadowlab-oiio.so), which is loaded on the first image
 * read or written. OpenImageIO pulls ~260 shared libraries and ~130 MB into
 * a process (0.4 s of start-up on a quiet machine here); `version`,
 * `validate`, `table` and `check` write no image and so never pay for it.
 *
 * Where the module is looked for, first found wins:
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

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static const struct sl_image_ops *ops;
static char load_why[768];

/* Append "path: reason; " to load_why; returns the table when path loads. */
static const struct sl_image_ops *try_dir(const char *dir)
{
    char path[PATH_MAX];
    size_t used = strlen(load_why);
    if (snprintf(path, sizeof path, "%s/%s", dir, SL_IMAGE_MODULE_FILE) >= (int)sizeof path)
        return NULL;
    if (access(path, R_OK) != 0) {
        snprintf(load_why + used, sizeof load_why - used, "%s%s (absent)", used ? "; " : "", path);
        return NULL;
    }
    /* NODELETE: the module (and OpenImageIO) stays until exit, like a linked
     * library; its static state is shared by every later call. */
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    sl_image_module_fn entry = h ? (sl_image_module_fn)(void (*)(void))dlsym(h, SL_IMAGE_MODULE_SYMBOL) : NULL;
    const struct sl_image_ops *t = entry ? entry(SL_IMAGE_ABI, sl_git_sha()) : NULL;
    if (!t)
        snprintf(load_why + used, sizeof load_why - used, "%s%s (%s)", used ? "; " : "", path,
                 !h ? dlerror() : !entry ? "no " SL_IMAGE_MODULE_SYMBOL : "built for another version");
    return t;
}

static void load_module(void)
{
    const char *env = getenv("SHADOWLAB_MODULE_DIR");
    if (env && *env && (ops = try_dir(env)))
        return;
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;
            if ((ops = try_dir(exe)))
                return;
            char rel[PATH_MAX];
            if (snprintf(rel, sizeof rel, "%s/%s", exe, SL_MODULE_REL) < (int)sizeof rel && (ops = try_dir(rel)))
                return;
        }
    }
    ops = try_dir(SL_MODULE_BUILD_DIR);
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

enum sl_err sl_image_read_attr(const char *path, const char *name, char *out, int n, struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->read_attr(path, name, out, n, d) : SL_E_IMAGE;
}

enum sl_err sl_image_write_sheet(const char *path, const struct sl_image_sheet *s, struct sl_diag *d)
{
    const struct sl_image_ops *t = image_ops(path, d);
    return t ? t->write_sheet(path, s, d) : SL_E_IMAGE;
}
