// bake/baker.cpp - the GPU bake: AO, then t_m, in one submission.
//
// Data flow (all on the GPU after one upload):
//   positions, normals, triangle corners (BVH order), BVH   -> ao_trace       -> hit counts
//   hit counts                                              -> ao_resolve     -> ao
//   positions, areas, ao, point-tree order                  -> gather_sources -> sources, visibility (tree order)
//   positions, areas, ao, near lists                        -> tm_near        -> partial sums (disk pairs, self)
//   sources, visibility                                     -> cluster_refit  -> node bounds, clusters
//   sources, visibility, clusters, partial sums             -> tm_cluster ×K  -> t_m
// The exact method replaces the last three steps by tm_exact over chunks of sources.
// Long sums are split over several dispatches that resume from saved partial sums: lavapipe
// ends an invocation after 65,535 loop iterations in total (docs/lavapipe.md), and desktop
// drivers reset a GPU that runs one dispatch for seconds.
#include "bake/gpu_profile.hpp"
#include "bake/bvh.hpp"
#include "bake/near_field.hpp"
#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/kernel.hpp"
#include "gpu/timer.hpp"

#include <jade/bake.hpp>
#include <jade/context.hpp>

#include "jade_shaders.hpp"

#include <glm/common.hpp>

#include <chrono>
#include <numeric>
#include <optional>

namespace jade {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkBufferUsageFlags kStorageUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
constexpr uint32_t kTriangleLeafSize = 4;
constexpr uint32_t kPointLeafSize = 8;
// Below this many vertices the all-pairs pass is as fast as building and walking the tree.
constexpr size_t kExactBelow = 2048;

// Sources per dispatch of the all-pairs pass, and node visits + leaf sources per dispatch of
// the clustered pass: each costs a few loop iterations (channels, quadrature) of the 65,535.
constexpr uint32_t kExactSourcesPerDispatch = 2048;
constexpr uint32_t kClusterWorkPerDispatch = 2048;

struct AoPush { uint32_t vertex_count, rays, seed, low_discrepancy; float epsilon, max_distance; uint32_t node_count; };
struct AoResolvePush { uint32_t vertex_count, rays; };
struct GatherPush { uint32_t vertex_count; };
struct RefitPush { uint32_t node_count; };
struct NearPush { uint32_t vertex_count; };
struct ExactPush { uint32_t vertex_count, source_begin, source_end; };
struct ClusterPush { uint32_t vertex_count, node_count; float epsilon; uint32_t work_budget; };

std::vector<VkDescriptorType> storage_bindings(size_t n) { return std::vector<VkDescriptorType>(n, kStorage); }

void validate_ao_settings(const AoSettings& s)
{
    if (s.rays == 0 || s.rays > 65536) throw Error("AO: rays per vertex must be in 1..65536, got " + std::to_string(s.rays));
    if (!(s.max_distance_rel > 0) || !std::isfinite(s.max_distance_rel))
        throw Error("AO: max distance must be a positive fraction of the diagonal");
    if (!(s.epsilon_rel >= 0) || !std::isfinite(s.epsilon_rel)) throw Error("AO: epsilon must be ≥ 0");
}

}  // namespace

BakeSettings BakeSettings::preset(Quality q)
{
    BakeSettings s;
    switch (q) {
    case Quality::Draft: s.ao.rays = 16, s.tm_epsilon = 1.2f; break;
    case Quality::Default: s.ao.rays = 64, s.tm_epsilon = 0.8f; break;
    case Quality::High: s.ao.rays = 256, s.tm_epsilon = 0.4f; break;
    }
    return s;
}

struct Baker::Impl {
    gpu::Context& ctx;
    // Pipelines are made on first use: a scene that never needs one never creates it.
    std::optional<gpu::Kernel> ao_trace, ao_resolve, gather, refit;
    std::optional<gpu::Kernel> tm_near[2], tm_exact[2], tm_cluster[2];  // [0]: grey (1 channel), [1]: RGB

    explicit Impl(gpu::Context& c) : ctx(c) {}

