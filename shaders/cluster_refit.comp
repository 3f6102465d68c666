#version 460
#extension GL_GOOGLE_include_directive : require
// Refits the point tree of the t_m pass after positions or AO changed, bottom-up: one dispatch
// per tree level, deepest first. A leaf scans its (at most 8) sources; an inner node combines
// its two children. Per node: bounds, weight W = Σ area·(1 − A_o), weighted centre c, bounding
// radius about c, covariance Σ w·(p − c)(p − c)ᵀ (parallel-axis sum of the children's), reach.
//
// Output: four RGBA32UI texels per node, fetched by tm_cluster.comp (floats as bit patterns),
// in the buffer that holds the sources after the nodes:
//   4i:     centre.xyz, W
//   4i + 1: radius, reach (largest NEAR_FACTOR·ρ_j of its sources), escape, range (bvh.glsl)
//   4i + 2: covariance xx, yy, zz, xy      units⁴
//   4i + 3: covariance xz, yz; |Σ w·n|, the direction of Σ w·n (direction.glsl): the
//           normal monopole of the scattering normal (tm_state.glsl)
#include "common.glsl"
#include "bvh.glsl"
#include "direction.glsl"

#include "bake_interface.h"  // struct RefitPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { RefitPush pc; };

// The tree's nodes (bvh_interface.h): the shape is fixed, the bounds are refitted here.
layout(binding = 0, scalar) buffer Topology { BvhNode topology[]; };
layout(binding = 1, scalar) readonly buffer Levels { uint level_nodes[]; };
// The node and the source windows of one buffer (bound separately: each fits a binding).
layout(binding = 2, scalar) buffer Tree { uvec4 tree[]; };
layout(binding = 3, scalar) readonly buffer Points { uvec4 points[]; };  // tm_common.glsl

const float NEAR_FACTOR = JADE_NEAR_FACTOR;  // bake_interface.h

struct Cluster {
    vec3 c;
    float w;
    float reach;
    float cov[6];
    vec3 normal;  // Σ w·n
};

Cluster read_cluster(uint i)
{
    vec4 a = uintBitsToFloat(tree[4u * i]);
    float reach = uintBitsToFloat(tree[4u * i + 1u].y);
    vec4 b = uintBitsToFloat(tree[4u * i + 2u]);
    vec4 d = uintBitsToFloat(tree[4u * i + 3u]);
    return Cluster(a.xyz, a.w, reach, float[6](b.x, b.y, b.z, b.w, d.x, d.y), d.z * decode_direction(d.w));
}

// Adds a point mass or a child cluster of weight w at p (covariance `cov` about p) to the
// covariance about c.
void add_covariance(inout float cov[6], float w, vec3 p, vec3 c, float own[6])
{
    vec3 d = p - c;
    cov[0] += own[0] + w * d.x * d.x;
    cov[1] += own[1] + w * d.y * d.y;
    cov[2] += own[2] + w * d.z * d.z;
    cov[3] += own[3] + w * d.x * d.y;
    cov[4] += own[4] + w * d.x * d.z;
    cov[5] += own[5] + w * d.y * d.z;
}

void main()
{
    uint e = jade_thread_index();
    if (e >= pc.count) return;
    uint i = level_nodes[pc.first + e];
    uint range = topology[i].range;
    const float none[6] = float[6](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38), c;
    float weight = 0.0, reach = 0.0;
    float cov[6] = none;
    vec3 normal = vec3(0.0);
    if (jade_range_is_leaf(range)) {
        uint first = jade_range_first(range), count = jade_range_count(range);
        vec3 moment = vec3(0.0);
        vec4 p[8];
        [[unroll]] for (uint k = 0u; k < 8u; ++k) {
            uint j = 2u * (first + min(k, count - 1u));
            p[k] = uintBitsToFloat(points[j]);
            vec4 extra = uintBitsToFloat(points[j + 1u]);
            float area = extra.y;
            if (k >= count) p[k].w = 0.0;
            normal += p[k].w * decode_direction(extra.w);
            lo = k < count ? min(lo, p[k].xyz) : lo;
            hi = k < count ? max(hi, p[k].xyz) : hi;
            weight += p[k].w;
            moment += p[k].w * p[k].xyz;
            reach = k < count ? max(reach, NEAR_FACTOR * sqrt(area / JADE_PI)) : reach;
        }
        c = weight > 0.0 ? moment / weight : 0.5 * (lo + hi);
        c = clamp(c, lo, hi);  // rounding must not put the centre outside its box
        [[unroll]] for (uint k = 0u; k < 8u; ++k) add_covariance(cov, p[k].w, p[k].xyz, c, none);
    } else {
        uint a = i + 1u, b = topology[a].escape;
        Cluster ca = read_cluster(a), cb = read_cluster(b);
        lo = min(topology[a].lo, topology[b].lo);
        hi = max(topology[a].hi, topology[b].hi);
        weight = ca.w + cb.w;
        c = weight > 0.0 ? (ca.w * ca.c + cb.w * cb.c) / weight : 0.5 * (lo + hi);
        c = clamp(c, lo, hi);
        add_covariance(cov, ca.w, ca.c, c, ca.cov);
        add_covariance(cov, cb.w, cb.c, c, cb.cov);
        reach = max(ca.reach, cb.reach);
        normal = ca.normal + cb.normal;
    }
    topology[i].lo = lo;
    topology[i].hi = hi;
    float radius = length(max(hi - c, c - lo));
    tree[4u * i] = floatBitsToUint(vec4(c, weight));
    tree[4u * i + 1u] = uvec4(floatBitsToUint(radius), floatBitsToUint(reach), topology[i].escape, range);
    tree[4u * i + 2u] = floatBitsToUint(vec4(cov[0], cov[1], cov[2], cov[3]));
    tree[4u * i + 3u] = floatBitsToUint(vec4(cov[4], cov[5], length(normal), encode_direction(normal)));
}
