#version 460
#extension GL_GOOGLE_include_directive : require
// The deforming mesh's current bounds, for the grids of the smooth part of t_m to follow it
// (grid_field.hpp: a DynamicBake's grids are cubes placed each frame around the mesh). Floats as
// order-preserving integers, so min and max are integer atomics. One thread per vertex.
#include "common.glsl"
#include "grid.glsl"

#include "bake_interface.h"  // struct GatherPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { GatherPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) buffer Bounds { uint bounds[6]; };  // ordered min xyz, then max xyz

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count) return;
    vec3 x = positions[v];
    [[unroll]] for (int a = 0; a < 3; ++a) {
        atomicMin(bounds[a], ordered_bits(x[a]));
        atomicMax(bounds[3 + a], ordered_bits(x[a]));
    }
}
