// bake/exact_pass.cpp - the all-pairs far field of t_m (bake/exact_pass.hpp).
#include "bake/exact_pass.hpp"

namespace jade::bake {

void ExactPass::record(VkCommandBuffer cmd, const MeshState& m, bool float64_sums)
{
    const TmVariant& v = m.variant;
    auto& slot = float64_sums ? float64_kernels_[v.grey][v.kind] : kernels_[v.grey][v.kind];
    if (!slot) require_subgroup_groups(ctx_);  // once, when the kernel is made
    const auto& kernel = lazy_kernel(ctx_, slot,
                                     {float64_sums ? "tm_exact_f64" : "tm_exact",
                                      float64_sums ? shaders::tm_exact_f64_comp() : shaders::tm_exact_comp(),
                                      {kStorage, kTexels, kStorage, kStorage, kStorage, kStorage},
                                      sizeof(ExactPush),
                                      64,
                                      tm_constants(v)});
    const uint32_t n = m.vertex_count;
    for (uint32_t begin = 0; begin < n; begin += kExactSourcesPerDispatch) {
        ExactPush push{n, begin, std::min(n, begin + kExactSourcesPerDispatch)};
        kernel.dispatch(cmd, n, push, {m.profiles, m.point_texels, m.partial_sum, m.partial_comp, m.tm, m.normal_sum});
        gpu::compute_barrier(cmd);
    }
}

}  // namespace jade::bake
