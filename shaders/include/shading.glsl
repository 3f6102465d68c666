// shading.glsl - what mesh.vert and mesh.frag share: the push and frame constants (their layout,
// shared with C++, is shading_interface.h), the shading modes and the light count.
#ifndef JADE_SHADING_GLSL
#define JADE_SHADING_GLSL

#extension GL_EXT_scalar_block_layout : require

const float JADE_PI = 3.14159265358979323846;

#include "shading_interface.h"  // FramePush, GpuLight, FrameData, the array sizes

layout(push_constant, scalar) uniform FramePushBlock { FramePush frame; };

const uint kColorMapStops = JADE_COLOR_MAP_STOPS;

// Shading modes (specialisation constant MODE of both stages, jade::ShadingMode), and the
// inputs pass: MODE = kInputs + k writes the k-th vec4 of the rasterised shading inputs
// (Renderer::shading_inputs) instead of shading.
const uint kLambert = 0, kCurvature = 1, kTm = 2, kFalseColor = 3, kInputs = 4;

const uint kMaxLights = JADE_MAX_LIGHTS;

layout(binding = 0, scalar) uniform FrameDataBlock { FrameData data; };

#endif
