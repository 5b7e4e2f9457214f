/*
 * preview.c — scene files on the command line (preview.h).
 *
 * The preview renders the G-buffer only, the cheapest pass that shows what
 * a viewpoint sees: one context, one mesh upload, one draw per viewpoint. Its
 * shading uses the light's direction (directional and spot: the direction it
 * travels; point and area: toward its position) so a user framing a camera
 * sees which side is lit, not whether it is shadowed (that needs the truth).
 */
#define _GNU_SOURCE
#include "preview.h"
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "gbuffer.h"
#include "image.h"
#include "scenefile.h"
#include "util.h"

int sl_file_is_scene(const char *path)
{
    return sl_scene_sniff(path, NULL, 0);
}

/* CSM is Morais 2015's conservative pair, exact, so the default study shows
 * a fast approximate method, an exact hybrid and the reference side by side. */
int sl_scene_default_study(const char *scene, char *out, size_t n)
{
    char abs[PATH_MAX];
    if (!realpath(scene, abs))
        return 0;
    snprintf(out, n, "/tmp/shadowlab-study-XXXXXX.yaml");
    int fd = mkstemps(out, 5);
    if (fd < 0)
        return 0;
    FILE *f = fdopen(fd, "w");
    if (!f) {
        close(fd);
        unlink(out);
        return 0;
    }
    /* the name: the scene file's own name without .yaml, kept to the
     * characters a config name allows */
    const char *base = strrchr(abs, '/') ? strrchr(abs, '/') + 1 : abs;
    char name[64];
    size_t k = 0;
    for (const char *p = base; *p && k + 1 < sizeof name && strcmp(p, ".yaml"); p++)
        name[k++] = strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.", *p) ? *p : '_';
    name[k] = '\0';
    fprintf(f, "name: %s\nscenes: [{scene: \"%s\"}]\nviewports: [{width: 1024, height: 1024}]\nmap_sizes: [2048]\n"
               "methods:\n  - {label: nsm, method: nsm}\n  - {label: csm, method: csm}\n"
               "  - {label: raytrace, method: raytrace}\n", name[0] && name[0] != '.' ? name : "scene", abs);
    return fclose(f) == 0;
}

static void shade(const struct sl_scene *s, const struct sl_view *v, unsigned char *rgb)
{
    const struct sl_light *L = &s->light;
    int toward_pos = L->type == SL_LIGHT_POINT || L->type == SL_LIGHT_AREA;
    for (int i = 0; i < v->w * v->h; i++) {
        unsigned char *o = rgb + 3 * (size_t)i;
        if (v->cls[i] == SL_C_BACKGROUND) {
            o[0] = 46, o[1] = 52, o[2] = 64;
            continue;
        }
        const float *n = v->nrm + 3 * (size_t)i, *p = v->pos + 3 * (size_t)i;
        float l[3];
        for (int k = 0; k < 3; k++)
            l[k] = toward_pos ? L->pos[k] - p[k] : -s->light_dir[k];
        float len = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        float ndl = len > 0 ? (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len : 0.0f;
        float g = v->cls[i] == SL_C_PFL && ndl > 0 ? 0.22f + 0.72f * ndl : 0.12f;
        o[0] = o[1] = o[2] = (unsigned char)(255.0f * g + 0.5f);
    }
}

enum sl_err sl_preview(const struct sl_preview_opts *o, struct sl_preview_result *r, struct sl_diag *d)
{
    memset(r, 0, sizeof *r);
    double t0 = sl_now();
    int w = o->w > 0 ? o->w : 512, h = o->h > 0 ? o->h : 512;
    const char *dir = o->out_dir ? o->out_dir : ".";
    struct sl_scene s;
    enum sl_err e = sl_file_is_scene(o->scene) ? sl_scene_load(o->scene, &s, d) : sl_scene_build(o->scene, &s, d);
    if (e)
        return e;
    int only = -1;
    if (o->viewpoint) {
        for (int i = 0; i < s.nvp && only < 0; i++)
            if (!strcmp(s.vp[i].name, o->viewpoint))
                only = i;
        if (only < 0) {
            char known[512] = "";
            for (int i = 0; i < s.nvp; i++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", i ? ", " : "", s.vp[i].name);
            e = sl_fail(d, SL_E_USAGE, o->scene, 0, o->viewpoint, "no such viewpoint (the scene has: %s)", known);
            sl_scene_free(&s);
            return e;
        }
    }
    if ((e = sl_mkdirs(dir, d))) {
        sl_scene_free(&s);
        return e;
    }
    struct sl_gl gl;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gp;
    memset(&gl, 0, sizeof gl);
    memset(&mesh, 0, sizeof mesh);
    memset(&gp, 0, sizeof gp);
    const struct sl_gl_desc gd = {.backend = o->gl};
    unsigned char *rgb = sl_calloc((size_t)w * (size_t)h, 3);
    if (!rgb)
        e = sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "preview image %dx%d", w, h);
    if (!e && !(e = sl_gl_open(&gl, &gd, d)) && !(e = sl_gl_mesh_upload(&mesh, &s, d)) &&
        !(e = sl_gbuffer_init(&gp, &s, d))) {
        snprintf(r->renderer, sizeof r->renderer, "%s", gl.renderer);
        for (int i = 0; i < s.nvp && !e; i++) {
            if (only >= 0 && i != only)
                continue;
            struct sl_view v;
            memset(&v, 0, sizeof v);
            if ((e = sl_gbuffer_render(&gp, &mesh, &s, i, w, h, &v, NULL, NULL, NULL, d)))
                break;
            shade(&s, &v, rgb);
            sl_view_free(&v);
            char *path = r->path[r->n];
            snprintf(path, sizeof r->path[0], "%s/%s-%s.png", dir, s.name, s.vp[i].name);
            if (!(e = sl_image_write_rgb8(path, w, h, rgb, d)))
                r->n++;
        }
    }
    if (gp.prog)
        sl_gbuffer_free(&gp);
    if (gl.backend) {
        sl_gl_mesh_free(&mesh);
        sl_gl_free(&gl);
    }
    free(rgb);
    sl_scene_free(&s);
    r->ms_total = 1e3 * (sl_now() - t0);
    return e;
}
