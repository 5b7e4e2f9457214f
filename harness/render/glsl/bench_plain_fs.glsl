#version 450 core
// The plain raster `shadowlab bench` compares every layer with: depth and
// one uint per texel, nothing computed.
layout(location = 0) out uint o_id;
void main()
{
    o_id = uint(gl_PrimitiveID) + 1u;
}
