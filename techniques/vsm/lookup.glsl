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

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float depth, float ndotl)
{
    vec2 m = textureLod(moments, uv, vsm_lod(uv)).xy;
    if (depth <= m.x)
        return 1.0;
    float var = max(m.y - m.x * m.x, min_variance);
    float dm = depth - m.x;
    float p = var / (var + dm * dm);
    return clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
}
