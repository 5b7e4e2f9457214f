// inf_map lookup: the home texel's depth test (the depth alone is read)
float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    ivec2 t = clamp(sl_home_texel, ivec2(0), textureSize(depth, 0) - 1);
    return z <= texelFetch(depth, t, 0).r ? 1.0 : 0.0;
}
