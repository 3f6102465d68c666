// deform/mesh_deformer.cpp - jade::MeshDeformer: the GPU passes that move the bake vertices
// (procedural or skinned) and recompute normals and areas, each a gpu::Kernel.
#include <jade/dev/clock.hpp>
#include <jade/context.hpp>
#include <jade/deform.hpp>
#include <jade/dev/deform.hpp>
#include <jade/error.hpp>

#include "deform/buffer_estimate.hpp"
#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/kernel.hpp"
#include "gpu/timer.hpp"

#include <jade_shaders.hpp>

#include "deform_interface.h"  // the shaders' push constants

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <chrono>
#include <functional>
#include <cmath>
#include <optional>

namespace jade {

namespace {

constexpr VkBufferUsageFlags kStorage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr double kTwoPi = 6.283185307179586;
using gpu::storage_bindings;

// The shaders' push constants: deform_interface.h.
using deform::NormalsPush, deform::ProceduralPush, deform::SkinPush, deform::TrianglesPush;
static_assert(uint32_t(DeformerKind::Bend) == JADE_DEFORM_BEND && uint32_t(DeformerKind::Twist) == JADE_DEFORM_TWIST &&
              uint32_t(DeformerKind::Squash) == JADE_DEFORM_SQUASH && uint32_t(DeformerKind::Wave) == JADE_DEFORM_WAVE);

/// A buffer holding `data`, at least gpu::kMinBufferBytes (Vulkan has no empty buffers; the
/// shaders do not read past the counts they get).
template <class T>
gpu::Buffer make_buffer(gpu::Context& ctx, const std::vector<T>& data, const char* name, bool host_visible = false)
{
    gpu::Buffer b(ctx, data.size() * sizeof(T), kStorage, name, host_visible);
    if (!data.empty()) b.upload(data.data(), data.size() * sizeof(T));
    return b;
}

// Bytes per triangle of the cross products (deform_triangles.comp: xyz the cross product, w the area).
constexpr VkDeviceSize kTriangleBytes = sizeof(glm::vec4);

}  // namespace

// The buffers of MeshDeformer::Impl's constructor below, in its order.
std::vector<dev::BufferEstimate> deform::estimate_buffers(size_t n, size_t tris)
{
    auto bytes = [](size_t b) { return std::max<uint64_t>(gpu::kMinBufferBytes, b); };
    const size_t vec3 = sizeof(glm::vec3), word = sizeof(uint32_t);
    return {{"deform: rest positions", bytes(vec3 * n)},
            {"deform: triangles", bytes(3 * word * tris)},
            {"deform: adjacency offsets", bytes(word * (n + 1))},
            {"deform: adjacent triangles", bytes(3 * word * tris)},
            {"deform: triangle cross products", bytes(kTriangleBytes * tris)},
            {"deform: deformed positions", bytes(vec3 * n)},
            {"deform: deformed normals", bytes(vec3 * n)},
            {"deform: deformed areas", bytes(sizeof(float) * n)}};
}

struct MeshDeformer::Impl {
    gpu::Context& ctx;
    uint32_t n, triangle_count;
    gpu::Kernel procedural, skin, triangles_kernel, normals_kernel;
    gpu::Buffer rest, indices, adjacency_offsets, adjacent_triangles, triangles, positions, normals, areas;
    // Skinning: set by set_skin.
    struct SkinSizes {
        uint32_t joint_count, morph_count;
    };
    std::optional<SkinSizes> binding_sizes;
    gpu::Buffer morph_deltas, morph_weights, joints, weights, joint_matrices;

