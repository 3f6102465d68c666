// bake/near_field.hpp - which source vertices each vertex integrates over their disks.
//
// The vertex-disk rule (jade/bake.hpp) integrates source j over its disk when the target is
// within kNearFactor·ρ_j of it, and treats it as a point beyond. The far passes (all pairs or
// clustered) only ever see point pairs; these lists hold, per target, the disk pairs, which
// the near pass (shaders/tm_near.comp) sums exactly together with the self disk.
#pragma once

#include "bake/bvh.hpp"

#include <jade/mesh.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace jade::bake {

constexpr float kNearFactor = 4.0f;  // = NEAR_FACTOR in shaders/include/tm_common.glsl

/// Compressed rows: the disk sources of target i are indices[offsets[i] .. offsets[i+1]).
struct NearLists {
    std::vector<uint32_t> offsets;
    std::vector<uint32_t> indices;
};

/// Finds, for every vertex i, all j ≠ i with |x_i − x_j| < margin·kNearFactor·√(A_j/π),
/// walking `point_tree` (built over the vertex positions) with each node's largest disk radius.
/// The near pass decides with the current positions which entries are disk pairs, so the
/// margin (> 1) covers float rounding at the boundary and, for a deforming mesh, how much
/// closer vertices may come than at rest.
NearLists build_near_lists(const PreparedMesh& mesh, const Bvh& point_tree, float margin);

/// The same lists with rows in the order `order` (row k = the list of vertex order[k]).
NearLists reorder_rows(const NearLists& lists, std::span<const uint32_t> order);

}  // namespace jade::bake
