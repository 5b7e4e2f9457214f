// ESM map: exp(c (z - 1/2)), the exponential warp of z (below) shifted by
// half the depth range.
//
// Why store the warp and not the depth: every filter the harness applies
// (the box blur, the mipmaps, bilinear lookups) is linear, and ESM needs the
// linear average of exp(c z) (Annen 2008, eq. 6). Averaging depth and warping
// after gives exp(c mean z), which is smaller (Jensen) and a different,
// wrong shadow; "log-space filtering" of stored depth would need the filter
// inside the lookup, reading (2 blur + 1)^2 texels a pixel instead of one.
// Why the shift: with c <= 88 and depth in [0, 1], exp(c depth) reaches
// e^88 = 1.7e38, half of FLT_MAX, and a blur summing its taps before it
// divides would overflow; exp(c (depth - 1/2)) stays in [e^-44, e^44]
// (7.8e-20 .. 1.3e19), normal floats both ends, and any sum of taps is safe.
// Floats keep the same relative precision at every magnitude, so the shift
// costs nothing.
// Depth the moments are taken of: window depth for a directional light (linear
// in distance already); for a perspective one the distance along the axis,
// normalised to [0, 1] from the near to the far plane. Window depth
// d = a + b / w is hyperbolic in the distance w: with f = 100 n the far half
// of the frustum lies in the last hundredth below 1, where min_variance and
// the exponential warps would see little difference between occluder and
// receiver. With a = f / (f - n) the normalised distance is
// d (1 - a) / (d - a); a comes from sl_light_vp alone (its depth row is
// a times its w row plus a constant). Map and lookup use the same function.
float esm_linear(float d)
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
    out_warped = vec4(exp(c * (esm_linear(depth) - 0.5)), 0.0, 0.0, 0.0);
}
