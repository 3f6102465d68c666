// bake/bvh.cpp - median-split BVH in pre-order with escape pointers (see bvh.hpp).
#include "bvh.hpp"

#include <jade/error.hpp>

#include <glm/common.hpp>

#include <algorithm>
#include <cassert>
#include <string>

namespace jade::bake {
namespace {

struct Builder {
    std::span<const glm::vec3> lo, hi;
    std::vector<glm::vec3> centroid;  // ×2 (lo + hi): the same order as the centroid, no rounding
    uint32_t leaf_size;
    Bvh bvh;

    /// Builds the subtree over order[first, first + count) at the given level (root = 1).
    void build(uint32_t first, uint32_t count, uint32_t level)
    {
        const uint32_t index = uint32_t(bvh.nodes.size());
        bvh.nodes.emplace_back();
        bvh.counts.push_back(count);
        bvh.depth = std::max(bvh.depth, level);

        glm::vec3 box_lo = lo[bvh.order[first]], box_hi = hi[bvh.order[first]];
        glm::vec3 c_lo = centroid[bvh.order[first]], c_hi = c_lo;
        for (uint32_t k = first + 1; k < first + count; ++k) {
            const uint32_t p = bvh.order[k];
            box_lo = glm::min(box_lo, lo[p]);
            box_hi = glm::max(box_hi, hi[p]);
            c_lo = glm::min(c_lo, centroid[p]);
            c_hi = glm::max(c_hi, centroid[p]);
        }
        const bool leaf = count <= leaf_size;
        if (!leaf) {
            const glm::vec3 extent = c_hi - c_lo;
            const int axis = (extent.x >= extent.y && extent.x >= extent.z) ? 0 : (extent.y >= extent.z ? 1 : 2);
            const uint32_t half = count / 2;
            auto begin = bvh.order.begin() + first;
            std::nth_element(begin, begin + half, begin + count, [&](uint32_t a, uint32_t b) {
                return centroid[a][axis] < centroid[b][axis] || (centroid[a][axis] == centroid[b][axis] && a < b);
            });
            build(first, half, level + 1);
            build(first + half, count - half, level + 1);
        }
        BvhNode& node = bvh.nodes[index];
        node.lo = box_lo;
        node.hi = box_hi;
        node.escape = uint32_t(bvh.nodes.size());  // the node after this subtree in pre-order
        node.range = BvhNode::pack_range(first, count, leaf);
    }
};

}  // namespace

BvhLevels bvh_levels(const Bvh& bvh)
{
    // Depth of every node: pre-order, so a node's children (i + 1 and its escape) follow it.
    const uint32_t n = uint32_t(bvh.nodes.size());
    std::vector<uint32_t> depth(n, 0);
    uint32_t deepest = 0;
    for (uint32_t i = 0; i < n; ++i) {
        deepest = std::max(deepest, depth[i]);
        if (bvh.nodes[i].leaf()) continue;
        depth[i + 1] = depth[i] + 1;
        depth[bvh.nodes[i + 1].escape] = depth[i] + 1;
    }
    BvhLevels levels;
    levels.offsets.push_back(0);
    for (uint32_t level = deepest + 1; n > 0 && level-- > 0;) {
        for (uint32_t i = 0; i < n; ++i)
            if (depth[i] == level) levels.nodes.push_back(i);
        levels.offsets.push_back(uint32_t(levels.nodes.size()));
    }
    return levels;
}

Bvh build_bvh(std::span<const glm::vec3> lo, std::span<const glm::vec3> hi, uint32_t leaf_size)
{
    assert(lo.size() == hi.size() && leaf_size >= 1 && leaf_size <= kMaxLeafSize);
    if (lo.size() >= kMaxPrimitives)
        throw Error("BVH: " + std::to_string(lo.size()) + " primitives exceed the limit of " + std::to_string(kMaxPrimitives));
    Builder b{lo, hi, {}, std::max(leaf_size, 1u), {}};
    const uint32_t n = uint32_t(lo.size());
    b.centroid.resize(n);
    b.bvh.order.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        b.centroid[i] = lo[i] + hi[i];
        b.bvh.order[i] = i;
    }
    if (n > 0) {
        const size_t reserve = 2 * ((n + b.leaf_size - 1) / b.leaf_size);
        b.bvh.nodes.reserve(reserve);
        b.bvh.counts.reserve(reserve);
        b.build(0, n, 1);
    }
    return std::move(b.bvh);
}

}  // namespace jade::bake
