/* Shared set-up for tests that need a rendered view: a built-in scene, its GL
 * context, G-buffer and Embree truth. */
#ifndef SL_TEST_FIXTURE_H
#define SL_TEST_FIXTURE_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "adjacency.h"
#include "scenefile.h"
#include "gbuffer.h"
#include "glctx.h"
#include "truth.h"

struct fixture {
    struct sl_scene scene;
    struct sl_gl gl;
    struct sl_gl_mesh mesh;
    struct sl_gbuffer_pass gp;
    struct sl_rt rt;
};

static inline int fixture_open(struct fixture *f, const char *scene, int threads)
{
    struct sl_diag d;
    memset(f, 0, sizeof *f);
    if (sl_scene_build(scene, &f->scene, &d) || sl_gl_init(&f->gl, &d) ||
        sl_gl_mesh_upload(&f->mesh, &f->scene, &d) || sl_gbuffer_init(&f->gp, &f->scene, &d) ||
        sl_rt_build(&f->rt, &f->scene, threads, 1, &d)) {
        fprintf(stderr, "fixture: %s\n", d.msg);
        return 0;
    }
    return 1;
}

static inline int fixture_view(struct fixture *f, int vp, int w, int h, struct sl_view *v)
{
    struct sl_diag d;
    if (sl_gbuffer_render(&f->gp, &f->mesh, &f->scene, vp, w, h, v, NULL, NULL, NULL, &d) ||
        sl_truth_trace(&f->rt, &f->scene, v, NULL, &d)) {
        fprintf(stderr, "fixture view: %s\n", d.msg);
        return 0;
    }
    return 1;
}

/* The scene's adjacency, built and uploaded beside its mesh (adj freed by
 * the caller with sl_adjacency_free). */
static inline int fixture_adjacency(struct fixture *f, struct sl_adjacency *adj)
{
    struct sl_diag d;
    memset(adj, 0, sizeof *adj);
    if (sl_adjacency_build(&f->scene, adj, &d) || sl_gl_mesh_upload_adjacency(&f->mesh, &f->scene, adj, &d)) {
        fprintf(stderr, "fixture adjacency: %s\n", d.msg);
        return 0;
    }
    return 1;
}

static inline void fixture_close(struct fixture *f)
{
    sl_rt_free(&f->rt);
    sl_gbuffer_free(&f->gp);
    sl_gl_mesh_free(&f->mesh);
    sl_gl_free(&f->gl);
    sl_scene_free(&f->scene);
}

#endif
