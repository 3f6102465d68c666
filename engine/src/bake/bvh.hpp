// bake/bvh.hpp - a bounding volume hierarchy laid out for stackless GPU traversal.
//
// Nodes are stored in depth-first pre-order: the first child of node i is node i + 1, and
// `escape` is the node to visit when the subtree of i is skipped or done (node_count = end).
// Every node covers a contiguous range [first, first + count) of the reordered primitives, so
// refitting after a deformation is one independent pass per node (scan its range), with no
// bottom-up dependencies. The same builder serves triangles (AO) and points (t_m clusters).
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace jade::bake {

/// GPU layout (std430, 32 bytes); mirrored by `BvhNode` in shaders/include/bvh.glsl.
struct BvhNode {
    glm::vec3 lo;       ///< bounds, mesh units
    uint32_t escape;    ///< next node in pre-order after this subtree
    glm::vec3 hi;
    uint32_t first_and_leaf; ///< bit 31: leaf; bits 0..30: first primitive of the range
};
static_assert(sizeof(BvhNode) == 32);

struct Bvh {
    std::vector<BvhNode> nodes;
    std::vector<uint32_t> counts;     ///< primitives in each node's range (for refit)
    std::vector<uint32_t> order;      ///< order[k] = original index of the k-th primitive
    uint32_t depth = 0;
};

constexpr uint32_t kLeafBit = 0x80000000u;

/// Builds over primitives given by their bounds (lo[i], hi[i]); leaves hold at most
/// `leaf_size` primitives. Splits at the median of the centroids along the widest axis of the
/// centroid bounds (balanced: depth ≤ ⌈log2(n / leaf_size)⌉ + 1).
Bvh build_bvh(std::span<const glm::vec3> lo, std::span<const glm::vec3> hi, uint32_t leaf_size);

}  // namespace jade::bake
