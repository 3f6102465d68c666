// bake/dynamic_bake.cpp - the per-frame re-bake of a deforming mesh (jade::DynamicBake): the
// static bake's passes (bake/*_pass.hpp, composed by baker_impl.hpp) recorded every frame after
// refitting both trees on the GPU, optionally a slice of the work per frame (jade::Amortisation).
#include "bake/baker_impl.hpp"

#include <jade/bake.hpp>

namespace jade {

struct DynamicBake::State {
    Baker::Impl& impl;
    gpu::Context& ctx;  // impl's: kept apart for ~DynamicBake, which must not need the Baker
    BakeSettings settings;
    Baker::Impl::MeshBake mesh;
    Amortisation amortisation;
    uint64_t frame = 0;  // record() calls since the last full re-bake
    bool stale = true;   // the next record() re-bakes everything
    State(Baker::Impl& i, const BakeSettings& s) : impl(i), ctx(i.ctx), settings(s) {}

    // Tree slots [begin, end) of t_m slice `k`: boundaries on multiples of 64 (a work group),
    // so the lanes of a subgroup stay neighbours in the tree (tm_cluster.comp).
    std::pair<uint32_t, uint32_t> tm_slice(uint32_t k) const
    {
        const uint64_t n = mesh.vertex_count, groups = (n + 63) / 64;
        const uint64_t slices = std::min<uint64_t>(amortisation.tm_slices, groups);
        const uint64_t begin = groups * (k % slices) / slices * 64, end = groups * (k % slices + 1) / slices * 64;
        return {uint32_t(std::min(begin, n)), uint32_t(std::min(end, n))};
    }

