// bake/gather_pass.cpp - the sources of t_m (bake/gather_pass.hpp).
#include "bake/gather_pass.hpp"

namespace jade::bake {

void GatherPass::record(VkCommandBuffer cmd, const MeshState& m)
{
    const uint32_t n = m.vertex_count;
    lazy_kernel(
        ctx_, kernel_,
        {"gather_sources", shaders::gather_sources_comp(), gpu::storage_bindings(6), sizeof(GatherPush), 64, {}})
        .dispatch(cmd, n, GatherPush{n}, {m.positions, m.areas, m.ao, m.point_order, m.sources_window(), m.normals});
}

}  // namespace jade::bake
