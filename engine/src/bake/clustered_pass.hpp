// bake/clustered_pass.hpp - the clustered far field of t_m: the point tree's nodes refitted
// bottom-up from the gathered sources (cluster_refit.comp), then a tree walk per target that
// sums far clusters as one source each (tm_cluster.comp), over several dispatches that resume
// from saved state. Recorded by the static bake and by DynamicBake. Private to engine/src/bake.
#pragma once

#include "bake/bvh.hpp"
#include "bake/far_field.hpp"
#include "bake/mesh_state.hpp"

namespace jade::bake {

// The pass's kernels, made on first use; one per Baker, shared by every mesh it bakes.
class ClusteredPass {
public:
    // One mesh's tree: its nodes and levels (deepest first), each target's saved walk, and the
    // nodes and sources of MeshState::points as one view.
    struct Buffers {
        gpu::Buffer nodes, node_levels, resume;
        std::vector<uint32_t> level_offsets;
        gpu::TexelView tree_texels;
        uint64_t bytes() const;  // what BakeResult::tm_bytes counts of them
    };

    explicit ClusteredPass(gpu::Context& ctx) : ctx_(ctx) {}

    // Uploads the point tree `tree` and lays out m.points: the nodes, then the sources.
    void prepare(Buffers& b, MeshState& m, const Bvh& tree) const;
    // Refits the nodes from the gathered sources, then clears every target's saved walk.
    void record_refit(VkCommandBuffer cmd, const Buffers& b, const MeshState& m, gpu::GpuTimer* timer);
    // The far field of the targets in tree slots [slot_begin, slot_end), after the near pass.
    void record(VkCommandBuffer cmd, const Buffers& b, const MeshState& m, float opening_ratio, uint32_t slot_begin,
                uint32_t slot_end);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> refit_;
    std::optional<gpu::Kernel> walk_[2][4];  // [grey][profile kind]
};

}  // namespace jade::bake
