// PCSS lookup (Fernando 2005), in three steps:
//  1. blocker search: the map's depths z < d - eps on a 2 search x 2 search
//     grid of taps at half-texel offsets (each lands within `search` texels
//     of the receiver's texel), averaged: z_b. None: lit.
//  2. penumbra: Fernando's w = (z_r - z_b) * light / z_b (world, at the
//     receiver), in texels of the map at the receiver:
//       perspective: w = light_size (z_r - z_b) / (z_b z_r), z the distance
//         along the light's axis in world units, light_size = the light's
//         width / the width of a texel at depth 1 (sl_texel_world);
//       directional (light at infinity, angular width a; Fernando's ratio
//         tends to (z_r - z_b) tan a): w = light_size (z_r - z_b), with
//         light_size = tan a / sl_texel_world, the penumbra in texels a
//         blocker edge casts on a receiver one world unit behind it.
//     Both read "the light's width in texels at unit depth"; neither depends
//     on where the harness put the map's near plane.
//  3. PCF over a box of width w (radius w / 2, clamped to max_filter): a box
//     as wide as the penumbra ramps from 0 to 1 across it. 2n x 2n taps,
//     n = ceil(radius), evenly inside the box, so each lands within
//     ceil(radius) <= max_filter texels. Reach: max(search, max_filter).
// Depth bias: eps = slope (bias + |offset|), slope the receiver's change of
// window depth per texel (tan of the light's angle to the normal, clamped at
// 10): the receiver itself is never its own blocker, taps away from the
// centre included.

// Window depth <-> distance along the axis (perspective): d = A + B / z.
// A and B from sl_light_vp at two points on the axis, so the lookup needs no
// near/far of its own.
vec2 pcss_persp_ab()
{
    vec3 axis = normalize(sl_light_dir);
    vec4 p1 = sl_light_vp * vec4(sl_light_pos + axis, 1.0);
    vec4 p2 = sl_light_vp * vec4(sl_light_pos + 2.0 * axis, 1.0);
    float d1 = p1.z / p1.w, d2 = p2.z / p2.w;
    float b = 2.0 * (d1 - d2);
    return vec2(d1 - b, b);
}

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float depth, float ndotl)
{
    vec2 ab = sl_persp != 0 ? pcss_persp_ab() : vec2(0.0);
    float zr = sl_persp != 0 ? ab.y / (depth - ab.x) : depth * sl_depth_range;
    float cosl = max(ndotl, 0.0995);   // tan clamped at 10
    float tanl = sqrt(1.0 - cosl * cosl) / cosl;
    // window depth across one texel of the receiver's slope
    float slope = sl_persp != 0 ? tanl * sl_texel_world * abs(ab.y) / zr
                                : tanl * sl_texel_world / sl_depth_range;

    // 1. blocker search
    float sum = 0.0;
    int n = 0;
    for (int j = -search; j < search; j++)
        for (int i = -search; i < search; i++) {
            vec2 o = vec2(float(i) + 0.5, float(j) + 0.5);
            float z = texture(zmap, uv + o * sl_texel).r;
            if (z < depth - slope * (bias + length(o))) {
                sum += z;
                n++;
            }
        }
    if (n == 0)
        return 1.0;
    float zb = sum / float(n);

    // 2. penumbra width in texels; light_size 0 (the default): an area
    // light's own width (sl_light_width) in texels of the map at depth 1,
    // 8 under a light without a width
    float w;
    float ls = light_size > 0.0 ? light_size : sl_light_width > 0.0 ? sl_light_width / sl_texel_world : 8.0;
    if (sl_persp != 0) {
        float zbl = ab.y / (zb - ab.x);
        w = ls * (zr - zbl) / (zbl * zr);
    } else {
        w = ls * (depth - zb) * sl_depth_range;
    }

    // 3. PCF of radius w / 2
    float radius = clamp(0.5 * w, 0.0, float(max_filter));
    // taps a half side; the 1e-3 keeps a radius a rounding above a whole
    // number (0.6 - 0.2 in float is 0.40000001) from adding a ring of taps.
    // Every tap stays inside the radius whatever k is.
    int k = int(ceil(radius - 1e-3));
    if (k == 0)
        return texture(zmap, uv).r < depth - slope * bias ? 0.0 : 1.0;
    float step = radius / float(k);
    float lit = 0.0;
    for (int j = -k; j < k; j++)
        for (int i = -k; i < k; i++) {
            vec2 o = vec2(float(i) + 0.5, float(j) + 0.5) * step;
            float z = texture(zmap, uv + o * sl_texel).r;
            lit += z < depth - slope * (bias + length(o)) ? 0.0 : 1.0;
        }
    return lit / float(4 * k * k);
}
