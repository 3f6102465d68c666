#version 460
#extension GL_GOOGLE_include_directive : require
// Ambient occlusion: one thread per (vertex, ray). A ray that hits a triangle within
// max_distance adds 1 to its vertex's hit count (ao_resolve turns counts into A_o). Any hit
// ends a ray, so the BVH is walked without a stack, in pre-order, following escape pointers.
// One ray per thread also keeps every invocation's loop count far below lavapipe's limit of
// 65,535 loop iterations per invocation (docs/lavapipe.md).
#include "common.glsl"
#include "rays.glsl"
#include "bvh.glsl"

layout(push_constant, scalar) uniform Push {
    uint vertex_count;
    uint rays;
    uint seed;
    uint low_discrepancy;
    float epsilon;       // origin offset along the normal, mesh units
    float max_distance;  // mesh units
    uint node_count;
} pc;

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Normals { vec3 normals[]; };
layout(binding = 2, scalar) readonly buffer Triangles { vec3 triangle_corners[]; }; // 3 per triangle, BVH order
layout(binding = 3, scalar) readonly buffer Nodes { BvhNode nodes[]; };
layout(binding = 4, scalar) readonly buffer Counts { uint node_counts[]; };
layout(binding = 5, scalar) buffer Hits { uint hits[]; };

// Möller–Trumbore, both faces; true when the hit lies in (0, tmax].
bool hits_triangle(vec3 o, vec3 d, float tmax, vec3 a, vec3 b, vec3 c)
{
    vec3 e1 = b - a, e2 = c - a;
    vec3 p = cross(d, e2);
    float det = dot(e1, p);
    float inv = 1.0 / det;
    vec3 s = o - a;
    float u = dot(s, p) * inv;
    vec3 q = cross(s, e1);
    float v = dot(d, q) * inv;
    float t = dot(e2, q) * inv;
    return det != 0.0 && u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t <= tmax;
}

bool occluded(vec3 o, vec3 d)
{
    vec3 inv_d = 1.0 / d;
    uint i = 0u;
    bool hit = false;
    // No early return from inside the loop: lavapipe mis-handles returns in divergent loops.
    while (i < pc.node_count && !hit) {
        BvhNode node = nodes[i];
        bool enter = ray_hits_box(o, inv_d, pc.max_distance, node.lo, node.hi);
        bool leaf = (node.first_and_leaf & JADE_LEAF_BIT) != 0u;
        if (enter && leaf) {
            uint first = node.first_and_leaf & ~JADE_LEAF_BIT;
            uint end = first + node_counts[i];
            for (uint t = first; t < end && !hit; ++t)
                hit = hits_triangle(o, d, pc.max_distance, triangle_corners[3u * t], triangle_corners[3u * t + 1u],
                                    triangle_corners[3u * t + 2u]);
        }
        i = (enter && !leaf) ? i + 1u : node.escape;  // first child, or skip the subtree
    }
    return hit;
}

void main()
{
    uint index = jade_thread_index();
    if (index >= pc.vertex_count * pc.rays) return;
    uint v = index / pc.rays, k = index % pc.rays;
    vec3 n = normals[v];
    vec3 o = positions[v] + pc.epsilon * n;
    vec3 d = ray_direction(n, ray_sample(v, k, pc.rays, pc.seed, pc.low_discrepancy != 0u));
    if (occluded(o, d)) atomicAdd(hits[v], 1u);
}
