#version 460
#extension GL_GOOGLE_include_directive : require
// The far field of t_m by brute force over all vertex pairs: the GPU ground truth, O(n²). One
// dispatch adds the point pairs of sources [source_begin, source_end) to every target's saved
// partial sum (tm_state.glsl), which the near pass (tm_near.comp) started.
//
// Every thread walks the sources in the same order, so each load is the same address across a
// subgroup (a broadcast). Sources are summed plainly in blocks of 64 and the blocks with
// compensated summation: float32 stays near 1e-6 relative for 10^6 sources, where a plain
// running sum drifts to ~1e-4.
#include "common.glsl"
#include "tm_common.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
    uint source_begin;
    uint source_end;
} pc;

layout(binding = 1, scalar) readonly buffer Sources { vec4 sources[]; };        // xyz position, w area
layout(binding = 2, scalar) readonly buffer Visibility { float visibility[]; }; // 1 − A_o

#define TM_STATE_BINDING 3
#include "tm_state.glsl"

const uint BLOCK = 64u;

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.vertex_count) return;
    vec3 x = sources[i].xyz;
    Profile prof[3] = load_profiles();
    vec3 sum = partial_sum[i], comp = partial_comp[i];
    vec3 block = vec3(0.0);
    for (uint j = pc.source_begin; j < pc.source_end; ++j) {
        float vis = visibility[j];
        vec4 s = sources[j];
        float r = distance(x, s.xyz);
        [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) block[c] += vis * far_pair(prof[c], r, s.w);
        if ((j - pc.source_begin) % BLOCK == BLOCK - 1u) {
            compensated_add(sum, comp, block);
            block = vec3(0.0);
        }
    }
    compensated_add(sum, comp, block);
    save_partial(i, i, sum, comp);
}
