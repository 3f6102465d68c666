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
#include "bake/ray_items.hpp"
#include "bake/near_field.hpp"
#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/kernel.hpp"
#include "gpu/texel_view.hpp"
#include "gpu/timer.hpp"

#include <jade/bake.hpp>
#include <jade/context.hpp>

#include "jade_shaders.hpp"

#include <glm/common.hpp>
#include <glm/vec4.hpp>

#include <chrono>
#include <numeric>
#include <optional>

namespace jade {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kTexels = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
constexpr VkBufferUsageFlags kStorageUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
// Written by one pass as a storage buffer, fetched by the next as texels (gpu/texel_view.hpp).
constexpr VkBufferUsageFlags kTexelUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
constexpr uint32_t kTriangleLeafSize = 4;
constexpr uint32_t kPointLeafSize = 8;
// Below this many vertices the all-pairs pass is as fast as building and walking the tree.
constexpr size_t kExactBelow = 2048;

// Sources per dispatch of the all-pairs pass (8 per loop iteration), and node visits per
// dispatch of the clustered pass (one loop iteration each): lavapipe caps an invocation at
// 65,535 loop iterations, and desktop drivers reset a GPU whose dispatch runs for seconds.
constexpr uint32_t kExactSourcesPerDispatch = 16384;
constexpr uint32_t kClusterWorkPerDispatch = 32768;

struct AoPush { uint32_t vertex_count, rays, seed, low_discrepancy; float epsilon, max_distance; uint32_t item_count; };
struct AoResolvePush { uint32_t vertex_count, rays; };
struct GatherPush { uint32_t vertex_count, first_texel; };
struct RefitPush { uint32_t node_count, first_point; };
struct NearPush { uint32_t vertex_count; };
struct ExactPush { uint32_t vertex_count, source_begin, source_end; };
struct ClusterPush { uint32_t vertex_count, node_count; float epsilon; uint32_t work_budget; };

std::vector<VkDescriptorType> storage_bindings(size_t n) { return std::vector<VkDescriptorType>(n, kStorage); }

// Which t_m kernel variant a material needs: one channel when grey, and the profile kind
// shared by all channels (3: mixed kinds, chosen per channel at run time).
struct TmVariant {
    uint32_t grey;  // 1: grey
    uint32_t kind;  // 0 Burley, 1 dipole, 2 Gaussians, 3 mixed (shaders/include/profile.glsl)
};
TmVariant tm_variant(const Material& m)
{
    const ProfileKind k = m.profile[0].kind;
    const bool same = m.profile[1].kind == k && m.profile[2].kind == k;
    return {m.grey() ? 1u : 0u, same ? uint32_t(k) : 3u};
}

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
    case Quality::Draft: s.ao.rays = 16, s.tm_epsilon = 1.6f; break;
    case Quality::Default: s.ao.rays = 64, s.tm_epsilon = 1.2f; break;
    case Quality::High: s.ao.rays = 256, s.tm_epsilon = 0.4f; break;
    }
    return s;
}

struct Baker::Impl {
    gpu::Context& ctx;
    // Pipelines are made on first use: a scene that never needs one never creates it.
    std::optional<gpu::Kernel> ao_trace, ao_resolve, gather, refit;
    // t_m kernels per [grey (1 channel) or RGB][profile kind: Burley, dipole, Gaussians, mixed].
    std::optional<gpu::Kernel> tm_near[2][4], tm_exact[2][4], tm_cluster[2][4];

    explicit Impl(gpu::Context& c) : ctx(c) {}

