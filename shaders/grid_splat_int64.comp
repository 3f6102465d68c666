#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// Two 64-bit atomics a tap (needs shaderInt64 and shaderBufferInt64Atomics): see grid_splat_body.glsl.
#define JADE_SPLAT_INT64
#include "grid_splat_body.glsl"
