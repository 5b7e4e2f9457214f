// pcf lookup: the mean of the plain depth test (lit iff z <= stored) over
// the kernel x kernel texels centred on the texel the point lands in, or
// over 16 Poisson-disc taps of radius kernel / 2 texels around the point.
// Taps are clamped to the map (the guard band keeps them off its border).

// a 16-point Poisson disc (as in Fernando's PCSS sample), scaled by 1 / 1.25
// into the unit disc so that no tap lies beyond kernel / 2 texels
const vec2 pcf_disc[16] = vec2[16](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

float pcf_tap(ivec2 t, ivec2 hi, float z)
{
    return z <= texelFetch(depth, clamp(t, ivec2(0), hi), 0).r ? 1.0 : 0.0;
}

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    ivec2 hi = textureSize(depth, 0) - 1;
    float lit = 0.0;
    if (poisson) {
        float r = 0.5 * float(kernel) / 1.25;
        for (int i = 0; i < 16; i++)
            lit += pcf_tap(ivec2(floor(sl_map_pos + r * pcf_disc[i])), hi, z);
        return lit / 16.0;
    }
    int h = kernel / 2;
    for (int j = -h; j <= h; j++)
        for (int i = -h; i <= h; i++)
            lit += pcf_tap(sl_home_texel + ivec2(i, j), hi, z);
    float n = float(2 * h + 1);
    return lit / (n * n);
}
