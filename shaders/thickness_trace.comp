#version 460
#extension GL_GOOGLE_include_directive : require
// Thickness: one thread per (vertex, ray of the slice traced now). The ray leaves the vertex
// inwards, in the cone about −n (jade/bake.hpp ThicknessSettings), and finds the distance to the
// nearest triangle, either face, capped at max_distance (a miss through an open mesh counts as
// max_distance). The distance, in fixed point (kQuantum steps per max_distance), is added to its
// vertex's sum of the slice: integer sums do not depend on the order of the threads, so a still
// mesh re-bakes bit for bit. thickness_resolve turns the sums into the mean distance.
// The walk is the stackless pre-order walk of ao_trace.comp with a shrinking tmax: a subtree
// whose box lies beyond the nearest hit found so far is skipped.
#include "common.glsl"
#include "rays.glsl"
#include "bvh.glsl"  // ray_hits_box

#include "bake_interface.h"  // struct ThicknessPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { ThicknessPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Normals { vec3 normals[]; };
layout(binding = 2) uniform usamplerBuffer items;  // engine/src/bake/ray_items.hpp
layout(binding = 3, scalar) buffer Sums { uint sums[]; };  // [slice][vertex], fixed point

const float kQuantum = JADE_THICKNESS_QUANTUM;  // bake_interface.h: 2^22 steps per max_distance

// Möller–Trumbore, both faces: the hit distance in (0, tmax], or tmax when there is none.
float nearest_on_triangle(vec3 o, vec3 d, float tmax, vec3 a, vec3 e1, vec3 e2)
{
    vec3 p = cross(d, e2);
    float det = dot(e1, p);
    float inv = 1.0 / det;
    vec3 s = o - a;
    float u = dot(s, p) * inv;
    vec3 q = cross(s, e1);
    float v = dot(d, q) * inv;
    float t = dot(e2, q) * inv;
    bool hit = det != 0.0 && u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < tmax;
    return hit ? t : tmax;
}

float nearest_hit(vec3 o, vec3 d)
{
    vec3 inv_d = 1.0 / d;
    float tmax = pc.max_distance;
    uint i = 0u;
    // One item per iteration, both tests on its texels (as in ao_trace.comp); no early return.
    while (i < pc.item_count) {
        uvec4 t0 = texelFetch(items, int(3u * i));
        uvec4 t1 = texelFetch(items, int(3u * i + 1u));
        uvec4 t2 = texelFetch(items, int(3u * i + 2u));
        vec3 p0 = uintBitsToFloat(t0.xyz), p1 = uintBitsToFloat(t1.xyz), p2 = uintBitsToFloat(t2.xyz);
        bool triangle = t1.w != 0u;
        bool enter = ray_hits_box(o, inv_d, tmax, p0, p1);
        if (triangle) tmax = nearest_on_triangle(o, d, tmax, p0, p1, p2);
        i = (triangle || enter) ? i + 1u : t0.w;
    }
    return tmax;
}

void main()
{
    uint index = jade_thread_index();
    uint rays_in_slice = pc.rays / pc.slices;
    if (index >= pc.vertex_count * rays_in_slice) return;
    uint v = index / rays_in_slice, k = (index % rays_in_slice) * pc.slices + pc.slice;
    vec3 n = normals[v];
    vec3 o = positions[v] - pc.ray_offset * n;
    vec3 d = cone_direction(-n, ray_sample(v, k, pc.rays, pc.seed, true), pc.cos_cone);
    // The origin sits ε inside the surface: the ray's distance from the surface point itself adds
    // ε / cos θ (on a thin slab ε alone would be a percent of the thickness).
    float t = min(nearest_hit(o, d) + pc.ray_offset / max(dot(d, -n), 0.05), pc.max_distance);
    atomicAdd(sums[pc.slice * pc.vertex_count + v], uint(clamp(t / pc.max_distance, 0.0, 1.0) * kQuantum + 0.5));
}
