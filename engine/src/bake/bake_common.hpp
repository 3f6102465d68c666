// bake/bake_common.hpp - the vocabulary every bake pass shares: descriptor and usage
// constants, limits, the t_m kernel variant, settings checks, read-backs, and the helpers that
// make kernels lazily and check device limits. Private to engine/src/bake.
#pragma once

#include "bake/bvh.hpp"
#include "bake/gpu_profile.hpp"
#include "bake/grid_field.hpp"
#include "bake/near_field.hpp"
#include "bake/ray_items.hpp"
#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/kernel.hpp"
#include "gpu/texel_view.hpp"
#include "gpu/timer.hpp"

#include <jade/dev/material.hpp>
#include <jade/bake.hpp>
#include <jade/dev/bake.hpp>
#include <jade/dev/clock.hpp>
#include <jade/context.hpp>

#include "bake_interface.h"     // the passes' push constants, shared with the shaders
#include "scattering_normal.h"  // shared with pack_vertices.comp
#include "jade_shaders.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

namespace jade::bake {

constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kTexels = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
constexpr VkBufferUsageFlags kStorageUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
// Written by one pass as a storage buffer, fetched by the next as texels (gpu/texel_view.hpp).
constexpr VkBufferUsageFlags kTexelUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
constexpr uint32_t kAoRetraceGroup = 64;  // threads per group of ao_retrace.comp (ao_changed.comp sizes its dispatch)
constexpr uint32_t kTriangleLeafSize = 4;
constexpr uint32_t kPointLeafSize = 8;
static_assert(kPointLeafSize <= 8, "cluster_refit.comp scans at most 8 sources per leaf");
// Near-field list margins (bake/near_field.hpp): a static bake only needs to cover rounding;
// a deforming mesh's lists, made at rest, must hold every pair that may come within 4ρ.
constexpr float kStaticNearMargin = 1.05f;
constexpr float kDynamicNearMargin = 1.5f;
// Below this many vertices the all-pairs pass is as fast as building and walking the tree.
constexpr size_t kExactBelow = 2048;
// Whether a bake of `vertices` sums t_m's far field over all pairs (TmMethod::Auto's first rule).
inline bool uses_exact_tm(TmMethod method, size_t vertices)
{
    return method == TmMethod::Exact || (method == TmMethod::Auto && vertices < kExactBelow);
}
// The grid far field's near lists beyond this are refused (TmMethod::Grid) or avoided (Auto).
constexpr uint64_t kGridMaxNearBytes = 512ull << 20;

// Sources per dispatch of the all-pairs pass (8 per loop iteration), and node visits per
// dispatch of the clustered pass (one loop iteration each): lavapipe caps an invocation at
// 65,535 loop iterations, and desktop drivers reset a GPU whose dispatch runs for seconds.
constexpr uint32_t kExactSourcesPerDispatch = 16384;
constexpr uint32_t kClusterWorkPerDispatch = 32768;

// Which t_m kernel variant a material needs: one channel when grey, and the profile kind
// shared by all channels (3: mixed kinds, chosen per channel at run time).
struct TmVariant {
    uint32_t grey;  // 1: grey
    uint32_t kind;  // JADE_PROFILE_* (profile_interface.h): a ProfileKind, or MIXED
};
inline TmVariant tm_variant(const Material& m)
{
    const ProfileKind k = m.profile[0].kind;
    const bool same = m.profile[1].kind == k && m.profile[2].kind == k;
    return {dev::is_grey(m) ? 1u : 0u, same ? uint32_t(k) : uint32_t(JADE_PROFILE_MIXED)};
}

inline void validate_ao_settings(const AoSettings& s)
{
    if (s.rays == 0 || s.rays > 65536)
        throw Error("AO: rays per vertex must be in 1..65536, got " + std::to_string(s.rays));
    if (!(s.max_distance_rel > 0) || !std::isfinite(s.max_distance_rel))
        throw Error("AO: max distance must be a positive fraction of the diagonal");
    if (!(s.ray_offset_rel >= 0) || !std::isfinite(s.ray_offset_rel)) throw Error("AO: the ray offset must be ≥ 0");
}

// The thickness only feeds the transmission term: a material without one does not trace it.
inline BakeSettings without_unused_passes(BakeSettings s, const Material& material)
{
    if (!material.transmission.enabled()) s.thickness.rays = 0;
    return s;
}

inline void validate_tm_settings(const BakeSettings& s, const gpu::Context& ctx)
{
    if (!(s.tm_opening_ratio > 0) || !std::isfinite(s.tm_opening_ratio))
        throw Error("t_m: the opening ratio θ must be > 0");
    if (dev::study_of(s).tm_float64_sums && !ctx.info().float64)
        throw Error("t_m: float64 sums (dev::BakeStudy::tm_float64_sums) need shaderFloat64, which this device lacks");
}

// BakeResult::scattering_normal and normal_spread from the per-channel normal sums N_c
// (tm_state.glsl) and t_m, by the rule pack_vertices.comp applies to a deforming mesh's
// (scattering_normal.h): the vertex normal where the sum has no direction.
inline void read_scattering_normals(BakeResult& r, const gpu::Buffer& sums, const gpu::Buffer& normals, uint32_t n)
{
    const std::vector<glm::vec3> s = sums.read<glm::vec3>(size_t(3) * n);
    std::vector<glm::vec3> fallback;
    r.scattering_normal.resize(n);
    r.normal_spread.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec3 direction = bake::scattering::scattering_direction(s[3 * i], s[3 * i + 1], s[3 * i + 2]);
        if (direction != glm::vec3(0.0f))
            r.scattering_normal[i] = direction;
        else {
            if (fallback.empty()) fallback = normals.read<glm::vec3>(n);
            r.scattering_normal[i] = fallback[i];
        }
        r.normal_spread[i] = bake::scattering::normal_spread(s[3 * i], s[3 * i + 1], s[3 * i + 2], r.tm[i]);
    }
}

inline void finish_timings(BakeTimings& t, const gpu::GpuTimer& timer, double setup, Clock::time_point t0)
{
    t.gpu_stages = timer.stages();
    t.gpu_total_ms = timer.total_ms();
    t.setup_ms = setup;
    t.wall_ms = ms_since(t0);
}

// Pipelines are made on first use: a scene that never needs one never creates it.
inline const gpu::Kernel& lazy_kernel(gpu::Context& ctx, std::optional<gpu::Kernel>& slot, gpu::KernelDesc desc)
{
    if (!slot) slot.emplace(ctx, desc);
    return *slot;
}

// Specialisation constants of the t_m kernels: channel count and profile kind.
inline std::vector<uint32_t> tm_constants(const TmVariant& v) { return {v.grey ? 1u : 3u, v.kind}; }

// The far passes share fetches across subgroups of at least 8 lanes (tm_common.glsl).
inline void require_subgroup_groups(const gpu::Context& ctx)
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

// Buffers bound whole as storage buffers must fit one binding; say so before the GPU is touched.
inline void check_storage_range(const gpu::Context& ctx, VkDeviceSize bytes, const char* what)
{
    if (bytes > ctx.limits().maxStorageBufferRange)
        throw Error(
            std::string(what) + ": " + std::to_string(bytes) + " bytes exceed the device's maxStorageBufferRange (" +
            std::to_string(ctx.limits().maxStorageBufferRange) + "): the mesh has too many vertices for this device");
}

}  // namespace jade::bake
