#version 460
#extension GL_GOOGLE_include_directive : require
// transmission_table.comp - the forward part A_b(t) of attenuation.glsl at t_i = i · step,
// i < count, for mesh.frag to interpolate (a texel fetch instead of three exponentials per
// fragment and light). Texel i holds A_b(t_i) and A_b(t_{i+1}) as six halves, so that one fetch
// gives both ends of the interval.
#include "common.glsl"
#include "attenuation.glsl"

#include "shading_interface.h"  // struct TablePush, shared with engine/src/shading
layout(push_constant, scalar) uniform Push { TablePush pc; };
layout(binding = 0, scalar) writeonly buffer Table { uvec4 texels[]; };

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.count) return;
    vec3 a = forward_attenuation(float(i) * pc.step, pc.extinction);
    vec3 b = forward_attenuation(float(min(i + 1u, pc.count - 1u)) * pc.step, pc.extinction);
    texels[i] = uvec4(packHalf2x16(a.rg), packHalf2x16(vec2(a.b, b.r)), packHalf2x16(b.gb), 0u);
}
