/*
 * lightfit.c — see lightfit.h. Invariant: every receiver and every triangle
 * able to shadow one lies inside the box (tests/test_lightfit.c checks it).
 */
#include "lightfit.h"
#include <cglm/clipspace/ortho_rh_zo.h>
#include <float.h>
#include <math.h>
#include <string.h>

void sl_light_view(const float dir[3], mat4 view)
{
    vec3 eye = {0, 0, 0}, d, up = {0, 1, 0};
    glm_vec3_copy((float *)dir, d);
    /* any up not parallel to the light: the axis least aligned with it */
    float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]);
    if (ay >= ax && ay >= az) {
        up[1] = 0.0f;
        if (ax <= az) up[0] = 1.0f; else up[2] = 1.0f;
    }
    glm_look(eye, d, up, view);
}

static void to_light(const mat4 view, const float p[3], float out[3])
{
    vec4 w = {p[0], p[1], p[2], 1.0f}, c;
    glm_mat4_mulv((vec4 *)view, w, c);
    out[0] = c[0];
    out[1] = c[1];
    out[2] = -c[2];   /* depth grows away from the light */
}

void sl_light_fit(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out)
{
    memset(out, 0, sizeof *out);
    sl_light_view(s->light_dir, out->view);
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    size_t n = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < n; i++) {
        if (v->cls[i] != SL_C_PFL)
            continue;
        float q[3];
        to_light(out->view, v->pos + 3 * i, q);
        for (int k = 0; k < 3; k++) {
            if (q[k] < lo[k]) lo[k] = q[k];
            if (q[k] > hi[k]) hi[k] = q[k];
        }
        out->n_receivers++;
    }
    if (out->n_receivers == 0) {
        /* nothing faces the light: no lookup will happen; fit the scene */
        for (uint32_t i = 0; i < s->nv; i++) {
            float q[3];
            to_light(out->view, s->pos + 3 * i, q);
            for (int k = 0; k < 3; k++) {
                if (q[k] < lo[k]) lo[k] = q[k];
                if (q[k] > hi[k]) hi[k] = q[k];
            }
        }
    }
    float near = lo[2];
    for (uint32_t t = 0; t < s->nt; t++) {
        float tl[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, th[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
        for (int c = 0; c < 3; c++) {
            float q[3];
            to_light(out->view, s->pos + 3 * s->idx[3 * t + c], q);
            for (int k = 0; k < 3; k++) {
                if (q[k] < tl[k]) tl[k] = q[k];
                if (q[k] > th[k]) th[k] = q[k];
            }
        }
        if (th[0] < lo[0] || tl[0] > hi[0] || th[1] < lo[1] || tl[1] > hi[1] || tl[2] > hi[2])
            continue;
        out->n_casters++;
        if (tl[2] < near)
            near = tl[2];
    }
    lo[2] = near;
    /* Margins: 1e-4 of the extent (at least 1e-6 of the coordinates' size)
     * so points on the boundary are strictly inside after float rounding;
     * the depth margin also keeps the farthest receiver below the cleared 1. */
    for (int k = 0; k < 3; k++) {
        float ext = hi[k] - lo[k];
        float mag = fmaxf(fabsf(lo[k]), fabsf(hi[k]));
        float m = fmaxf(1e-4f * ext, 1e-6f * mag + 1e-6f);
        lo[k] -= m;
        hi[k] += m;
    }
    memcpy(out->lo, lo, sizeof lo);
    memcpy(out->hi, hi, sizeof hi);
    glm_ortho_rh_zo(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], out->proj);
    glm_mat4_mul(out->proj, out->view, out->vp);
}
