// bake/near_pass.hpp - the near pass of t_m (tm_near.comp): per target, the exact sum over
// its near sources (disk pairs over their disk; with the grid far field, the short part of
// the profile over every source within r_cut) and its own disk. It starts every target's
// partial sums, which the far field adds to. The lists: bake/near_field.hpp. Private to
// engine/src/bake.
#pragma once

#include "bake/grid_pass.hpp"
#include "bake/mesh_state.hpp"
#include "bake/near_field.hpp"

#include <span>

namespace jade::bake {

// The pass's kernels, made on first use; one per Baker, shared by every mesh it bakes.
class NearPass {
public:
    // One mesh's near lists, rows in tree-slot order, read as texels through one view per window.
    struct Buffers {
        gpu::Buffer offsets, disks, indices;
        struct Window {
            NearWindow span;         // rows = tree slots
            gpu::TexelView indices;  // `indices` from entry span.first_entry on
        };
        std::vector<Window> windows;  // near-pass dispatches, each within one texel view
        uint64_t bytes() const;       // what BakeResult::tm_bytes counts of them
    };

    explicit NearPass(gpu::Context& ctx) : ctx_(ctx) {}

    // Builds the lists over `tree` (the point tree) with rows in `slot_order`; unless `exact`
    // (sources in vertex order), entries name source slots. `min_reach`: the grid's r_cut, else 0.
    void prepare(Buffers& b, const PreparedMesh& mesh, const Bvh& tree, std::span<const uint32_t> slot_order,
                 bool exact, float margin, float min_reach) const;
    // The targets in tree slots [slot_begin, slot_end); `grids` gives the smooth-part table.
    void record(VkCommandBuffer cmd, const Buffers& b, const MeshState& m, const GridPass::Buffers& grids,
                uint32_t slot_begin, uint32_t slot_end);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> kernels_[2][2][4];  // [grid far field][grey][profile kind]
};

}  // namespace jade::bake
