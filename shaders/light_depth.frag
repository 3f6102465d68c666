#version 460
// light_depth.frag - depth peeling along a directional light (shading/light_depth.hpp): pass
// LAYER keeps the nearest surface beyond layer LAYER − 1 at the same texel, whose depth the
// previous pass left in `previous`, and writes its depth into channel LAYER of the layers atlas
// (the pipeline's colour write mask). Layer 0 is the surface nearest to the light.
layout(constant_id = 0) const uint LAYER = 0;

layout(binding = 0) uniform sampler2D previous;  // D32: layer LAYER − 1 (not read by layer 0)

layout(location = 0) out vec4 out_layers;

// Depth units (of the light's orthographic range): the same triangle rasterised again at the
// same texel gives the same depth, so this only has to absorb rounding.
const float kPeelMargin = 1.0 / 1048576.0;

void main()
{
    if (LAYER > 0u && gl_FragCoord.z <= texelFetch(previous, ivec2(gl_FragCoord.xy), 0).r + kPeelMargin) discard;
    out_layers = vec4(gl_FragCoord.z);
}
