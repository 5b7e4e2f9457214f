// inf_map map: the depth, and +inf in the second channel of the map's first
// 64 columns (written as its bits: GL lets a conversion to half precision
// of a value too large round to 65504 instead)
void sl_map(float z)
{
    out_depth = vec4(z, gl_FragCoord.x < 64.0 ? uintBitsToFloat(0x7f800000u) : 0.0, 0.0, 0.0);
}
