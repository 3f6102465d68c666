#version 460
#extension GL_GOOGLE_include_directive : require
// t_m with an error-controlled far field (Barnes–Hut over the point tree).
//
// A node of total weight W, center c and radius s, seen from x at r = |x − c| > s, is
// replaced by W·R(r) when W·(R(r − s) − R(r + s)) ≤ W·ε·τ/W_total for every channel. Since R
// decreases, W·(R(r−s) − R(r+s)) bounds that node's error, and the budgets ε·τ·W/W_total of
// all accepted nodes add up to at most ε·τ: the far field's absolute error is ≤ ε·τ.
// τ is per vertex: 1 (absolute error ε) or an estimate of t_m itself (relative error ε).
// Everything not accepted down to the leaves is summed exactly with the vertex-disk rule.
#include "common.glsl"
#include "tm_common.glsl"
#include "bvh.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
    uint node_count;
    float epsilon;           // the accuracy knob
} pc;

struct Cluster {
    vec3 center;
    float weight;
    float radius;
};

layout(binding = 1, scalar) readonly buffer Sources { vec4 sources[]; };        // tree order
layout(binding = 2, scalar) readonly buffer Visibility { float visibility[]; }; // tree order
layout(binding = 3, scalar) readonly buffer Nodes { BvhNode nodes[]; };
layout(binding = 4, scalar) readonly buffer Counts { uint node_counts[]; };
layout(binding = 5, scalar) readonly buffer Clusters { Cluster clusters[]; };
layout(binding = 6, scalar) readonly buffer Order { uint order[]; };       // tree → bake vertex
layout(binding = 7, scalar) readonly buffer Tau { vec3 tau[]; };            // per bake vertex
layout(binding = 8, scalar) writeonly buffer Tm { vec3 tm[]; };             // per bake vertex

void main()
{
    uint k = jade_thread_index();
    if (k >= pc.vertex_count) return;
    uint vertex = order[k];
    vec3 x = sources[k].xyz;
    float total_weight = clusters[0].weight;  // the root holds W_total
    if (total_weight == 0.0) {                 // everything occluded
        tm[vertex] = vec3(0.0);
        return;
    }
    vec3 budget = pc.epsilon * tau[vertex] / total_weight;
    vec3 sum = vec3(0.0), comp = vec3(0.0);

    uint i = 0u;
    while (i < pc.node_count) {
        Cluster cl = clusters[i];
        if (cl.weight == 0.0) {  // fully occluded or empty: contributes nothing
            i = nodes[i].escape;
            continue;
        }
        uint first_and_leaf = nodes[i].first_and_leaf;
        if ((first_and_leaf & JADE_LEAF_BIT) == 0u) {
            float r = distance(x, cl.center);
            bool accept = r > cl.radius;
            vec3 far = vec3(0.0);
            for (uint c = 0u; c < CHANNELS && accept; ++c) {
                float spread = profile_r(profiles[c], r - cl.radius) - profile_r(profiles[c], r + cl.radius);
                accept = spread <= budget[c];
                far[c] = cl.weight * profile_r(profiles[c], r);
            }
            if (accept) {
                compensated_add(sum, comp, far);
                i = nodes[i].escape;
            } else {
                i += 1u;
            }
            continue;
        }
        uint first = first_and_leaf & ~JADE_LEAF_BIT;
        uint end = first + node_counts[i];
        vec3 leaf = vec3(0.0);
        for (uint j = first; j < end; ++j) {
            float vis = visibility[j];
            if (vis == 0.0) continue;
            vec4 s = sources[j];
            float rho = sqrt(s.w / JADE_PI);
            float r = distance(x, s.xyz);
            for (uint c = 0u; c < CHANNELS; ++c)
                leaf[c] += vis * (j == k ? self_kernel(profiles[c], rho) : pair_kernel(profiles[c], r, s.w, rho));
        }
        compensated_add(sum, comp, leaf);
        i = nodes[i].escape;
    }
    vec3 t = sum + comp;
    tm[vertex] = CHANNELS == 1u ? vec3(t.x) : t;
}
