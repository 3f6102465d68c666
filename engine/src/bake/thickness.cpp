// bake/thickness.cpp - the thickness pass (jade/bake.hpp ThicknessSettings): inward cone rays
// through the AO pass's BVH (thickness_trace.comp), fixed-point sums per ray slice, the mean
// distance per vertex (thickness_resolve.comp). Recorded by the static bake and by DynamicBake.
#include "bake/baker_impl.hpp"

#include <numbers>

namespace jade {
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

void Baker::Impl::prepare_thickness(MeshState& m, const ThicknessSettings& s)
{
    validate_thickness_settings(s);
    if (!s.enabled()) return;
    m.thickness_sums = gpu::Buffer(ctx, VkDeviceSize(m.vertex_count) * m.ao_slices * sizeof(uint32_t), kStorageUsage,
                                   "thickness sums (per ray slice)");
    m.thickness = gpu::Buffer(ctx, VkDeviceSize(m.vertex_count) * sizeof(float), kStorageUsage, "thickness");
}

void Baker::Impl::record_thickness(VkCommandBuffer cmd, MeshState& m, const ThicknessSettings& s, uint32_t first,
                                   uint32_t count)
{
    if (!s.enabled()) return;
    if (count == 0) count = m.ao_slices;
    const VkDeviceSize slice_bytes = VkDeviceSize(m.vertex_count) * sizeof(uint32_t);
    vkCmdFillBuffer(cmd, m.thickness_sums.handle(), first * slice_bytes, count * slice_bytes, 0);
    gpu::compute_barrier(cmd);
    const float max_distance = s.max_distance_rel * m.diagonal;
    const float cos_cone = float(std::cos(double(s.cone_degrees) * std::numbers::pi / 180.0));
    const uint32_t rays_in_slice = s.rays / m.ao_slices;
    for (uint32_t slice = first; slice < first + count; ++slice) {
        ThicknessPush push{m.vertex_count, s.rays,       s.seed,      cos_cone, s.ray_offset_rel * m.diagonal,
                           max_distance,   m.item_count, m.ao_slices, slice};
        thickness_kernel().dispatch(cmd, uint64_t(m.vertex_count) * rays_in_slice, push,
                                    {m.positions, m.normals, m.ray_item_texels, m.thickness_sums});
    }
    gpu::compute_barrier(cmd);
    thickness_resolve_kernel().dispatch(cmd, m.vertex_count,
                                        ThicknessResolvePush{m.vertex_count, s.rays, m.ao_slices, max_distance},
                                        {m.thickness_sums, m.thickness});
}

}  // namespace jade
