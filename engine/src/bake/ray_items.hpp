// bake/ray_items.hpp - the triangle BVH flattened for any-hit rays on lavapipe.
//
// Lavapipe runs every instruction of a loop body on every iteration, whichever branch a lane
// takes (docs/lavapipe.md), so a traversal loop whose body holds both a box test and a leaf's
// four triangle tests pays for all five on every node. Here nodes and triangles are one
// sequence of *items* in pre-order - each leaf node followed by its triangles - and one loop
// iteration tests one item: its box test and its triangle test run side by side on the same
// three texels and the item's kind picks the answer.
//
// Item k is texels 3k, 3k + 1, 3k + 2 of an RGBA32UI buffer (floats as bit patterns):
//   node:     (lo.xyz, escape item), (hi.xyz, 0), unused
//   triangle: (a.xyz, 0),            (b − a, 1),  (c − a, 0)
// After a node whose box the ray misses, the walk goes to `escape`; after anything else, to
// the next item.
#pragma once

#include "bake/bvh.hpp"

#include <jade/mesh.hpp>

#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace jade::bake {

constexpr uint32_t kItemTriangleBit = 0x80000000u;

struct RayItems {
    std::vector<glm::uvec4> texels;  ///< 3 per item
    /// Per item: the node it is (index into Bvh::nodes), or its triangle | kItemTriangleBit
    /// (index into the mesh's triangles): what a refit after deformation recomputes it from.
    std::vector<uint32_t> origin;
    uint32_t count() const { return uint32_t(origin.size()); }
};

/// Flattens `bvh` (built over the triangles of `mesh`) into ray items.
RayItems flatten_ray_items(const Bvh& bvh, const PreparedMesh& mesh);

}  // namespace jade::bake
