#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require
// t_m with an error-controlled far field (Barnes–Hut over the point tree).
//
// A node of total weight W, centroid c, radius s and weighted covariance C is replaced, seen
// from x at distance r = |c − x| along u, by its monopole plus quadrupole term:
//   W·R(r) + ½·[(R'' − R'/r)·uᵀCu + (R'/r)·tr C]        (the dipole term is 0 about the centroid)
// with R', R'' analytic (Burley, Gaussians; finite differences for the dipole). What remains is
// third order in s/r and s/ℓ, ℓ = R/|R'| the length over which the profile changes at r. A
// node is accepted when s ≤ θ·min(r, ℓ) for every channel (θ = the push constant `epsilon`,
// BakeSettings::tm_epsilon): the classic Barnes–Hut opening angle, tightened by the profile's
// own length scale - or when the node is faint (its nearest point adds less than θ³/1000 of
// its share of an open plane's t_m). The error against θ is measured, not assumed.
// The lanes of a subgroup hold neighbouring targets (tree order) and walk the tree together: a
// node is accepted only when every lane accepts it (subgroupAll), so control flow never
// diverges - each loop iteration costs one node or one leaf for the whole subgroup.
// Everything not accepted down to the leaves is summed as point pairs; the disk pairs and the
// self disk come from the near pass (tm_near.comp), which started the partial sums. A node is
// never accepted while it could hold a disk pair (r − s below its largest reach 4ρ_j).
#include "common.glsl"
#include "tm_common.glsl"
#include "bvh.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
    uint node_count;
    float epsilon;    // θ, the opening ratio
    uint work_budget; // node visits + leaf sources per dispatch (lavapipe's loop limit)
} pc;

struct Cluster {
    vec3 center;
    float weight;
    float radius;
    float reach;  // largest NEAR_FACTOR·ρ_j of the node's sources
    float cov[6]; // Σ w·(p − center)(p − center)ᵀ: xx, yy, zz, xy, xz, yz
};

layout(binding = 1, scalar) readonly buffer Sources { vec4 sources[]; };        // tree order
layout(binding = 2, scalar) readonly buffer Visibility { float visibility[]; }; // tree order
layout(binding = 3, scalar) readonly buffer Nodes { BvhNode nodes[]; };
layout(binding = 4, scalar) readonly buffer Counts { uint node_counts[]; };
layout(binding = 5, scalar) readonly buffer Clusters { Cluster clusters[]; };
layout(binding = 6, scalar) readonly buffer Order { uint order[]; };        // tree → bake vertex
layout(binding = 7, scalar) buffer Resume { uint resume_node[]; };          // per tree slot; 0 at start

#define TM_STATE_BINDING 8
#include "tm_state.glsl"

void main()
{
    // Lanes past the end walk along with a copy of the last target (subgroup operations need
    // every lane) and write nothing.
    uint k_lane = jade_thread_index();
    bool in_range = k_lane < pc.vertex_count;
    uint k = min(k_lane, pc.vertex_count - 1u);
    uint i = resume_node[k];
    float total_weight = clusters[0].weight;  // the root holds W_total
    if (i >= pc.node_count || total_weight == 0.0) return;  // done (uniform: the subgroup moves as one)
    uint vertex = order[k];
    vec3 x = sources[k].xyz;
    vec3 sum = partial_sum[k], comp = partial_comp[k];
    Profile prof[3] = load_profiles();

    uint work = 0u;
    while (i < pc.node_count && work < pc.work_budget) {
        i = subgroupBroadcastFirst(i);  // uniform in fact; saying so turns node loads into one load
        Cluster cl = clusters[i];
        uint first_and_leaf = nodes[i].first_and_leaf;
        uint escape = nodes[i].escape;
        work += 1u;
        if (cl.weight == 0.0) {  // fully occluded: contributes nothing
            i = escape;
        } else if ((first_and_leaf & JADE_LEAF_BIT) == 0u) {
            vec3 to_node = cl.center - x;
            float r = length(to_node);
            float s = cl.radius;
            bool accept = r - s >= cl.reach;
            vec3 u = to_node / r;
            float cuu = u.x * u.x * cl.cov[0] + u.y * u.y * cl.cov[1] + u.z * u.z * cl.cov[2] +
                        2.0 * (u.x * u.y * cl.cov[3] + u.x * u.z * cl.cov[4] + u.y * u.z * cl.cov[5]);
            float trace = cl.cov[0] + cl.cov[1] + cl.cov[2];
            vec3 far = vec3(0.0);
            [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) {
                ProfileDerivatives at = profile_derivatives(prof[c], r);
                float second, tangential, decay_length;
                if (at.has_derivatives) {
                    second = at.r2;
                    tangential = at.r1 / r;
                    decay_length = at.r0 / max(abs(at.r1), 1e-30);
                } else {
                    // Dipole: finite differences over the node.
                    float inner = profile_r(prof[c], max(r - s, 1e-30)), outer = profile_r(prof[c], r + s);
                    second = (inner - 2.0 * at.r0 + outer) / (s * s);
                    tangential = (outer - inner) / (2.0 * s * r);
                    decay_length = 2.0 * s * at.r0 / max(inner - outer, 1e-30);
                }
                // Opening criterion: the node is small against both its distance and the length
                // over which R changes there; the quadrupole's remainder is O((s/r)³, (s/ℓ)³).
                // Or the node is faint: even its nearest point contributes less than θ³/1000 of
                // its share of an open plane's t_m = 1 (what far nodes of a narrow channel are).
                bool faint = profile_r(prof[c], max(r - s, 1e-30)) * total_weight <= 1e-3 * pc.epsilon * pc.epsilon * pc.epsilon;
                accept = accept && (s <= pc.epsilon * min(r, decay_length) || faint);
                float quadrupole = 0.5 * ((second - tangential) * cuu + tangential * trace);
                far[c] = cl.weight * at.r0 + quadrupole;
            }
            accept = subgroupAll(accept);
            if (accept) compensated_add(sum, comp, far);
            i = accept ? escape : i + 1u;
        } else {
            uint begin = first_and_leaf & ~JADE_LEAF_BIT;
            uint end = begin + node_counts[i];
            vec3 leaf = vec3(0.0);
            for (uint j = begin; j < end; ++j) {
                float vis = visibility[j];
                vec4 s = sources[j];
                float r = distance(x, s.xyz);
                [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) leaf[c] += vis * far_pair(prof[c], r, s.w);
            }
            work += end - begin;
            compensated_add(sum, comp, leaf);
            i = escape;
        }
    }
    if (!in_range) return;
    resume_node[k] = i;
    save_partial(k, vertex, sum, comp);
}
