// bake/gather_pass.hpp - the first t_m pass (gather_sources.comp): every vertex's source
// (position, weight, normal) into MeshState::points in tree-slot order, for the near and far
// passes. Private to engine/src/bake.
#pragma once

#include "bake/mesh_state.hpp"

namespace jade::bake {

// The pass's kernel, made on first use; one per Baker.
class GatherPass {
public:
    explicit GatherPass(gpu::Context& ctx) : ctx_(ctx) {}
    void record(VkCommandBuffer cmd, const MeshState& m);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> kernel_;
};

}  // namespace jade::bake
