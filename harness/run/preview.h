/*
 * preview.h — what the command line does with a scene file where a config
 * is expected: tell the two apart, write a default study of a scene, and
 * `shadowlab preview`, a quick shaded picture per viewpoint for framing
 * cameras (the G-buffer only: no truth, no Embree, no method).
 *
 * Does not: print (main.c does), or run the study (run.c does).
 */
#ifndef SL_PREVIEW_H
#define SL_PREVIEW_H
#include <stddef.h>
#include "glctx.h"
#include "scene.h"

/* 1 when the YAML file has a top-level meshes, light or base key (a scene
 * file), 0 otherwise (a config, or a file that cannot be read). */
int sl_file_is_scene(const char *path);

/* A default study of a scene file as a temporary config (its path in out,
 * removed by the caller once read): every viewpoint; nsm, csm and raytrace;
 * 1024² viewport; 2048² map. 0 on failure (errno says why). */
int sl_scene_default_study(const char *scene, char *out, size_t n);

struct sl_preview_opts {
    const char *scene;       /* a scene file or a built-in scene's name */
    const char *viewpoint;   /* NULL: every viewpoint */
    const char *out_dir;     /* NULL: "." */
    int         w, h;        /* 0: 512 x 512 */
    enum sl_gl_backend gl;
};
struct sl_preview_result {
    int    n;
    char   path[SL_MAX_VIEWPOINTS][1200];
    double ms_total;         /* scene load to the last file written */
    char   renderer[128];
};
/* One PNG per viewpoint, <out_dir>/<scene>-<viewpoint>.png: lit faces shaded
 * by the angle to the light, faces turned from it (PnFL) dark, background
 * blue-grey. SL_E_USAGE for an unknown viewpoint, naming the known ones. */
enum sl_err sl_preview(const struct sl_preview_opts *o, struct sl_preview_result *r, struct sl_diag *d);

#endif
