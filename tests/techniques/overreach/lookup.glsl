// overreach lookup: the 3 x 3 box of the plain depth test around the home
// texel (within the declared reach of 1), and four taps 1 + beyond texels
// away along the axes (beyond the reach when beyond > 0); 13 reads a pixel.
float overreach_tap(ivec2 t, ivec2 hi, float z)
{
    return z <= texelFetch(depth, clamp(t, ivec2(0), hi), 0).r + 1e-4 ? 1.0 : 0.0;
}

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    ivec2 hi = textureSize(depth, 0) - 1;
    float lit = 0.0;
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++)
            lit += overreach_tap(sl_home_texel + ivec2(i, j), hi, z);
    int far = 1 + beyond;
    lit += overreach_tap(sl_home_texel + ivec2(far, 0), hi, z);
    lit += overreach_tap(sl_home_texel + ivec2(-far, 0), hi, z);
    lit += overreach_tap(sl_home_texel + ivec2(0, far), hi, z);
    lit += overreach_tap(sl_home_texel + ivec2(0, -far), hi, z);
    return lit / 13.0;
}
