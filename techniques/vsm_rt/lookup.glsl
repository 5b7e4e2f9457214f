// VSM lookup: Chebyshev's one-tailed inequality bounds the fraction of the
// filter region's depths at or beyond the receiver,
//   P(z >= d) <= p_max = var / (var + (d - mean)^2)   for d > mean,
// which VSM takes as visibility (exact for a single planar occluder and
// receiver). The variance is clamped below by min_variance (float32 loses
// E[z^2] - E[z]^2 to cancellation on flat surfaces) and the bound is cut by
// linstep(bleed, 1, p) against light bleeding.

// The coarsest mip level whose bilinear footprint stays inside the declared
// reach R = blur + 1 texels: a bilinear read of level L touches texels up to
// 1.5 * 2^L - 1 away from the one the point lands in (L >= 1; 1 at L = 0), so
// L = floor(log2((R + 1) / 1.5)). And no deeper than the number of times the
// map's side halves exactly: a level of an odd-sided one is resampled, not a
// 2 x 2 box (Mesa blits it bilinearly), and its footprint drifts off the
// blocks the bound above assumes. The level itself comes from the
// screen-space derivatives as a texture() call would choose it, clamped.
float vsm_lod(vec2 uv)
{
    float max_lod = min(floor(log2((float(blur) + 2.0) / 1.5)),
                        float(findLSB(int(sl_map_size))));
    return clamp(textureQueryLod(moments, uv).y, 0.0, max_lod);
}

// The depth the moments are taken of (window depth, or for a perspective
// light the normalised distance along its axis): as in map.glsl.
float vsm_linear(float d)
{
    if (sl_persp == 0)
        return d;
    vec3 r2 = vec3(sl_light_vp[0][2], sl_light_vp[1][2], sl_light_vp[2][2]);
    vec3 r3 = vec3(sl_light_vp[0][3], sl_light_vp[1][3], sl_light_vp[2][3]);
    float a = dot(r2, r3) / dot(r3, r3);
    return d * (1.0 - a) / (d - a);
}

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float depth, float ndotl)
{
    vec2 m = textureLod(moments, uv, vsm_lod(uv)).xy;
    float z = vsm_linear(depth);
    if (z <= m.x)
        return 1.0;
    float var = max(m.y - m.x * m.x, min_variance);
    float dm = z - m.x;
    float p = var / (var + dm * dm);
    return clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
}