    Impl(gpu::Context& c, const PreparedMesh& mesh)
        : ctx(c), n(uint32_t(mesh.vertex_count())), triangle_count(uint32_t(mesh.triangle_count())),
          procedural(c, {"deform_procedural",
                         shaders::deform_procedural_comp(),
                         storage_bindings(2),
                         sizeof(ProceduralPush),
                         64,
                         {}}),
          skin(c, {"deform_skin", shaders::deform_skin_comp(), storage_bindings(7), sizeof(SkinPush), 64, {}}),
          triangles_kernel(c, {"deform_triangles",
                               shaders::deform_triangles_comp(),
                               storage_bindings(3),
                               sizeof(TrianglesPush),
                               64,
                               {}}),
          normals_kernel(
              c, {"deform_normals", shaders::deform_normals_comp(), storage_bindings(5), sizeof(NormalsPush), 64, {}})
    {
        // Each vertex's adjacent triangles, in ascending triangle order (the order prepare.cpp
        // visits them in, which decides ties of the largest triangle).
        std::vector<uint32_t> offsets(size_t(n) + 1, 0), list(mesh.indices.size());
        for (uint32_t v : mesh.indices) ++offsets[size_t(v) + 1];
        for (size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
        std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
        for (size_t i = 0; i < mesh.indices.size(); ++i) list[fill[mesh.indices[i]]++] = uint32_t(i / 3);
        rest = make_buffer(ctx, mesh.positions, "deform: rest positions");
        indices = make_buffer(ctx, mesh.indices, "deform: triangles");
        adjacency_offsets = make_buffer(ctx, offsets, "deform: adjacency offsets");
        adjacent_triangles = make_buffer(ctx, list, "deform: adjacent triangles");
        triangles = gpu::Buffer(ctx, VkDeviceSize(triangle_count) * kTriangleBytes, kStorage,
                                "deform: triangle cross products");
        positions = make_buffer(ctx, mesh.positions, "deform: deformed positions");
        normals = make_buffer(ctx, mesh.normals, "deform: deformed normals");
        areas = make_buffer(ctx, mesh.areas, "deform: deformed areas");
    }

    /// The deform pass `record_deform`, then normals and areas, with the barriers between.
    void record(VkCommandBuffer cmd, const std::function<void(VkCommandBuffer)>& record_deform, gpu::GpuTimer* timer)
    {
        // Each barrier comes before its stage's timestamp: lavapipe writes a timestamp when it
        // reaches it in the command stream, while the dispatch before it may still be running.
        record_deform(cmd);
        gpu::compute_barrier(cmd);
        if (timer) timer->mark(cmd, "deform");
        // Normals in two passes: each triangle's cross product once (as prepare.cpp computes it),
        // then each vertex gathers its triangles' (a third of the loads of computing them per
        // vertex, and no atomics).
        triangles_kernel.dispatch(cmd, triangle_count, TrianglesPush{triangle_count}, {positions, indices, triangles});
        gpu::compute_barrier(cmd);
        normals_kernel.dispatch(cmd, n, NormalsPush{n},
                                {triangles, adjacency_offsets, adjacent_triangles, normals, areas});
        gpu::compute_barrier(cmd);  // the results are read by the next pass or the host
        if (timer) timer->mark(cmd, "normals");
    }

    DeformTimings run(const std::function<void(VkCommandBuffer)>& record_deform)
    {
        const auto t0 = std::chrono::steady_clock::now();
        gpu::GpuTimer timer(ctx, 4);
        ctx.submit_and_wait([&](VkCommandBuffer cmd) {
            timer.begin(cmd);
            record(cmd, record_deform, &timer);
        });
        const auto stages = timer.stages();
        DeformTimings t;
        t.deform_ms = stages.at(0).second;
        t.normals_ms = stages.at(1).second;
        t.wall_ms = ms_since(t0);
        return t;
    }

    std::function<void(VkCommandBuffer)> procedural_pass(const ProceduralDeformer& d, double t)
    {
        dev::validate_deformer(d);
        if (!std::isfinite(t)) throw Error("deform: time is not finite");
        const double s = std::sin(kTwoPi * t / d.period);
        ProceduralPush push{n, uint32_t(d.kind), d.axis, 0.0f, d.origin, 0.0f, 0.0f};
        switch (d.kind) {
        case DeformerKind::Bend: push.amount = float(d.amplitude * s / d.length); break;
        case DeformerKind::Twist: push.amount = float(d.amplitude * s / d.length); break;
        case DeformerKind::Squash: push.amount = float(1.0 + d.amplitude * s); break;
        case DeformerKind::Wave:
            push.amount = d.amplitude;
            push.wave_k = float(kTwoPi / d.wavelength);
            push.wave_phase = float(std::fmod(kTwoPi * t / d.period, kTwoPi));
            break;
        }
        return [this, push](VkCommandBuffer cmd) { procedural.dispatch(cmd, n, push, {rest, positions}); };
    }

    std::function<void(VkCommandBuffer)> skin_pass(const Pose& pose)
    {
        if (!binding_sizes) throw Error("MeshDeformer::deform(Pose): set_skin was not called");
        if (pose.joint_matrices.size() != binding_sizes->joint_count ||
            pose.morph_weights.size() != binding_sizes->morph_count)
            throw Error("MeshDeformer::deform(Pose): " + std::to_string(pose.joint_matrices.size()) +
                        " joint matrices and " + std::to_string(pose.morph_weights.size()) +
                        " morph weights, the skin has " + std::to_string(binding_sizes->joint_count) + " and " +
                        std::to_string(binding_sizes->morph_count));
        // Small per-frame data, written before the submission that reads it.
        joint_matrices.upload(pose.joint_matrices.data(), pose.joint_matrices.size() * sizeof(glm::mat4));
        if (!pose.morph_weights.empty())
            morph_weights.upload(pose.morph_weights.data(), pose.morph_weights.size() * sizeof(float));
        const SkinPush push{n, binding_sizes->morph_count, binding_sizes->joint_count};
        return [this, push](VkCommandBuffer cmd) {
            skin.dispatch(cmd, n, push,
                          {rest, morph_deltas, morph_weights, joints, weights, joint_matrices, positions});
        };
    }
};

MeshDeformer::MeshDeformer(Context& context, const PreparedMesh& rest)
{
    if (rest.vertex_count() == 0 || rest.normals.size() != rest.vertex_count() ||
        rest.areas.size() != rest.vertex_count())
        throw Error("MeshDeformer: the mesh is not prepared (" + std::to_string(rest.vertex_count()) + " vertices, " +
                    std::to_string(rest.normals.size()) + " normals, " + std::to_string(rest.areas.size()) + " areas)");
    impl_ = std::make_unique<Impl>(gpu_of(context), rest);
}

MeshDeformer::~MeshDeformer()
{
    // Frames the host recorded may still be running: the buffers go when the GPU is done.
    if (impl_) impl_->ctx.release_after_gpu(std::move(impl_));
}

void MeshDeformer::set_skin(const SkinBinding& b)
{
    auto& m = *impl_;
    if (b.joint_indices.size() != m.n || b.joint_weights.size() != m.n ||
        b.morph_deltas.size() != size_t(b.morph_count) * m.n)
        throw Error("MeshDeformer::set_skin: the binding is for another mesh (" +
                    std::to_string(b.joint_indices.size()) + " vertices, this mesh has " + std::to_string(m.n) + ")");
    if (b.joint_count == 0) throw Error("MeshDeformer::set_skin: no joints");
    for (size_t v = 0; v < m.n; ++v)
        for (int c = 0; c < 4; ++c)
            if (b.joint_indices[v][c] >= b.joint_count)
                throw Error("MeshDeformer::set_skin: vertex " + std::to_string(v) + " uses joint " +
                            std::to_string(b.joint_indices[v][c]) + " of " + std::to_string(b.joint_count));
    m.morph_deltas = make_buffer(m.ctx, b.morph_deltas, "deform: morph deltas");
    m.joints = make_buffer(m.ctx, b.joint_indices, "deform: joint indices");
    m.weights = make_buffer(m.ctx, b.joint_weights, "deform: joint weights");
    m.morph_weights = make_buffer(m.ctx, std::vector<float>(b.morph_count, 0.0f), "deform: morph weights", true);
    m.joint_matrices =
        make_buffer(m.ctx, std::vector<glm::mat4>(b.joint_count, glm::mat4(1.0f)), "deform: joint matrices", true);
    m.binding_sizes = Impl::SkinSizes{b.joint_count, b.morph_count};
}

DeformTimings MeshDeformer::deform(const ProceduralDeformer& d, double t)
{
    return impl_->run(impl_->procedural_pass(d, t));
}

DeformTimings MeshDeformer::deform(const Pose& pose) { return impl_->run(impl_->skin_pass(pose)); }

void MeshDeformer::record(VkCommandBuffer cmd, const ProceduralDeformer& d, double t)
{
    impl_->record(cmd, impl_->procedural_pass(d, t), nullptr);
}

void MeshDeformer::record(VkCommandBuffer cmd, const Pose& pose)
{
    impl_->record(cmd, impl_->skin_pass(pose), nullptr);
}

DeformedVertices MeshDeformer::read() const
{
    DeformedVertices out;
    out.positions = impl_->positions.read<glm::vec3>(impl_->n);
    out.normals = impl_->normals.read<glm::vec3>(impl_->n);
    out.areas = impl_->areas.read<float>(impl_->n);
    return out;
}

MeshDeformer::Buffers MeshDeformer::buffers() const
{
    return {impl_->positions.handle(), impl_->normals.handle(), impl_->areas.handle(), impl_->n};
}

PreparedMesh deformed_mesh(const PreparedMesh& rest, DeformedVertices deformed)
{
    PreparedMesh out;
    out.indices = rest.indices;
    out.render_to_bake = rest.render_to_bake;
    out.positions = std::move(deformed.positions);
    out.normals = std::move(deformed.normals);
    out.areas = std::move(deformed.areas);
    if (out.positions.size() != rest.vertex_count() || out.normals.size() != out.positions.size() ||
        out.areas.size() != out.positions.size())
        throw Error("deformed_mesh: " + std::to_string(out.positions.size()) + " deformed vertices for a mesh of " +
                    std::to_string(rest.vertex_count()));
    glm::vec3 lo = out.positions[0], hi = out.positions[0];
    for (const auto& p : out.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw Error("deformed_mesh: a deformed position is not finite");
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    out.bbox_min = lo, out.bbox_max = hi;
    out.diagonal = float(glm::length(glm::dvec3(hi) - glm::dvec3(lo)));
    out.input_vertices = rest.input_vertices, out.input_triangles = rest.input_triangles;
    out.welded_vertices = rest.welded_vertices, out.dropped_triangles = rest.dropped_triangles;
    out.unused_vertices = rest.unused_vertices;
    return out;
}

}  // namespace jade
