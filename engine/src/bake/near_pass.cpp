// bake/near_pass.cpp - the near pass of t_m (bake/near_pass.hpp).
#include "bake/near_pass.hpp"

namespace jade::bake {

uint64_t NearPass::Buffers::bytes() const
{
    uint64_t b = 0;
    for (const gpu::Buffer* x : {&offsets, &disks, &indices}) b += *x ? x->size() : 0;
    return b;
}

void NearPass::prepare(Buffers& b, const PreparedMesh& mesh, const Bvh& tree, std::span<const uint32_t> slot_order,
                       bool exact, float margin, float min_reach) const
{
    const size_t n = mesh.vertex_count();
    NearLists near = build_near_lists(mesh, tree, margin, min_reach);
    // Rows in slot order, so a range of slots has a contiguous window of entries.
    near = reorder_rows(near, slot_order);
    // Entries name source slots: the near pass reads the sources in slot order as texels.
    if (!exact) {
        std::vector<uint32_t> slot_of(n);
        for (uint32_t k = 0; k < n; ++k) slot_of[slot_order[k]] = k;
        for (uint32_t& j : near.indices) j = slot_of[j];
    }
    b.offsets = gpu::Buffer::from(ctx_, near.offsets, kStorageUsage, "near-field offsets");
    b.disks = gpu::Buffer::from(ctx_, near.disk_counts, kStorageUsage, "near-field disk candidates");
    near.indices.resize(near.indices.size() + 64, 0);  // room for a window's aligned start and minimum size
    // Read as texels (one SIMD gather on lavapipe, not a loop of bounds-checked loads), through
    // one view per window of slots, so the lists may outgrow one view (maxTexelBufferElements).
    b.indices = gpu::Buffer(ctx_, near.indices.size() * 4, kTexelUsage, "near-field sources", false,
                            gpu::StorageBinding::Windows);
    b.indices.upload(near.indices.data(), near.indices.size() * 4);
    const auto& lim = ctx_.limits();
    b.windows.clear();
    for (const NearWindow& w :
         plan_near_windows(near.offsets, std::max<VkDeviceSize>(lim.minTexelBufferOffsetAlignment, 4),
                           VkDeviceSize(lim.maxTexelBufferElements) * 4))
        b.windows.push_back({w, gpu::TexelView(ctx_, b.indices, VK_FORMAT_R32_UINT, 4, "near-field sources (texels)",
                                               VkDeviceSize(w.first_entry) * 4, w.bytes)});
}

void NearPass::record(VkCommandBuffer cmd, const Buffers& b, const MeshState& m, const GridPass::Buffers& grids,
                      uint32_t slot_begin, uint32_t slot_end)
{
    const TmVariant& v = m.variant;
    for (const auto& [w, indices] : b.windows) {
        const uint32_t first = std::max(w.first_row, slot_begin), end = std::min(w.first_row + w.row_count, slot_end);
        if (first >= end) continue;
        std::vector<uint32_t> constants = tm_constants(v);
        constants.push_back(m.grid ? 1u : 0u);
        lazy_kernel(ctx_, kernels_[m.grid][v.grey][v.kind],
                    {"tm_near",
                     shaders::tm_near_comp(),
                     {kStorage, kTexels, kStorage, kTexels, kStorage, kStorage, kTexels, kStorage, kStorage, kStorage,
                      kStorage},
                     sizeof(NearPush),
                     64,
                     constants})
            .dispatch(cmd, end - first,
                      NearPush{first, end - first, w.first_entry, m.source_base, grids.cut2, grids.table_scale},
                      {m.profiles, m.source_texels, b.offsets, indices, b.disks, m.point_order,
                       grids.smooth_table_texels, m.partial_sum, m.partial_comp, m.tm, m.normal_sum});
    }
    gpu::compute_barrier(cmd);
}

}  // namespace jade::bake
