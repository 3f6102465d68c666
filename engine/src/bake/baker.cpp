// bake/baker.cpp - the GPU bake: AO, then t_m, in one submission (the passes are bake/*_pass.hpp,
// composed by Baker::Impl, bake/baker_impl.hpp; the per-frame re-bake of a deforming mesh, which
// records the same passes after refitting both trees, is bake/dynamic_bake.cpp).
//
// Data flow (all on the GPU after one upload):
//   positions, indices                                      -> ray_refit      -> ray items (dynamic only)
//   positions, normals, ray items (BVH nodes + triangles)   -> ao_trace       -> hit counts
//   hit counts                                              -> ao_resolve     -> ao
//   positions, normals, ray items                           -> thickness_trace -> distance sums (optional)
//   distance sums                                           -> thickness_resolve -> thickness
//   positions, areas, ao, point-tree order                  -> gather_sources -> sources (tree order)
//   sources                                                 -> cluster_refit  -> cluster nodes (per level)
//   positions, areas, ao, near lists                        -> tm_near        -> partial sums (disk pairs, self)
//   cluster nodes, sources, partial sums                    -> tm_cluster ×K  -> t_m
// The exact method replaces the refit and tm_cluster by tm_exact over chunks of sources.
// Long sums are split over several dispatches that resume from saved partial sums: lavapipe
// ends an invocation after 65,535 loop iterations in total (docs/lavapipe.md), and desktop
// drivers reset a GPU that runs one dispatch for seconds.
#include "bake/baker_impl.hpp"

#include <jade/dev/names.hpp>

namespace jade {

const dev::BakeStudy& dev::study_of(const BakeSettings& settings)
{
    static const BakeStudy defaults;
    return settings.study ? *settings.study : defaults;
}

void dev::set_study(BakeSettings& settings, const BakeStudy& study)
{
    settings.study = std::make_shared<const BakeStudy>(study);
}

BakeSettings BakeSettings::preset(Quality q)
{
    BakeSettings s;
    switch (q) {
    case Quality::Draft:
        s.ao.rays = 16, s.thickness.rays = 16, s.tm_opening_ratio = 1.6f, s.tm_grid_resolution = 1.5f;
        break;
    case Quality::Default:
        s.ao.rays = 64, s.thickness.rays = 32, s.tm_opening_ratio = 1.2f, s.tm_grid_resolution = 2.0f;
        break;
    case Quality::High:
        s.ao.rays = 256, s.thickness.rays = 64, s.tm_opening_ratio = 0.4f, s.tm_grid_resolution = 3.0f;
        break;
    }
    return s;
}

const char* dev::quality_name(Quality quality)
{
    switch (quality) {
    case Quality::Draft: return "draft";
    case Quality::High: return "high";
    case Quality::Default: break;
    }
    return "default";
}

Quality dev::parse_quality(std::string_view name)
{
    for (Quality q : {Quality::Draft, Quality::Default, Quality::High})
        if (name == dev::quality_name(q)) return q;
    throw Error("unknown quality '" + std::string(name) + "' (draft, default or high)");
}

const char* dev::tm_method_name(TmMethod method)
{
    switch (method) {
    case TmMethod::Exact: return "exact";
    case TmMethod::Clustered: return "clustered";
    case TmMethod::Grid: return "grid";
    case TmMethod::Auto: break;
    }
    return "auto";
}

TmMethod dev::parse_tm_method(std::string_view name)
{
    for (TmMethod m : {TmMethod::Auto, TmMethod::Exact, TmMethod::Clustered, TmMethod::Grid})
        if (name == dev::tm_method_name(m)) return m;
    throw Error("unknown t_m method '" + std::string(name) + "' (auto, exact, clustered or grid)");
}

// What every static bake reads back after its one submission: t_m with its scattering normals,
// how t_m was summed, and the timings (after the read-backs, which the wall time includes).
void Baker::Impl::read_tm_result(BakeResult& r, const MeshBake& m, const gpu::GpuTimer& timer, double setup,
                                 Clock::time_point t0)
{
    r.tm = m.tm.read<glm::vec3>(m.vertex_count);
    read_scattering_normals(r, m.normal_sum, m.normals, m.vertex_count);
    r.method_used = m.method();
    r.tm_bytes = m.tm_bytes();
    finish_timings(r.timings, timer, setup, t0);
}

Baker::Baker(Context& context) : impl_(std::make_unique<Impl>(gpu_of(context))) {}
Baker::~Baker() = default;

BakeResult Baker::bake(const PreparedMesh& mesh, const Material& material, const BakeSettings& requested)
{
    validate_ao_settings(requested.ao);
    const BakeSettings settings = bake::without_unused_passes(requested, material);
    auto t0 = Clock::now();
    Impl::MeshBake m;
    impl_->upload_mesh(m, mesh);
    impl_->ao.prepare(m.ao_pass, m, mesh);
    impl_->thickness.prepare(m.thickness, m, settings.thickness);
    impl_->prepare_tm(m, mesh, material, settings, kStaticNearMargin);
    double setup = ms_since(t0);
    gpu::GpuTimer timer(impl_->ctx);
    impl_->ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        impl_->ao.record(cmd, m.ao_pass, m, settings.ao);
        gpu::compute_barrier(cmd);
        timer.mark(cmd, "ao");
        if (settings.thickness.enabled()) {
            impl_->thickness.record(cmd, m.thickness, m, settings.thickness);
            gpu::compute_barrier(cmd);
            timer.mark(cmd, "thickness");
        }
        impl_->record_tm(cmd, m, settings, &timer);
    });
    BakeResult r;
    r.ao = m.ao.read<float>(mesh.vertex_count());
    if (settings.thickness.enabled()) r.thickness = m.thickness.result.read<float>(mesh.vertex_count());
    Impl::read_tm_result(r, m, timer, setup, t0);
    return r;
}

