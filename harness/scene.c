/*
 * scene.c — scenes in memory and the built-in scenes.
 *
 * Invariants: sl_scene arrays are owned by the scene; face normals are unit
 * and computed once here in double precision; a scene never holds a
 * zero-area triangle (it would have no normal and no well-defined shadow).
 */
#include "scene.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "util.h"

void sl_scene_free(struct sl_scene *s)
{
    if (!s)
        return;
    free(s->pos);
    free(s->idx);
    free(s->fn);
    memset(s, 0, sizeof *s);
}

enum sl_err sl_scene_from_mesh(struct sl_scene *s, const struct sl_mesh *m, struct sl_diag *d)
{
    if (m->oom)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "mesh generation ran out of memory");
    s->nv = m->nv;
    s->nt = m->nt;
    s->pos = malloc((size_t)m->nv * 3 * sizeof(float));
    s->idx = malloc((size_t)m->nt * 3 * sizeof(uint32_t));
    s->fn = malloc((size_t)m->nt * 3 * sizeof(float));
    if (!s->pos || !s->idx || !s->fn)
        return sl_fail(d, SL_E_NOMEM, NULL, 0, NULL, "scene of %u triangles", m->nt);
    memcpy(s->pos, m->pos, (size_t)m->nv * 3 * sizeof(float));
    memcpy(s->idx, m->idx, (size_t)m->nt * 3 * sizeof(uint32_t));
    for (int k = 0; k < 3; k++) {
        s->lo[k] = INFINITY;
        s->hi[k] = -INFINITY;
    }
    for (uint32_t i = 0; i < s->nv; i++)
        for (int k = 0; k < 3; k++) {
            float v = s->pos[3 * i + k];
            if (v < s->lo[k]) s->lo[k] = v;
            if (v > s->hi[k]) s->hi[k] = v;
        }
    for (uint32_t t = 0; t < s->nt; t++) {
        const uint32_t *ix = s->idx + 3 * t;
        if (ix[0] >= s->nv || ix[1] >= s->nv || ix[2] >= s->nv)
            return sl_fail(d, SL_E_SCENE, NULL, 0, NULL, "triangle %u indexes a missing vertex", t);
        const float *a = s->pos + 3 * ix[0], *b = s->pos + 3 * ix[1], *c = s->pos + 3 * ix[2];
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = (double)b[k] - a[k];
            e2[k] = (double)c[k] - a[k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0.0))
            return sl_fail(d, SL_E_SCENE, NULL, 0, NULL, "triangle %u has zero area", t);
        for (int k = 0; k < 3; k++)
            s->fn[3 * t + k] = (float)(n[k] / len);
    }
    return SL_OK;
}

static void set_vp(struct sl_viewpoint *v, const char *name, float px, float py, float pz,
                   float dx, float dy, float dz, float fov, float zn, float zf)
{
    memset(v, 0, sizeof *v);
    snprintf(v->name, sizeof v->name, "%s", name);
    v->pos[0] = px; v->pos[1] = py; v->pos[2] = pz;
    float l = sqrtf(dx * dx + dy * dy + dz * dz);
    v->dir[0] = dx / l; v->dir[1] = dy / l; v->dir[2] = dz / l;
    v->up[0] = 0.0f; v->up[1] = 1.0f; v->up[2] = 0.0f;
    v->fov_deg = fov;
    v->znear = zn;
    v->zfar = zf;
}

static void set_light(struct sl_scene *s, float x, float y, float z)
{
    float l = sqrtf(x * x + y * y + z * z);
    s->light_dir[0] = x / l; s->light_dir[1] = y / l; s->light_dir[2] = z / l;
}

/*
 * Moderno 2011, Table 1, "Primitives": a plane with a torus, a cylinder, a
 * pyramid and a sphere on top, 4,944 triangles in the thesis.
 *
 * The thesis gives the viewpoints, the light and the frustum but not the
 * object sizes or tessellation, so these are our choice:
 * - the plane is 600 x 600 units, a 16 x 16 grid (512 triangles): every
 *   published viewpoint then sees ground up to its far plane, as the thesis's
 *   whole-image pixel counts (no background) imply;
 * - objects sit where the three published cameras look (near x=-5, z=-3),
 *   sized 10-12 units so that shadows land in view from all three;
 * - torus 48 x 24 (2,304), sphere 32 x 32 (1,984), cylinder 32 sides (128),
 *   pyramid 6: 4,934 triangles in all, 10 fewer than the thesis's 4,944.
 * The light direction is the thesis's (0.528542, -0.376004, 0.761095), the
 * direction the light travels (y is up).
 */
