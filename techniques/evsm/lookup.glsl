// EVSM lookup: VSM's Chebyshev bound in each warped space. Both warps are
// increasing in depth, so "d > mean" keeps its meaning, and the true
// visibility lies below each bound: take the smaller.
// min_variance is given in depth squared, like vsm's, and carried into a warp
// by the warp's slope at the receiver: var_w = min_variance * (de/dz)^2 with
// de/dz = 2 c e (e = exp(c w), w = 2z - 1), formed as
// (sqrt(min_variance) de/dz)^2: (de/dz)^2 alone reaches (84 e^42)^2 = 2e40,
// beyond FLT_MAX.

float evsm_lod(vec2 uv)
{
    // the coarsest mip level within reach blur + 1 (see vsm/lookup.glsl)
    float max_lod = min(floor(log2((float(blur) + 2.0) / 1.5)),
                        float(findLSB(int(sl_map_size))));
    return clamp(textureQueryLod(warped, uv).y, 0.0, max_lod);
}

float evsm_chebyshev(vec2 m, float x, float min_var)
{
    if (x <= m.x)
        return 1.0;
    float var = max(m.y - m.x * m.x, min_var);
    float dm = x - m.x;
    return var / (var + dm * dm);
}

// The depth the moments are taken of (window depth, or for a perspective
// light the normalised distance along its axis): as in map.glsl.
float evsm_linear(float d)
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
    vec4 m = textureLod(warped, uv, evsm_lod(uv));
    float w = 2.0 * evsm_linear(depth) - 1.0;
    float ep = exp(positive * w);
    float sd = sqrt(min_variance);
    float sp = sd * 2.0 * positive * ep;
    float p = evsm_chebyshev(m.xy, ep, sp * sp);
    if (moments >= 4) {
        float en = exp(-negative * w);
        float sn = sd * 2.0 * negative * en;
        p = min(p, evsm_chebyshev(m.zw, -en, sn * sn));
    }
    return clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
}
