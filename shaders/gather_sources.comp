#version 460
#extension GL_GOOGLE_include_directive : require
// Gathers the per-vertex inputs of the far passes into tree order, as the source texels
// described in tm_common.glsl.
#include "common.glsl"
#include "direction.glsl"

#include "bake_interface.h"  // struct GatherPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { GatherPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Areas { float areas[]; };
layout(binding = 2, scalar) readonly buffer Ao { float ao[]; };
layout(binding = 3, scalar) readonly buffer PointOrder { uint point_order[]; };
// The sources' window of the buffer (after the cluster nodes when they share it).
layout(binding = 4, scalar) writeonly buffer Points { vec4 points[]; };
layout(binding = 5, scalar) readonly buffer Normals { vec3 normals[]; };

const float NEAR_FACTOR = JADE_NEAR_FACTOR;  // bake_interface.h

void main()
{
    uint k = jade_thread_index();
    if (k >= pc.vertex_count) return;
    uint v = point_order[k];
    float area = areas[v], visibility = 1.0 - ao[v];
    points[2u * k] = vec4(positions[v], area * visibility);
    points[2u * k + 1u] = vec4(NEAR_FACTOR * NEAR_FACTOR / JADE_PI * area, area, visibility, encode_direction(normals[v]));
}
