#version 450 core
// The exact per-texel decisions of the conservative layers, in double
// precision. The texel is the square [i, i+1] x [j, j+1] in window space.
//
// SL_MODE 0 (BGSM) and 1 (BGSM, second layer): keep the texel if the square
// and the triangle overlap (separating axes: the box axes and the three edge
// normals, each with a margin of u_eps texels in the triangle's favour); the
// depth written is a lower bound of the triangle's depth over the square:
// the minimum of its plane over the four corners (the plane is linear, so
// that is its minimum over the square), never below the triangle's nearest
// vertex (which bounds steep, nearly edge-on planes), minus u_zeps.
// Mode 1 drops the triangle stored by mode 0 at this texel, so the second
// layer holds the nearest of all the others.
// SL_MODE 2 (SGSM): keep the texel only if the whole square lies inside the
// triangle by at least u_eps texels; the depth written is an upper bound of
// the triangle's depth over the square (maximum of the plane over the corners,
// never beyond its farthest vertex), plus u_zeps.
// Mode 0 also marks the id with SL_FULL (the top bit) when the whole square
// lies inside the triangle by u_eps (Hertel 2009's "fully covered").
// All write the triangle's id; the depth test keeps the smallest value.
//
// SL_MODE is defined by shadowmap.c, one program per layer, and the
// per-triangle quantities come from the geometry shader (cons_setup.glsl):
// llvmpipe executes every instruction of a fragment shader on every
// fragment (branches are masks), so code for the other layers, or per-
// triangle work redone per texel, would cost on every fragment.
//
// Distances: for an edge from a with outward unit normal n, the corners'
// signed distances outside it are dot(n, q - a) over the four corners q;
// their minimum and maximum are those of the corners the normal's signs
// pick (dmin: the corner at t + (n.x < 0, n.y < 0), dmax: the opposite), so
// each is one dot product, evaluated as the per-texel test always did.
// Likewise the plane's minimum and maximum over the square are at the
// corners its gradient's signs pick.
// The margins are constants of the source (shadowmap.c defines SL_EPS and
// SL_ZEPS from frame.h's values, printed exactly): llvmpipe loads a uniform
// at a non-zero offset as a gather of one scalar per fragment (eight loads
// per batch of eight): as uniforms they cost BGSM 849 M instructions a
// layer against 794 M (valgrind, Bench 2048^2, LP_NUM_THREADS=0).
const double u_eps = SL_EPS;
const double u_zeps = SL_ZEPS;
#if SL_MODE == 1
layout(binding = 0, r32ui) readonly uniform uimage2D u_first_ids;   // the ids of mode 0
#endif
flat in vec3 g_v0;
flat in vec3 g_v1;
flat in vec3 g_v2;
flat in uint g_tri;
flat in dvec2 g_e0;     // outward unit normal of edge v_i -> v_i+1 (0: zero length)
flat in dvec2 g_e1;
flat in dvec2 g_e2;
flat in dvec2 g_grad;   // depth plane gradient (from v0)
#if SL_MODE != 3
flat in float g_zb;     // the vertices' nearest depth (modes 0, 1), farthest (2): the min or max
                        // of three floats is one of them, so double(g_zb) is what the double
                        // min or max of the three gave, without its NaN handling per fragment
#endif
#if SL_MODE == 0 || SL_MODE == 1
flat in ivec4 g_box;    // texel indices x first, last, y first, last of the box test
#endif
flat in uint g_flags;   // bit 0: |area| > 1e-12; bit 1: |area| >= 1e-12 (mode 3: bits 2 + i, 5 + i the same per neighbour)
#if SL_MODE == 3
flat in vec3 g_n0;      // the vertex of the neighbour across edge i opposite to it
flat in vec3 g_n1;
flat in vec3 g_n2;
flat in uint g_keep;    // bit i set when edge i stays in place (its neighbour takes over)
flat in dvec2 g_na0;    // kept edge i: the neighbour's edge normals a -> opposite, opposite -> b
flat in dvec2 g_nb0;
flat in dvec2 g_na1;
flat in dvec2 g_nb1;
flat in dvec2 g_na2;
flat in dvec2 g_nb2;
flat in dvec2 g_ngrad0; // kept edge i: the neighbour's depth plane gradient (from b)
flat in dvec2 g_ngrad1;
flat in dvec2 g_ngrad2;
#endif
layout(location = 0) out uint o_tri;

