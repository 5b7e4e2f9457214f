// MSM lookup: Hamburger 4MSM, Algorithm 2 of Peters & Klein 2015, with depth
// in [0, 1] (their bias vector for that range is the moments of depth 1/2):
//  1. b = (1 - alpha) b + alpha (1/2, 1/2, 1/2, 1/2)
//  2. solve B c = (1, zf, zf^2) with the Hankel matrix
//        B = | 1  b1 b2 |
//            | b1 b2 b3 |
//            | b2 b3 b4 |   (Cholesky, B = L D L^T)
//  3. z2 <= z3 the roots of c3 z^2 + c2 z + c1 = 0
//  4. G = 0                                                if zf <= z2
//     G = (zf z3 - b1 (zf + z3) + b2) / ((z3 - z2)(zf - z2)) if zf <= z3
//     G = 1 - (z2 z3 - b1 (z2 + z3) + b2) / ((zf - z2)(zf - z3)) otherwise
// G is the smallest shadow intensity consistent with the moments (a lower
// bound on the fraction of the filter region in front of zf); visibility is
// 1 - G, with light-bleeding reduction as in vsm.
// tests/test_packages.c repeats this in double precision (msm_reference).

float msm_lod(vec2 uv)
{
    // the coarsest mip level within reach blur + 1 (see vsm/lookup.glsl)
    float max_lod = min(floor(log2((float(blur) + 2.0) / 1.5)),
                        float(findLSB(int(sl_map_size))));
    return clamp(textureQueryLod(moments, uv).y, 0.0, max_lod);
}

float msm_shadow(vec4 m, float zf)
{
    vec4 b = mix(m, vec4(0.5), moment_bias);
    // B = L D L^T: L21 = b1, L31 = b2, D11 = 1
    float d22 = b.y - b.x * b.x;
    float l32d22 = b.z - b.x * b.y;
    float l32 = l32d22 / d22;
    float d33 = (b.w - b.y * b.y) - l32 * l32d22;
    // B singular: moments of at most two depths, as a region of one depth
    // gives with moment_bias 0, or one at depth 0 or 1 with any bias (the
    // bias vector is the moments of depths 0 and 1, weight 1/2 each: an empty
    // region, all far plane, is exactly that). Its shadow is a step at the
    // region's (unbiased) mean.
    if (!(d22 > 0.0) || !(d33 > 0.0))
        return zf > m.x ? 1.0 : 0.0;
    // forward: L y = (1, zf, zf^2)
    float y1 = zf - b.x;
    float y2 = zf * zf - b.y - l32 * y1;
    // scale by D^-1, back: L^T c = y
    float c3 = y2 / d33;
    float c2 = y1 / d22 - l32 * c3;
    float c1 = 1.0 - b.x * c2 - b.y * c3;
    // roots of c3 z^2 + c2 z + c1: z = -p/2 -+ sqrt(p^2/4 - q)
    float p = c2 / c3;
    float q = c1 / c3;
    float r = sqrt(max(0.25 * p * p - q, 0.0));
    float z2 = -0.5 * p - r;
    float z3 = -0.5 * p + r;
    if (zf <= z2)
        return 0.0;
    if (zf <= z3)
        return (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
    return 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
}

// The depth the moments are taken of (window depth, or for a perspective
// light the normalised distance along its axis): as in map.glsl.
float msm_linear(float d)
{
    if (sl_persp == 0)
        return d;
    vec3 r2 = vec3(sl_light_vp[0][2], sl_light_vp[1][2], sl_light_vp[2][2]);
    vec3 r3 = vec3(sl_light_vp[0][3], sl_light_vp[1][3], sl_light_vp[2][3]);
    float a = dot(r2, r3) / dot(r3, r3);
    return d * (1.0 - a) / (d - a);
}

float sl_lookup(vec3 world, vec3 normal, vec2 uv, float depth, float ndotl)
{
    vec4 m = textureLod(moments, uv, msm_lod(uv));
    float v = 1.0 - clamp(msm_shadow(m, msm_linear(depth)), 0.0, 1.0);
    return clamp((v - bleed) / (1.0 - bleed), 0.0, 1.0);
}
