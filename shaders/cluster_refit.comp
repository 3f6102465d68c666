#version 460
#extension GL_GOOGLE_include_directive : require
// Refits the point tree of the t_m pass after positions or AO changed: one thread per node
// scans the node's contiguous range of sources (tree order) for its weight
// W = Σ area·(1 − A_o), weighted centre, bounding radius and covariance. No bottom-up
// dependencies, so one dispatch refits the whole tree (n·depth loads).
//
// Output: four RGBA32UI texels per node, fetched by tm_cluster.comp (floats as bit patterns),
// in the buffer that holds the sources after the nodes:
//   4i:     centre.xyz, W
//   4i + 1: radius, reach (largest NEAR_FACTOR·ρ_j of its sources), escape, range (bvh.glsl)
//   4i + 2: covariance xx, yy, zz, xy      Σ w·(p − c)(p − c)ᵀ, units⁴
//   4i + 3: covariance xz, yz, 0, 0
#include "common.glsl"
#include "bvh.glsl"

layout(push_constant, scalar) uniform Push {
    uint node_count;
    uint first_point;  // texel of source 0 (tm_common.glsl), after the nodes in the same buffer
} pc;

struct TopologyNode {  // bake::BvhNode: the tree's shape, fixed while the mesh deforms
    vec3 lo;
    uint escape;
    vec3 hi;
    uint range;
};

layout(binding = 0, scalar) readonly buffer Topology { TopologyNode topology[]; };
layout(binding = 1, scalar) readonly buffer Counts { uint node_counts[]; };
layout(binding = 2, scalar) readonly buffer Points { vec4 points[]; };  // the tree buffer: sources from first_point
layout(binding = 3, scalar) writeonly buffer Tree { uvec4 tree[]; };   // the same buffer: nodes

const float NEAR_FACTOR = 4.0;  // as in tm_common.glsl

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.node_count) return;
    uint first = jade_range_first(topology[i].range);
    uint end = first + node_counts[i];
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    float weight = 0.0, max_area = 0.0;
    vec3 moment = vec3(0.0);
    for (uint j = first; j < end; ++j) {
        vec4 s = points[pc.first_point + 2u * j];
        lo = min(lo, s.xyz);
        hi = max(hi, s.xyz);
        weight += s.w;
        moment += s.w * s.xyz;
        max_area = max(max_area, points[pc.first_point + 2u * j + 1u].y);
    }
    vec3 c = weight > 0.0 ? moment / weight : 0.5 * (lo + hi);
    c = clamp(c, lo, hi);  // rounding must not put the center outside its box
    // Second pass for the covariance about the centre (no cancellation, unlike Σw·p·pᵀ − W·c·cᵀ).
    float cov[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (uint j = first; j < end; ++j) {
        vec4 s = points[pc.first_point + 2u * j];
        vec3 d = s.xyz - c;
        cov[0] += s.w * d.x * d.x;
        cov[1] += s.w * d.y * d.y;
        cov[2] += s.w * d.z * d.z;
        cov[3] += s.w * d.x * d.y;
        cov[4] += s.w * d.x * d.z;
        cov[5] += s.w * d.y * d.z;
    }
    float radius = length(max(hi - c, c - lo));
    float reach = NEAR_FACTOR * sqrt(max_area / JADE_PI);
    tree[4u * i] = floatBitsToUint(vec4(c, weight));
    tree[4u * i + 1u] = uvec4(floatBitsToUint(radius), floatBitsToUint(reach), topology[i].escape, topology[i].range);
    tree[4u * i + 2u] = floatBitsToUint(vec4(cov[0], cov[1], cov[2], cov[3]));
    tree[4u * i + 3u] = floatBitsToUint(vec4(cov[4], cov[5], 0.0, 0.0));
}
