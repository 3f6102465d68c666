#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// The near field of t_m: the self disk, (1 − A_o(i))·cdf(ρ_i), plus every disk pair of the
// target's near list (bake/near_field.hpp), integrated exactly over the source's disk. Starts
// the partial sums that the far passes (tm_exact, tm_cluster) add to. One thread per tree slot.
// The lists are in slot order; a dispatch covers slots [first_slot, first_slot + slot_count)
// and sees only their window of the list entries, from entry index_base: lists of large meshes
// outgrow one storage-buffer binding (maxStorageBufferRange, 128 MiB on lavapipe).
#include "common.glsl"
#include "tm_common.glsl"

layout(push_constant, scalar) uniform Push {
    uint first_slot;
    uint slot_count;
    uint index_base;  // list entry at the start of the bound window of near_indices
} pc;

layout(binding = 1, scalar) readonly buffer Positions { vec3 positions[]; };  // bake order
layout(binding = 2, scalar) readonly buffer Areas { float areas[]; };
layout(binding = 3, scalar) readonly buffer Ao { float ao[]; };
layout(binding = 4, scalar) readonly buffer NearOffsets { uint near_offsets[]; };  // per slot, + 1
layout(binding = 5, scalar) readonly buffer NearIndices { uint near_indices[]; };
layout(binding = 6, scalar) readonly buffer Order { uint order[]; };  // slot → bake vertex

const float DISK_CAP = 0.6;

#define TM_STATE_BINDING 7
#include "tm_state.glsl"

void main()
{
    uint t = jade_thread_index();
    if (t >= pc.slot_count) return;
    uint k = pc.first_slot + t;
    uint v = order[k];
    Profile prof[3] = load_profiles();
    vec3 x = positions[v];
    vec3 sum = vec3(0.0);
    float own_rho = sqrt(areas[v] / JADE_PI);
    [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) sum[c] = (1.0 - ao[v]) * profile_cdf(prof[c], own_rho);
    for (uint e = near_offsets[k]; e < near_offsets[k + 1u]; ++e) {
        uint j = near_indices[e - pc.index_base];
        float rho = sqrt(areas[j] / JADE_PI);
        vec3 to_source = positions[j] - x;
        float r2 = dot(to_source, to_source);
        float r = sqrt(r2);
        // A disk pair now, by the far passes' own test (tm_common.glsl): the list holds a
        // margin of candidates (bake/near_field.hpp), the others are the far passes' points.
        float weight = r2 < NEAR_RADIUS2_PER_AREA * areas[j] ? 1.0 - ao[j] : 0.0;
        // The disk reaches at most DISK_CAP·r towards the target; the rest of the area stays a
        // point (kDiskCap in bake/disk_integral.hpp): irregular meshes must not count a second
        // self term for stiff profiles.
        float capped = min(rho, DISK_CAP * r);
        float rest = max(areas[j] - JADE_PI * capped * capped, 0.0);
        [[unroll]] for (uint c = 0u; c < CHANNELS; ++c)
            sum[c] += weight * (disk_integral(prof[c], r, capped) + rest * profile_r(prof[c], max(r, 1e-30)));
    }
    save_partial(k, v, sum, vec3(0.0));
}
