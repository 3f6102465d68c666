#version 460
#extension GL_GOOGLE_include_directive : require
// The other slices' AO rays of the vertices that ao_changed.comp listed (ao_trace_body.glsl).
#define JADE_AO_RETRACE
#include "ao_trace_body.glsl"
