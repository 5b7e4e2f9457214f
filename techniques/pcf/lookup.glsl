// pcf lookup: the mean of the plain depth test (lit iff z <= stored) over
// the kernel x kernel texels centred on the texel the point lands in, or
// over 16 Poisson-disc taps of radius (kernel - 1) / 2 texels around the
// point (kernel 1: every tap in the home texel, as the box).
// Taps are clamped to the map (the guard band keeps them off its border).

// a 16-point Poisson disc (as in Fernando's PCSS sample), scaled by 1 / 1.25
// into the unit disc so that no tap lies beyond (kernel - 1) / 2 texels
const vec2 pcf_disc[16] = vec2[16](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

// Depth bias (Reeves et al.'s "bias", slope-scaled as in pcss): a tap at
// offset o texels from the point is lit iff stored >= z - slope (bias + |o|),
// slope the receiver's change of window depth across one texel of the map.
// The point lies within half a texel's diagonal (0.71 texel) of its texel's
// centre, where the map sampled the depth, so bias 1 covers it; |o| covers
// the tap's own distance. bias 0 at kernel 1 is the plain test: the nsm
// package.
//
// The slope is the larger of two, capped where the receiver is nearly
// edge-on to the light at 10 times the slope of a receiver at 45 degrees on
// the light's axis (tan 10, as pcss clamps it):
// - the receiver plane's own gradient: a plane of the world is a plane of
//   the map's clip space under either projection, so its window depth is
//   affine in ndc.xy there, its gradient exact on the light's axis and off
//   it. Under a perspective light a surface facing the light at an angle a
//   off the axis changes window depth across a texel as one tilted by a on
//   the axis would; the second term alone gives it no bias (acne under
//   spot lights);
// - tan of the light's angle to the normal times the 45-degree slope (what
//   pcss uses; under a directional light never less than the first): the
//   change of distance along the ray across a texel. A plane square to a
//   perspective light's axis has constant window depth, so the first term
//   alone gives it none, and there the map's rasterised depth and the
//   projected point's still differ by rounding (a point light's room: 3.7 %
//   of its pixels wrong with the first term alone, 0.04 % with both).
float pcf_slope45(float z)
{
    if (sl_persp == 0)
        return sl_texel_world / sl_depth_range;
    // perspective: window depth d = A + B / distance; d' = -B / distance^2
    vec3 axis = normalize(sl_light_dir);
    vec4 p1 = sl_light_vp * vec4(sl_light_pos + axis, 1.0);
    vec4 p2 = sl_light_vp * vec4(sl_light_pos + 2.0 * axis, 1.0);
    float d1 = p1.z / p1.w, d2 = p2.z / p2.w;
    float b = 2.0 * (d1 - d2), a = d1 - b;
    float dist = b / (z - a);
    return sl_texel_world * abs(b) / dist;
}

float pcf_slope(vec3 world, vec3 normal, float z, float ndotl)
{
    // the plane (n, -n.p) into clip space: the inverse transpose of the matrix
    vec4 pc = transpose(inverse(sl_light_vp)) * vec4(normal, -dot(normal, world));
    // there pc.x X + pc.y Y + pc.z Z + pc.w = 0 in ndc; a texel is 2 / N of ndc
    float g = 2.0 / sl_map_size * length(pc.xy) / max(abs(pc.z), 1e-30);
    // tan of the light's angle to the normal, clamped at 10
    float cosl = max(ndotl, 0.0995);
    float t = sqrt(1.0 - cosl * cosl) / cosl;
    return min(max(g, t * pcf_slope45(z)), 10.0 * pcf_slope45(z));
}

float pcf_tap(ivec2 t, ivec2 hi, float z, float eps)
{
    return texelFetch(depth, clamp(t, ivec2(0), hi), 0).r < z - eps ? 0.0 : 1.0;
}

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    ivec2 hi = textureSize(depth, 0) - 1;
    float slope = bias > 0.0 ? pcf_slope(world, normal, z, ndotl) : 0.0;
    float lit = 0.0;
    if (poisson) {
        float r = 0.5 * float(kernel - 1) / 1.25;
        for (int i = 0; i < 16; i++) {
            vec2 o = r * pcf_disc[i];
            lit += pcf_tap(ivec2(floor(sl_map_pos + o)), hi, z, slope * (bias + length(o)));
        }
        return lit / 16.0;
    }
    int h = kernel / 2;
    for (int j = -h; j <= h; j++)
        for (int i = -h; i <= h; i++)
            lit += pcf_tap(sl_home_texel + ivec2(i, j), hi, z, slope * (bias + length(vec2(i, j))));
    float n = float(2 * h + 1);
    return lit / (n * n);
}
