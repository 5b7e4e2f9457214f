#version 450 core
layout(location = 0) out uint o_tri;
void main()
{
    o_tri = uint(gl_PrimitiveID) + 1u;
}
