#version 450 core
// The exact per-texel decisions of the conservative layers, in double
// precision. The texel is the square [i, i+1] x [j, j+1] in window space.
//
// u_mode 0 (BGSM) and 1 (BGSM, second layer): keep the texel if the square
// and the triangle overlap (separating axes: the box axes and the three edge
// normals, each with a margin of u_eps texels in the triangle's favour); the
// depth written is a lower bound of the triangle's depth over the square:
// the minimum of its plane over the four corners (the plane is linear, so
// that is its minimum over the square), never below the triangle's nearest
// vertex (which bounds steep, nearly edge-on planes), minus u_zeps.
// Mode 1 drops the triangle stored by mode 0 at this texel, so the second
// layer holds the nearest of all the others.
// u_mode 2 (SGSM): keep the texel only if the whole square lies inside the
// triangle by at least u_eps texels; the depth written is an upper bound of
// the triangle's depth over the square (maximum of the plane over the corners,
// never beyond its farthest vertex), plus u_zeps.
// Mode 0 also marks the id with SL_FULL (the top bit) when the whole square
// lies inside the triangle by u_eps (Hertel 2009's "fully covered").
// All write the triangle's id; the depth test keeps the smallest value.
uniform int u_mode;
uniform double u_eps;
uniform double u_zeps;
layout(binding = 0) uniform usampler2D u_first_ids;   // mode 1: the ids of mode 0
flat in vec3 g_v0;
flat in vec3 g_v1;
flat in vec3 g_v2;
flat in uint g_tri;
flat in vec3 g_n0;      // mode 3: the vertex of the neighbour across edge i opposite to it
flat in vec3 g_n1;
flat in vec3 g_n2;
flat in uint g_keep;    // mode 3: bit i set when edge i stays in place (its neighbour takes over)
layout(location = 0) out uint o_tri;

// signed distances of the square's corners outside the line a->b, with the
// outward side given by s (the sign of the polygon's area)
void corner_dist(dvec2 a, dvec2 b, double s, dvec2 c[4], out double dmin, out double dmax, out bool ok)
{
    dvec2 e = b - a;
    double len = length(e);
    ok = len > 0.0;
    dmin = 1e300;
    dmax = -1e300;
    if (!ok)
        return;
    dvec2 n = s * dvec2(e.y, -e.x) / len;
    for (int k = 0; k < 4; k++) {
        double dist = dot(n, c[k] - a);
        dmin = min(dmin, dist);
        dmax = max(dmax, dist);
    }
}

// highest depth of the plane through a, b, c over the square, never beyond
// the farthest of the three
double plane_max(dvec3 a, dvec3 b, dvec3 c, dvec2 q[4])
{
    double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    double zhi = max(a.z, max(b.z, c.z));
    if (abs(area) <= 1e-12)
        return zhi;
    double gx = ((b.z - a.z) * (c.y - a.y) - (c.z - a.z) * (b.y - a.y)) / area;
    double gy = ((c.z - a.z) * (b.x - a.x) - (b.z - a.z) * (c.x - a.x)) / area;
    double pmax = -1e300;
    for (int k = 0; k < 4; k++)
        pmax = max(pmax, a.z + gx * (q[k].x - a.x) + gy * (q[k].y - a.y));
    return min(pmax, zhi);
}

