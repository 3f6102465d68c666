#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// float64 sums (needs shaderFloat64): see tm_exact_body.glsl.
#define JADE_FLOAT64_SUMS
#include "tm_exact_body.glsl"
