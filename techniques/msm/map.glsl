// MSM map: the raw power moments (z, z^2, z^3, z^4) of window depth z.
// Peters & Klein's optimised quantisation (sec. 4.3, an affine transform of
// the moments) exists to make them survive 16-bit storage; in 32-bit floats
// the raw moments keep ~7 significant digits each, which the 3e-5 moment bias
// is chosen for, so they are stored as they are.
void sl_map(float depth)
{
    float z2 = depth * depth;
    out_moments = vec4(depth, z2, z2 * depth, z2 * z2);
}
