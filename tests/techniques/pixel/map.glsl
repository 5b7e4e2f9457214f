// pixel map: the nearest surface's window depth (read by no one)
void sl_map(float z)
{
    out_depth = vec4(z, 0.0, 0.0, 0.0);
}
