#version 460
#extension GL_GOOGLE_include_directive : require
// Amortised AO (jade/bake.hpp, Amortisation::retrace_changed): a vertex whose fresh slice hits a
// different number of times than the same rays did when that slice was last traced has moved
// against its surroundings, and its other slices are up to slices − 1 frames stale. Its other
// slices' counts are cleared and it is listed, for ao_retrace.comp to trace them again this
// frame. A vertex that did not move against anything (a still mesh, a rigidly moving part) is
// not listed: its counts are exact. One thread per vertex; the list's order varies from run to
// run, the counts it leads to do not.
#include "common.glsl"

layout(constant_id = 1) const uint RETRACE_GROUP = 64;  // ao_retrace.comp's threads per group

#include "bake_interface.h"  // struct AoPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { AoPush pc; };

layout(binding = 0, scalar) buffer Hits { uint hits[]; };  // [slice][vertex]
layout(binding = 1, scalar) readonly buffer Previous { uint previous[]; };  // slice pc.slice before this frame
// ao_retrace.comp's indirect dispatch (groups.z is 1, the rest 0 before this pass), then the list.
layout(binding = 2, scalar) buffer Changed { uvec3 groups; uint changed_count; uint changed[]; };

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count || hits[pc.slice * pc.vertex_count + v] == previous[v]) return;
    for (uint s = 0u; s < pc.slices; ++s)
        if (s != pc.slice) hits[s * pc.vertex_count + v] = 0u;
    uint at = atomicAdd(changed_count, 1u);
    changed[at] = v;
    // Groups for the rays of the listed vertices so far, spread over y past 65,535 as
    // gpu::Kernel::dispatch does: both grow with the count, so the largest is the last.
    uint threads = (at + 1u) * (pc.rays / pc.slices) * (pc.slices - 1u);
    uint needed = (threads + RETRACE_GROUP - 1u) / RETRACE_GROUP;
    atomicMax(groups.x, min(needed, 65535u));
    atomicMax(groups.y, (needed + 65534u) / 65535u);
}
