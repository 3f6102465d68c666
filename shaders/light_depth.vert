#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// light_depth.vert - the mesh seen from a light (orthographic along a directional light, in
// perspective from a point light), for the depths of the first surfaces along it
// (shading/light_depth.hpp). Vertex layout: shading/renderer.cpp.
#include "shading_interface.h"  // LightTile
layout(push_constant, scalar) uniform Push { LightTile tile; } pc;
layout(location = 0) in vec3 in_position;  // mesh units
layout(location = 0) out vec3 out_position;
void main()
{
    out_position = in_position;
    gl_Position = pc.tile.view_proj * vec4(in_position, 1.0);
}
