#version 460
#extension GL_GOOGLE_include_directive : require
// Every vertex's AO rays of one slice (ao_trace_body.glsl).
#include "ao_trace_body.glsl"
