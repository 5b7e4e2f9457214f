#version 450 core
// Conservative rasterisation in a geometry shader (no conservative-raster
// extension on llvmpipe). Coordinates are window space: x, y in texels,
// z the zero-to-one depth.
//
// Coverage: the triangle is enlarged by moving each edge out by u_lambda
// texels (Morais 2015 eq. 21: the half texel diagonal times eta, plus a
// small margin), so that every texel the triangle touches has its centre
// inside the enlarged triangle. The corner of two moved edges lies
// u_lambda / cos(phi / 2) from the original vertex (phi: angle between the
// edge normals); at a sharp vertex that runs off towards infinity, so the
// triangle's bounding box grown by u_lambda is emitted instead when it is
// smaller, when a vertex is very sharp, or when the triangle has (almost)
// no area in the map: still a superset of every texel centre within
// u_lambda of the triangle, hence still conservative.
// Which texels really count is decided exactly per texel in cons_fs.glsl,
// from the set-up computed here once per triangle (cons_setup.glsl).
// SL_MODE (shadowmap.c defines it, one program per layer): 0 BGSM, 1 BGSM's
// second layer, 2 SGSM (see cons_fs.glsl).
layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;
uniform float u_size;          // map size in texels
uniform float u_lambda;        // enlargement, texels
uniform uint u_first;          // scene index of this draw's first triangle
uniform float u_wmin;          // a point light's frustum: least clip w kept
uniform float u_guard;         // ... and largest |NDC x, y| kept; 0: keep all (orthographic)
flat out vec3 g_v0;            // window-space vertices: x, y in texels, z depth
flat out vec3 g_v1;
flat out vec3 g_v2;
flat out uint g_tri;
flat out dvec2 g_e0;           // outward unit normal of edge v0 -> v1
flat out dvec2 g_e1;           //                            v1 -> v2
flat out dvec2 g_e2;           //                            v2 -> v0
flat out dvec2 g_grad;         // depth plane gradient
flat out uint g_flags;         // bit 0: |area| > 1e-12 (the plane is used); bit 1: |area| >= 1e-12
flat out float g_zb;           // the vertices' nearest depth (BGSM's bound), farthest for SGSM
#if SL_MODE != 2
flat out ivec4 g_box;          // BGSM's box test: texel indices x first, last, y first, last
#endif

// Window space of a clip-space vertex. The division is exact (by 1) in a
// directional light's orthographic frustum; in a point light's perspective
// one, window depth z / w is still affine across the triangle in window
// space, so the depth planes of cons_setup.glsl hold as they are.
bool unmapped(vec4 c)
{
    return u_guard > 0.0 && (c.w < u_wmin || abs(c.x / c.w) > u_guard || abs(c.y / c.w) > u_guard);
}

#if SL_MODE != 2
// BGSM's box test (cons_fs.glsl) drops texel i along an axis when the
// square [i - eps, i + 1 + eps] misses the vertices' range [lo, hi]:
// hi < i - eps or lo > i + 1 + eps, each side exact in float (the vertices
// are floats; i - eps and i + 1 + eps are too, eps = 1/128, i < 2^14), so
// the test is one of reals. For an integer i and a real x, i > x exactly
// when i > floor(x), and i < x exactly when i < ceil(x); so i is dropped
// exactly when i < ceil(lo - 1 - eps) or i > floor(hi + eps): two integers
// per axis, once per triangle, where the fragment shader computed the
// range and four float comparisons per texel.
// In double, lo - (1 + eps) and hi + eps are exact for 2^-28 <= |x| < 2^44
// (1 + eps = 1.0078125 is a double; the operands' bits span at most 53);
// below, the sum lies within 2^-28 of -1 - eps or eps, far from an
// integer, and rounds inside that interval, so floor and ceil are the
// same; above, both lie beyond the clamp to +-2^20, far outside every
// texel index (maps are at most 2^14), on the same side. A NaN bound (all
// three vertices NaN: min and max return the other operand) compared
// false, dropping nothing: the far bound does the same (such a triangle
// has no window position, and llvmpipe rasterises none of it anyway).
const double SL_BOX_FAR = 1048576.0;

int box_first(float lo)
{
    return isnan(lo) ? -int(SL_BOX_FAR) : int(clamp(ceil(double(lo) - (1.0 + SL_EPS)), -SL_BOX_FAR, SL_BOX_FAR));
}

int box_last(float hi)
{
    return isnan(hi) ? int(SL_BOX_FAR) : int(clamp(floor(double(hi) + SL_EPS), -SL_BOX_FAR, SL_BOX_FAR));
}
#endif

