// nsm_glsl map: the nearest surface's window depth, the value the C depth
// layers store (1 where nothing is: the empty pass calls sl_map(1.0)).
void sl_map(float z)
{
    out_depth = vec4(z, 0.0, 0.0, 0.0);
}
