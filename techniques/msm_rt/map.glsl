// MSM map: the raw power moments (z, z^2, z^3, z^4) of depth z (below).
// Peters & Klein's optimised quantisation (sec. 4.3, an affine transform of
// the moments) exists to make them survive 16-bit storage; in 32-bit floats
// the raw moments keep ~7 significant digits each, which the 3e-5 moment bias
// is chosen for, so they are stored as they are.
// Depth the moments are taken of: window depth for a directional light (linear
// in distance already); for a perspective one the distance along the axis,
// normalised to [0, 1] from the near to the far plane. Window depth
// d = a + b / w is hyperbolic in the distance w: with f = 100 n the far half
// of the frustum lies in the last hundredth below 1, where min_variance and
// the exponential warps would see little difference between occluder and
// receiver. With a = f / (f - n) the normalised distance is
// d (1 - a) / (d - a); a comes from sl_light_vp alone (its depth row is
// a times its w row plus a constant). Map and lookup use the same function.
float msm_linear(float d)
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
    float z = msm_linear(depth);
    float z2 = z * z;
    out_moments = vec4(z, z2, z2 * z, z2 * z2);
}
