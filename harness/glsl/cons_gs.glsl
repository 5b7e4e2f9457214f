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
// edge normals); at a sharp vertex that runs off towards infinity, so when
// 1 + dot(n0, n1) < 0.1 (a vertex angle under about 26 degrees) or the
// triangle has (almost) no area in the map, we fall back to its bounding box
// grown by u_lambda: still a superset of every texel centre within u_lambda
// of the triangle, hence still conservative, and never far from it.
// Which texels really count is decided exactly per texel in cons_fs.glsl.
layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;
uniform float u_size;          // map size in texels
uniform float u_lambda;        // enlargement, texels
uniform uint u_first;          // scene index of this draw's first triangle
flat out vec3 g_v0;
flat out vec3 g_v1;
flat out vec3 g_v2;
flat out uint g_tri;
flat out vec3 g_n0;            // unused here: sgsm_adj's neighbours (cons_adj_gs.glsl)
flat out vec3 g_n1;
flat out vec3 g_n2;
flat out uint g_keep;
uniform int u_mode;

vec3 win(vec4 c) { return vec3((c.xy * 0.5 + 0.5) * u_size, c.z); }

void emit(vec2 p, float z)
{
    gl_Position = vec4(p / u_size * 2.0 - 1.0, z, 1.0);
    EmitVertex();
}

void main()
{
    vec3 v[3] = vec3[3](win(gl_in[0].gl_Position), win(gl_in[1].gl_Position), win(gl_in[2].gl_Position));
    g_v0 = v[0];
    g_v1 = v[1];
    g_v2 = v[2];
    g_tri = u_first + uint(gl_PrimitiveIDIn) + 1u;
    g_n0 = g_n1 = g_n2 = vec3(0.0);
    g_keep = 0u;
    // every emitted vertex at the nearest depth of the triangle, clamped into
    // the box: clipping must never cut a fragment we want (cons_fs writes the
    // real conservative depth)
    float z = clamp(min(v[0].z, min(v[1].z, v[2].z)), 0.0, 1.0);
    float area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
    if (u_mode == 2 || u_mode == 3) {
        // SGSM keeps only texels wholly inside the triangle, whose centres
        // the triangle itself covers: no enlargement
        for (int i = 0; i < 3; i++)
            emit(v[i].xy, z);
        EndPrimitive();
        return;
    }
    bool fallback = abs(area) < 1e-6;
    vec2 n[3];
    if (!fallback) {
        float s = area > 0.0 ? 1.0 : -1.0;        // outward normals for either winding
        for (int i = 0; i < 3; i++) {
            vec2 e = v[(i + 1) % 3].xy - v[i].xy;
            n[i] = normalize(s * vec2(e.y, -e.x));
        }
        for (int i = 0; i < 3; i++)
            fallback = fallback || (1.0 + dot(n[(i + 2) % 3], n[i]) < 0.1);
    }
    if (fallback) {
        vec2 lo = min(v[0].xy, min(v[1].xy, v[2].xy)) - vec2(u_lambda);
        vec2 hi = max(v[0].xy, max(v[1].xy, v[2].xy)) + vec2(u_lambda);
        emit(vec2(lo.x, lo.y), z);
        emit(vec2(hi.x, lo.y), z);
        emit(vec2(lo.x, hi.y), z);
        emit(vec2(hi.x, hi.y), z);
    } else {
        for (int i = 0; i < 3; i++) {
            vec2 a = n[(i + 2) % 3], b = n[i];      // the normals of the two edges at vertex i
            emit(v[i].xy + u_lambda * (a + b) / (1.0 + dot(a, b)), z);
        }
    }
    EndPrimitive();
}