    const gpu::Kernel& kernel(std::optional<gpu::Kernel>& slot, gpu::KernelDesc desc)
    {
        if (!slot) slot.emplace(ctx, desc);
        return *slot;
    }
    const gpu::Kernel& ao_kernel()
    {
        return kernel(ao_trace, {"ao_trace", shaders::ao_trace_comp(), storage_bindings(6), sizeof(AoPush), 64, {}});
    }
    const gpu::Kernel& ao_resolve_kernel()
    {
        return kernel(ao_resolve, {"ao_resolve", shaders::ao_resolve_comp(), storage_bindings(2), sizeof(AoResolvePush), 64, {}});
    }
    const gpu::Kernel& gather_kernel()
    {
        return kernel(gather, {"gather_sources", shaders::gather_sources_comp(), storage_bindings(6), sizeof(GatherPush), 64, {}});
    }
    const gpu::Kernel& refit_kernel()
    {
        return kernel(refit, {"cluster_refit", shaders::cluster_refit_comp(), storage_bindings(5), sizeof(RefitPush), 64, {}});
    }
    const gpu::Kernel& near_kernel(bool grey)
    {
        return kernel(tm_near[grey ? 0 : 1], {grey ? "tm_near (grey)" : "tm_near", shaders::tm_near_comp(),
                                              storage_bindings(10), sizeof(NearPush), 64, {grey ? 1u : 3u}});
    }
    const gpu::Kernel& exact_kernel(bool grey)
    {
        return kernel(tm_exact[grey ? 0 : 1], {grey ? "tm_exact (grey)" : "tm_exact", shaders::tm_exact_comp(),
                                               storage_bindings(6), sizeof(ExactPush), 64, {grey ? 1u : 3u}});
    }
    const gpu::Kernel& cluster_kernel(bool grey)
    {
        return kernel(tm_cluster[grey ? 0 : 1], {grey ? "tm_cluster (grey)" : "tm_cluster", shaders::tm_cluster_comp(),
                                                 storage_bindings(11), sizeof(ClusterPush), 64, {grey ? 1u : 3u}});
    }

    // Buffers of one bake, alive until its submission has finished.
    struct Frame {
        gpu::Buffer positions, normals, areas, corners, tri_nodes, tri_counts, hits, ao;
        gpu::Buffer profiles, point_order, sources, visibility, nodes, node_counts, clusters, tm;
        gpu::Buffer partial_sum, partial_comp, resume, near_offsets, near_indices;
    };

    void upload_mesh(Frame& f, const PreparedMesh& mesh)
    {
        f.positions = gpu::Buffer::from(ctx, mesh.positions, kStorageUsage, "positions");
        f.normals = gpu::Buffer::from(ctx, mesh.normals, kStorageUsage, "normals");
        f.areas = gpu::Buffer::from(ctx, mesh.areas, kStorageUsage, "areas");
    }

    uint32_t prepare_ao(Frame& f, const PreparedMesh& mesh)
    {
        const size_t tris = mesh.triangle_count();
        std::vector<glm::vec3> lo(tris), hi(tris);
        for (size_t t = 0; t < tris; ++t) {
            glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                      c = mesh.positions[mesh.indices[3 * t + 2]];
            lo[t] = glm::min(a, glm::min(b, c));
            hi[t] = glm::max(a, glm::max(b, c));
        }
        bake::Bvh bvh = bake::build_bvh(lo, hi, kTriangleLeafSize);
        std::vector<glm::vec3> corners(3 * tris);
        for (size_t k = 0; k < tris; ++k)
            for (int c = 0; c < 3; ++c) corners[3 * k + c] = mesh.positions[mesh.indices[3 * bvh.order[k] + c]];
        f.corners = gpu::Buffer::from(ctx, corners, kStorageUsage, "triangle corners (BVH order)");
        f.tri_nodes = gpu::Buffer::from(ctx, bvh.nodes, kStorageUsage, "triangle BVH nodes");
        f.tri_counts = gpu::Buffer::from(ctx, bvh.counts, kStorageUsage, "triangle BVH counts");
        f.hits = gpu::Buffer(ctx, mesh.vertex_count() * sizeof(uint32_t), kStorageUsage, "ao hit counts");
        f.ao = gpu::Buffer(ctx, mesh.vertex_count() * sizeof(float), kStorageUsage, "ao");
        return uint32_t(bvh.nodes.size());
    }

    void record_ao(VkCommandBuffer cmd, Frame& f, const PreparedMesh& mesh, const AoSettings& s, uint32_t node_count)
    {
        AoPush push{uint32_t(mesh.vertex_count()), s.rays, s.seed, s.low_discrepancy ? 1u : 0u,
                    s.epsilon_rel * mesh.diagonal, s.max_distance_rel * mesh.diagonal, node_count};
        vkCmdFillBuffer(cmd, f.hits.handle(), 0, VK_WHOLE_SIZE, 0);
        gpu::compute_barrier(cmd);
        ao_kernel().dispatch(cmd, uint64_t(mesh.vertex_count()) * s.rays, push,
                             {f.positions, f.normals, f.corners, f.tri_nodes, f.tri_counts, f.hits});
        gpu::compute_barrier(cmd);
        ao_resolve_kernel().dispatch(cmd, mesh.vertex_count(), AoResolvePush{uint32_t(mesh.vertex_count()), s.rays},
                                     {f.hits, f.ao});
    }
};

