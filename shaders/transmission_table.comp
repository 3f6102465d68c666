#version 460
#extension GL_GOOGLE_include_directive : require
// transmission_table.comp - A(t) of attenuation.glsl at t_i = i · step, i < count, for mesh.frag
// to interpolate (one texel fetch instead of nine exponentials per fragment and light). Texel i
// holds A(t_i) and A(t_{i+1}) as six halves, so that one fetch gives both ends of the interval.
#include "common.glsl"
#include "attenuation.glsl"

layout(push_constant, scalar) uniform Push {
    vec4 extinction, diffusion, scatter;  // as transmission_attenuation(); scatter.w: step (mesh units)
    vec4 source, boundary;                // z_s, z_b (xyz) of transmission_attenuation()
    uint count;
} pc;
layout(binding = 0, scalar) writeonly buffer Table { uvec4 texels[]; };

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.count) return;
    float step = pc.scatter.w;
    vec3 a = transmission_attenuation(float(i) * step, pc.extinction, pc.diffusion, pc.scatter.xyz, pc.source.xyz,
                                      pc.boundary.xyz);
    vec3 b = transmission_attenuation(float(min(i + 1u, pc.count - 1u)) * step, pc.extinction, pc.diffusion,
                                      pc.scatter.xyz, pc.source.xyz, pc.boundary.xyz);
    texels[i] = uvec4(packHalf2x16(a.rg), packHalf2x16(vec2(a.b, b.r)), packHalf2x16(b.gb), 0u);
}
