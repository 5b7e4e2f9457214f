// slow lookup: the home texel's depth test, after `loops` turns of a loop
// of 256 steps written out (pass 0), whose value the result depends on so
// no compiler drops it. The steps are written out, not looped: llvmpipe
// ends a shader's loops after 65,535 turns in all, and the loop must run
// as written (doc/techniques.md, "Time limits").
#define SL_STEP a = fract(a * 1.0001 + 0.1);
#define SL_STEP8 SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP SL_STEP
#define SL_STEP64 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8 SL_STEP8
float sl_lookup(vec3 world, vec3 normal, vec2 uv, float z, float ndotl)
{
    float a = fract(z);
    if (pass == 0)
        for (int i = 0; loops == 0 || i < loops; i++) {
            SL_STEP64 SL_STEP64 SL_STEP64 SL_STEP64
        }
    ivec2 t = clamp(sl_home_texel, ivec2(0), textureSize(depth, 0) - 1);
    return a > 2.0 ? 0.5 : z <= texelFetch(depth, t, 0).r ? 1.0 : 0.0;
}
