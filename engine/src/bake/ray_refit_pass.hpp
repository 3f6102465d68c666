// bake/ray_refit_pass.hpp - a deforming mesh's ray items follow its current positions
// (ray_refit.comp): triangles, then node boxes bottom-up, one dispatch per level. Recorded by
// DynamicBake before its AO pass. Private to engine/src/bake.
#pragma once

#include "bake/ao_pass.hpp"

namespace jade::bake {

// The pass's kernel, made on first use; one per Baker.
class RayRefitPass {
public:
    // One mesh's refit data: the triangles, each ray item's origin, and the work list.
    struct Buffers {
        gpu::Buffer indices, item_origin, work;
        std::vector<uint32_t> work_offsets;  // [0, triangles) then one range per level
    };

    explicit RayRefitPass(gpu::Context& ctx) : ctx_(ctx) {}

    // The work lists of `tree` (AoPass::prepare's), uploaded with the triangles.
    void prepare(Buffers& b, const AoPass::Tree& tree, const PreparedMesh& mesh) const;
    void record(VkCommandBuffer cmd, const Buffers& b, const MeshState& m);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> kernel_;
};

}  // namespace jade::bake
