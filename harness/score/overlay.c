/*
 * overlay.c — see overlay.h. The grey is Lambert on the face normal:
 * 0.2 ambient, plus 0.7 * dot(n, l) where the method says lit.
 */
#include "overlay.h"
#include <math.h>
#include <string.h>
#include "contour.h"

void sl_overlay_build(const struct sl_view *v, const float light_dir[3], const struct sl_verdicts *vd,
                      const uint8_t *band, int thickness, uint8_t *rgb)
{
    static const uint8_t green[3] = {0, 200, 0}, red[3] = {230, 0, 0}, yellow[3] = {255, 230, 0},
                         blue[3] = {0, 60, 255}, purple[3] = {160, 0, 200}, bg[3] = {0, 0, 0};
    size_t n = (size_t)v->w * (size_t)v->h;
    for (size_t i = 0; i < n; i++) {
        uint8_t *o = rgb + 3 * i;
        uint8_t t = v->truth[i], verdict = vd->v[i];
        if (t == SL_T_BACKGROUND) {
            memcpy(o, bg, 3);
            continue;
        }
        int inside = sl_in_contour(band[i], thickness);
        int truth_lit = t == SL_T_LIT;
        const uint8_t *c = NULL;
        if (verdict == SL_V_LIT && !truth_lit)
            c = inside ? red : blue;
        else if (verdict == SL_V_SHADOW && truth_lit)
            c = inside ? yellow : blue;
        else if (verdict == SL_V_UNCERTAIN)
            c = purple;
        else if (inside && thickness > 0)
            c = green;
        if (c) {
            memcpy(o, c, 3);
            continue;
        }
        const float *nn = v->nrm + 3 * i;
        float ndl = -(nn[0] * light_dir[0] + nn[1] * light_dir[1] + nn[2] * light_dir[2]);
        float g = 0.2f + (verdict == SL_V_LIT && ndl > 0.0f ? 0.7f * ndl : 0.0f);
        uint8_t gg = (uint8_t)(255.0f * g + 0.5f);
        o[0] = o[1] = o[2] = gg;
    }
}

void sl_overlay_soft(int w, int h, const uint32_t *tri, const float *vis, const float *truth, uint8_t *rgb)
{
    size_t npx = (size_t)w * (size_t)h;
    for (size_t i = 0; i < npx; i++) {
        uint8_t *p = rgb + 3 * i;
        if (!tri[i]) {
            p[0] = p[1] = p[2] = 0;
            continue;
        }
        float e = vis[i] - truth[i], g = 40.0f + 180.0f * vis[i];
        float a = fabsf(e) > 0.05f ? fminf(1.0f, 0.3f + fabsf(e)) : 0.0f;
        p[0] = (uint8_t)((1 - a) * g + a * (e < 0 ? 255.0f : 0.0f));
        p[1] = (uint8_t)((1 - a) * g);
        p[2] = (uint8_t)((1 - a) * g + a * (e > 0 ? 255.0f : 0.0f));
    }
}
