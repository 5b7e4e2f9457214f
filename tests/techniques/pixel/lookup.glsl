// pixel lookup: 0.75 on odd columns of the view, plus 0.25 on odd rows, so
// the verdict (threshold 0.5) is lit exactly on odd columns and the value
// tells both coordinates apart
float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    return 0.75 * float(sl_pixel.x & 1) + 0.25 * float(sl_pixel.y & 1);
}
