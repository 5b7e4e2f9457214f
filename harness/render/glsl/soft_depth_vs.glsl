#version 450 core
// Curtis 2009 layers: the fragment's linear depth (distance from the
// projection point along the light's normal) rides along as a varying,
// which GL interpolates perspective-correctly, so the layer stores world
// units with float precision at every depth instead of a window depth.
layout(location = 0) in vec3 a_pos;
uniform mat4 u_vp;
uniform mat4 u_view;
out float v_depth;
void main()
{
    v_depth = -(u_view * vec4(a_pos, 1.0)).z;
    gl_Position = u_vp * vec4(a_pos, 1.0);
}
