// ao_trace_body.glsl - ao_trace.comp and ao_retrace.comp.
// Ambient occlusion: one thread per (vertex, ray). A ray that hits a triangle within
// max_distance adds 1 to its vertex's hit count of its slice (ao_resolve sums the slices and
// turns counts into A_o). Slices interleave the ray set: ray k of `rays` belongs to slice
// k mod `slices`, so every slice is itself a stratified subset (an amortised re-bake traces one
// slice a frame, jade/bake.hpp Amortisation; a full bake has one slice).
//   ao_trace.comp:   every vertex's rays of slice `slice`;
//   ao_retrace.comp (JADE_AO_RETRACE): the rays of every other slice, for the vertices that
//                    ao_changed.comp listed (an indirect dispatch).
// Any hit ends a ray, so the BVH is walked without a stack, in pre-order, following escape
// pointers. One ray per thread also keeps every invocation's loop count far below lavapipe's
// limit of 65,535 loop iterations per invocation (docs/lavapipe.md).
#include "common.glsl"
#include "rays.glsl"
#include "bvh.glsl"  // ray_hits_box

#include "bake_interface.h"  // struct AoPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { AoPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 1, scalar) readonly buffer Normals { vec3 normals[]; };
// The BVH flattened into items, nodes and triangles in pre-order (engine/src/bake/ray_items.hpp).
layout(binding = 2) uniform usamplerBuffer items;
layout(binding = 3, scalar) buffer Hits { uint hits[]; };  // [slice][vertex]
#ifdef JADE_AO_RETRACE
// ao_changed.comp: this dispatch's groups, then the vertices to retrace.
layout(binding = 4, scalar) readonly buffer Changed { uvec3 groups; uint changed_count; uint changed[]; };
#endif

// Möller–Trumbore, both faces; true when the hit lies in (0, tmax]. e1 = b − a, e2 = c − a.
bool hits_triangle(vec3 o, vec3 d, float tmax, vec3 a, vec3 e1, vec3 e2)
{
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
    // One item per iteration; both tests run on its texels and its kind picks the answer
    // (lavapipe would run both anyway). No early return from inside the loop: lavapipe
    // mis-handles returns in divergent loops.
    while (i < pc.item_count && !hit) {
        uvec4 t0 = texelFetch(items, int(3u * i));
        uvec4 t1 = texelFetch(items, int(3u * i + 1u));
        uvec4 t2 = texelFetch(items, int(3u * i + 2u));
        vec3 p0 = uintBitsToFloat(t0.xyz), p1 = uintBitsToFloat(t1.xyz), p2 = uintBitsToFloat(t2.xyz);
        bool triangle = t1.w != 0u;
        bool enter = ray_hits_box(o, inv_d, pc.max_distance, p0, p1);
        hit = triangle && hits_triangle(o, d, pc.max_distance, p0, p1, p2);
        i = (triangle || enter) ? i + 1u : t0.w;
    }
    return hit;
}

void main()
{
    uint index = jade_thread_index();
    uint rays_in_slice = pc.rays / pc.slices;
#ifdef JADE_AO_RETRACE
    uint others = pc.slices - 1u, rays_of_others = rays_in_slice * others;
    if (index >= changed_count * rays_of_others) return;
    uint v = changed[index / rays_of_others], j = index % rays_of_others;
    uint slice = j % others < pc.slice ? j % others : j % others + 1u;
    uint k = (j / others) * pc.slices + slice;
#else
    if (index >= pc.vertex_count * rays_in_slice) return;
    uint v = index / rays_in_slice, slice = pc.slice, k = (index % rays_in_slice) * pc.slices + slice;
#endif
    vec3 n = normals[v];
    vec3 o = positions[v] + pc.ray_offset * n;
    vec3 d = ray_direction(n, ray_sample(v, k, pc.rays, pc.seed, pc.low_discrepancy != 0u));
    if (occluded(o, d)) atomicAdd(hits[slice * pc.vertex_count + v], 1u);
}
