// Per-triangle set-up of the exact per-texel tests of cons_fs.glsl, shared by
// cons_gs.glsl and cons_adj_gs.glsl (shadowmap.c puts it after their
// #version and SL_MODE lines).
//
// Why here: llvmpipe runs a fragment shader as SIMD code in which branches
// are masks, not jumps, so every instruction of it costs on every fragment,
// whichever branch the fragment takes. What depends on the triangle only
// (edge normals with their square roots and divisions, the depth plane's
// gradient with its division by the area) is computed once per triangle
// here, in double, from the float window-space vertices, with the very
// expressions the per-texel test used to evaluate for each texel; the
// fragment shader is left with the per-texel part.

// Outward unit normal of edge a -> b for orientation s (+1 counter-
// clockwise), 0 for a zero-length edge (it separates nothing).
dvec2 cons_edge_normal(vec3 a, vec3 b, double s)
{
    dvec2 e = dvec2(b.xy) - dvec2(a.xy);
    double len = length(e);
    return len > 0.0 ? s * dvec2(e.y, -e.x) / len : dvec2(0.0);
}

// Twice the signed area of a, b, c in double.
double cons_area(vec3 a, vec3 b, vec3 c)
{
    dvec3 p = dvec3(a), q = dvec3(b), r = dvec3(c);
    return (q.x - p.x) * (r.y - p.y) - (r.x - p.x) * (q.y - p.y);
}

// Gradient (depth per texel in x and y) of the plane through a, b, c:
// depth = a.z + g.x (x - a.x) + g.y (y - a.y). Only meaningful when
// |area| > 1e-12; 0 otherwise.
dvec2 cons_plane_grad(vec3 a, vec3 b, vec3 c, double area)
{
    if (abs(area) <= 1e-12)
        return dvec2(0.0);
    dvec3 p = dvec3(a), q = dvec3(b), r = dvec3(c);
    double gx = ((q.z - p.z) * (r.y - p.y) - (r.z - p.z) * (q.y - p.y)) / area;
    double gy = ((r.z - p.z) * (q.x - p.x) - (q.z - p.z) * (r.x - p.x)) / area;
    return dvec2(gx, gy);
}
