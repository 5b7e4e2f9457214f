/*
 * grade.c — `shadowlab grade` as a library call (grade.h): read the image
 * and the depth, check them as input, write the grade's config, run it.
 *
 * The image is input from outside: every refusal names the file and what
 * is wrong (size, bits, channels, values) before any GL or Embree work.
 * The channel graded is the one named V, Y, R, visibility or shadow, else
 * the first that is not alpha or depth; other colour channels must equal
 * it (an RGB shadow mask is fine, a shaded image is not). Values must lie
 * in 0..1 (NaN allowed: background, or a pixel the engine left undecided).
 */
#define _GNU_SOURCE
#include "grade.h"
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>
#include "config.h"
#include "image.h"
#include "run.h"
#include "util.h"

static int name_is(const char *n, const char *const *list)
{
    for (; *list; list++)
        if (!strcasecmp(n, *list))
            return 1;
    return 0;
}
static const char *const alpha_names[] = {"A", "alpha", NULL};
static const char *const depth_names[] = {"Z", "depth", NULL};
static const char *const vis_names[] = {"V", "Y", "R", "visibility", "shadow", NULL};

/* The channel of a visibility (depth = 0) or of a depth (depth = 1), -1 none. */
static int pick_channel(const struct sl_image_floats *im, int depth)
{
    for (int c = 0; c < im->nch; c++)
        if (name_is(im->names[c], depth ? depth_names : vis_names))
            return c;
    for (int c = 0; c < im->nch; c++)
        if (!name_is(im->names[c], alpha_names) && (depth || !name_is(im->names[c], depth_names)))
            return c;
    return -1;
}

static enum sl_err check_bits(const char *path, const struct sl_image_floats *im, struct sl_diag *d)
{
    if (im->bits < 16)
        return sl_fail(d, SL_E_USAGE, path, 0, NULL,
                       "%d-bit %s: a visibility or depth needs 16 bits (PNG) or half / float (EXR); 8 bits "
                       "round every fraction to 1/255",
                       im->bits, im->format);
    return SL_OK;
}

/* vis, bg and has_bg of e from the image at path. */
static enum sl_err read_visibility(const char *path, struct sl_external *e, float **vis, uint8_t **bg,
                                   struct sl_diag *d)
{
    struct sl_image_floats im;
    enum sl_err err = sl_image_read_floats(path, &im, d);
    if (err)
        return err == SL_E_NOMEM ? err : SL_E_USAGE;
    if ((err = check_bits(path, &im, d))) {
        sl_image_floats_free(&im);
        return err;
    }
    int vc = pick_channel(&im, 0), ac = -1;
    for (int c = 0; c < im.nch; c++)
        if (name_is(im.names[c], alpha_names))
            ac = c;
    if (vc < 0) {
        sl_image_floats_free(&im);
        return sl_fail(d, SL_E_USAGE, path, 0, NULL, "no visibility channel: only alpha or depth");
    }
    size_t n = (size_t)im.w * (size_t)im.h, nch = (size_t)im.nch;
    *vis = malloc(n * sizeof **vis);
    *bg = calloc(n, 1);
    if (!*vis || !*bg) {
        sl_image_floats_free(&im);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "visibility %d x %d", im.w, im.h);
    }
    e->w = im.w;
    e->h = im.h;
    e->has_bg = ac >= 0;
    for (size_t i = 0; i < n && !err; i++) {
        const float *p = im.px + i * nch;
        float v = p[vc];
        /* other colour channels agree with the graded one */
        for (int c = 0; c < im.nch && !err; c++)
            if (c != vc && c != ac && !name_is(im.names[c], depth_names) && !(p[c] == v || (isnan(p[c]) && isnan(v))))
                err = sl_fail(d, SL_E_USAGE, path, 0, NULL,
                              "channels %s and %s differ at pixel (%zu, %zu from the top): %g and %g; a "
                              "visibility is one channel (a shaded colour image is not one)",
                              im.names[vc], im.names[c], i % (size_t)im.w, (size_t)im.h - 1 - i / (size_t)im.w,
                              (double)v, (double)p[c]);
        if (err)
            break;
        int is_bg = isnan(v) || (ac >= 0 && !(p[ac] > 0.0f));
        if (isnan(v))
            e->has_bg = 1;
        if (!is_bg && !(v >= 0.0f && v <= 1.0f))
            err = sl_fail(d, SL_E_USAGE, path, 0, NULL,
                          "value %g at pixel (%zu, %zu from the top) outside 0..1: a visibility is 1 lit, 0 "
                          "shadowed (a lit colour or radiance is not one)",
                          (double)v, i % (size_t)im.w, (size_t)im.h - 1 - i / (size_t)im.w);
        (*bg)[i] = (uint8_t)is_bg;
        (*vis)[i] = is_bg ? NAN : v;
    }
    sl_image_floats_free(&im);
    return err;
}

