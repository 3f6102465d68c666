// bvh.glsl - the node layout of engine/src/bake/bvh.hpp (pre-order, escape pointers).
#ifndef JADE_BVH_GLSL
#define JADE_BVH_GLSL

struct BvhNode {
    vec3 lo;
    uint escape;          // next node after this subtree
    vec3 hi;
    uint first_and_leaf;  // bit 31: leaf; bits 0..30: first primitive of the node's range
};

const uint JADE_LEAF_BIT = 0x80000000u;

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
