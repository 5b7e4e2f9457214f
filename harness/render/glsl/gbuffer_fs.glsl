#version 450 core
// World position, and the triangle id + 1 with the top bit set where the
// camera sees the triangle's back. gbuffer.c turns that into the face
// normal (looked up by triangle, so that the PFL/PnFL test and the truth
// use the geometric normal of the very triangle the pixel lies on) turned
// toward the camera: the same values a normal attachment would hold, for
// 16 bytes less per pixel to write and read back.
in vec3 v_world;
layout(location = 0) out vec4 o_pos;
layout(location = 1) out uint o_tri;
void main()
{
    o_pos = vec4(v_world, 1.0);
    o_tri = (uint(gl_PrimitiveID) + 1u) | (gl_FrontFacing ? 0u : 0x80000000u);
}
