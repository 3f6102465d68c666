// bake/tm_passes.cpp - the t_m passes of Baker::Impl: set-up (method choice, near lists, the far
// field's buffers) and recording (gather → near field → all pairs | refit → clustered | grid).
// Recorded by the static bake and by DynamicBake.
#include "bake/baker_impl.hpp"
#include "bake/far_field.hpp"

namespace jade {

void Baker::Impl::prepare_tm(MeshState& m, const PreparedMesh& mesh, const Material& material, const BakeSettings& s,
                             float near_margin)
{
    validate_tm_settings(s, ctx);
    const size_t n = mesh.vertex_count();
    m.variant = tm_variant(material);
    bake::Bvh tree = bake::build_point_tree(mesh);
    // The far field: docs/bake.md, "Choosing the far field"; the buffer estimate calls the same rule.
    bake::FarField far = bake::choose_far_field(mesh, material, s, tree, near_margin);
    if (s.method == TmMethod::Grid && far.method != TmMethod::Grid)
        throw Error("t_m grid: " + std::to_string(n) + " vertices spread over these bounds need " +
                    std::to_string(far.grid->cells_needed) + " grid cells at resolution " +
                    std::to_string(s.tm_grid_resolution) + " (the limit is " + std::to_string(bake::kGridMaxCells) +
                    ") or near lists of ~" + std::to_string(far.near_entries * 4 >> 20) + " MiB (the limit is " +
                    std::to_string(kGridMaxNearBytes >> 20) +
                    " MiB): use the clustered far field "
                    "(TmMethod::Clustered, --method clustered) or a lower resolution");
    m.exact = far.method == TmMethod::Exact;
    m.grid = far.method == TmMethod::Grid;
    auto profiles = bake::to_gpu(material);
    if (!m.exact && !m.grid) {
        // The faint test of tm_cluster.comp against the total area (≥ the total weight, so
        // never laxer than against the weight).
        double area = 0;
        for (float a : mesh.areas) area += a;
        const double threshold = 1e-3 * std::pow(double(s.tm_opening_ratio), 3);
        for (int c = 0; c < 3; ++c)
            profiles[c].faint_radius = bake::faint_radius(material.profile[c], area, threshold, mesh.diagonal);
    }
    m.profiles = gpu::Buffer::from(ctx, std::span<const bake::GpuProfile>(profiles), kStorageUsage, "profiles");
    auto per_vertex = [&](const bake::PerVertexBuffer& b) {
        return gpu::Buffer(ctx, n * b.bytes_per_vertex, kStorageUsage, b.name);
    };
    m.tm = per_vertex(bake::kTmValues);
    m.normal_sum = per_vertex(bake::kTmNormalSums);
    m.partial_sum = per_vertex(bake::kTmPartialSums);
    m.partial_comp = per_vertex(bake::kTmPartialCompensation);
    if (m.grid)
        grid.prepare(m.grids, *far.grid);
    else
        grid.prepare_placeholder(m.grids);
    std::vector<uint32_t> identity;
    if (m.exact) {
        identity.resize(n);
        std::iota(identity.begin(), identity.end(), 0u);
    }
    near.prepare(m.near_lists, mesh, tree,
                 m.exact ? std::span<const uint32_t>(identity) : std::span<const uint32_t>(tree.order), m.exact,
                 near_margin, float(m.grids.r_cut));
    if (m.exact || m.grid) {
        m.point_order = m.exact ? gpu::Buffer::from(ctx, identity, kStorageUsage, "identity order")
                                : gpu::Buffer::from(ctx, tree.order, kStorageUsage, "point tree order");
        m.points = gpu::Buffer(ctx, n * bake::kTmSources.bytes_per_vertex, kTexelUsage, bake::kTmSources.name);
        m.point_texels = gpu::TexelView(ctx, m.points, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "t_m sources (texels)");
        m.source_texels =
            gpu::TexelView(ctx, m.points, VK_FORMAT_R32G32B32A32_UINT, 16, "t_m sources (integer texels)");
        return;
    }
    m.point_order = gpu::Buffer::from(ctx, tree.order, kStorageUsage, "point tree order");
    m.node_count = uint32_t(tree.nodes.size());
    m.nodes = gpu::Buffer::from(ctx, tree.nodes, kStorageUsage, "point tree nodes");
    bake::BvhLevels levels = bake::bvh_levels(tree);
    m.node_levels = gpu::Buffer::from(ctx, levels.nodes, kStorageUsage, "point tree levels");
    m.level_offsets = levels.offsets;
    // One buffer holds the nodes (4 texels each) and then the sources (2 texels each), so one
    // fetch per lane brings a node and a source (tm_cluster.comp).
    // Sources start at a texel that is a multiple of 16 (256 bytes): any device's allowed
    // offset for binding them alone as a storage buffer.
    m.first_point = (4 * m.node_count + 15) / 16 * 16;
    check_storage_range(VkDeviceSize(n) * bake::kTmSources.bytes_per_vertex, bake::kTmSources.name);
    check_storage_range(VkDeviceSize(m.node_count) * 64, "t_m cluster nodes");
    m.points = gpu::Buffer(ctx, VkDeviceSize(m.first_point) * 16 + n * bake::kTmSources.bytes_per_vertex, kTexelUsage,
                           "t_m cluster tree and sources", false,
                           gpu::StorageBinding::Windows);  // bound as two windows, each checked above
    m.tree_texels =
        gpu::TexelView(ctx, m.points, VK_FORMAT_R32G32B32A32_UINT, 16, "t_m cluster tree and sources (texels)");
    m.source_texels =
        gpu::TexelView(ctx, m.points, VK_FORMAT_R32G32B32A32_UINT, 16, "t_m cluster tree and sources (texels)");
    m.source_base = m.first_point;
    m.resume = gpu::Buffer(ctx, n * bake::kTmResume.bytes_per_vertex, kStorageUsage, bake::kTmResume.name);
}

void Baker::Impl::record_tm(VkCommandBuffer cmd, MeshState& m, const BakeSettings& s, gpu::GpuTimer* timer,
                            uint32_t slot_begin, uint32_t slot_end)
{
    auto mark = [&](const char* stage) {
        if (timer) timer->mark(cmd, stage);
    };
    const uint32_t n = m.vertex_count;
    if (m.exact) slot_begin = 0, slot_end = n;
    slot_end = std::min(slot_end, n);
    const gpu::Binding nodes_window(m.points.handle(), 0, std::max<VkDeviceSize>(VkDeviceSize(m.node_count) * 64, 16));
    const gpu::Binding points_window(m.points.handle(), VkDeviceSize(m.first_point) * 16, VkDeviceSize(n) * 32);
    gather_kernel().dispatch(cmd, n, GatherPush{n},
                             {m.positions, m.areas, m.ao, m.point_order, points_window, m.normals});
    gpu::compute_barrier(cmd);
    mark("gather");
    if (m.grid) {
        near.record(cmd, m.near_lists, m, m.grids, slot_begin, slot_end);
        mark("t_m near field");
        grid.record(cmd, m.grids, m, timer, slot_begin, slot_end);
        return;
    }
    if (!m.exact) {
        for (size_t l = 0; l + 1 < m.level_offsets.size(); ++l) {
            const uint32_t first = m.level_offsets[l], count = m.level_offsets[l + 1] - first;
            refit_kernel().dispatch(cmd, count, RefitPush{count, first},
                                    {m.nodes, m.node_levels, nodes_window, points_window});
            gpu::compute_barrier(cmd);
        }
        mark("refit");
        vkCmdFillBuffer(cmd, m.resume.handle(), 0, VK_WHOLE_SIZE, 0);
    }
    near.record(cmd, m.near_lists, m, m.grids, slot_begin, slot_end);
    mark("t_m near field");
    if (m.exact) {
        const auto& kernel = exact_kernel(m.variant, dev::study_of(s).tm_float64_sums);
        for (uint32_t begin = 0; begin < n; begin += kExactSourcesPerDispatch) {
            ExactPush push{n, begin, std::min(n, begin + kExactSourcesPerDispatch)};
            kernel.dispatch(cmd, n, push,
                            {m.profiles, m.point_texels, m.partial_sum, m.partial_comp, m.tm, m.normal_sum});
            gpu::compute_barrier(cmd);
        }
        mark("t_m far field (all pairs)");
        return;
    }
    const auto& kernel = cluster_kernel(m.variant);
    // Every thread visits each node and each source at most once: this many dispatches finish
    // every traversal; threads that are done return at once.
    const uint32_t dispatches = (m.node_count + n) / kClusterWorkPerDispatch + 1;
    ClusterPush push{n, m.node_count, s.tm_opening_ratio, kClusterWorkPerDispatch, m.first_point, slot_begin, slot_end};
    for (uint32_t d = 0; d < dispatches; ++d) {
        kernel.dispatch(
            cmd, slot_end - slot_begin, push,
            {m.profiles, m.tree_texels, m.point_order, m.resume, m.partial_sum, m.partial_comp, m.tm, m.normal_sum});
        gpu::compute_barrier(cmd);
    }
    mark("t_m far field (clustered)");
}

}  // namespace jade