Baker::Baker(Context& context) : impl_(std::make_unique<Impl>(context.gpu())) {}
Baker::~Baker() = default;

std::vector<float> Baker::bake_ao(const PreparedMesh& mesh, const AoSettings& settings, BakeTimings* timings)
{
    validate_ao_settings(settings);
    auto t0 = Clock::now();
    Impl::Frame f;
    impl_->upload_mesh(f, mesh);
    uint32_t nodes = impl_->prepare_ao(f, mesh);
    double setup = ms_since(t0);
    gpu::GpuTimer timer(impl_->ctx);
    impl_->ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        impl_->record_ao(cmd, f, mesh, settings, nodes);
        timer.mark(cmd, "ao");
    });
    auto ao = f.ao.read<float>(mesh.vertex_count());
    if (timings) {
        timings->gpu_stages = timer.stages();
        timings->gpu_total_ms = timer.total_ms();
        timings->setup_ms = setup;
        timings->wall_ms = ms_since(t0);
    }
    return ao;
}

}  // namespace jade

namespace jade {

namespace {

bake::Bvh build_point_tree(const PreparedMesh& mesh)
{
    return bake::build_bvh(mesh.positions, mesh.positions, kPointLeafSize);
}

}  // namespace

struct TmPlan {
    bool exact;
    bool grey;
    uint32_t node_count = 0;
};

// Records gather → near field → (all pairs | refit → clustered) reading f.ao, writing f.tm.
static TmPlan prepare_tm(Baker::Impl& impl, Baker::Impl::Frame& f, const PreparedMesh& mesh, const Material& material,
                         const BakeSettings& s)
{
    gpu::Context& ctx = impl.ctx;
    const size_t n = mesh.vertex_count();
    TmPlan plan;
    plan.grey = material.grey();
    plan.exact = s.method == TmMethod::Exact || (s.method == TmMethod::Auto && n < kExactBelow);
    if (!(s.tm_epsilon > 0) || !std::isfinite(s.tm_epsilon)) throw Error("t_m: epsilon must be > 0");
    auto profiles = bake::to_gpu(material);
    f.profiles = gpu::Buffer::from(ctx, std::span<const bake::GpuProfile>(profiles), kStorageUsage, "profiles");
    f.sources = gpu::Buffer(ctx, n * 16, kStorageUsage, "t_m sources");
    f.visibility = gpu::Buffer(ctx, n * 4, kStorageUsage, "t_m visibility");
    f.tm = gpu::Buffer(ctx, n * 12, kStorageUsage, "t_m");
    f.partial_sum = gpu::Buffer(ctx, n * 12, kStorageUsage, "t_m partial sums");
    f.partial_comp = gpu::Buffer(ctx, n * 12, kStorageUsage, "t_m partial compensation");
    bake::Bvh tree = build_point_tree(mesh);
    bake::NearLists near = bake::build_near_lists(mesh, tree);
    f.near_offsets = gpu::Buffer::from(ctx, near.offsets, kStorageUsage, "near-field offsets");
    f.near_indices = gpu::Buffer::from(ctx, near.indices, kStorageUsage, "near-field sources");
    if (plan.exact) {
        std::vector<uint32_t> identity(n);
        std::iota(identity.begin(), identity.end(), 0u);
        f.point_order = gpu::Buffer::from(ctx, identity, kStorageUsage, "identity order");
        return plan;
    }
    plan.node_count = uint32_t(tree.nodes.size());
    f.point_order = gpu::Buffer::from(ctx, tree.order, kStorageUsage, "point tree order");
    f.nodes = gpu::Buffer::from(ctx, tree.nodes, kStorageUsage, "point tree nodes");
    f.node_counts = gpu::Buffer::from(ctx, tree.counts, kStorageUsage, "point tree counts");
    f.clusters = gpu::Buffer(ctx, tree.nodes.size() * 48, kStorageUsage, "clusters");
    f.resume = gpu::Buffer(ctx, n * 4, kStorageUsage, "t_m traversal resume node");
    return plan;
}

static void record_tm(Baker::Impl& impl, VkCommandBuffer cmd, Baker::Impl::Frame& f, const PreparedMesh& mesh,
                      const BakeSettings& s, const TmPlan& plan, gpu::GpuTimer& timer)
{
    const uint32_t n = uint32_t(mesh.vertex_count());
    impl.gather_kernel().dispatch(cmd, n, GatherPush{n}, {f.positions, f.areas, f.ao, f.point_order, f.sources, f.visibility});
    gpu::compute_barrier(cmd);
    timer.mark(cmd, "gather");
    auto near_pass = [&](gpu::Buffer& out) {
        impl.near_kernel(plan.grey).dispatch(cmd, n, NearPush{n}, {f.profiles, f.positions, f.areas, f.ao, f.near_offsets,
                                                                   f.near_indices, f.point_order, f.partial_sum, f.partial_comp, out});
        gpu::compute_barrier(cmd);
    };
    if (plan.exact) {
        near_pass(f.tm);
        timer.mark(cmd, "t_m near field");
        const auto& kernel = impl.exact_kernel(plan.grey);
        for (uint32_t begin = 0; begin < n; begin += kExactSourcesPerDispatch) {
            ExactPush push{n, begin, std::min(n, begin + kExactSourcesPerDispatch)};
            kernel.dispatch(cmd, n, push, {f.profiles, f.sources, f.visibility, f.partial_sum, f.partial_comp, f.tm});
            gpu::compute_barrier(cmd);
        }
        timer.mark(cmd, "t_m far field (all pairs)");
        return;
    }
    impl.refit_kernel().dispatch(cmd, plan.node_count, RefitPush{plan.node_count},
                                 {f.nodes, f.node_counts, f.sources, f.visibility, f.clusters});
    gpu::compute_barrier(cmd);
    timer.mark(cmd, "refit");
    const auto& kernel = impl.cluster_kernel(plan.grey);
    // Every thread visits each node at most once and each source at most once: this many
    // dispatches finish every traversal; threads that are done return at once.
    const uint32_t dispatches = (plan.node_count + n) / kClusterWorkPerDispatch + 1;
    vkCmdFillBuffer(cmd, f.resume.handle(), 0, VK_WHOLE_SIZE, 0);
    near_pass(f.tm);
    timer.mark(cmd, "t_m near field");
    ClusterPush push{n, plan.node_count, s.tm_epsilon, kClusterWorkPerDispatch};
    for (uint32_t d = 0; d < dispatches; ++d) {
        kernel.dispatch(cmd, n, push, {f.profiles, f.sources, f.visibility, f.nodes, f.node_counts, f.clusters,
                                       f.point_order, f.resume, f.partial_sum, f.partial_comp, f.tm});
        gpu::compute_barrier(cmd);
    }
    timer.mark(cmd, "t_m far field (clustered)");
}

static void finish_timings(BakeTimings& t, const gpu::GpuTimer& timer, double setup, Clock::time_point t0)
{
    t.gpu_stages = timer.stages();
    t.gpu_total_ms = timer.total_ms();
    t.setup_ms = setup;
    t.wall_ms = ms_since(t0);
}

BakeResult Baker::bake_tm(const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                          const BakeSettings& settings)
{
    if (ao.size() != mesh.vertex_count())
        throw Error("bake_tm: " + std::to_string(ao.size()) + " AO values for " + std::to_string(mesh.vertex_count()) + " vertices");
    auto t0 = Clock::now();
    Impl::Frame f;
    impl_->upload_mesh(f, mesh);
    f.ao = gpu::Buffer::from(impl_->ctx, ao, kStorageUsage, "ao (given)");
    TmPlan plan = prepare_tm(*impl_, f, mesh, material, settings);
    double setup = ms_since(t0);
    gpu::GpuTimer timer(impl_->ctx);
    impl_->ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        record_tm(*impl_, cmd, f, mesh, settings, plan, timer);
    });
    BakeResult r;
    r.ao.assign(ao.begin(), ao.end());
    r.tm = f.tm.read<glm::vec3>(mesh.vertex_count());
    r.method_used = plan.exact ? TmMethod::Exact : TmMethod::Clustered;
    finish_timings(r.timings, timer, setup, t0);
    return r;
}

BakeResult Baker::bake(const PreparedMesh& mesh, const Material& material, const BakeSettings& settings)
{
    validate_ao_settings(settings.ao);
    auto t0 = Clock::now();
    Impl::Frame f;
    impl_->upload_mesh(f, mesh);
    uint32_t tri_nodes = impl_->prepare_ao(f, mesh);
    TmPlan plan = prepare_tm(*impl_, f, mesh, material, settings);
    double setup = ms_since(t0);
    gpu::GpuTimer timer(impl_->ctx);
    impl_->ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        impl_->record_ao(cmd, f, mesh, settings.ao, tri_nodes);
        gpu::compute_barrier(cmd);
        timer.mark(cmd, "ao");
        record_tm(*impl_, cmd, f, mesh, settings, plan, timer);
    });
    BakeResult r;
    r.ao = f.ao.read<float>(mesh.vertex_count());
    r.tm = f.tm.read<glm::vec3>(mesh.vertex_count());
    r.method_used = plan.exact ? TmMethod::Exact : TmMethod::Clustered;
    finish_timings(r.timings, timer, setup, t0);
    return r;
}

}  // namespace jade