// A texel's corner coordinates: lo = t, hi = t + 1, in double (exact:
// t < 2^14). Made once per fragment and shared by every corner below.
struct texel { dvec2 lo, hi; };

// The corner of texel t at which dot(n, q) is smallest (sgn = 1) or
// largest (sgn = -1). It picks lo or hi per axis, where this once added
// 0.0 or 1.0 to dvec2(t) per corner: t + 0.0 is t and t + 1.0 is hi, both
// exact, so the corner and every distance from it are the same doubles,
// for one select per axis instead of a select and an addition.
dvec2 corner(texel t, dvec2 n, double sgn)
{
    return dvec2(sgn * n.x < 0.0 ? t.hi.x : t.lo.x, sgn * n.y < 0.0 ? t.hi.y : t.lo.y);
}

// Lowest signed distance of the texel's corners outside the edge through a.
double dist_min(texel t, vec3 a, dvec2 n)
{
    return dot(n, corner(t, n, 1.0) - dvec2(a.xy));
}

// Highest.
double dist_max(texel t, vec3 a, dvec2 n)
{
    return dot(n, corner(t, n, -1.0) - dvec2(a.xy));
}

// Depth of the plane through a with gradient g at corner q.
double plane_at(vec3 a, dvec2 g, dvec2 q)
{
    return double(a.z) + g.x * (q.x - double(a.x)) + g.y * (q.y - double(a.y));
}

// Highest depth of the plane over the texel, never beyond zhi; zhi when the
// plane is degenerate.
double plane_max(texel t, vec3 a, dvec2 g, bool has_plane, double zhi)
{
    return has_plane ? min(plane_at(a, g, corner(t, g, -1.0)), zhi) : zhi;
}

