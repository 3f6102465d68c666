#version 460
#extension GL_GOOGLE_include_directive : require
// A_o = hits / rays per vertex.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
    uint rays;
} pc;

layout(binding = 0, scalar) buffer Hits { uint hits[]; };
layout(binding = 1, scalar) writeonly buffer Ao { float ao[]; };

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count) return;
    ao[v] = float(hits[v]) / float(pc.rays);
}
