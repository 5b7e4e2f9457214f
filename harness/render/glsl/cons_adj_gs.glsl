#version 450 core
// SGSM with adjacency (Morais 2015, chapter 4), fed GL_TRIANGLES_ADJACENCY:
// gl_in[0, 2, 4] is the triangle, gl_in[1, 3, 5] the vertex opposite edges
// (0,2), (2,4), (4,0) in the neighbour across them, or a repeat of the
// edge's first vertex where there is no neighbour (or more than one).
// An edge stays in place when the triangle and that neighbour both face
// away from the light ("in shadow"); a missing neighbour counts as lit.
// Morais moves the other edges inwards and emits 1, 1, 2 or 4 triangles for
// 0..3 kept edges; here the exact per-texel test of cons_fs.glsl (mode 3)
// does the shrinking, so the triangle is emitted as it is: a texel wholly
// inside the triangle and its kept neighbours has its centre in one of
// them, and each rasterises itself.
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 3) out;
uniform float u_size;
uniform uint u_first;
uniform float u_wmin;          // a point light's frustum: least clip w kept
uniform float u_guard;         // ... and largest |NDC x, y| kept; 0: keep all (orthographic)
flat out vec3 g_v0;
flat out vec3 g_v1;
flat out vec3 g_v2;
flat out uint g_tri;
flat out vec3 g_n0;
flat out vec3 g_n1;
flat out vec3 g_n2;
flat out uint g_keep;
flat out dvec2 g_e0;       // the triangle's outward unit edge normals (cons_setup.glsl)
flat out dvec2 g_e1;
flat out dvec2 g_e2;
flat out dvec2 g_grad;     // its depth plane gradient
flat out dvec2 g_na0;      // kept edge i: the neighbour's edge normals a -> opposite, opposite -> b
flat out dvec2 g_nb0;
flat out dvec2 g_na1;
flat out dvec2 g_nb1;
flat out dvec2 g_na2;
flat out dvec2 g_nb2;
flat out dvec2 g_ngrad0;   // kept edge i: the neighbour's depth plane gradient (from b)
flat out dvec2 g_ngrad1;
flat out dvec2 g_ngrad2;
#if SL_MODE == 4
flat out float g_zb;       // the vertices' farthest depth (SGSM's fragment shader's bound)
#endif
flat out uint g_flags;     // bits 0, 1: the triangle's |area| > 1e-12, >= 1e-12; 2 + i, 5 + i: the same of neighbour i

// Window space of a clip-space vertex. The division is exact (by 1) in a
// directional light's orthographic frustum; in a point light's perspective
// one, window depth z / w is still affine across the triangle in window
// space, so the depth planes of cons_setup.glsl hold as they are.
bool unmapped(vec4 c)
{
    return u_guard > 0.0 && (c.w < u_wmin || abs(c.x / c.w) > u_guard || abs(c.y / c.w) > u_guard);
}

vec3 win(vec4 c) { return vec3((c.xy / c.w * 0.5 + 0.5) * u_size, c.z / c.w); }

float area2(vec3 a, vec3 b, vec3 c) { return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y); }

void main()
{
    // a point light's triangles too close to its plane (or behind it) or
    // beyond the guard band across it have no precise window position: they
    // are left out (lightfit.c lists them for the methods to test)
    // (a lost triangle only loses proofs of shadow; such a neighbour counts
    // as missing)
    if (unmapped(gl_in[0].gl_Position) || unmapped(gl_in[2].gl_Position) || unmapped(gl_in[4].gl_Position))
        return;
    vec3 v[3] = vec3[3](win(gl_in[0].gl_Position), win(gl_in[2].gl_Position), win(gl_in[4].gl_Position));
    vec3 o[3] = vec3[3](win(gl_in[1].gl_Position), win(gl_in[3].gl_Position), win(gl_in[5].gl_Position));
    g_v0 = v[0];
    g_v1 = v[1];
    g_v2 = v[2];
    g_n0 = o[0];
    g_n1 = o[1];
    g_n2 = o[2];
    g_tri = u_first + uint(gl_PrimitiveIDIn) + 1u;
    // seen from the light (window space, counter-clockwise = front), a
    // triangle faces away from the light when its signed area is negative
    bool away = area2(v[0], v[1], v[2]) < 0.0;
    uint keep = 0u;
    for (int i = 0; i < 3; i++) {
        vec3 a = v[i], b = v[(i + 1) % 3];
        bool exists = o[i] != a && o[i] != b && !unmapped(gl_in[2 * i + 1].gl_Position);
        // the neighbour winds b -> a -> opposite
        if (away && exists && area2(b, a, o[i]) < 0.0)
            keep |= 1u << i;
    }
    // SL_MODE 4 (shadowmap.c draws it first) takes the triangles that keep
    // no edge, SL_MODE 3 the others: for a triangle that keeps none, mode
    // 3's per-texel test is SGSM's (inside all three edges, the plane's
    // highest depth), so those go to mode 2's fragment shader, which lacks
    // the neighbours' part: on llvmpipe that part costs every fragment of
    // a draw whether its triangle keeps an edge or not (a loop runs its
    // first round, masked, for all)
#if SL_MODE == 4
    if (keep != 0u)
        return;
#else
    if (keep == 0u)
        return;
#endif
    g_keep = keep;
    // the per-texel test's set-up: the triangle, then each kept neighbour,
    // which runs b -> a -> opposite (cons_fs.glsl, mode 3)
    double ta = cons_area(v[0], v[1], v[2]);
    double st = ta > 0.0 ? 1.0 : -1.0;
    g_e0 = cons_edge_normal(v[0], v[1], st);
    g_e1 = cons_edge_normal(v[1], v[2], st);
    g_e2 = cons_edge_normal(v[2], v[0], st);
    g_grad = cons_plane_grad(v[0], v[1], v[2], ta);
    uint flags = (abs(ta) > 1e-12 ? 1u : 0u) | (abs(ta) >= 1e-12 ? 2u : 0u);
    dvec2 na[3], nb[3], ng[3];
    for (int i = 0; i < 3; i++) {
        na[i] = nb[i] = ng[i] = dvec2(0.0);
        if ((keep & (1u << i)) == 0u)
            continue;
        vec3 a = v[i], b = v[(i + 1) % 3];
        double narea = cons_area(b, a, o[i]);
        double sn = narea > 0.0 ? 1.0 : -1.0;
        na[i] = cons_edge_normal(a, o[i], sn);
        nb[i] = cons_edge_normal(o[i], b, sn);
        ng[i] = cons_plane_grad(b, a, o[i], narea);
        flags |= (abs(narea) > 1e-12 ? 1u : 0u) << (5 + i);
        flags |= (abs(narea) >= 1e-12 ? 1u : 0u) << (2 + i);
    }
    g_na0 = na[0]; g_nb0 = nb[0]; g_ngrad0 = ng[0];
    g_na1 = na[1]; g_nb1 = nb[1]; g_ngrad1 = ng[1];
    g_na2 = na[2]; g_nb2 = nb[2]; g_ngrad2 = ng[2];
    g_flags = flags;
#if SL_MODE == 4
    g_zb = max(v[0].z, max(v[1].z, v[2].z));
#endif
    float z = clamp(min(v[0].z, min(v[1].z, v[2].z)), 0.0, 1.0);
    for (int i = 0; i < 3; i++) {
        gl_Position = vec4(v[i].xy / u_size * 2.0 - 1.0, z, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
