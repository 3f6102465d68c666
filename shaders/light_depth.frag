#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// light_depth.frag - depth peeling along a light (shading/light_depth.hpp): pass LAYER keeps the
// nearest surface beyond layer LAYER − 1 at the same texel, whose depth the previous pass left in
// `previous`, and writes its depth along the light into channel LAYER of the layers atlas (the
// pipeline's colour write mask). Layer 0 is the surface nearest to the light. The peeling
// compares the depth buffer's values (monotonic along the light's ray in either projection); the
// atlas gets what the shaders subtract: the clip depth of an orthographic tile (linear), and for
// a perspective tile the distance from the light along its ray (the clip depth is not linear).
#include "shading_interface.h"  // LightTile
layout(constant_id = 0) const uint LAYER = 0;

layout(push_constant, scalar) uniform Push { LightTile tile; } pc;
layout(binding = 0) uniform sampler2D previous;  // D32: layer LAYER − 1 (not read by layer 0)

layout(location = 0) in vec3 in_position;
layout(location = 0) out vec4 out_layers;

// Depth units (of the light's range): the same triangle rasterised again at the same texel gives
// the same depth, so this only has to absorb rounding.
const float kPeelMargin = 1.0 / 1048576.0;

void main()
{
    if (LAYER > 0u && gl_FragCoord.z <= texelFetch(previous, ivec2(gl_FragCoord.xy), 0).r + kPeelMargin) discard;
    float linear = (length(in_position - pc.tile.origin.xyz) - pc.tile.depth.x) / pc.tile.depth.y;
    out_layers = vec4(pc.tile.origin.w > 0.5 ? linear : gl_FragCoord.z);
}