    const gpu::Kernel& kernel(std::optional<gpu::Kernel>& slot, gpu::KernelDesc desc)
    {
        if (!slot) slot.emplace(ctx, desc);
        return *slot;
    }
    const gpu::Kernel& ao_kernel()
    {
        return kernel(ao_trace, {"ao_trace", shaders::ao_trace_comp(), {kStorage, kStorage, kTexels, kStorage},
                                 sizeof(AoPush), 64, {}});
    }
    const gpu::Kernel& ao_resolve_kernel()
    {
        return kernel(ao_resolve, {"ao_resolve", shaders::ao_resolve_comp(), storage_bindings(2), sizeof(AoResolvePush), 64, {}});
    }
    const gpu::Kernel& gather_kernel()
    {
        return kernel(gather, {"gather_sources", shaders::gather_sources_comp(), storage_bindings(5), sizeof(GatherPush), 64, {}});
    }
    const gpu::Kernel& refit_kernel()
    {
        return kernel(refit, {"cluster_refit", shaders::cluster_refit_comp(), storage_bindings(4), sizeof(RefitPush), 64, {}});
    }
    // Specialisation constants of the t_m kernels: channel count and profile kind.
    static std::vector<uint32_t> tm_constants(const TmVariant& v) { return {v.grey ? 1u : 3u, v.kind}; }
    const gpu::Kernel& near_kernel(const TmVariant& v)
    {
        return kernel(tm_near[v.grey][v.kind],
                      {"tm_near", shaders::tm_near_comp(), storage_bindings(10), sizeof(NearPush), 64, tm_constants(v)});
    }
    const gpu::Kernel& exact_kernel(const TmVariant& v)
    {
        require_subgroup_groups();
        return kernel(tm_exact[v.grey][v.kind], {"tm_exact", shaders::tm_exact_comp(),
                                                 {kStorage, kTexels, kStorage, kStorage, kStorage}, sizeof(ExactPush), 64,
                                                 tm_constants(v)});
    }
    const gpu::Kernel& cluster_kernel(const TmVariant& v)
    {
        require_subgroup_groups();
        return kernel(tm_cluster[v.grey][v.kind],
                      {"tm_cluster", shaders::tm_cluster_comp(),
                       {kStorage, kTexels, kStorage, kStorage, kStorage, kStorage, kStorage}, sizeof(ClusterPush), 64,
                       tm_constants(v)});
    }
    // The far passes share fetches across subgroups of at least 8 lanes (tm_common.glsl).
    void require_subgroup_groups() const
    {
        VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sub};
        vkGetPhysicalDeviceProperties2(ctx.physical_device(), &props);
        const VkSubgroupFeatureFlags need =
            VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
        if (sub.subgroupSize < 8 || !(sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) ||
            (sub.supportedOperations & need) != need)
            throw Error("t_m: the device's compute subgroups (" + std::to_string(sub.subgroupSize) +
                        " lanes) lack what the far passes need: 8 or more lanes with basic, vote and ballot operations");
    }

    // Buffers of one bake, alive until its submission has finished.
    struct Frame {
        gpu::Buffer positions, normals, areas, ray_items, hits, ao;
        gpu::Buffer profiles, point_order, points, nodes, node_counts, tm;
        gpu::Buffer partial_sum, partial_comp, resume, near_offsets, near_indices;
        gpu::TexelView ray_item_texels, point_texels, tree_texels;
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
        bake::RayItems items = bake::flatten_ray_items(bvh, mesh);
        f.ray_items = gpu::Buffer::from(ctx, items.texels, kTexelUsage, "ray items (BVH nodes and triangles)");
        f.ray_item_texels = gpu::TexelView(ctx, f.ray_items, VK_FORMAT_R32G32B32A32_UINT, 16, "ray items (texels)");
        f.hits = gpu::Buffer(ctx, mesh.vertex_count() * sizeof(uint32_t), kStorageUsage, "ao hit counts");
        f.ao = gpu::Buffer(ctx, mesh.vertex_count() * sizeof(float), kStorageUsage, "ao");
        return items.count();
    }

    void record_ao(VkCommandBuffer cmd, Frame& f, const PreparedMesh& mesh, const AoSettings& s, uint32_t item_count)
    {
        AoPush push{uint32_t(mesh.vertex_count()), s.rays, s.seed, s.low_discrepancy ? 1u : 0u,
                    s.epsilon_rel * mesh.diagonal, s.max_distance_rel * mesh.diagonal, item_count};
        vkCmdFillBuffer(cmd, f.hits.handle(), 0, VK_WHOLE_SIZE, 0);
        gpu::compute_barrier(cmd);
        ao_kernel().dispatch(cmd, uint64_t(mesh.vertex_count()) * s.rays, push, {f.positions, f.normals, f.ray_item_texels, f.hits});
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
    TmVariant variant;
    uint32_t node_count = 0;
};