double sl_grade_linear_depth(enum sl_depth_kind kind, int reversed, double nz, double fz, double z)
{
    if (!isfinite(z))
        return NAN;
    if (kind == SL_DEPTH_LINEAR)
        return z > 0.0 ? z : NAN;
    /* window depth: reversed-Z stores 1 - d; the far plane (or beyond) is
     * where nothing was drawn */
    double w01 = reversed ? 1.0 - z : z;
    if (w01 >= 1.0 || w01 < 0.0)
        return NAN;
    return nz * fz / (fz - w01 * (fz - nz));   /* w = f (z - n) / ((f - n) z), solved for z */
}

/* The engine's depth at path as linear depth (NaN where it drew nothing). */
static enum sl_err read_depth(const struct sl_grade_desc *g, int w, int h, float **out, struct sl_diag *d)
{
    struct sl_image_floats im;
    enum sl_err err = sl_image_read_floats(g->depth, &im, d);
    if (err)
        return err == SL_E_NOMEM ? err : SL_E_USAGE;
    if ((err = check_bits(g->depth, &im, d))) {
        sl_image_floats_free(&im);
        return err;
    }
    if (im.w != w || im.h != h) {
        sl_image_floats_free(&im);
        return sl_fail(d, SL_E_USAGE, g->depth, 0, NULL, "%d x %d pixels where the image is %d x %d", im.w, im.h, w,
                       h);
    }
    int zc = pick_channel(&im, 1);
    size_t n = (size_t)w * (size_t)h;
    if (zc < 0 || !(*out = malloc(n * sizeof **out))) {
        sl_image_floats_free(&im);
        return zc < 0 ? sl_fail(d, SL_E_USAGE, g->depth, 0, NULL, "no depth channel")
                      : sl_fail(d, SL_E_NOMEM, g->depth, 0, NULL, "depth %d x %d", w, h);
    }
    const double nz = g->near_z, fz = g->far_z;
    for (size_t i = 0; i < n; i++) {
        double lin = sl_grade_linear_depth(g->depth_kind, g->reversed_z, nz, fz, im.px[i * (size_t)im.nch + (size_t)zc]);
        (*out)[i] = (float)lin;
    }
    sl_image_floats_free(&im);
    return SL_OK;
}

/* A scene given as a path is written absolute (the config lives under
 * --out); a built-in scene's name as it is. YAML's double quotes escaped. */
