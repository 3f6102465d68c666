// bake/near_field.hpp - which source vertices each vertex integrates over their disks.
//
// The vertex-disk rule (jade/bake.hpp) integrates source j over its disk when the target is
// within kNearFactor·ρ_j of it, and treats it as a point beyond. The far passes (all pairs or
// clustered) only ever see point pairs; these lists hold, per target, the disk pairs, which
// the near pass (shaders/tm_near.comp) sums exactly together with the self disk.
#pragma once

#include "bake/bvh.hpp"

#include <jade/mesh.hpp>

#include "bake_interface.h"  // JADE_NEAR_FACTOR, shared with the shaders

#include <cstdint>
#include <span>
#include <vector>

namespace jade::bake {

constexpr float kNearFactor = float(JADE_NEAR_FACTOR);  // bake_interface.h, shared with the shaders

/// Compressed rows: the near sources of target i are indices[offsets[i] .. offsets[i+1]), the
/// disk candidates (within margin·kNearFactor·ρ_j) first: disk_counts[i] of them. The others
/// (only with a min_reach) are point pairs whatever the mesh does.
struct NearLists {
    std::vector<uint32_t> offsets;
    std::vector<uint32_t> indices;
    std::vector<uint32_t> disk_counts;
};

/// Finds, for every vertex i, all j ≠ i with |x_i − x_j| < margin·max(kNearFactor·√(A_j/π),
/// min_reach), walking `point_tree` (built over the vertex positions) with each node's largest
/// reach. min_reach: the grid far field's r_cut (bake/grid_field.hpp), else 0.
/// The near pass decides with the current positions which entries are disk pairs, so the
/// margin (> 1) covers float rounding at the boundary and, for a deforming mesh, how much
/// closer vertices may come than at rest.
NearLists build_near_lists(const PreparedMesh& mesh, const Bvh& point_tree, float margin, float min_reach = 0);

/// The entries build_near_lists would make, estimated from up to 1,024 evenly spread vertices.
uint64_t sample_near_entries(const PreparedMesh& mesh, const Bvh& point_tree, float margin, float min_reach = 0);

/// The same lists with rows in the order `order` (row k = the list of vertex order[k]).
NearLists reorder_rows(const NearLists& lists, std::span<const uint32_t> order);

/// Rows [first_row, first_row + row_count) of the lists, whose entries a view of `bytes` from
/// entry `first_entry` holds (it may start before the first row's entries, to be aligned).
struct NearWindow {
    uint32_t first_row = 0, row_count = 0, first_entry = 0;
    uint64_t bytes = 0;
};

/// Splits the rows into windows of at most `max_bytes` of 4-byte entries, each starting at a
/// multiple of `align` bytes (a power of two ≥ 4), the fewest of them (each as long as it can be).
/// Throws jade::Error when one row alone does not fit.
std::vector<NearWindow> plan_near_windows(std::span<const uint32_t> offsets, uint64_t align, uint64_t max_bytes);

}  // namespace jade::bake