// The partial bakes of jade/dev/bake.hpp.
struct dev::BakerAccess {
    using Impl = Baker::Impl;
    static Impl& impl(Baker& baker) { return *baker.impl_; }
};

std::vector<float> dev::bake_ao(Baker& baker, const PreparedMesh& mesh, const AoSettings& settings,
                                BakeTimings* timings)
{
    BakerAccess::Impl& impl = BakerAccess::impl(baker);
    validate_ao_settings(settings);
    auto t0 = Clock::now();
    BakerAccess::Impl::MeshBake m;
    impl.upload_mesh(m, mesh);
    impl.ao.prepare(m.ao_pass, m, mesh);
    double setup = ms_since(t0);
    gpu::GpuTimer timer(impl.ctx);
    impl.ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        impl.ao.record(cmd, m.ao_pass, m, settings);
        timer.mark(cmd, "ao");
    });
    auto ao = m.ao.read<float>(mesh.vertex_count());
    if (timings) finish_timings(*timings, timer, setup, t0);
    return ao;
}

BakeResult dev::bake_tm(Baker& baker, const PreparedMesh& mesh, std::span<const float> ao, const Material& material,
                        const BakeSettings& settings)
{
    BakerAccess::Impl& impl = BakerAccess::impl(baker);
    if (ao.size() != mesh.vertex_count())
        throw Error("bake_tm: " + std::to_string(ao.size()) + " AO values for " + std::to_string(mesh.vertex_count()) +
                    " vertices");
    auto t0 = Clock::now();
    BakerAccess::Impl::MeshBake m;
    impl.upload_mesh(m, mesh);
    m.ao = gpu::Buffer::from(impl.ctx, ao, kStorageUsage, "ao (given)");
    impl.prepare_tm(m, mesh, material, settings, kStaticNearMargin);
    double setup = ms_since(t0);
    gpu::GpuTimer timer(impl.ctx);
    impl.ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        impl.record_tm(cmd, m, settings, &timer);
    });
    BakeResult r;
    r.ao.assign(ao.begin(), ao.end());
    BakerAccess::Impl::read_tm_result(r, m, timer, setup, t0);
    return r;
}

}  // namespace jade
