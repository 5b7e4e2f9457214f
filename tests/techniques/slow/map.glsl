// slow map: the nearest surface's window depth, after `loops` turns of a
// loop of 256 steps written out (pass 1), as the lookup's
#define SL_STEP a = fract(a * 1.0001 + 0.1);
#define SL_STEP8 SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP
#define SL_STEP64 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8
void sl_map(float z)
{
    float a = z;
    if (pass == 1)
        for (int i = 0; loops == 0 || i < loops; i++) {
            SL_STEP64 SL_STEP64 SL_STEP64 SL_STEP64
        }
    out_depth = vec4(a > 2.0 ? 0.5 : z, 0.0, 0.0, 0.0);
}
