// bake/bvh.hpp - a bounding volume hierarchy laid out for stackless GPU traversal.
//
// Nodes are stored in depth-first pre-order: the first child of node i is node i + 1, and
// `escape` is the node to visit when the subtree of i is skipped or done (node_count = end).
// Every node covers a contiguous range [first, first + count) of the reordered primitives, so
// refitting after a deformation is one independent pass per node (scan its range), with no
// bottom-up dependencies. The same builder serves triangles (AO) and points (t_m clusters).
#pragma once

#include <glm/vec3.hpp>

#include "bvh_interface.h"

#include <cstdint>
#include <span>
#include <vector>

namespace jade::bake {

constexpr uint32_t kLeafBit = JADE_BVH_LEAF_BIT;
constexpr uint32_t kMaxLeafSize = JADE_BVH_MAX_LEAF_SIZE;        ///< leaf counts are stored in 4 bits
constexpr uint32_t kMaxPrimitives = 1u << JADE_BVH_COUNT_SHIFT;  ///< first primitives are stored in 27 bits

// struct BvhNode, two RGBA32UI texels (32 bytes) on the GPU: bvh_interface.h, shared with the
// shaders.

struct Bvh {
    std::vector<BvhNode> nodes;
    std::vector<uint32_t> counts;  ///< primitives in each node's range (for refit)
    std::vector<uint32_t> order;   ///< order[k] = original index of the k-th primitive
    uint32_t depth = 0;
};

/// The nodes grouped by depth, deepest level first: a bottom-up refit processes level by level
/// (one dispatch each), every node after its children.
struct BvhLevels {
    std::vector<uint32_t> nodes;    ///< node indices, level after level
    std::vector<uint32_t> offsets;  ///< level k is nodes[offsets[k] .. offsets[k + 1])
    size_t count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};
BvhLevels bvh_levels(const Bvh& bvh);

/// How build_bvh splits a node.
enum class BvhSplit {
    /// At the median of the centroids along the widest axis of the centroid bounds (balanced:
    /// depth ≤ ⌈log2(n / leaf_size)⌉ + 1). For the t_m point tree, whose walk cost follows
    /// the node count, not the boxes' areas.
    Median,
    /// Binned surface-area heuristic (32 bins per axis; a node and a triangle each cost one
    /// step) for every node above leaf_size: on the bunny's AO rays 11 % fewer loop
    /// iterations per 8-lane group than the median split, with 2 % fewer items. Past 48
    /// levels, or when no bin boundary separates the centroids, a median split.
    Sah,
};

/// Builds over primitives given by their bounds (lo[i], hi[i]); leaves hold at most
/// `leaf_size` (≤ kMaxLeafSize) primitives; at most kMaxPrimitives primitives.
Bvh build_bvh(std::span<const glm::vec3> lo, std::span<const glm::vec3> hi, uint32_t leaf_size,
              BvhSplit split = BvhSplit::Median);

}  // namespace jade::bake
