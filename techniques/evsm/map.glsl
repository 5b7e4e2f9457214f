// EVSM map: (e+, e+^2, -e-, e-^2) with e+ = exp(c+ w), e- = exp(-c- w) and
// w = 2 depth - 1 in [-1, 1] (as in Lauritzen's thesis and MJP's Shadows
// sample, whose presets the exponents follow). Centring the warp on depth
// 1/2 keeps both squares within e^(2 * 42) = e^84 < FLT_MAX = e^88.7 for
// exponents up to 42 (technique.yaml's max) while giving twice the slope of
// a warp over [0, 1] with the same range. Depth 1 (an empty texel) gives the
// warped far plane (e^c+, e^2c+, -e^-c-, e^-2c-).
void sl_map(float depth)
{
    float w = 2.0 * depth - 1.0;
    float ep = exp(positive * w);
    float en = exp(-negative * w);
    out_warped = vec4(ep, ep * ep, -en, en * en);
}
