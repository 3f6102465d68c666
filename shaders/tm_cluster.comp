#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
// t_m with an error-controlled far field (Barnes–Hut over the point tree).
//
// A node of total weight W, centroid c, radius s and weighted covariance C is replaced, seen
// from x at distance r = |c − x| along u, by its monopole plus quadrupole term:
//   W·R(r) + ½·[(R'' − R'/r)·uᵀCu + (R'/r)·tr C]        (the dipole term is 0 about the centroid)
// with R', R'' analytic (Burley, Gaussians; finite differences for the dipole). What remains is
// third order in s/r and s/ℓ, ℓ = R/|R'| the length over which the profile changes at r. A
// node is accepted when s ≤ θ·min(r, ℓ) for every channel (θ = the push constant `theta`,
// BakeSettings::tm_opening_ratio): the classic Barnes–Hut opening angle, tightened by the profile's
// own length scale - or when the node is faint (its nearest point adds less than θ³/1000 of
// its share of an open plane's t_m). The error against θ is measured, not assumed.
// The lanes of a subgroup hold neighbouring targets (tree order) and walk the tree together: a
// node is accepted only when every lane accepts it (subgroupAll), so control flow never
// diverges - each loop iteration costs one node or one leaf for the whole subgroup.
// Everything not accepted down to the leaves is summed as point pairs; the disk pairs and the
// self disk come from the near pass (tm_near.comp), which started the partial sums. A node is
// never accepted while it could hold a disk pair (r − s below its largest reach 4ρ_j).
//
// Lavapipe (docs/lavapipe.md): a memory load is a loop over the lanes and both sides of every
// branch run, so each iteration makes one texel fetch per lane and shares the results across
// the subgroup (8 lanes at least), and one evaluation serves nodes and sources alike.
#include "common.glsl"
#include "tm_common.glsl"
#include "bvh.glsl"

#include "bake_interface.h"  // struct ClusterPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { ClusterPush pc; };

// Nodes (cluster_refit.comp: 4 texels each), then the sources in tree order (tm_common.glsl:
// 2 texels each), as RGBA32UI.
layout(binding = 1) uniform usamplerBuffer tree;
layout(binding = 2, scalar) readonly buffer Order { uint order[]; };  // tree → bake vertex
// Per tree slot: the node to resume from, and the cursor over an opened leaf's sources.
layout(binding = 3, scalar) buffer Resume { uvec3 resume[]; };        // zero at start

#define TM_STATE_BINDING 4
#include "tm_state.glsl"

