#version 460
#extension GL_GOOGLE_include_directive : require
// Four 32-bit atomics a tap: see grid_splat_body.glsl.
#include "grid_splat_body.glsl"