void main()
{
    ivec2 t = ivec2(gl_FragCoord.xy);
    if (u_mode == 1 && (texelFetch(u_first_ids, t, 0).r & 0x7fffffffu) == g_tri)
        discard;
    dvec3 v[3] = dvec3[3](dvec3(g_v0), dvec3(g_v1), dvec3(g_v2));
    if (u_mode == 3) {
        // SGSM with adjacency: the square must lie inside the triangle and,
        // across each kept edge, inside the neighbour: inside the half-planes
        // of the triangle's other edges and of each kept neighbour's two
        // other edges. Every point of such a square is in the triangle or in
        // a neighbour (a point outside the triangle is beyond a kept edge and
        // inside that neighbour's other two edges), so the pixel's ray meets
        // one of them; both are in front of the pixel when the larger of
        // their highest depths over the square is.
        dvec2 q[4] = dvec2[4](dvec2(t), dvec2(t) + dvec2(1, 0), dvec2(t) + dvec2(0, 1), dvec2(t) + dvec2(1, 1));
        dvec3 nb[3] = dvec3[3](dvec3(g_n0), dvec3(g_n1), dvec3(g_n2));
        double ta = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
        if (abs(ta) < 1e-12)
            discard;
        double st = ta > 0.0 ? 1.0 : -1.0;
        double zmax = plane_max(v[0], v[1], v[2], q);
        // wholly inside the triangle itself: as plain SGSM, so this layer
        // proves at least every texel SGSM proves
        bool inside = true;
        for (int i = 0; i < 3; i++) {
            double dmin, dmax;
            bool ok;
            corner_dist(v[i].xy, v[(i + 1) % 3].xy, st, q, dmin, dmax, ok);
            inside = inside && ok && dmax <= -u_eps;
        }
        for (int i = 0; i < 3 && !inside; i++) {
            dvec3 a = v[i], b = v[(i + 1) % 3];
            double dmin, dmax;
            bool ok;
            if ((g_keep & (1u << i)) == 0u) {
                corner_dist(a.xy, b.xy, st, q, dmin, dmax, ok);
                if (!ok || dmax > -u_eps)
                    discard;
                continue;
            }
            // the neighbour runs b -> a -> opposite
            dvec3 o = nb[i];
            double na = (a.x - b.x) * (o.y - b.y) - (o.x - b.x) * (a.y - b.y);
            if (abs(na) < 1e-12)
                discard;
            double sn = na > 0.0 ? 1.0 : -1.0;
            corner_dist(a.xy, o.xy, sn, q, dmin, dmax, ok);
            if (!ok || dmax > -u_eps)
                discard;
            corner_dist(o.xy, b.xy, sn, q, dmin, dmax, ok);
            if (!ok || dmax > -u_eps)
                discard;
            zmax = max(zmax, plane_max(b, a, o, q));
        }
        gl_FragDepth = float(clamp(zmax + u_zeps, 0.0, 1.0));
        o_tri = g_tri;
        return;
    }
    dvec2 c[4] = dvec2[4](dvec2(t), dvec2(t) + dvec2(1, 0), dvec2(t) + dvec2(0, 1), dvec2(t) + dvec2(1, 1));
    double area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
    double s = area >= 0.0 ? 1.0 : -1.0;
    // box axes
    dvec2 lo = min(v[0].xy, min(v[1].xy, v[2].xy)), hi = max(v[0].xy, max(v[1].xy, v[2].xy));
    if (u_mode != 2 && (hi.x < double(t.x) - u_eps || lo.x > double(t.x + 1) + u_eps ||
                        hi.y < double(t.y) - u_eps || lo.y > double(t.y + 1) + u_eps))
        discard;
    // edge axes: signed distance of each corner outside edge i, in texels
    bool full = abs(area) >= 1e-12;
    for (int i = 0; i < 3; i++) {
        dvec2 a = v[i].xy, b = v[(i + 1) % 3].xy;
        dvec2 e = b - a;
        double len = length(e);
        if (len == 0.0)
            continue;                      // a degenerate edge separates nothing
        dvec2 n = s * dvec2(e.y, -e.x) / len;
        double dmin = 1e300, dmax = -1e300;
        for (int k = 0; k < 4; k++) {
            double dist = dot(n, c[k] - a);
            dmin = min(dmin, dist);
            dmax = max(dmax, dist);
        }
        if (u_mode != 2 && dmin > u_eps)
            discard;                       // the whole square is outside this edge
        full = full && dmax <= -u_eps;
        if (u_mode == 2 && (dmax > -u_eps || abs(area) < 1e-12))
            discard;                       // some of the square is not surely inside
    }
    // depth bounds from the plane through the three vertices
    double zlo = min(v[0].z, min(v[1].z, v[2].z)), zhi = max(v[0].z, max(v[1].z, v[2].z));
    double z = u_mode == 2 ? zhi : zlo;
    if (abs(area) > 1e-12) {
        // z = v0.z + gx (x - v0.x) + gy (y - v0.y)
        double gx = ((v[1].z - v[0].z) * (v[2].y - v[0].y) - (v[2].z - v[0].z) * (v[1].y - v[0].y)) / area;
        double gy = ((v[2].z - v[0].z) * (v[1].x - v[0].x) - (v[1].z - v[0].z) * (v[2].x - v[0].x)) / area;
        double pmin = 1e300, pmax = -1e300;
        for (int k = 0; k < 4; k++) {
            double pz = v[0].z + gx * (c[k].x - v[0].x) + gy * (c[k].y - v[0].y);
            pmin = min(pmin, pz);
            pmax = max(pmax, pz);
        }
        z = u_mode == 2 ? min(pmax, zhi) : max(pmin, zlo);
    }
    z = u_mode == 2 ? z + u_zeps : z - u_zeps;
    gl_FragDepth = float(clamp(z, 0.0, 1.0));
    o_tri = (u_mode == 0 && full) ? (g_tri | 0x80000000u) : g_tri;
}
