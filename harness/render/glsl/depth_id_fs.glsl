#version 450 core
// gl_PrimitiveID restarts with every draw call; u_first is the scene index
// of the draw's first triangle.
uniform uint u_first;
layout(location = 0) out uint o_tri;
void main()
{
    o_tri = u_first + uint(gl_PrimitiveID) + 1u;
}
