// bake/exact_pass.hpp - the all-pairs far field of t_m (tm_exact.comp): every target sums
// every source as a point, over chunks of sources, one dispatch each (the near pass has added
// the disk pairs). Its buffers are the mesh state's. Private to engine/src/bake.
#pragma once

#include "bake/mesh_state.hpp"

namespace jade::bake {

// The pass's kernels, made on first use; one per Baker, shared by every mesh it bakes.
class ExactPass {
public:
    explicit ExactPass(gpu::Context& ctx) : ctx_(ctx) {}

    // `float64_sums`: dev::BakeStudy::tm_float64_sums.
    void record(VkCommandBuffer cmd, const MeshState& m, bool float64_sums);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> kernels_[2][4], float64_kernels_[2][4];  // [grey][profile kind]
};

}  // namespace jade::bake
