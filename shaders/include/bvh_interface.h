// bvh_interface.h - a BVH node as the bake's C++ builds it (bake/bvh.hpp) and its shaders read
// it (bvh.glsl, as two RGBA32UI texels; cluster_refit.comp, as a storage buffer), written once.
#ifndef JADE_BVH_INTERFACE_H
#define JADE_BVH_INTERFACE_H

// range = first | (count − 1) << JADE_BVH_COUNT_SHIFT | leaf bit: the first primitive in the
// low 27 bits, a leaf's count − 1 in the next 4 (count ≤ JADE_BVH_MAX_LEAF_SIZE).
#define JADE_BVH_LEAF_BIT 0x80000000u
#define JADE_BVH_COUNT_SHIFT 27
#define JADE_BVH_MAX_LEAF_SIZE 16

#ifdef __cplusplus
#include <glm/vec3.hpp>

#include <cstdint>

namespace jade::bake {
namespace glsl {
using uint = std::uint32_t;
using vec3 = glm::vec3;
}  // namespace glsl
using namespace glsl;  // only these names: the struct below is written in GLSL's words
#endif

struct BvhNode {
    vec3 lo;      // bounds, mesh units
    uint escape;  // next node in pre-order after this subtree
    vec3 hi;
    uint range;  // see above
#ifdef __cplusplus
    bool leaf() const { return (range & JADE_BVH_LEAF_BIT) != 0; }
    uint first() const { return range & ((1u << JADE_BVH_COUNT_SHIFT) - 1u); }
    uint leaf_count() const { return ((range >> JADE_BVH_COUNT_SHIFT) & (JADE_BVH_MAX_LEAF_SIZE - 1u)) + 1; }
    static uint pack_range(uint first, uint count, bool leaf)
    {
        return leaf ? first | ((count - 1) << JADE_BVH_COUNT_SHIFT) | JADE_BVH_LEAF_BIT : first;
    }
#endif
};

#ifdef __cplusplus
static_assert(sizeof(BvhNode) == 32);
}  // namespace jade::bake
#endif

#endif  // JADE_BVH_INTERFACE_H
