// tm_exact_body.glsl - the all-pairs t_m pass, included by tm_exact.comp (compensated float32
// sums) and tm_exact_f64.comp (float64 sums).
// The far field of t_m by brute force over all vertex pairs: the GPU ground truth, O(n²). One
// dispatch adds the point pairs of sources [source_begin, source_end) to every target's saved
// partial sum (tm_state.glsl), which the near pass (tm_near.comp) started.
//
// Sources are fetched eight at a time, one per lane, and shared across the subgroup
// (far_group in tm_common.glsl). They are summed plainly in blocks of 64 and the blocks with
// compensated summation: float32 stays near 1e-6 relative for 10^6 sources, where a plain
// running sum drifts to ~1e-4. With JADE_FLOAT64_SUMS defined (tm_exact_f64.comp, for
// BakeSettings::tm_float64_sums) the blocks go into a float64 sum instead, saved between
// dispatches as its float32 head and tail in the partial-sum buffers.
#include "common.glsl"
#include "tm_common.glsl"

#include "bake_interface.h"  // struct ExactPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { ExactPush pc; };

layout(binding = 1) uniform samplerBuffer points;  // tm_common.glsl, bake order

#define TM_STATE_BINDING 2
#include "tm_state.glsl"

void main()
{
    // Lanes past the end compute along (the subgroup shares its fetches) and write nothing.
    uint i_lane = jade_thread_index();
    uint i = min(i_lane, pc.vertex_count - 1u);
    uint lane = gl_SubgroupInvocationID;
    vec3 x = texelFetch(points, int(2u * i)).xyz;
    Profile prof[3] = load_profiles();
    vec3 sum = partial_sum[i], comp = partial_comp[i];
#ifdef JADE_FLOAT64_SUMS
    dvec3 total = dvec3(sum) + dvec3(comp);
#endif
    vec3 block = vec3(0.0);
    vec3 normal[3] = vec3[3](vec3(0.0), vec3(0.0), vec3(0.0));
    for (uint g = pc.source_begin; g < pc.source_end; g += 8u) {
        uint j = min(g + (lane & 7u), pc.source_end - 1u);
        vec4 pw = texelFetch(points, int(2u * j));
        vec4 extra = texelFetch(points, int(2u * j + 1u));
        block += far_group(prof, x, pw, extra, min(pc.source_end - g, 8u), normal);
        if ((g - pc.source_begin) % 64u == 56u) {
#ifdef JADE_FLOAT64_SUMS
            total += dvec3(block);
#else
            compensated_add(sum, comp, block);
#endif
            block = vec3(0.0);
        }
    }
#ifdef JADE_FLOAT64_SUMS
    total += dvec3(block);
    sum = vec3(total);
    comp = vec3(total - dvec3(sum));
#else
    compensated_add(sum, comp, block);
#endif
    if (i_lane < pc.vertex_count) {
        save_partial(i, i, sum, comp);
        add_normal_sums(i, normal);
    }
}
