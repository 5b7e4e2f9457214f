// VSM map: the first two moments of window depth. Depth 1 (the fill of an
// empty texel) gives (1, 1): a far surface of zero variance, never a blocker.
void sl_map(float depth)
{
    out_moments = vec4(depth, depth * depth, 0.0, 0.0);
}
