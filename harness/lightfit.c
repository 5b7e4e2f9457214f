/*
 * lightfit.c — see lightfit.h. Invariant: every receiver and every triangle
 * able to shadow one lies inside the box (tests/test_lightfit.c checks it).
 */
#include "lightfit.h"
#include <cglm/clipspace/ortho_rh_zo.h>
#include <cglm/clipspace/persp_rh_zo.h>
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

/* An area light as a point at its centre: a perspective frustum from the
 * centre along the light's normal. Across the axis it bounds the receivers'
 * tangents x/d, y/d (every receiver is on the emitting side, d > 0: the
 * G-buffer's classes say so); its far plane is the farthest receiver, its
 * near plane the nearest point of a triangle whose tangents overlap theirs
 * (a shadow ray runs from the receiver to the centre, so its tangents stay
 * the receiver's and its depth falls toward 0: only such triangles, between
 * the light and the receiver, can block it). A triangle reaching behind the
 * light's plane (some vertex at d <= 0) has no bounded projection: it may
 * still block rays near the light, so it is counted as straddling, and the
 * near plane is then kept at 1/1024 of the far one: the plain layers clip it
 * there, the conservative ones leave it out (their geometry shader needs
 * every vertex in front of the light). Near is also never below far/2^20,
 * so that window depth keeps ~2^-4 of float's relative precision at the
 * far end. */
static void fit_point(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out)
{
    const float *c = s->light.pos;
    vec3 eye = {c[0], c[1], c[2]}, ctr, up;
    float ax = fabsf(s->light.normal[0]), ay = fabsf(s->light.normal[1]), az = fabsf(s->light.normal[2]);
    up[0] = up[1] = up[2] = 0.0f;
    if (ay >= ax && ay >= az)
        up[ax <= az ? 0 : 2] = 1.0f;
    else
        up[1] = 1.0f;
    for (int k = 0; k < 3; k++)
        ctr[k] = c[k] + s->light.normal[k];
    glm_lookat(eye, ctr, up, out->view);
    out->persp = 1;
    memcpy(out->eye, c, sizeof out->eye);
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    size_t n = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < n; i++) {
        if (v->cls[i] != SL_C_PFL)
            continue;
        float q[3];
        to_light(out->view, v->pos + 3 * i, q);
        if (!(q[2] > 0.0f))
            continue;   /* not on the emitting side: never PFL (sl_point_faces) */
        float t[3] = {q[0] / q[2], q[1] / q[2], q[2]};
        for (int k = 0; k < 3; k++) {
            if (t[k] < lo[k]) lo[k] = t[k];
            if (t[k] > hi[k]) hi[k] = t[k];
        }
        out->n_receivers++;
    }
    if (out->n_receivers == 0) {
        /* nothing lit: no lookup will happen; any valid frustum */
        lo[0] = lo[1] = -1.0f;
        hi[0] = hi[1] = 1.0f;
        lo[2] = hi[2] = 1.0f;
    }
    float near = lo[2];
    for (uint32_t t = 0; t < s->nt; t++) {
        float tl[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, th[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
        int behind = 0;
        for (int k = 0; k < 3; k++) {
            float q[3];
            to_light(out->view, s->pos + 3 * s->idx[3 * t + k], q);
            behind |= !(q[2] > 0.0f);
            float r[3] = {q[0] / q[2], q[1] / q[2], q[2]};
            for (int j = 0; j < 3; j++) {
                if (r[j] < tl[j]) tl[j] = r[j];
                if (r[j] > th[j]) th[j] = r[j];
            }
        }
        if (th[2] <= 0.0f || tl[2] > hi[2])
            continue;   /* wholly behind the light, or beyond every receiver */
        if (behind) {
            out->n_casters++;
            out->n_straddling++;
            continue;
        }
        if (th[0] < lo[0] || tl[0] > hi[0] || th[1] < lo[1] || tl[1] > hi[1])
            continue;
        out->n_casters++;
        if (tl[2] < near)
            near = tl[2];
    }
    float far = hi[2] * (1.0f + 1e-4f) + 1e-6f * fabsf(hi[2]);
    if (out->n_straddling)
        near = fminf(near, far / 1024.0f);
    near = fmaxf(near * (1.0f - 1e-4f), far * 0x1p-20f);
    /* tangents: 1e-4 of the extent, at least 1e-6 absolute */
    for (int k = 0; k < 2; k++) {
        float m = fmaxf(1e-4f * (hi[k] - lo[k]), 1e-6f);
        lo[k] -= m;
        hi[k] += m;
    }
    lo[2] = near;
    hi[2] = far;
    memcpy(out->lo, lo, sizeof lo);
    memcpy(out->hi, hi, sizeof hi);
    glm_frustum_rh_zo(lo[0] * near, hi[0] * near, lo[1] * near, hi[1] * near, near, far, out->proj);
    glm_mat4_mul(out->proj, out->view, out->vp);
}

void sl_light_fit(const struct sl_scene *s, const struct sl_view *v, struct sl_light_box *out)
{
    memset(out, 0, sizeof *out);
    if (s->light.type == SL_LIGHT_AREA) {
        fit_point(s, v, out);
        return;
    }
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