    // Inputs taken from the caller's buffers (record with buffers, bake with buffers).
    struct Inputs {
        VkBuffer positions, normals, areas;
    };
    void copy_inputs(VkCommandBuffer cmd, const Inputs& in);
    // The re-bake, with GPU timestamps per stage when `timer` is given.
    void record(VkCommandBuffer cmd, gpu::GpuTimer* timer);
    // Records (after copying `inputs` in, when given), submits, waits, reads back when asked.
    BakeResult submit(const Inputs* inputs, Clock::time_point t0, bool read_back);
};

DynamicBake::DynamicBake(Baker& baker, const PreparedMesh& rest, const Material& material, const BakeSettings& settings)
    : state_(std::make_unique<State>(*baker.impl_, bake::without_unused_passes(settings, material)))
{
    validate_ao_settings(settings.ao);
    auto& impl = state_->impl;
    // Deformers write the inputs on the GPU (or the host uploads them): transfer and storage.
    impl.upload_mesh(state_->mesh, rest, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    const bake::AoPass::Tree ray_tree = impl.ao.prepare(state_->mesh.ao_pass, state_->mesh, rest);
    impl.ray_refit.prepare(state_->mesh.ray_refit, ray_tree, rest);
    impl.thickness.prepare(state_->mesh.thickness, state_->mesh, state_->settings.thickness);
    impl.prepare_tm(state_->mesh, rest, material, settings, kDynamicNearMargin);
}

DynamicBake::~DynamicBake()
{
    // Frames the host recorded may still be running: the buffers go when the GPU is done.
    if (state_) state_->ctx.release_after_gpu(std::move(state_));
}

DynamicBake::Buffers DynamicBake::buffers() const
{
    const auto& m = state_->mesh;
    return {m.positions.handle(),
            m.normals.handle(),
            m.areas.handle(),
            m.ao.handle(),
            m.tm.handle(),
            m.vertex_count,
            m.thickness.result ? m.thickness.result.handle() : VK_NULL_HANDLE,
            m.normal_sum.handle()};
}

void DynamicBake::record(VkCommandBuffer cmd) { state_->record(cmd, nullptr); }

void DynamicBake::record(VkCommandBuffer cmd, VkBuffer positions, VkBuffer normals, VkBuffer areas)
{
    state_->copy_inputs(cmd, {positions, normals, areas});
    state_->record(cmd, nullptr);  // begins with the barrier that orders the copies before the refit
}

void DynamicBake::State::copy_inputs(VkCommandBuffer cmd, const Inputs& in)
{
    auto& m = mesh;
    gpu::compute_barrier(cmd);  // the caller's writes before the copies read them
    const VkDeviceSize n = m.vertex_count;
    const VkBufferCopy vec3s{0, 0, n * 12}, floats{0, 0, n * 4};
    vkCmdCopyBuffer(cmd, in.positions, m.positions.handle(), 1, &vec3s);
    vkCmdCopyBuffer(cmd, in.normals, m.normals.handle(), 1, &vec3s);
    vkCmdCopyBuffer(cmd, in.areas, m.areas.handle(), 1, &floats);
}

void DynamicBake::State::record(VkCommandBuffer cmd, gpu::GpuTimer* timer)
{
    auto& m = mesh;
    gpu::compute_barrier(cmd);  // the inputs' writes (transfer or compute) before the refit reads them
    impl.ray_refit.record(cmd, m.ray_refit, m);
    if (timer) timer->mark(cmd, "BVH refit");
    // Amortised: one AO slice and one t_m slice per record(), in turn; everything when stale.
    const bool full = stale;
    const uint64_t this_frame = frame;
    stale = false;
    frame = full ? 1 : this_frame + 1;
    // The ray slices of this frame: all of them (count 0) after a full re-bake, else one in turn.
    const uint32_t slice = full ? 0 : uint32_t(this_frame % m.ao_slices), slices = full ? 0 : 1;
    impl.ao.record(cmd, m.ao_pass, m, settings.ao, slice, slices, amortisation.retrace_changed);
    gpu::compute_barrier(cmd);
    if (timer) timer->mark(cmd, "ao");
    if (settings.thickness.enabled()) {
        impl.thickness.record(cmd, m.thickness, m, settings.thickness, slice, slices);
        gpu::compute_barrier(cmd);
        if (timer) timer->mark(cmd, "thickness");
    }
    const auto [begin, end] = full ? std::pair<uint32_t, uint32_t>{0, m.vertex_count}
                                   : tm_slice(uint32_t(this_frame % amortisation.tm_slices));
    impl.record_tm(cmd, m, settings, timer, begin, end);
}

void DynamicBake::set_amortisation(const Amortisation& a)
{
    const uint32_t rays = state_->settings.ao.rays;
    if (a.ao_slices == 0 || rays % a.ao_slices != 0)
        throw Error("DynamicBake: Amortisation::ao_slices (" + std::to_string(a.ao_slices) +
                    ") must be ≥ 1 and divide the " + std::to_string(rays) + " AO rays per vertex");
    if (a.tm_slices == 0) throw Error("DynamicBake: Amortisation::tm_slices must be ≥ 1");
    const uint32_t thickness_rays = state_->settings.thickness.rays;
    if (thickness_rays > 0 && thickness_rays % a.ao_slices != 0)
        throw Error("DynamicBake: Amortisation::ao_slices (" + std::to_string(a.ao_slices) + ") must divide the " +
                    std::to_string(thickness_rays) + " thickness rays per vertex too");
    auto& m = state_->mesh;
    if (a.ao_slices != m.ao_slices) {
        // Recorded frames may still use the old per-slice sums.
        state_->impl.ctx.release_after_gpu(std::move(m.ao_pass.hits), std::move(m.thickness.sums),
                                           std::move(m.ao_pass.previous), std::move(m.ao_pass.changed_list));
        m.ao_pass.set_slices(state_->impl.ctx, m.vertex_count, a.ao_slices);
        m.ao_slices = a.ao_slices;
        if (thickness_rays > 0) m.thickness.allocate_sums(state_->impl.ctx, m.vertex_count, a.ao_slices);
    }
    state_->amortisation = a;
    state_->stale = true;
}

const Amortisation& DynamicBake::amortisation() const { return state_->amortisation; }

BakeResult DynamicBake::bake(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                             std::span<const float> areas)
{
    auto& m = state_->mesh;
    if (positions.size() != m.vertex_count || normals.size() != m.vertex_count || areas.size() != m.vertex_count)
        throw Error("DynamicBake::bake: " + std::to_string(positions.size()) + " positions, " +
                    std::to_string(normals.size()) + " normals and " + std::to_string(areas.size()) +
                    " areas for a mesh of " + std::to_string(m.vertex_count) + " vertices");
    for (size_t i = 0; i < positions.size(); ++i)
        if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z) ||
            !std::isfinite(areas[i]) || areas[i] < 0)
            throw Error("DynamicBake::bake: vertex " + std::to_string(i) +
                        " has a non-finite position or a negative area");
    auto t0 = Clock::now();
    m.positions.upload(positions.data(), positions.size_bytes());
    m.normals.upload(normals.data(), normals.size_bytes());
    m.areas.upload(areas.data(), areas.size_bytes());
    return state_->submit(nullptr, t0, true);
}

BakeResult DynamicBake::bake(VkBuffer positions, VkBuffer normals, VkBuffer areas, bool read_back)
{
    const State::Inputs inputs{positions, normals, areas};
    return state_->submit(&inputs, Clock::now(), read_back);
}

BakeResult DynamicBake::State::submit(const Inputs* inputs, Clock::time_point t0, bool read_back)
{
    auto& m = mesh;
    gpu::GpuTimer timer(impl.ctx);
    impl.ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.begin(cmd);
        if (inputs) copy_inputs(cmd, *inputs);
        record(cmd, &timer);
    });
    BakeResult r;
    if (read_back) {
        r.ao = m.ao.read<float>(m.vertex_count);
        r.tm = m.tm.read<glm::vec3>(m.vertex_count);
        read_scattering_normals(r, m.normal_sum, m.normals, m.vertex_count);
        if (m.thickness.result) r.thickness = m.thickness.result.read<float>(m.vertex_count);
    }
    r.method_used = m.method();
    r.tm_bytes = m.tm_bytes();
    finish_timings(r.timings, timer, 0, t0);
    return r;
}

}  // namespace jade
