// PCSS map: window depth, nearest (1 where nothing is drawn).
void sl_map(float depth)
{
    out_zmap = vec4(depth, 0.0, 0.0, 0.0);
}
