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
    free(s->ranges);
    memset(s, 0, sizeof *s);
}

double sl_tri_normal_d(const float a[3], const float b[3], const float c[3], double n[3])
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    return sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
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
        double n[3];
        double len = sl_tri_normal_d(s->pos + 3 * ix[0], s->pos + 3 * ix[1], s->pos + 3 * ix[2], n);
        if (!(len > 0.0))
            return sl_fail(d, SL_E_SCENE, NULL, 0, NULL, "triangle %u has zero area", t);
        for (int k = 0; k < 3; k++)
            s->fn[3 * t + k] = (float)(n[k] / len);
    }
    return SL_OK;
}

int sl_scene_find_viewpoint(const struct sl_scene *s, const char *name)
{
    for (int i = 0; i < s->nvp + s->nframes; i++)
        if (strcmp(s->vp[i].name, name) == 0)
            return i;
    return -1;
}

int sl_scene_find_path(const struct sl_scene *s, const char *name)
{
    for (int i = 0; i < s->npaths; i++)
        if (strcmp(s->paths[i].name, name) == 0)
            return i;
    return -1;
}

void sl_scene_use_view_light(struct sl_scene *s, int vp)
{
    if (s->light.type != SL_LIGHT_DIRECTIONAL)
        return;
    const float *d = vp >= 0 && vp < s->nvp + s->nframes && s->vp[vp].has_light ? s->vp[vp].light_dir
                                                                                   : s->base_light_dir;
    memcpy(s->light.dir, d, sizeof s->light.dir);
    memcpy(s->light_dir, d, sizeof s->light_dir);
}