void main()
{
    ivec2 it = ivec2(gl_FragCoord.xy);
    texel t;
    t.lo = dvec2(it);
    t.hi = t.lo + 1.0;
#if SL_MODE == 3
    dvec3 zs = dvec3(g_v0.z, g_v1.z, g_v2.z);
    double zlo = min(zs.x, min(zs.y, zs.z)), zhi = max(zs.x, max(zs.y, zs.z));
#else
    double zlo = double(g_zb), zhi = zlo;
#endif
    // One discard, at the end: on llvmpipe each discard statement costs
    // (measured: a second, early one for the box test nearly doubled the
    // time of BGSM), and an early one saves nothing, since the rest of the
    // shader runs anyway, masked.
    bool drop = false;
#if SL_MODE == 3
    // SGSM with adjacency: the square must lie inside the triangle and,
    // across each kept edge, inside the neighbour: inside the half-planes
    // of the triangle's other edges and of each kept neighbour's two
    // other edges. Every point of such a square is in the triangle or in
    // a neighbour (a point outside the triangle is beyond a kept edge and
    // inside that neighbour's other two edges), so the pixel's ray meets
    // one of them; both are in front of the pixel when the larger of
    // their highest depths over the square is.
    vec3 v[3] = vec3[3](g_v0, g_v1, g_v2);
    dvec2 e[3] = dvec2[3](g_e0, g_e1, g_e2);
    double zmax = plane_max(t, v[0], g_grad, (g_flags & 1u) != 0u, zhi);
    // wholly inside the triangle itself: as plain SGSM, so this layer
    // proves at least every texel SGSM proves
    bool inside = true, across = true;
    for (int i = 0; i < 3; i++) {
        bool in_edge = dist_max(t, v[i], e[i]) <= -u_eps;
        inside = inside && in_edge;
        across = across && (in_edge || (g_keep & (1u << i)) != 0u);
    }
    // across each kept edge (the neighbour runs b -> a -> opposite): a
    // loop over the kept edges only, since a loop, unlike an if, ends when
    // no fragment of the batch needs another round (most triangles keep
    // none and pay one masked round)
    double zn = zmax;
    for (uint k = g_keep; k != 0u; k &= k - 1u) {
        int i = findLSB(k);
        vec3 a = i == 0 ? g_v0 : i == 1 ? g_v1 : g_v2;
        vec3 b = i == 0 ? g_v1 : i == 1 ? g_v2 : g_v0;
        vec3 o = i == 0 ? g_n0 : i == 1 ? g_n1 : g_n2;
        dvec2 na = i == 0 ? g_na0 : i == 1 ? g_na1 : g_na2;
        dvec2 nb = i == 0 ? g_nb0 : i == 1 ? g_nb1 : g_nb2;
        dvec2 ng = i == 0 ? g_ngrad0 : i == 1 ? g_ngrad1 : g_ngrad2;
        across = across && (g_flags & (4u << i)) != 0u && dist_max(t, a, na) <= -u_eps &&
                 dist_max(t, o, nb) <= -u_eps;
        double nzhi = max(double(b.z), max(double(a.z), double(o.z)));
        zn = max(zn, plane_max(t, b, ng, (g_flags & (32u << i)) != 0u, nzhi));
    }
    drop = (g_flags & 2u) == 0u || (!inside && !across);
    double z = (inside ? zmax : zn) + u_zeps;
#else
    vec3 v[3] = vec3[3](g_v0, g_v1, g_v2);
#if SL_MODE != 2
    // box axes: the square [t - eps, t + 1 + eps] misses the vertices'
    // range, as integer bounds on t from the geometry shader (cons_gs.glsl
    // says why they decide exactly as the float comparisons did)
    drop = it.x < g_box.x || it.x > g_box.y || it.y < g_box.z || it.y > g_box.w;
#endif
#if SL_MODE == 1
    drop = drop || (imageLoad(u_first_ids, it).r & 0x7fffffffu) == g_tri;
#endif
    // edge axes: signed distances of the corners outside each edge, in texels
    dvec2 e[3] = dvec2[3](g_e0, g_e1, g_e2);
    bool full = (g_flags & 2u) != 0u;
    for (int i = 0; i < 3; i++) {
        // a zero-length edge (normal 0) separates nothing and leaves a
        // triangle of zero area, which is never full
#if SL_MODE != 2
        drop = drop || dist_min(t, v[i], e[i]) > u_eps;   // the whole square is outside this edge
#endif
#if SL_MODE != 1
        full = full && dist_max(t, v[i], e[i]) <= -u_eps;
#endif
    }
#if SL_MODE == 2
    drop = !full;                          // some of the square is not surely inside
    double z = plane_max(t, v[0], g_grad, (g_flags & 1u) != 0u, zhi) + u_zeps;
#else
    // lowest depth of the plane over the square, never below zlo
    // (a compare, not max(): llvmpipe's max is NaN-aware; with no NaN here
    // the two differ at most in the sign of a zero, which z - u_zeps drops)
    double p = plane_at(v[0], g_grad, corner(t, g_grad, 1.0));
    double z = (g_flags & 1u) != 0u && p > zlo ? p : zlo;
    z -= u_zeps;
#endif
#endif
    if (drop)
        discard;
    // no clamp here: GL clamps the depth written to the depth range [0, 1]
    // itself (llvmpipe after the conversion), and rounding to float is
    // monotonic with 0 and 1 exact, so float(z) clamped is float(clamp(z))
    gl_FragDepth = float(z);
#if SL_MODE == 0
    o_tri = full ? (g_tri | 0x80000000u) : g_tri;
#else
    o_tri = g_tri;
#endif
}
