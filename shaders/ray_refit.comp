#version 460
#extension GL_GOOGLE_include_directive : require
// Refits the ray items (engine/src/bake/ray_items.hpp) to deformed positions, in place, with
// the BVH's shape kept. Mode 0: every triangle item gets (a, b − a, c − a) from the positions.
// Mode 1: the node items of one tree level, deepest level first (one dispatch per level), get
// the union of their children's boxes, or for a leaf the box of its triangles' corners - taken
// from the positions themselves, so a corner never falls outside its box by a rounding.
#include "common.glsl"

#include "bake_interface.h"  // struct RayRefitPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { RayRefitPush pc; };

layout(binding = 0, scalar) readonly buffer Positions { vec3 positions[]; };  // bake order
layout(binding = 1, scalar) readonly buffer Indices { uint indices[]; };      // 3 per triangle
layout(binding = 2, scalar) readonly buffer Origin { uint origin[]; };        // per item
// Work entries: (item, triangles of the leaf, 0 for an inner node). Mode 0: (item, 0).
layout(binding = 3, scalar) readonly buffer Work { uvec2 work[]; };
layout(binding = 4, scalar) buffer Items { uvec4 items[]; };                  // 3 texels per item

const uint TRIANGLE_BIT = 0x80000000u;

vec3 corner(uint triangle, uint k) { return positions[indices[3u * triangle + k]]; }

void main()
{
    uint e = jade_thread_index();
    if (e >= pc.count) return;
    uvec2 entry = work[pc.first + e];
    uint item = entry.x;
    if (pc.mode == 0u) {
        uint t = origin[item] & ~TRIANGLE_BIT;
        vec3 a = corner(t, 0u);
        items[3u * item] = uvec4(floatBitsToUint(a), 0u);
        items[3u * item + 1u] = uvec4(floatBitsToUint(corner(t, 1u) - a), 1u);
        items[3u * item + 2u] = uvec4(floatBitsToUint(corner(t, 2u) - a), 0u);
        return;
    }
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    uint leaf_triangles = entry.y;
    if (leaf_triangles == 0u) {
        // Inner node: the first child is the next item, the second is where the first escapes to.
        uint a = item + 1u, b = items[3u * a].w;
        lo = min(uintBitsToFloat(items[3u * a].xyz), uintBitsToFloat(items[3u * b].xyz));
        hi = max(uintBitsToFloat(items[3u * a + 1u].xyz), uintBitsToFloat(items[3u * b + 1u].xyz));
    }
    [[unroll]] for (uint k = 0u; k < 4u; ++k) {
        bool use = k < leaf_triangles;
        // (Inner nodes and unused slots read triangle 0: both sides of a branch run anyway.)
        uint t = leaf_triangles == 0u ? 0u : origin[item + 1u + min(k, leaf_triangles - 1u)] & ~TRIANGLE_BIT;
        [[unroll]] for (uint c = 0u; c < 3u; ++c) {
            vec3 p = corner(t, c);
            lo = use ? min(lo, p) : lo;
            hi = use ? max(hi, p) : hi;
        }
    }
    items[3u * item] = uvec4(floatBitsToUint(lo), items[3u * item].w);
    items[3u * item + 1u] = uvec4(floatBitsToUint(hi), 0u);
}
