// bake/thickness_pass.cpp - the thickness pass (bake/thickness_pass.hpp).
#include "bake/thickness_pass.hpp"

#include <numbers>

namespace jade::bake {
namespace {

void validate_thickness_settings(const ThicknessSettings& s)
{
    if (s.rays > 1023) throw Error("thickness: rays per vertex must be in 0..1023, got " + std::to_string(s.rays));
    if (!(s.cone_degrees > 0.0f && s.cone_degrees <= 90.0f))
        throw Error("thickness: cone half-angle must be in (0, 90] degrees, got " + std::to_string(s.cone_degrees));
    if (!(s.max_distance_rel > 0) || !std::isfinite(s.max_distance_rel))
        throw Error("thickness: max distance must be a positive fraction of the diagonal");
    if (!(s.ray_offset_rel >= 0) || !std::isfinite(s.ray_offset_rel))
        throw Error("thickness: the ray offset must be ≥ 0");
}

}  // namespace

void ThicknessPass::Buffers::allocate_sums(gpu::Context& ctx, uint32_t vertex_count, uint32_t slices)
{
    sums = gpu::Buffer(ctx, VkDeviceSize(vertex_count) * slices * sizeof(uint32_t), kStorageUsage,
                       "thickness sums (per ray slice)");
}

void ThicknessPass::prepare(Buffers& b, const MeshState& m, const ThicknessSettings& s) const
{
    validate_thickness_settings(s);
    if (!s.enabled()) return;
    b.allocate_sums(ctx_, m.vertex_count, m.ao_slices);
    b.result = gpu::Buffer(ctx_, VkDeviceSize(m.vertex_count) * sizeof(float), kStorageUsage, "thickness");
}

void ThicknessPass::record(VkCommandBuffer cmd, Buffers& b, const MeshState& m, const ThicknessSettings& s,
                           uint32_t first, uint32_t count)
{
    if (!s.enabled()) return;
    if (count == 0) count = m.ao_slices;
    const VkDeviceSize slice_bytes = VkDeviceSize(m.vertex_count) * sizeof(uint32_t);
    vkCmdFillBuffer(cmd, b.sums.handle(), first * slice_bytes, count * slice_bytes, 0);
    gpu::compute_barrier(cmd);
    const float max_distance = s.max_distance_rel * m.diagonal;
    const float cos_cone = float(std::cos(double(s.cone_degrees) * std::numbers::pi / 180.0));
    const uint32_t rays_in_slice = s.rays / m.ao_slices;
    const gpu::Kernel& trace = lazy_kernel(ctx_, trace_,
                                           {"thickness_trace",
                                            shaders::thickness_trace_comp(),
                                            {kStorage, kStorage, kTexels, kStorage},
                                            sizeof(ThicknessPush),
                                            64,
                                            {}});
    for (uint32_t slice = first; slice < first + count; ++slice) {
        ThicknessPush push{m.vertex_count, s.rays,       s.seed,      cos_cone, s.ray_offset_rel * m.diagonal,
                           max_distance,   m.item_count, m.ao_slices, slice};
        trace.dispatch(cmd, uint64_t(m.vertex_count) * rays_in_slice, push,
                       {m.positions, m.normals, m.ray_item_texels, b.sums});
    }
    gpu::compute_barrier(cmd);
    lazy_kernel(ctx_, resolve_,
                {"thickness_resolve",
                 shaders::thickness_resolve_comp(),
                 gpu::storage_bindings(2),
                 sizeof(ThicknessResolvePush),
                 64,
                 {}})
        .dispatch(cmd, m.vertex_count, ThicknessResolvePush{m.vertex_count, s.rays, m.ao_slices, max_distance},
                  {b.sums, b.result});
}

}  // namespace jade::bake
