// ESM map: exp(c (depth - 1/2)), the exponential warp shifted by half the
// depth range.
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
void sl_map(float depth)
{
    out_warped = vec4(exp(c * (depth - 0.5)), 0.0, 0.0, 0.0);
}