static void yaml_quoted(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static enum sl_err write_config(const struct sl_grade_desc *g, const char *path, struct sl_diag *d)
{
    char scene[PATH_MAX];
    const size_t sl = strlen(g->scene);
    if (strchr(g->scene, '/') || (sl > 5 && !strcmp(g->scene + sl - 5, ".yaml"))) {
        if (!realpath(g->scene, scene))
            return sl_fail(d, SL_E_USAGE, g->scene, 0, "--scene", "no such scene file");
    } else {
        snprintf(scene, sizeof scene, "%s", g->scene);
    }
    FILE *f = fopen(path, "w");
    if (!f)
        return sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the grade's config");
    fprintf(f, "# shadowlab grade: the image below, graded as label %s (method external, doc/grade.md)\n",
            g->label);
    fprintf(f, "#   image: %s\n", g->image);
    if (g->depth)
        fprintf(f, "#   depth: %s (%s%s, near %g, far %g)\n", g->depth,
                g->depth_kind == SL_DEPTH_LINEAR ? "linear" : "window",
                g->reversed_z ? ", reversed-Z" : "", g->near_z, g->far_z);
    fprintf(f, "#   threshold %g, registration tolerance %g %% of the pixels\n", g->threshold, 100.0 * g->tolerance);
    fprintf(f, "# `shadowlab run` cannot run it: only `shadowlab grade` hands the label its image.\n");
    fprintf(f, "name: grade-%s\nscenes:\n  - scene: ", g->label);
    yaml_quoted(f, scene);
    fprintf(f, "\n    viewpoints: [");
    yaml_quoted(f, g->viewpoint);
    fprintf(f, "]\nviewports: [{width: %d, height: %d}]\nmap_sizes: [%d]\n", g->w, g->h, g->map_size);
    fprintf(f, "contour_from: %s\nmethods:\n  - {label: ", g->contour_own ? "own" : "nsm");
    yaml_quoted(f, g->label);
    fprintf(f, ", method: external}\nrepetitions: {warmup: 0, runs: 1}\nthreads: %d\n", g->threads);
    if (g->gl)
        fprintf(f, "gl: %s\n", sl_gl_backend_name(g->gl));
    return fclose(f) == 0 ? SL_OK : sl_fail(d, SL_E_OUTPUT, path, 0, NULL, "cannot write the grade's config");
}

enum sl_err sl_grade(const struct sl_grade_desc *gin, FILE *table_out, struct sl_grade_result *r,
                     struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    struct sl_grade_desc g = *gin;
    if (!g.out_root)
        g.out_root = "results";
    if (!g.map_size)
        g.map_size = 1024;
    if (g.threshold == 0.0)
        g.threshold = 0.5;
    if (g.tolerance == 0.0)
        g.tolerance = 0.01;
    if (g.depth_tolerance == 0.0)
        g.depth_tolerance = 0.01;
    /* the label names the config, its folder and its files: a plain word */
    size_t ll = g.label ? strlen(g.label) : 0;
    if (ll < 1 || ll > 40 || strspn(g.label, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") != ll ||
        g.label[0] == '.')
        return sl_fail(d, SL_E_USAGE, NULL, 0, "--label", "'%s': 1 to 40 letters, digits, -, _ or . (not first)",
                       g.label ? g.label : "");
    if (g.depth && g.depth_kind != SL_DEPTH_LINEAR && !(g.near_z > 0.0 && g.far_z > g.near_z))
        return sl_fail(d, SL_E_USAGE, g.depth, 0, "--near", "window depth needs the engine's --near and --far "
                                                            "(0 < near < far)");
    struct sl_external ext = {.threshold = g.threshold, .tolerance = g.tolerance,
                              .depth_tolerance = g.depth_tolerance, .image = g.image, .depth_file = g.depth,
                              .report = &r->reg};
    float *vis = NULL, *depth = NULL;
    uint8_t *bg = NULL;
    struct sl_config c;
    int loaded = 0;
    enum sl_err e = read_visibility(g.image, &ext, &vis, &bg, d);
    if (!e && (ext.w != g.w || ext.h != g.h))
        e = sl_fail(d, SL_E_USAGE, g.image, 0, NULL, "%d x %d pixels where --viewport is %d x %d", ext.w, ext.h,
                    g.w, g.h);
    if (!e && g.depth)
        e = read_depth(&g, ext.w, ext.h, &depth, d);
    ext.vis = vis;
    ext.bg = bg;
    ext.depth = depth;
    /* a store this grade creates is removed again when it is refused: a
     * refused grade leaves nothing of itself (a store that was there keeps
     * the run's row, as after any failed run) */
    char store[1200];
    if (g.store)
        snprintf(store, sizeof store, "%s", g.store);
    else
        snprintf(store, sizeof store, "%s/shadowlab.db", g.out_root);
    const int store_new = access(store, F_OK) != 0;
    if (!e)
        e = sl_mkdirs(g.out_root, d);
    if (!e) {
        snprintf(r->config, sizeof r->config, "%s/grade-%s.yaml", g.out_root, g.label);
        e = write_config(&g, r->config, d);
    }
    if (!e) {
        if (!(e = sl_config_load(r->config, &c, d)))
            loaded = 1;
        /* the grade's own config is removed below: the message names the
         * option the refused key came from instead of its line */
        else if (d && !strcmp(d->file, r->config)) {
            const char *opt = strstr(d->key, "viewpoint") ? "--viewpoint"
                              : strstr(d->key, "scene")    ? "--scene"
                              : strstr(d->key, "label")    ? "--label"
                              : strstr(d->key, "viewport") ? "--viewport"
                              : strstr(d->key, "map")      ? "--map"
                                                           : d->key;
            char key[sizeof d->key];
            snprintf(key, sizeof key, "%s", opt);
            snprintf(d->key, sizeof d->key, "%s", key);
            d->file[0] = '\0';
            d->line = 0;
        }
    }
    if (!e) {
        c.methods[0].params.external = &ext;
        struct sl_run_opts o = {.out_root = g.out_root, .write_files = 1, .table_out = table_out,
                                .store = g.store};
        struct sl_run_result res;
        e = sl_run(&c, &o, &res, d);
        if (!e) {
            snprintf(r->out_dir, sizeof r->out_dir, "%s", res.out_dir);
            snprintf(r->store_path, sizeof r->store_path, "%s", res.store_path);
            r->has_cell = res.ncells == 1;
            r->nonfinite = res.ncells ? res.cells[0].nonfinite : 0;
        }
        sl_run_result_free(&res);
    }
    if (loaded)
        sl_config_free(&c);
    if (e && r->config[0])
        unlink(r->config);
    if (e && store_new) {
        static const char *const side[] = {"", "-wal", "-shm", "-journal"};
        for (size_t k = 0; k < sizeof side / sizeof side[0]; k++) {
            char p[1300];
            snprintf(p, sizeof p, "%s%s", store, side[k]);
            unlink(p);
        }
    }
    free(vis);
    free(bg);
    free(depth);
    return e;
}
