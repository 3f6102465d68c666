#version 460
#extension GL_GOOGLE_include_directive : require
// A_o = hits / rays per vertex, the hits summed over the ray slices (ao_trace.comp).
#include "common.glsl"

#include "bake_interface.h"  // struct AoResolvePush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { AoResolvePush pc; };

layout(binding = 0, scalar) readonly buffer Hits { uint hits[]; };  // [slice][vertex]
layout(binding = 1, scalar) writeonly buffer Ao { float ao[]; };

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count) return;
    uint total = 0u;
    for (uint s = 0u; s < pc.slices; ++s) total += hits[s * pc.vertex_count + v];
    ao[v] = float(total) / float(pc.rays);
}
