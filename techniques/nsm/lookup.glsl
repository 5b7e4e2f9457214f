// nsm_glsl lookup: one texel, the one the point lands in (sl_home_texel is
// floor(u) + g, floor(v) + g of the u, v sl_frame_project gives), clamped
// to the map as sl_frame_texel clamps; lit iff the point's depth is not
// beyond the stored one. With a guard band of 0 the map is the C depth
// layer itself, so this is C nsm with self_shadow none, pixel for pixel.
float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    ivec2 t = clamp(sl_home_texel, ivec2(0), textureSize(depth, 0) - 1);
    return z <= texelFetch(depth, t, 0).r ? 1.0 : 0.0;
}
