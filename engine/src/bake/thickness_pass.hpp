// bake/thickness_pass.hpp - the thickness pass (jade/bake.hpp ThicknessSettings): inward cone
// rays through the AO pass's ray items (thickness_trace.comp), fixed-point sums per ray slice,
// the mean distance per vertex (thickness_resolve.comp). Recorded by the static bake and by
// DynamicBake. Private to engine/src/bake.
#pragma once

#include "bake/mesh_state.hpp"

namespace jade::bake {

// The pass's kernels, made on first use; one per Baker, shared by every mesh it bakes.
class ThicknessPass {
public:
    // One mesh's buffers: the distance sums per ray slice, per vertex, and the thickness (result).
    struct Buffers {
        gpu::Buffer sums, result;
        // (Re)allocates the sums for `slices` ray slices (DynamicBake's amortisation changes them).
        void allocate_sums(gpu::Context& ctx, uint32_t vertex_count, uint32_t slices);
    };

    explicit ThicknessPass(gpu::Context& ctx) : ctx_(ctx) {}

    // Checks the settings; allocates the buffers when the pass is enabled. The ray items are the
    // AO pass's: prepare it first.
    void prepare(Buffers& b, const MeshState& m, const ThicknessSettings& s) const;
    // Traces the ray slices [first, first + count) of m.ao_slices (all by default), then
    // resolves the mean distance from the sums of every slice.
    void record(VkCommandBuffer cmd, Buffers& b, const MeshState& m, const ThicknessSettings& s, uint32_t first = 0,
                uint32_t count = 0);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> trace_, resolve_;
};

}  // namespace jade::bake
