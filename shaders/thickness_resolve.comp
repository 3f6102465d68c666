#version 460
#extension GL_GOOGLE_include_directive : require
// Thickness t̄ = the mean inward ray distance per vertex, mesh units: the fixed-point sums of
// thickness_trace.comp added over the ray slices, divided by the ray count.
#include "common.glsl"

#include "bake_interface.h"  // struct ThicknessResolvePush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { ThicknessResolvePush pc; };

layout(binding = 0, scalar) readonly buffer Sums { uint sums[]; };  // [slice][vertex]
layout(binding = 1, scalar) writeonly buffer Thickness { float thickness[]; };

const float kQuantum = JADE_THICKNESS_QUANTUM;  // bake_interface.h

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count) return;
    uint total = 0u;
    for (uint s = 0u; s < pc.slices; ++s) total += sums[s * pc.vertex_count + v];
    // float(total) rounds to 2^-24 relative: far below the ray noise (no float64 needed, which a
    // host's device may not enable).
    thickness[v] = float(total) * (pc.max_distance / (float(pc.rays) * kQuantum));
}
