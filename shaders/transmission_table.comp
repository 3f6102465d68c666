#version 460
#extension GL_GOOGLE_include_directive : require
// transmission_table.comp - the two parts A_b(t), A_d(t) of attenuation.glsl at t_i = i · step,
// i < count, for mesh.frag to interpolate (a texel fetch a part instead of nine exponentials per
// fragment and light). Texel i holds A_b(t_i) and A_b(t_{i+1}) as six halves, so that one fetch
// gives both ends of the interval; texel count + i holds the same of A_d.
#include "common.glsl"
#include "attenuation.glsl"

#include "shading_interface.h"  // struct TablePush, shared with engine/src/shading
layout(push_constant, scalar) uniform Push { TablePush pc; };
layout(binding = 0, scalar) writeonly buffer Table { uvec4 texels[]; };

void main()
{
    uint thread = jade_thread_index();
    if (thread >= 2u * pc.count) return;
    uint part = thread / pc.count, i = thread - part * pc.count;
    float step = pc.scatter.w;
    vec3 a = transmission_attenuation(part, float(i) * step, pc.extinction, pc.diffusion, pc.scatter.xyz,
                                      pc.source.xyz, pc.boundary.xyz);
    vec3 b = transmission_attenuation(part, float(min(i + 1u, pc.count - 1u)) * step, pc.extinction, pc.diffusion,
                                      pc.scatter.xyz, pc.source.xyz, pc.boundary.xyz);
    texels[thread] = uvec4(packHalf2x16(a.rg), packHalf2x16(vec2(a.b, b.r)), packHalf2x16(b.gb), 0u);
}
