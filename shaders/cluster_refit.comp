#version 460
#extension GL_GOOGLE_include_directive : require
// Refits the point tree of the t_m pass after positions or AO changed: one thread per node
// scans the node's contiguous range of sources (tree order) for its bounds, its weight
// W = Σ area·(1 − A_o), weighted center and bounding radius. No bottom-up dependencies, so
// one dispatch refits the whole tree (n·depth loads).
#include "common.glsl"
#include "bvh.glsl"

layout(push_constant, scalar) uniform Push {
    uint node_count;
} pc;

struct Cluster {
    vec3 center;
    float weight;   // Σ area·visibility, units²
    float radius;   // every source of the node lies within radius of center
};

layout(binding = 0, scalar) buffer Nodes { BvhNode nodes[]; };
layout(binding = 1, scalar) readonly buffer Counts { uint node_counts[]; };
layout(binding = 2, scalar) readonly buffer Sources { vec4 sources[]; };     // tree order
layout(binding = 3, scalar) readonly buffer Visibility { float visibility[]; }; // tree order
layout(binding = 4, scalar) writeonly buffer Clusters { Cluster clusters[]; };

void main()
{
    uint i = jade_thread_index();
    if (i >= pc.node_count) return;
    uint first = nodes[i].first_and_leaf & ~JADE_LEAF_BIT;
    uint end = first + node_counts[i];
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    float weight = 0.0;
    vec3 moment = vec3(0.0);
    for (uint j = first; j < end; ++j) {
        vec4 s = sources[j];
        float w = s.w * visibility[j];
        lo = min(lo, s.xyz);
        hi = max(hi, s.xyz);
        weight += w;
        moment += w * s.xyz;
    }
    vec3 c = weight > 0.0 ? moment / weight : 0.5 * (lo + hi);
    c = clamp(c, lo, hi);  // rounding must not put the center outside its box
    nodes[i].lo = lo;
    nodes[i].hi = hi;
    clusters[i].center = c;
    clusters[i].weight = weight;
    clusters[i].radius = length(max(hi - c, c - lo));
}
