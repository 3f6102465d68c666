#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// The near field of t_m: the self disk, (1 − A_o(i))·cdf(ρ_i), plus every disk pair of the
// target's near list (bake/near_field.hpp), integrated exactly over the source's disk. Starts
// the partial sums that the far passes (tm_exact, tm_cluster, grid_gather) add to. One thread
// per tree slot.
// With the grid far field (GRID = 1, bake/grid_field.hpp) the grids sum the smooth part S of
// the profile over every source as a point, this one included, so here each source within
// r_cut adds R − S instead: the disk pairs their disk integral minus S at their centre, the
// point pairs R − S, the target itself its self disk minus S(0).
// The lists are in slot order and hold source slots; a dispatch covers slots [first_slot,
// first_slot + slot_count) and sees only their window of the list entries, from entry
// index_base: lists of large meshes outgrow one texel view (maxTexelBufferElements). Sources are read as texels (gather_sources.comp; tm_common.glsl).
#include "common.glsl"
#include "tm_common.glsl"

#include "bake_interface.h"  // struct NearPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { NearPush pc; };

layout(constant_id = 3) const uint GRID = 0u;

layout(binding = 1) uniform usamplerBuffer sources;  // two texels per source slot
layout(binding = 2, scalar) readonly buffer NearOffsets { uint near_offsets[]; };  // per slot, + 1
layout(binding = 3) uniform usamplerBuffer near_indices;  // source slots, R32UI texels
layout(binding = 4, scalar) readonly buffer NearDisks { uint near_disks[]; };      // per slot: disk candidates first
layout(binding = 5, scalar) readonly buffer Order { uint order[]; };               // slot → bake vertex
// GRID: S(r), then (R − S)(r)·r, per channel at r = k / table_scale (bake/grid_field.hpp).
layout(binding = 6) uniform samplerBuffer smooth_table;

const float DISK_CAP = JADE_DISK_CAP;  // bake_interface.h: the float64 reference's kDiskCap too

#define TM_STATE_BINDING 7
#include "tm_state.glsl"

const int TABLE_SIZE = JADE_GRID_TABLE_SIZE;  // bake_interface.h: S, then (R − S)·r

vec3 table_lookup(float r, int first)
{
    float u = r * pc.table_scale;
    int i = min(int(u), TABLE_SIZE - 2);
    return mix(texelFetch(smooth_table, first + i).xyz, texelFetch(smooth_table, first + i + 1).xyz, clamp(u - float(i), 0.0, 1.0));
}
vec3 smooth_part(float r) { return table_lookup(r, 0); }

vec4 source_texel(uint slot, uint half_) { return uintBitsToFloat(texelFetch(sources, int(pc.source_base + 2u * slot + half_))); }

void main()
{
    uint t = jade_thread_index();
    if (t >= pc.slot_count) return;
    uint k = pc.first_slot + t;
    Profile prof[3] = load_profiles();
    vec4 own = source_texel(k, 0u), own_extra = source_texel(k, 1u);  // (x, weight), (near r², area, 1 − A_o)
    vec3 x = own.xyz;
    vec3 sum = vec3(0.0);
    float own_rho = sqrt(own_extra.y / JADE_PI);
    [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) sum[c] = own_extra.z * profile_cdf(prof[c], own_rho);
    if (GRID == 1u) sum -= own.w * texelFetch(smooth_table, 0).xyz;
    vec3 normal[3] = vec3[3](vec3(0.0), vec3(0.0), vec3(0.0));
    add_weighted(normal, sum, decode_direction(own_extra.w));
    // The disk candidates first, then (GRID) the point pairs within r_cut: lavapipe runs both
    // sides of a branch, so the disk integral stays out of the second, longer loop.
    uint split = near_offsets[k] + near_disks[k];
    for (uint e = near_offsets[k]; e < split; ++e) {
        uint j = texelFetch(near_indices, int(e - pc.index_base)).x;
        vec4 s = source_texel(j, 0u), extra = source_texel(j, 1u);
        float area = extra.y;
        float rho = sqrt(area / JADE_PI);
        vec3 to_source = s.xyz - x;
        float r2 = dot(to_source, to_source);
        float r = sqrt(r2);
        // A disk pair now, by the far passes' own test (tm_common.glsl): the list holds a
        // margin of candidates (bake/near_field.hpp), the others are the far passes' points.
        bool disk = r2 < extra.x;
        float weight = disk ? extra.z : 0.0;
        // The disk reaches at most DISK_CAP·r towards the target; the rest of the area stays a
        // point (as kDiskCap in bake/disk_integral.hpp): irregular meshes must not count a second
        // self term for stiff profiles.
        // That rest lies around the source, at the RMS distance of its annulus from the target,
        // so a source (nearly) on top of the target stays finite (rest_distance in
        // bake/disk_integral.hpp).
        float capped = min(rho, DISK_CAP * r);
        float rest = max(area - JADE_PI * capped * capped, 0.0);
        float rest_r = sqrt(r2 + 0.5 * (area / JADE_PI + capped * capped));
        vec3 point = vec3(0.0), pair = vec3(0.0);
        [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) {
            point[c] = profile_r(prof[c], max(r, 1e-30));
            float disk_part = capped > 0.0 ? disk_integral(prof[c], r, capped) : 0.0;
            pair[c] = weight * (disk_part + rest * profile_r(prof[c], rest_r));
        }
        if (GRID == 1u) {
            float near_weight = disk || r2 < pc.cut2 ? s.w : 0.0;
            pair += near_weight * ((disk ? vec3(0.0) : point) - smooth_part(r));
        }
        sum += pair;
        add_weighted(normal, pair, decode_direction(extra.w));
    }
    if (GRID == 1u) {
        uint end = near_offsets[k + 1u];
        for (uint e = split; e < end; ++e) {
            uint j = texelFetch(near_indices, int(e - pc.index_base)).x;
            vec4 s = source_texel(j, 0u);
            vec3 to_source = s.xyz - x;
            float r2 = dot(to_source, to_source);
            float r = sqrt(r2);
            vec3 pair = (r2 < pc.cut2 ? s.w / max(r, 1e-30) : 0.0) * table_lookup(r, TABLE_SIZE);
            sum += pair;
            add_weighted(normal, pair, decode_direction(source_texel(j, 1u).w));
        }
    }
    save_partial(k, order[k], sum, vec3(0.0));
    start_normal_sums(order[k], normal);
}
