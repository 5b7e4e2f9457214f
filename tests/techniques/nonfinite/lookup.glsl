// nonfinite lookup: the home texel's depth test; on the map's left half a
// value that is not finite (the bits of NaN, -inf or +inf)
float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    if (uv.x < 0.5)
        return uintBitsToFloat(value == 0 ? 0x7fc00000u : value == 1 ? 0xff800000u : 0x7f800000u);
    ivec2 t = clamp(sl_home_texel, ivec2(0), textureSize(depth, 0) - 1);
    return z <= texelFetch(depth, t, 0).r ? 1.0 : 0.0;
}