vec3 win(vec4 c) { return vec3((c.xy / c.w * 0.5 + 0.5) * u_size, c.z / c.w); }

void emit(vec2 p, float z)
{
    gl_Position = vec4(p / u_size * 2.0 - 1.0, z, 1.0);
    EmitVertex();
}

void main()
{
    // a point light's triangles too close to its plane (or behind it) or
    // beyond the guard band across it have no precise window position: they
    // are left out (lightfit.c lists them for the methods to test)
    if (unmapped(gl_in[0].gl_Position) || unmapped(gl_in[1].gl_Position) || unmapped(gl_in[2].gl_Position))
        return;
    vec3 v[3] = vec3[3](win(gl_in[0].gl_Position), win(gl_in[1].gl_Position), win(gl_in[2].gl_Position));
    g_v0 = v[0];
    g_v1 = v[1];
    g_v2 = v[2];
    g_tri = u_first + uint(gl_PrimitiveIDIn) + 1u;
    double darea = cons_area(v[0], v[1], v[2]);
    double ds = darea >= 0.0 ? 1.0 : -1.0;      // the per-texel test's orientation
    g_e0 = cons_edge_normal(v[0], v[1], ds);
    g_e1 = cons_edge_normal(v[1], v[2], ds);
    g_e2 = cons_edge_normal(v[2], v[0], ds);
    g_grad = cons_plane_grad(v[0], v[1], v[2], darea);
    g_flags = (abs(darea) > 1e-12 ? 1u : 0u) | (abs(darea) >= 1e-12 ? 2u : 0u);
#if SL_MODE == 2
    g_zb = max(v[0].z, max(v[1].z, v[2].z));
#else
    g_zb = min(v[0].z, min(v[1].z, v[2].z));
    // the same min and max as the fragment shader's box test took per texel
    vec2 blo = min(v[0].xy, min(v[1].xy, v[2].xy)), bhi = max(v[0].xy, max(v[1].xy, v[2].xy));
    g_box = ivec4(box_first(blo.x), box_last(bhi.x), box_first(blo.y), box_last(bhi.y));
#endif
    // every emitted vertex at the nearest depth of the triangle, clamped into
    // the box: clipping must never cut a fragment we want (cons_fs writes the
    // real conservative depth)
    float z = clamp(min(v[0].z, min(v[1].z, v[2].z)), 0.0, 1.0);
    float area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
#if SL_MODE == 2
    // SGSM keeps only texels wholly inside the triangle, whose centres the
    // triangle itself covers: no enlargement
    for (int i = 0; i < 3; i++)
        emit(v[i].xy, z);
#else
    // The enlarged triangle, its corners in double (the miter's 1 / (1 +
    // dot(a, b)) amplifies the error of the normals, which double makes
    // negligible; only the final rounding to float remains, as for any
    // vertex), or the grown bounding box: whichever has the smaller area,
    // and the box whenever a vertex is sharper than about 2.6 degrees
    // (1 + dot < 1e-3), where the corner runs off (up to 45 lambda here).
    vec2 lo = min(v[0].xy, min(v[1].xy, v[2].xy)) - vec2(u_lambda);
    vec2 hi = max(v[0].xy, max(v[1].xy, v[2].xy)) + vec2(u_lambda);
    bool fallback = abs(area) < 1e-6;
    vec2 w[3];
    if (!fallback) {
        dvec2 n[3];
        for (int i = 0; i < 3; i++) {
            dvec2 e = dvec2(v[(i + 1) % 3].xy) - dvec2(v[i].xy);
            n[i] = normalize(double(area > 0.0 ? 1.0 : -1.0) * dvec2(e.y, -e.x));  // outward, either winding
        }
        for (int i = 0; i < 3; i++) {
            dvec2 a = n[(i + 2) % 3], b = n[i];     // the normals of the two edges at vertex i
            double c = 1.0 + dot(a, b);
            fallback = fallback || c < 1e-3;
            w[i] = vec2(dvec2(v[i].xy) + double(u_lambda) * (a + b) / max(c, 1e-3));
        }
        float tri = abs((w[1].x - w[0].x) * (w[2].y - w[0].y) - (w[2].x - w[0].x) * (w[1].y - w[0].y));
        fallback = fallback || (hi.x - lo.x) * (hi.y - lo.y) < 0.5 * tri;
    }
    if (fallback) {
        emit(vec2(lo.x, lo.y), z);
        emit(vec2(hi.x, lo.y), z);
        emit(vec2(lo.x, hi.y), z);
        emit(vec2(hi.x, hi.y), z);
    } else {
        for (int i = 0; i < 3; i++)
            emit(w[i], z);
    }
#endif
    EndPrimitive();
}
