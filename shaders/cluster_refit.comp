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
    float reach;    // largest NEAR_FACTOR·ρ_j (disk-pair distance) of the node's sources
    float cov[6];   // Σ w·(p − center)(p − center)ᵀ: xx, yy, zz, xy, xz, yz (units⁴)
};

const float NEAR_FACTOR = 4.0;  // as in tm_common.glsl

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
    float weight = 0.0, max_area = 0.0;
    vec3 moment = vec3(0.0);
    for (uint j = first; j < end; ++j) {
        vec4 s = sources[j];
        float w = s.w * visibility[j];
        lo = min(lo, s.xyz);
        hi = max(hi, s.xyz);
        weight += w;
        moment += w * s.xyz;
        max_area = max(max_area, s.w);
    }
    vec3 c = weight > 0.0 ? moment / weight : 0.5 * (lo + hi);
    c = clamp(c, lo, hi);  // rounding must not put the center outside its box
    // Second pass for the covariance about the centre (no cancellation, unlike Σw·p·pᵀ − W·c·cᵀ).
    float cov[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (uint j = first; j < end; ++j) {
        vec4 s = sources[j];
        float w = s.w * visibility[j];
        vec3 d = s.xyz - c;
        cov[0] += w * d.x * d.x;
        cov[1] += w * d.y * d.y;
        cov[2] += w * d.z * d.z;
        cov[3] += w * d.x * d.y;
        cov[4] += w * d.x * d.z;
        cov[5] += w * d.y * d.z;
    }
    clusters[i].cov = cov;
    nodes[i].lo = lo;
    nodes[i].hi = hi;
    clusters[i].center = c;
    clusters[i].weight = weight;
    clusters[i].radius = length(max(hi - c, c - lo));
    clusters[i].reach = NEAR_FACTOR * sqrt(max_area / JADE_PI);
}
