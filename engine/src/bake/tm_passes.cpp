// bake/tm_passes.cpp - how Baker::Impl runs the t_m passes: set-up (the far field's choice, the
// shared t_m buffers, then each pass's own: near lists, grids or cluster tree) and recording
// (gather → near field → all pairs | refit → clustered | grid). Recorded by the static bake and
// by DynamicBake.
#include "bake/baker_impl.hpp"
#include "bake/far_field.hpp"

namespace jade {

void Baker::Impl::prepare_tm(MeshBake& m, const PreparedMesh& mesh, const Material& material, const BakeSettings& s,
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
    clustered.prepare(m.cluster_tree, m, tree);
}

void Baker::Impl::record_tm(VkCommandBuffer cmd, MeshBake& m, const BakeSettings& s, gpu::GpuTimer* timer,
                            uint32_t slot_begin, uint32_t slot_end)
{
    auto mark = [&](const char* stage) {
        if (timer) timer->mark(cmd, stage);
    };
    const uint32_t n = m.vertex_count;
    if (m.exact) slot_begin = 0, slot_end = n;
    slot_end = std::min(slot_end, n);
    gather.record(cmd, m);
    gpu::compute_barrier(cmd);
    mark("gather");
    if (m.grid) {
        near.record(cmd, m.near_lists, m, m.grids, slot_begin, slot_end);
        mark("t_m near field");
        grid.record(cmd, m.grids, m, timer, slot_begin, slot_end);
        return;
    }
    if (!m.exact) clustered.record_refit(cmd, m.cluster_tree, m, timer);
    near.record(cmd, m.near_lists, m, m.grids, slot_begin, slot_end);
    mark("t_m near field");
    if (m.exact) {
        exact.record(cmd, m, dev::study_of(s).tm_float64_sums);
        mark("t_m far field (all pairs)");
        return;
    }
    clustered.record(cmd, m.cluster_tree, m, s.tm_opening_ratio, slot_begin, slot_end);
    mark("t_m far field (clustered)");
}

}  // namespace jade
