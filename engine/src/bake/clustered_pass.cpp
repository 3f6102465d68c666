// bake/clustered_pass.cpp - the clustered far field of t_m (bake/clustered_pass.hpp).
#include "bake/clustered_pass.hpp"

namespace jade::bake {

uint64_t ClusteredPass::Buffers::bytes() const
{
    uint64_t b = 0;
    for (const gpu::Buffer* x : {&nodes, &node_levels, &resume}) b += *x ? x->size() : 0;
    return b;
}

void ClusteredPass::prepare(Buffers& b, MeshState& m, const Bvh& tree) const
{
    const size_t n = m.vertex_count;
    m.point_order = gpu::Buffer::from(ctx_, tree.order, kStorageUsage, "point tree order");
    m.node_count = uint32_t(tree.nodes.size());
    b.nodes = gpu::Buffer::from(ctx_, tree.nodes, kStorageUsage, "point tree nodes");
    BvhLevels levels = bvh_levels(tree);
    b.node_levels = gpu::Buffer::from(ctx_, levels.nodes, kStorageUsage, "point tree levels");
    b.level_offsets = levels.offsets;
    // One buffer holds the nodes (4 texels each) and then the sources (2 texels each), so one
    // fetch per lane brings a node and a source (tm_cluster.comp).
    // Sources start at a texel that is a multiple of 16 (256 bytes): any device's allowed
    // offset for binding them alone as a storage buffer.
    m.first_point = (4 * m.node_count + 15) / 16 * 16;
    check_storage_range(ctx_, VkDeviceSize(n) * kTmSources.bytes_per_vertex, kTmSources.name);
    check_storage_range(ctx_, VkDeviceSize(m.node_count) * 64, "t_m cluster nodes");
    m.points = gpu::Buffer(ctx_, VkDeviceSize(m.first_point) * 16 + n * kTmSources.bytes_per_vertex, kTexelUsage,
                           "t_m cluster tree and sources", false,
                           gpu::StorageBinding::Windows);  // bound as two windows, each checked above
    b.tree_texels =
        gpu::TexelView(ctx_, m.points, VK_FORMAT_R32G32B32A32_UINT, 16, "t_m cluster tree and sources (texels)");
    m.source_texels =
        gpu::TexelView(ctx_, m.points, VK_FORMAT_R32G32B32A32_UINT, 16, "t_m cluster tree and sources (texels)");
    m.source_base = m.first_point;
    b.resume = gpu::Buffer(ctx_, n * kTmResume.bytes_per_vertex, kStorageUsage, kTmResume.name);
}

void ClusteredPass::record_refit(VkCommandBuffer cmd, const Buffers& b, const MeshState& m, gpu::GpuTimer* timer)
{
    for (size_t l = 0; l + 1 < b.level_offsets.size(); ++l) {
        const uint32_t first = b.level_offsets[l], count = b.level_offsets[l + 1] - first;
        lazy_kernel(
            ctx_, refit_,
            {"cluster_refit", shaders::cluster_refit_comp(), gpu::storage_bindings(4), sizeof(RefitPush), 64, {}})
            .dispatch(cmd, count, RefitPush{count, first},
                      {b.nodes, b.node_levels, m.nodes_window(), m.sources_window()});
        gpu::compute_barrier(cmd);
    }
    if (timer) timer->mark(cmd, "refit");
    vkCmdFillBuffer(cmd, b.resume.handle(), 0, VK_WHOLE_SIZE, 0);
}

void ClusteredPass::record(VkCommandBuffer cmd, const Buffers& b, const MeshState& m, float opening_ratio,
                           uint32_t slot_begin, uint32_t slot_end)
{
    const TmVariant& v = m.variant;
    if (!walk_[v.grey][v.kind]) require_subgroup_groups(ctx_);
    const auto& kernel = lazy_kernel(ctx_, walk_[v.grey][v.kind],
                                     {"tm_cluster",
                                      shaders::tm_cluster_comp(),
                                      {kStorage, kTexels, kStorage, kStorage, kStorage, kStorage, kStorage, kStorage},
                                      sizeof(ClusterPush),
                                      64,
                                      tm_constants(v)});
    const uint32_t n = m.vertex_count;
    // Every thread visits each node and each source at most once: this many dispatches finish
    // every traversal; threads that are done return at once.
    const uint32_t dispatches = (m.node_count + n) / kClusterWorkPerDispatch + 1;
    ClusterPush push{n, m.node_count, opening_ratio, kClusterWorkPerDispatch, m.first_point, slot_begin, slot_end};
    for (uint32_t d = 0; d < dispatches; ++d) {
        kernel.dispatch(
            cmd, slot_end - slot_begin, push,
            {m.profiles, b.tree_texels, m.point_order, b.resume, m.partial_sum, m.partial_comp, m.tm, m.normal_sum});
        gpu::compute_barrier(cmd);
    }
}

}  // namespace jade::bake