// Records gather → near field → (all pairs | refit → clustered) reading f.ao, writing f.tm.
static TmPlan prepare_tm(Baker::Impl& impl, Baker::Impl::Frame& f, const PreparedMesh& mesh, const Material& material,
                         const BakeSettings& s)
{
    gpu::Context& ctx = impl.ctx;
    const size_t n = mesh.vertex_count();
    TmPlan plan;
    plan.variant = tm_variant(material);
    plan.exact = s.method == TmMethod::Exact || (s.method == TmMethod::Auto && n < kExactBelow);
    if (!(s.tm_epsilon > 0) || !std::isfinite(s.tm_epsilon)) throw Error("t_m: epsilon must be > 0");
    auto profiles = bake::to_gpu(material);
    if (!plan.exact) {
        // The faint test of tm_cluster.comp against the total area (≥ the total weight, so
        // never laxer than against the weight).
        double area = 0;
        for (float a : mesh.areas) area += a;
        const double threshold = 1e-3 * std::pow(double(s.tm_epsilon), 3);
        for (int c = 0; c < 3; ++c)
            profiles[c].faint_radius = bake::faint_radius(material.profile[c], area, threshold, mesh.diagonal);
    }
    f.profiles = gpu::Buffer::from(ctx, std::span<const bake::GpuProfile>(profiles), kStorageUsage, "profiles");
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
        f.points = gpu::Buffer(ctx, n * 32, kTexelUsage, "t_m sources");
        f.point_texels = gpu::TexelView(ctx, f.points, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "t_m sources (texels)");
        return plan;
    }
    plan.node_count = uint32_t(tree.nodes.size());
    f.point_order = gpu::Buffer::from(ctx, tree.order, kStorageUsage, "point tree order");
    f.nodes = gpu::Buffer::from(ctx, tree.nodes, kStorageUsage, "point tree nodes");
    f.node_counts = gpu::Buffer::from(ctx, tree.counts, kStorageUsage, "point tree counts");
    // One buffer holds the nodes (4 texels each) and then the sources (2 texels each), so one
    // fetch per lane brings a node and a source (tm_cluster.comp).
    f.points = gpu::Buffer(ctx, tree.nodes.size() * 64 + n * 32, kTexelUsage, "t_m cluster tree and sources");
    f.tree_texels = gpu::TexelView(ctx, f.points, VK_FORMAT_R32G32B32A32_UINT, 16, "t_m cluster tree and sources (texels)");
    f.resume = gpu::Buffer(ctx, n * 12, kStorageUsage, "t_m traversal resume state");
    return plan;
}

static void record_tm(Baker::Impl& impl, VkCommandBuffer cmd, Baker::Impl::Frame& f, const PreparedMesh& mesh,
                      const BakeSettings& s, const TmPlan& plan, gpu::GpuTimer& timer)
{
    const uint32_t n = uint32_t(mesh.vertex_count());
    const uint32_t first_point = 4 * plan.node_count;  // texel of source 0
    impl.gather_kernel().dispatch(cmd, n, GatherPush{n, first_point}, {f.positions, f.areas, f.ao, f.point_order, f.points});
    gpu::compute_barrier(cmd);
    timer.mark(cmd, "gather");
    auto near_pass = [&](gpu::Buffer& out) {
        impl.near_kernel(plan.variant).dispatch(cmd, n, NearPush{n}, {f.profiles, f.positions, f.areas, f.ao, f.near_offsets,
                                                                   f.near_indices, f.point_order, f.partial_sum, f.partial_comp, out});
        gpu::compute_barrier(cmd);
    };
    if (plan.exact) {
        near_pass(f.tm);
        timer.mark(cmd, "t_m near field");
        const auto& kernel = impl.exact_kernel(plan.variant);
        for (uint32_t begin = 0; begin < n; begin += kExactSourcesPerDispatch) {
            ExactPush push{n, begin, std::min(n, begin + kExactSourcesPerDispatch)};
            kernel.dispatch(cmd, n, push, {f.profiles, f.point_texels, f.partial_sum, f.partial_comp, f.tm});
            gpu::compute_barrier(cmd);
        }
        timer.mark(cmd, "t_m far field (all pairs)");
        return;
    }
    impl.refit_kernel().dispatch(cmd, plan.node_count, RefitPush{plan.node_count, first_point},
                                 {f.nodes, f.node_counts, f.points, f.points});
    gpu::compute_barrier(cmd);
    timer.mark(cmd, "refit");
    const auto& kernel = impl.cluster_kernel(plan.variant);
    // Every thread visits each node and each source at most once: this many dispatches finish
    // every traversal; threads that are done return at once.
    const uint32_t dispatches = (plan.node_count + n) / kClusterWorkPerDispatch + 1;
    vkCmdFillBuffer(cmd, f.resume.handle(), 0, VK_WHOLE_SIZE, 0);
    near_pass(f.tm);
    timer.mark(cmd, "t_m near field");
    ClusterPush push{n, plan.node_count, s.tm_epsilon, kClusterWorkPerDispatch};
    for (uint32_t d = 0; d < dispatches; ++d) {
        kernel.dispatch(cmd, n, push, {f.profiles, f.tree_texels, f.point_order, f.resume, f.partial_sum, f.partial_comp, f.tm});
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
