#version 460
#extension GL_GOOGLE_include_directive : require
// Gathers per-vertex inputs of the t_m pass into tree order: sources (position, area) and
// visibility 1 − A_o.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
} pc;

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Areas { float areas[]; };
layout(binding = 2, scalar) readonly buffer Ao { float ao[]; };
layout(binding = 3, scalar) readonly buffer PointOrder { uint point_order[]; };
layout(binding = 4, scalar) writeonly buffer Sources { vec4 sources[]; };
layout(binding = 5, scalar) writeonly buffer Visibility { float visibility[]; };

void main()
{
    uint k = jade_thread_index();
    if (k >= pc.vertex_count) return;
    uint v = point_order[k];
    sources[k] = vec4(positions[v], areas[v]);
    visibility[k] = 1.0 - ao[v];
}