static enum sl_err build_primitives(struct sl_scene *s, struct sl_diag *d)
{
    struct sl_mesh m = {0};
    sl_gen_plane(&m, 0.0f, 0.0f, 0.0f, 600.0f, 16);
    sl_gen_torus(&m, 6.0f, 1.5f, -14.0f, 6.0f, 1.5f, 48, 24);
    sl_gen_sphere(&m, -14.0f, 5.0f, -10.0f, 5.0f, 32, 32);
    sl_gen_cylinder(&m, -6.0f, 0.0f, 4.0f, 3.0f, 12.0f, 32);
    sl_gen_pyramid(&m, 8.0f, 0.0f, 4.0f, 10.0f, 10.0f);
    enum sl_err e = sl_scene_from_mesh(s, &m, d);
    sl_mesh_free(&m);
    if (e)
        return e;
    set_light(s, 0.528542f, -0.376004f, 0.761095f);
    set_vp(&s->vp[0], "side", 35.0f, 50.0f, -43.0f, -1.0f, -1.2f, 1.0f, 60.0f, 20.0f, 250.0f);
    set_vp(&s->vp[1], "with", -28.0f, 38.0f, -40.0f, 0.4f, -0.7f, 0.6f, 60.0f, 20.0f, 250.0f);
    set_vp(&s->vp[2], "against", 31.0f, 54.0f, 38.0f, -0.4f, -0.7f, -0.5f, 60.0f, 20.0f, 250.0f);
    s->nvp = 3;
    return SL_OK;
}

/*
 * "blocks": a small scene for tests that check against brute force: two boxes
 * and a pyramid over a 40 x 40 plane, 38 triangles, one viewpoint that sees
 * background too, and a light at a steep angle so that shadows fall in view.
 */
static enum sl_err build_blocks(struct sl_scene *s, struct sl_diag *d)
{
    struct sl_mesh m = {0};
    sl_gen_plane(&m, 0.0f, 0.0f, 0.0f, 40.0f, 2);
    const float a0[3] = {-6, 0, -6}, a1[3] = {-2, 5, -2};
    const float b0[3] = {2, 3, 0}, b1[3] = {6, 4, 1};      /* floating slab */
    sl_gen_box(&m, a0, a1);
    sl_gen_box(&m, b0, b1);
    sl_gen_pyramid(&m, -4.0f, 0.0f, 7.0f, 4.0f, 6.0f);
    enum sl_err e = sl_scene_from_mesh(s, &m, d);
    sl_mesh_free(&m);
    if (e)
        return e;
    set_light(s, 0.5f, -0.8f, 0.3f);
    set_vp(&s->vp[0], "above", 0.0f, 30.0f, 40.0f, 0.0f, -0.7f, -1.0f, 60.0f, 1.0f, 200.0f);
    s->nvp = 1;
    return SL_OK;
}

static const struct {
    const char *name;
    const char *summary;
    enum sl_err (*build)(struct sl_scene *, struct sl_diag *);
} sl_scenes[] = {
    {"primitives", "Moderno 2011 Table 1: plane, torus, cylinder, pyramid, sphere", build_primitives},
    {"blocks", "test scene: two boxes and a pyramid over a plane, 38 triangles", build_blocks},
    {NULL, NULL, NULL},
};

int sl_scene_count(void)
{
    int n = 0;
    while (sl_scenes[n].name)
        n++;
    return n;
}

const char *sl_scene_name(int i) { return sl_scenes[i].name; }
const char *sl_scene_summary(int i) { return sl_scenes[i].summary; }

enum sl_err sl_scene_build(const char *name, struct sl_scene *out, struct sl_diag *d)
{
    memset(out, 0, sizeof *out);
    for (int i = 0; sl_scenes[i].name; i++)
        if (strcmp(sl_scenes[i].name, name) == 0) {
            snprintf(out->name, sizeof out->name, "%s", name);
            enum sl_err e = sl_scenes[i].build(out, d);
            if (e)
                sl_scene_free(out);
            return e;
        }
    return sl_fail(d, SL_E_SCENE, NULL, 0, "scene", "unknown scene '%s'", name);
}

int sl_scene_find_viewpoint(const struct sl_scene *s, const char *name)
{
    for (int i = 0; i < s->nvp; i++)
        if (strcmp(s->vp[i].name, name) == 0)
            return i;
    return -1;
}
