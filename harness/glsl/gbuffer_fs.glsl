#version 450 core
// Face normals are looked up by triangle rather than interpolated, so that
// the PFL/PnFL test and the truth use the geometric normal of the very
// triangle whose surface the pixel lies on.
layout(std430, binding = 0) readonly buffer FaceNormals { vec4 face_n[]; };
in vec3 v_world;
layout(location = 0) out vec4 o_pos;
layout(location = 1) out vec4 o_nrm;
layout(location = 2) out uint o_tri;
void main()
{
    vec3 n = face_n[gl_PrimitiveID].xyz;
    o_pos = vec4(v_world, 1.0);
    o_nrm = vec4(gl_FrontFacing ? n : -n, 0.0);
    o_tri = uint(gl_PrimitiveID) + 1u;
}
