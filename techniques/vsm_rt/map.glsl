// Depth the moments are taken of: window depth for a directional light (linear
// in distance already); for a perspective one the distance along the axis,
// normalised to [0, 1] from the near to the far plane. Window depth
// d = a + b / w is hyperbolic in the distance w: with f = 100 n the far half
// of the frustum lies in the last hundredth below 1, where min_variance and
// the exponential warps would see little difference between occluder and
// receiver. With a = f / (f - n) the normalised distance is
// d (1 - a) / (d - a); a comes from sl_light_vp alone (its depth row is
// a times its w row plus a constant). Map and lookup use the same function.
float vsm_linear(float d)
{
    if (sl_persp == 0)
        return d;
    vec3 r2 = vec3(sl_light_vp[0][2], sl_light_vp[1][2], sl_light_vp[2][2]);
    vec3 r3 = vec3(sl_light_vp[0][3], sl_light_vp[1][3], sl_light_vp[2][3]);
    float a = dot(r2, r3) / dot(r3, r3);
    return d * (1.0 - a) / (d - a);
}

// VSM map: the first two moments of that depth. Depth 1 (the fill of an
// empty texel) gives (1, 1): a far surface of zero variance, never a blocker.
void sl_map(float depth)
{
    float z = vsm_linear(depth);
    out_moments = vec4(z, z * z, 0.0, 0.0);
}
