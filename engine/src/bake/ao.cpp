// bake/ao.cpp - the AO pass of Baker::Impl (jade/bake.hpp AoSettings): the triangle BVH
// flattened into ray items, their refit when the mesh deforms (ray_refit.comp), cosine rays per
// vertex in slices (ao_trace.comp) and A_o from the hit counts (ao_resolve.comp). Recorded by the
// static bake and by DynamicBake; the thickness pass traces the same ray items.
#include "bake/baker_impl.hpp"

namespace jade {

void Baker::Impl::prepare_ao(MeshState& m, const PreparedMesh& mesh, bool refittable)
{
    const size_t tris = mesh.triangle_count();
    std::vector<glm::vec3> lo(tris), hi(tris);
    for (size_t t = 0; t < tris; ++t) {
        glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                  c = mesh.positions[mesh.indices[3 * t + 2]];
        lo[t] = glm::min(a, glm::min(b, c));
        hi[t] = glm::max(a, glm::max(b, c));
    }
    bake::Bvh bvh = bake::build_bvh(lo, hi, kTriangleLeafSize, bake::BvhSplit::Sah);
    bake::RayItems items = bake::flatten_ray_items(bvh, mesh);
    m.item_count = items.count();
    // Fetched as texels; bound whole as a storage buffer only by a refit (checked below).
    m.ray_items = gpu::Buffer(ctx, items.texels.size() * 16, kTexelUsage, "ray items (BVH nodes and triangles)", false,
                              gpu::StorageBinding::Windows);
    m.ray_items.upload(items.texels.data(), items.texels.size() * 16);
    m.ray_item_texels = gpu::TexelView(ctx, m.ray_items, VK_FORMAT_R32G32B32A32_UINT, 16, "ray items (texels)");
    m.hits = gpu::Buffer(ctx, mesh.vertex_count() * sizeof(uint32_t), kStorageUsage, "ao hit counts");
    m.ao = gpu::Buffer(ctx, mesh.vertex_count() * sizeof(float), kStorageUsage, "ao");
    if (!refittable) return;
    check_storage_range(VkDeviceSize(items.count()) * 48, "ray items (refitted as a storage buffer)");
    // Work for ray_refit.comp: every triangle item, then the node items level by level,
    // deepest first, each with its leaf's triangle count (0: inner node).
    std::vector<uint32_t> item_of_node(bvh.nodes.size());
    std::vector<glm::uvec2> work;
    for (uint32_t k = 0; k < items.count(); ++k) {
        if (items.origin[k] & bake::kItemTriangleBit)
            work.push_back({k, 0});
        else
            item_of_node[items.origin[k]] = k;
    }
    m.ray_work_offsets = {0, uint32_t(work.size())};
    bake::BvhLevels levels = bake::bvh_levels(bvh);
    for (size_t l = 0; l < levels.count(); ++l) {
        for (uint32_t k = levels.offsets[l]; k < levels.offsets[l + 1]; ++k) {
            const bake::BvhNode& node = bvh.nodes[levels.nodes[k]];
            work.push_back({item_of_node[levels.nodes[k]], node.leaf() ? node.leaf_count() : 0});
        }
        m.ray_work_offsets.push_back(uint32_t(work.size()));
    }
    m.indices = gpu::Buffer::from(ctx, mesh.indices, kStorageUsage, "triangle indices");
    m.item_origin = gpu::Buffer::from(ctx, items.origin, kStorageUsage, "ray item origins");
    m.ray_work = gpu::Buffer::from(ctx, work, kStorageUsage, "ray refit work");
}

// Ray items follow the current positions: triangles, then node boxes bottom-up.
void Baker::Impl::record_ray_refit(VkCommandBuffer cmd, MeshState& m)
{
    const auto& k = ray_refit_kernel();
    for (size_t r = 0; r + 1 < m.ray_work_offsets.size(); ++r) {
        const uint32_t first = m.ray_work_offsets[r], count = m.ray_work_offsets[r + 1] - first;
        k.dispatch(cmd, count, RayRefitPush{count, first, r == 0 ? 0u : 1u},
                   {m.positions, m.indices, m.item_origin, m.ray_work, m.ray_items});
        gpu::compute_barrier(cmd);
    }
}

void Baker::Impl::record_ao(VkCommandBuffer cmd, MeshState& m, const AoSettings& s, uint32_t first, uint32_t count,
                            bool retrace_changed)
{
    if (count == 0) count = m.ao_slices;
    const VkDeviceSize slice_bytes = VkDeviceSize(m.vertex_count) * sizeof(uint32_t);
    const bool retrace = retrace_changed && count == 1 && m.ao_slices > 1;
    if (retrace) {  // the slice's counts as the frame that last traced it left them; an empty list
        const VkBufferCopy slice{first * slice_bytes, 0, slice_bytes};
        vkCmdCopyBuffer(cmd, m.hits.handle(), m.ao_previous.handle(), 1, &slice);
        const uint32_t no_groups_no_list[4] = {0, 0, 1, 0};  // groups (x, y, z), count: ao_changed.comp
        vkCmdUpdateBuffer(cmd, m.ao_changed_list.handle(), 0, sizeof(no_groups_no_list), no_groups_no_list);
        gpu::compute_barrier(cmd);
    }
    vkCmdFillBuffer(cmd, m.hits.handle(), first * slice_bytes, count * slice_bytes, 0);
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
    for (uint32_t slice = first; slice < first + count; ++slice)
        ao_kernel().dispatch(cmd, uint64_t(m.vertex_count) * rays_in_slice, push(slice),
                             {m.positions, m.normals, m.ray_item_texels, m.hits});
    gpu::compute_barrier(cmd);
    if (retrace) {
        ao_changed_kernel().dispatch(cmd, m.vertex_count, push(first), {m.hits, m.ao_previous, m.ao_changed_list});
        gpu::indirect_barrier(cmd);
        ao_retrace_kernel().dispatch_indirect(cmd, m.ao_changed_list, 0, push(first),
                                              {m.positions, m.normals, m.ray_item_texels, m.hits, m.ao_changed_list});
        gpu::compute_barrier(cmd);
    }
    ao_resolve_kernel().dispatch(cmd, m.vertex_count, AoResolvePush{m.vertex_count, s.rays, m.ao_slices},
                                 {m.hits, m.ao});
}

}  // namespace jade
