// ESM lookup: visibility = exp(c z_f) exp(-c d) = exp(-c (d - z_f)), z_f the
// occluders' depth filtered in exponential space, clamped to 1 (a receiver in
// front of its filtered occluders, or on them, is lit). Evaluated in log
// space, log(m) - c (d - 1/2), so no intermediate exponential can overflow.

// The coarsest mip level whose bilinear footprint stays inside the declared
// reach blur + 1 (see vsm/lookup.glsl for the arithmetic).
float esm_lod(vec2 uv)
{
    float max_lod = min(floor(log2((float(blur) + 2.0) / 1.5)),
                        float(findLSB(int(sl_map_size))));
    return clamp(textureQueryLod(warped, uv).y, 0.0, max_lod);
}

// The depth the moments are taken of (window depth, or for a perspective
// light the normalised distance along its axis): as in map.glsl.
float esm_linear(float d)
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
    float m = textureLod(warped, uv, esm_lod(uv)).r;
    return exp(min(log(m) - c * (esm_linear(depth) - 0.5), 0.0));
}
