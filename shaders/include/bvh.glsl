// bvh.glsl - BVH nodes as texels (engine/src/bake/bvh.hpp: pre-order, escape pointers).
//
// Node i is texels 2i and 2i + 1 of an RGBA32UI texel buffer: (lo.xyz, escape), (hi.xyz, range)
// with the floats as bit patterns (range: bvh_interface.h).
#ifndef JADE_BVH_GLSL
#define JADE_BVH_GLSL

#include "bvh_interface.h"  // struct BvhNode and its range's bits, shared with engine/src/bake

const uint JADE_LEAF_BIT = JADE_BVH_LEAF_BIT;

bool jade_range_is_leaf(uint range) { return (range & JADE_LEAF_BIT) != 0u; }
uint jade_range_first(uint range) { return range & ((1u << JADE_BVH_COUNT_SHIFT) - 1u); }
uint jade_range_count(uint range) { return ((range >> JADE_BVH_COUNT_SHIFT) & (JADE_BVH_MAX_LEAF_SIZE - 1u)) + 1u; }

BvhNode jade_fetch_node(usamplerBuffer nodes, uint i)
{
    uvec4 a = texelFetch(nodes, int(2u * i));
    uvec4 b = texelFetch(nodes, int(2u * i + 1u));
    return BvhNode(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w);
}

// Does the ray o + t·d, t ∈ [0, tmax], touch the box? (slab test, inv_d = 1/d)
bool ray_hits_box(vec3 o, vec3 inv_d, float tmax, vec3 lo, vec3 hi)
{
    vec3 t0 = (lo - o) * inv_d;
    vec3 t1 = (hi - o) * inv_d;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float enter = max(max(tn.x, tn.y), max(tn.z, 0.0));
    float leave = min(min(tf.x, tf.y), min(tf.z, tmax));
    return enter <= leave;
}

#endif
