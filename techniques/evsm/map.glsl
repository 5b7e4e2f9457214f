// EVSM map: (e+, e+^2, -e-, e-^2) with e+ = exp(c+ w), e- = exp(-c- w) and
// w = 2 z - 1 in [-1, 1] (z below) (as in Lauritzen's thesis and MJP's Shadows
// sample, whose presets the exponents follow). Centring the warp on depth
// 1/2 keeps both squares within e^(2 * 42) = e^84 < FLT_MAX = e^88.7 for
// exponents up to 42 (technique.yaml's max) while giving twice the slope of
// a warp over [0, 1] with the same range. Depth 1 (an empty texel) gives the
// warped far plane (e^c+, e^2c+, -e^-c-, e^-2c-).
// Depth the moments are taken of: window depth for a directional light (linear
// in distance already); for a perspective one the distance along the axis,
// normalised to [0, 1] from the near to the far plane. Window depth
// d = a + b / w is hyperbolic in the distance w: with f = 100 n the far half
// of the frustum lies in the last hundredth below 1, where min_variance and
// the exponential warps would see little difference between occluder and
// receiver. With a = f / (f - n) the normalised distance is
// d (1 - a) / (d - a); a comes from sl_light_vp alone (its depth row is
// a times its w row plus a constant). Map and lookup use the same function.
float evsm_linear(float d)
{
    if (sl_persp == 0)
        return d;
    vec3 r2 = vec3(sl_light_vp[0][2], sl_light_vp[1][2], sl_light_vp[2][2]);
    vec3 r3 = vec3(sl_light_vp[0][3], sl_light_vp[1][3], sl_light_vp[2][3]);
    float a = dot(r2, r3) / dot(r3, r3);
    return d * (1.0 - a) / (d - a);
}

void sl_map(float depth)
{
    float w = 2.0 * evsm_linear(depth) - 1.0;
    float ep = exp(positive * w);
    float en = exp(-negative * w);
    out_warped = vec4(ep, ep * ep, -en, en * en);
}