void main()
{
    // Lanes past the end walk along with a copy of the last target (subgroup operations need
    // every lane) and write nothing.
    uint k_lane = pc.slot_begin + jade_thread_index();
    bool in_range = k_lane < pc.slot_end;
    uint k = min(k_lane, pc.slot_end - 1u);
    uint lane = gl_SubgroupInvocationID & 7u;
    uvec3 state = subgroupBroadcastFirst(resume[k]);
    uint i = state.x, j = state.y, j_end = state.z;  // node; source cursor [j, j_end)
    float total_weight = uintBitsToFloat(texelFetch(tree, 0).w);  // the root holds W_total
    if ((i >= pc.node_count && j >= j_end) || total_weight == 0.0) return;  // done (uniform)
    uint first_point = pc.first_point;
    uint vertex = order[k];
    vec3 x = uintBitsToFloat(texelFetch(tree, int(first_point + 2u * k)).xyz);
    vec3 sum = partial_sum[k], comp = partial_comp[k];
    vec3 normal[3] = vec3[3](vec3(0.0), vec3(0.0), vec3(0.0));
    Profile prof[3] = load_profiles();

    // One loop iteration is one node, or one source of an opened leaf (a cluster of radius 0):
    // lavapipe runs every instruction of the loop body on every iteration, so the body is one
    // evaluation that serves both, and no branch holds arithmetic of its own.
    uint work = 0u;
    while ((i < pc.node_count || j < j_end) && work < pc.work_budget) {
        bool in_leaf = j < j_end;  // uniform
        // One fetch per lane: lanes 0..3 the node's texels, lanes 4..5 the source's.
        uint node_texel = 4u * min(i, pc.node_count - 1u) + (lane & 3u);
        uint source_texel = first_point + 2u * min(j, pc.vertex_count - 1u) + (lane & 1u);
        uvec4 mine = texelFetch(tree, int(lane < 4u ? node_texel : source_texel));
        vec4 node_cw = uintBitsToFloat(subgroupBroadcast(mine, 0u));
        uvec4 shape = subgroupBroadcast(mine, 1u);
        vec4 cov_a = uintBitsToFloat(subgroupBroadcast(mine, 2u));
        vec4 node_d = uintBitsToFloat(subgroupBroadcast(mine, 3u));
        vec2 cov_b = node_d.xy;
        vec4 source_pw = uintBitsToFloat(subgroupBroadcast(mine, 4u));
        vec4 source_extra = uintBitsToFloat(subgroupBroadcast(mine, 5u));
        float source_near_r2 = source_extra.x;
        work += 1u;
        if (in_leaf) {
            node_cw = source_pw;
            cov_a = vec4(0.0);
            cov_b = vec2(0.0);
        }
        float weight = node_cw.w;
        float s = in_leaf ? 0.0 : uintBitsToFloat(shape.x);
        float reach = uintBitsToFloat(shape.y);
        uint escape = shape.z, range = shape.w;

        vec3 to_node = node_cw.xyz - x;
        float r = length(to_node);
        vec3 u = to_node / max(r, 1e-30);
        float cuu = u.x * u.x * cov_a.x + u.y * u.y * cov_a.y + u.z * u.z * cov_a.z +
                    2.0 * (u.x * u.y * cov_a.w + u.x * u.z * cov_b.x + u.y * u.z * cov_b.y);
        float trace = cov_a.x + cov_a.y + cov_a.z;
        float r_safe = max(r, 1e-30);
        bool accept = r - s >= reach;
        vec3 far = vec3(0.0), point = vec3(0.0);
        [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) {
            ProfileDerivatives at = profile_derivatives(prof[c], r_safe);
            float second, tangential, decay_length;
            if (at.has_derivatives) {
                second = at.r2;
                tangential = at.r1 / r_safe;
                decay_length = at.r0 / max(abs(at.r1), 1e-30);
            } else {
                // Dipole: finite differences over the node.
                float h = max(s, 1e-30);
                float inner = profile_r(prof[c], max(r - h, 1e-30)), outer = profile_r(prof[c], r + h);
                second = (inner - 2.0 * at.r0 + outer) / (h * h);
                tangential = (outer - inner) / (2.0 * h * r_safe);
                decay_length = 2.0 * h * at.r0 / max(inner - outer, 1e-30);
            }
            // Opening criterion: the node is small against both its distance and the length
            // over which R changes there (the quadrupole's remainder is O((s/r)³, (s/ℓ)³)), or
            // it is faint: even its nearest point adds less than θ³/1000 of its share of an
            // open plane's t_m = 1, R(r − s)·A_total ≤ θ³/1000, a distance precomputed per
            // channel (Profile.faint_radius, bake/gpu_profile.hpp).
            bool is_faint = r - s >= prof[c].faint_radius;
            accept = accept && (s <= pc.theta * min(r, decay_length) || is_faint);
            // (A point - a source, or a node of radius 0 - has no quadrupole; the dipole's finite
            // differences would divide by zero.)
            float quadrupole = s > 0.0 ? 0.5 * ((second - tangential) * cuu + tangential * trace) : 0.0;
            far[c] = weight * at.r0 + quadrupole;
            point[c] = at.r0;
        }
        if (in_leaf) {
            // A source within its near radius is the near pass's, and the target is not its own source.
            bool counts = r * r >= source_near_r2 && r > 0.0;
            compensated_add(sum, comp, counts ? far : vec3(0.0));
            add_weighted(normal, counts ? far : vec3(0.0), decode_direction(source_extra.w));
            j += 1u;
        } else {
            accept = subgroupAll(accept) && weight > 0.0;  // uniform: the subgroup walks as one
            if (accept) compensated_add(sum, comp, far);
            // The node's normal sum Σ w·n as a monopole (cluster_refit.comp: its length, its direction).
            if (accept) add_weighted(normal, point * node_d.z, decode_direction(node_d.w));
            bool open_leaf = !accept && weight > 0.0 && jade_range_is_leaf(range);
            if (open_leaf) {
                j = jade_range_first(range);
                j_end = j + jade_range_count(range);
            }
            // Accepted, empty or an opened leaf: skip the subtree; else descend.
            i = (accept || weight == 0.0 || open_leaf) ? escape : i + 1u;
        }
    }
    if (!in_range) return;
    resume[k] = uvec3(i, j, j_end);
    save_partial(k, vertex, sum, comp);
    add_normal_sums(vertex, normal);
}
