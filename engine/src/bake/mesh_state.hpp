// bake/mesh_state.hpp - the GPU state of one mesh's bake that the passes share. Private to
// engine/src/bake.
#pragma once

#include "bake/bake_common.hpp"

namespace jade::bake {

// What several passes of one mesh's bake read or write: the uploaded inputs, the ray items,
// A_o, the t_m sources and sums. Each pass keeps its own buffers beside it (Baker::Impl::
// MeshBake). A static bake builds it, records once and drops it; a DynamicBake keeps it and
// records every frame.
struct MeshState {
    uint32_t vertex_count = 0;
    float diagonal = 0;
    gpu::Buffer positions, normals, areas;
    // The triangle BVH as ray items (bake/ao_pass.hpp), traced by the AO and thickness passes in
    // ao_slices slices of their rays; A_o, which the t_m passes read.
    uint32_t item_count = 0;
    gpu::Buffer ray_items, ao;
    uint32_t ao_slices = 1;
    gpu::TexelView ray_item_texels;
    // t_m.
    bool exact = false;
    bool grid = false;  // the grid far field (bake/grid_pass.hpp) instead of the cluster tree
    TmVariant variant{};
    uint32_t node_count = 0, first_point = 0;  // first_point: texel of source 0 in `points`
    gpu::Buffer profiles, point_order, points, tm;
    gpu::Buffer normal_sum;  // per vertex: the scattering normal's unnormalised sum (tm_state.glsl)
    gpu::Buffer partial_sum, partial_comp;
    gpu::TexelView point_texels;
    gpu::TexelView source_texels;  // the sources as RGBA32UI (the near pass), from texel source_base
    uint32_t source_base = 0;
    // `points` as two storage windows: the cluster tree's nodes (none but for the clustered far
    // field), and the sources from texel first_point.
    gpu::Binding nodes_window() const
    {
        return {points.handle(), 0, std::max<VkDeviceSize>(VkDeviceSize(node_count) * 64, 16)};
    }
    gpu::Binding sources_window() const
    {
        return {points.handle(), VkDeviceSize(first_point) * 16, VkDeviceSize(vertex_count) * 32};
    }
    TmMethod method() const { return exact ? TmMethod::Exact : grid ? TmMethod::Grid : TmMethod::Clustered; }
    // What BakeResult::tm_bytes counts of these (the composite adds each pass's own).
    uint64_t shared_tm_bytes() const
    {
        uint64_t b = 0;
        for (const gpu::Buffer* x : {&profiles, &point_order, &points, &tm, &normal_sum, &partial_sum, &partial_comp})
            b += *x ? x->size() : 0;
        return b;
    }
};

inline void upload_mesh(gpu::Context& ctx, MeshState& m, const PreparedMesh& mesh, VkBufferUsageFlags extra_usage = 0)
{
    m.vertex_count = uint32_t(mesh.vertex_count());
    m.diagonal = mesh.diagonal;
    m.positions = gpu::Buffer::from(ctx, mesh.positions, kStorageUsage | extra_usage, "positions");
    m.normals = gpu::Buffer::from(ctx, mesh.normals, kStorageUsage | extra_usage, "normals");
    m.areas = gpu::Buffer::from(ctx, mesh.areas, kStorageUsage | extra_usage, "areas");
}

}  // namespace jade::bake
