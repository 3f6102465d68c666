#version 460
// light_depth.vert - the mesh seen from a directional light (orthographic), for the depths of the
// first surfaces along it (shading/light_depth.hpp). Vertex layout: shading/renderer.cpp.
layout(push_constant) uniform Push { mat4 light_view_proj; } pc;
layout(location = 0) in vec3 in_position;  // mesh units
void main() { gl_Position = pc.light_view_proj * vec4(in_position, 1.0); }
