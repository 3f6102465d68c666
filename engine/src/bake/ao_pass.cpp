// bake/ao_pass.cpp - the AO pass (bake/ao_pass.hpp).
#include "bake/ao_pass.hpp"

namespace jade::bake {

void AoPass::Buffers::set_slices(gpu::Context& ctx, uint32_t vertex_count, uint32_t slices)
{
    hits = gpu::Buffer(ctx, VkDeviceSize(vertex_count) * slices * sizeof(uint32_t), kStorageUsage,
                       "ao hit counts (per ray slice)");
    if (slices > 1) {
        previous = gpu::Buffer(ctx, VkDeviceSize(vertex_count) * sizeof(uint32_t), kStorageUsage,
                               "ao hit counts of the fresh slice, before");
        changed_list = gpu::Buffer(ctx, 16 + VkDeviceSize(vertex_count) * sizeof(uint32_t),
                                   kStorageUsage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                                   "ao vertices to retrace (ao_changed.comp)");
    }
}

AoPass::Tree AoPass::prepare(Buffers& b, MeshState& m, const PreparedMesh& mesh) const
{
    const size_t tris = mesh.triangle_count();
    std::vector<glm::vec3> lo(tris), hi(tris);
    for (size_t t = 0; t < tris; ++t) {
        glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                  c = mesh.positions[mesh.indices[3 * t + 2]];
        lo[t] = glm::min(a, glm::min(b, c));
        hi[t] = glm::max(a, glm::max(b, c));
    }
    Tree tree{build_bvh(lo, hi, kTriangleLeafSize, BvhSplit::Sah), {}};
    tree.items = flatten_ray_items(tree.bvh, mesh);
    const RayItems& items = tree.items;
    m.item_count = items.count();
    // Fetched as texels; bound whole as a storage buffer only by a refit (bake/ray_refit_pass.cpp
    // checks its size).
    m.ray_items = gpu::Buffer(ctx_, items.texels.size() * 16, kTexelUsage, "ray items (BVH nodes and triangles)", false,
                              gpu::StorageBinding::Windows);
    m.ray_items.upload(items.texels.data(), items.texels.size() * 16);
    m.ray_item_texels = gpu::TexelView(ctx_, m.ray_items, VK_FORMAT_R32G32B32A32_UINT, 16, "ray items (texels)");
    b.hits = gpu::Buffer(ctx_, mesh.vertex_count() * sizeof(uint32_t), kStorageUsage, "ao hit counts");
    m.ao = gpu::Buffer(ctx_, mesh.vertex_count() * sizeof(float), kStorageUsage, "ao");
    return tree;
}

void AoPass::record(VkCommandBuffer cmd, Buffers& b, const MeshState& m, const AoSettings& s, uint32_t first,
                    uint32_t count, bool retrace_changed)
{
    if (count == 0) count = m.ao_slices;
    const VkDeviceSize slice_bytes = VkDeviceSize(m.vertex_count) * sizeof(uint32_t);
    const bool retrace = retrace_changed && count == 1 && m.ao_slices > 1;
    if (retrace) {  // the slice's counts as the frame that last traced it left them; an empty list
        const VkBufferCopy slice{first * slice_bytes, 0, slice_bytes};
        vkCmdCopyBuffer(cmd, b.hits.handle(), b.previous.handle(), 1, &slice);
        const uint32_t no_groups_no_list[4] = {0, 0, 1, 0};  // groups (x, y, z), count: ao_changed.comp
        vkCmdUpdateBuffer(cmd, b.changed_list.handle(), 0, sizeof(no_groups_no_list), no_groups_no_list);
        gpu::compute_barrier(cmd);
    }
    vkCmdFillBuffer(cmd, b.hits.handle(), first * slice_bytes, count * slice_bytes, 0);
    gpu::compute_barrier(cmd);
    const uint32_t rays_in_slice = s.rays / m.ao_slices;
    auto push = [&](uint32_t slice) {
        return AoPush{m.vertex_count,
                      s.rays,
                      s.seed,
                      s.low_discrepancy ? 1u : 0u,
                      s.ray_offset_rel * m.diagonal,
                      s.max_distance_rel * m.diagonal,
                      m.item_count,
                      m.ao_slices,
                      slice};
    };
    const gpu::Kernel& trace = lazy_kernel(
        ctx_, trace_,
        {"ao_trace", shaders::ao_trace_comp(), {kStorage, kStorage, kTexels, kStorage}, sizeof(AoPush), 64, {}});
    for (uint32_t slice = first; slice < first + count; ++slice)
        trace.dispatch(cmd, uint64_t(m.vertex_count) * rays_in_slice, push(slice),
                       {m.positions, m.normals, m.ray_item_texels, b.hits});
    gpu::compute_barrier(cmd);
    if (retrace) {
        lazy_kernel(
            ctx_, changed_,
            {"ao_changed", shaders::ao_changed_comp(), gpu::storage_bindings(3), sizeof(AoPush), 64, {kAoRetraceGroup}})
            .dispatch(cmd, m.vertex_count, push(first), {b.hits, b.previous, b.changed_list});
        gpu::indirect_barrier(cmd);
        lazy_kernel(ctx_, retrace_,
                    {"ao_retrace",
                     shaders::ao_retrace_comp(),
                     {kStorage, kStorage, kTexels, kStorage, kStorage},
                     sizeof(AoPush),
                     kAoRetraceGroup,
                     {}})
            .dispatch_indirect(cmd, b.changed_list, 0, push(first),
                               {m.positions, m.normals, m.ray_item_texels, b.hits, b.changed_list});
        gpu::compute_barrier(cmd);
    }
    lazy_kernel(ctx_, resolve_,
                {"ao_resolve", shaders::ao_resolve_comp(), gpu::storage_bindings(2), sizeof(AoResolvePush), 64, {}})
        .dispatch(cmd, m.vertex_count, AoResolvePush{m.vertex_count, s.rays, m.ao_slices}, {b.hits, m.ao});
}

}  // namespace jade::bake
