// bake/baker_impl.hpp - what the static bake (baker.cpp) and the per-frame re-bake
// (dynamic_bake.cpp) share: the passes' push constants and limits, and Baker::Impl, which owns
// the bake kernels and records every pass of one mesh's bake (its data flow: baker.cpp).
// Private to engine/src/bake.
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

namespace jade {
namespace bake {

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
    return {m.grey() ? 1u : 0u, same ? uint32_t(k) : uint32_t(JADE_PROFILE_MIXED)};
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

}  // namespace bake

// The bake's own vocabulary, for the two files that include this one.
using bake::AoPush;
using bake::AoResolvePush;
using bake::ClusterPush;
using bake::ExactPush;
using bake::finish_timings;
using bake::GatherPush;
using bake::GridGatherPush;
using bake::GridSplatPush;
using bake::kAoRetraceGroup;
using bake::kClusterWorkPerDispatch;
using bake::kDynamicNearMargin;
using bake::kExactSourcesPerDispatch;
using bake::kGridMaxNearBytes;
using bake::kPointLeafSize;
using bake::kStaticNearMargin;
using bake::kStorage;
using bake::kStorageUsage;
using bake::kTexels;
using bake::kTexelUsage;
using bake::kTriangleLeafSize;
using bake::NearPush;
using bake::RayRefitPush;
using bake::read_scattering_normals;
using bake::RefitPush;
using bake::ThicknessPush;
using bake::ThicknessResolvePush;
using bake::tm_variant;
using bake::TmVariant;
using bake::uses_exact_tm;
using bake::validate_ao_settings;
using bake::validate_tm_settings;
using gpu::storage_bindings;

struct Baker::Impl {
    gpu::Context& ctx;
    // Pipelines are made on first use: a scene that never needs one never creates it.
    std::optional<gpu::Kernel> ao_trace, ao_resolve, ao_changed, ao_retrace, gather, refit, ray_refit, thickness_trace,
        thickness_resolve;
    // t_m kernels per [grey (1 channel) or RGB][profile kind: Burley, dipole, Gaussians, mixed].
    std::optional<gpu::Kernel> tm_exact[2][4], tm_cluster[2][4];
    std::optional<gpu::Kernel> tm_near[2][2][4];  // [grid far field][grey][kind]
    std::optional<gpu::Kernel> grid_splat, grid_gather, grid_bounds, grid_boxes;
    std::optional<gpu::Kernel>
        grid_axis[2][2][bake::kGridMaxHalfWidth + 1];  // [fixed-point input][blur, restrict][half-width]
    std::optional<gpu::Kernel> tm_exact_f64[2][4];     // dev::BakeStudy::tm_float64_sums

    explicit Impl(gpu::Context& c) : ctx(c) {}

    const gpu::Kernel& kernel(std::optional<gpu::Kernel>& slot, gpu::KernelDesc desc)
    {
        if (!slot) slot.emplace(ctx, desc);
        return *slot;
    }
    const gpu::Kernel& ao_kernel()
    {
        return kernel(
            ao_trace,
            {"ao_trace", shaders::ao_trace_comp(), {kStorage, kStorage, kTexels, kStorage}, sizeof(AoPush), 64, {}});
    }
    const gpu::Kernel& ao_retrace_kernel()
    {
        return kernel(ao_retrace, {"ao_retrace",
                                   shaders::ao_retrace_comp(),
                                   {kStorage, kStorage, kTexels, kStorage, kStorage},
                                   sizeof(AoPush),
                                   kAoRetraceGroup,
                                   {}});
    }
    const gpu::Kernel& ao_changed_kernel()
    {
        return kernel(
            ao_changed,
            {"ao_changed", shaders::ao_changed_comp(), storage_bindings(3), sizeof(AoPush), 64, {kAoRetraceGroup}});
    }
    const gpu::Kernel& ao_resolve_kernel()
    {
        return kernel(ao_resolve,
                      {"ao_resolve", shaders::ao_resolve_comp(), storage_bindings(2), sizeof(AoResolvePush), 64, {}});
    }
    const gpu::Kernel& thickness_kernel()
    {
        return kernel(thickness_trace, {"thickness_trace",
                                        shaders::thickness_trace_comp(),
                                        {kStorage, kStorage, kTexels, kStorage},
                                        sizeof(ThicknessPush),
                                        64,
                                        {}});
    }
    const gpu::Kernel& thickness_resolve_kernel()
    {
        return kernel(thickness_resolve, {"thickness_resolve",
                                          shaders::thickness_resolve_comp(),
                                          storage_bindings(2),
                                          sizeof(ThicknessResolvePush),
                                          64,
                                          {}});
    }
    const gpu::Kernel& gather_kernel()
    {
        return kernel(
            gather,
            {"gather_sources", shaders::gather_sources_comp(), storage_bindings(6), sizeof(GatherPush), 64, {}});
    }
    const gpu::Kernel& refit_kernel()
    {
        return kernel(refit,
                      {"cluster_refit", shaders::cluster_refit_comp(), storage_bindings(4), sizeof(RefitPush), 64, {}});
    }
    const gpu::Kernel& ray_refit_kernel()
    {
        return kernel(ray_refit,
                      {"ray_refit", shaders::ray_refit_comp(), storage_bindings(5), sizeof(RayRefitPush), 64, {}});
    }
    // Specialisation constants of the t_m kernels: channel count and profile kind.
    static std::vector<uint32_t> tm_constants(const TmVariant& v) { return {v.grey ? 1u : 3u, v.kind}; }
    const gpu::Kernel& near_kernel(const TmVariant& v, bool grid)
    {
        std::vector<uint32_t> constants = tm_constants(v);
        constants.push_back(grid ? 1u : 0u);
        return kernel(tm_near[grid][v.grey][v.kind], {"tm_near",
                                                      shaders::tm_near_comp(),
                                                      {kStorage, kTexels, kStorage, kTexels, kStorage, kStorage,
                                                       kTexels, kStorage, kStorage, kStorage, kStorage},
                                                      sizeof(NearPush),
                                                      64,
                                                      constants});
    }
    const gpu::Kernel& exact_kernel(const TmVariant& v, bool float64_sums)
    {
        auto& slot = float64_sums ? tm_exact_f64[v.grey][v.kind] : tm_exact[v.grey][v.kind];
        if (!slot) require_subgroup_groups();  // once, when the kernel is made
        return kernel(slot, {float64_sums ? "tm_exact_f64" : "tm_exact",
                             float64_sums ? shaders::tm_exact_f64_comp() : shaders::tm_exact_comp(),
                             {kStorage, kTexels, kStorage, kStorage, kStorage, kStorage},
                             sizeof(ExactPush),
                             64,
                             tm_constants(v)});
    }
    const gpu::Kernel& cluster_kernel(const TmVariant& v)
    {
        if (!tm_cluster[v.grey][v.kind]) require_subgroup_groups();
        return kernel(tm_cluster[v.grey][v.kind],
                      {"tm_cluster",
                       shaders::tm_cluster_comp(),
                       {kStorage, kTexels, kStorage, kStorage, kStorage, kStorage, kStorage, kStorage},
                       sizeof(ClusterPush),
                       64,
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
            throw Error(
                "t_m: the device's compute subgroups (" + std::to_string(sub.subgroupSize) +
                " lanes) lack what the far passes need: 8 or more lanes with basic, vote and ballot operations");
    }

    // GPU state of one mesh's bake: uploaded inputs, both trees, the passes' buffers. A static
    // bake builds it, records once and drops it; a DynamicBake keeps it and records every frame.
    struct MeshState {
        uint32_t vertex_count = 0;
        float diagonal = 0;
        gpu::Buffer positions, normals, areas;
        // AO: the BVH as ray items; refit data when the mesh deforms.
        uint32_t item_count = 0;
        gpu::Buffer ray_items, hits, ao;  // hits: per ray slice, per vertex
        // Amortised AO (Amortisation::retrace_changed): the fresh slice's counts from the frame
        // that last traced it, and ao_changed.comp's indirect dispatch and list of vertices.
        gpu::Buffer ao_previous, ao_changed_list;
        uint32_t ao_slices = 1;
        gpu::TexelView ray_item_texels;
        gpu::Buffer indices, item_origin, ray_work;  // dynamic only
        gpu::Buffer thickness_sums, thickness;       // thickness pass: per ray slice, per vertex; result
        std::vector<uint32_t> ray_work_offsets;      // [0, triangles) then one range per level
        // t_m.
        bool exact = false;
        bool grid = false;  // the grid far field (bake/tm_grid.cpp) instead of the cluster tree
        TmVariant variant{};
        uint32_t node_count = 0, first_point = 0;  // first_point: texel of source 0 in `points`
        gpu::Buffer profiles, point_order, points, nodes, node_levels, tm;
        gpu::Buffer normal_sum;  // per vertex: the scattering normal's unnormalised sum (tm_state.glsl)
        gpu::Buffer partial_sum, partial_comp, resume, near_offsets, near_disks, near_indices;
        gpu::TexelView point_texels, tree_texels;
        gpu::TexelView source_texels;  // the sources as RGBA32UI (the near pass), from texel source_base
        uint32_t source_base = 0;
        std::vector<uint32_t> level_offsets;
        struct NearWindow {
            bake::NearWindow span;   // rows = tree slots
            gpu::TexelView indices;  // near_indices from entry span.first_entry on
        };
        std::vector<NearWindow> near_windows;  // near-pass dispatches, each within one texel view
        // The grid far field: its plan's sizes, cells (fixed-point splats, blurred values; four
        // fields per cell, grid_splat_body.glsl: the weight, then times n.x, n.y, n.z), two blur
        // buffers for the largest grid, the levels and S(r) table. smooth_table is a placeholder for the
        // other methods (the near pass always binds one).
        float grid_cut2 = 0, grid_table_scale = 0, grid_cube_side = 0;
        uint32_t grid_splat_levels = 0;  // the finest grids, splatted into; the others restricted
        std::vector<bake::GpuGridLevel> grid_plan_levels;
        uint64_t grid_bytes = 0;
        double grid_r_cut = 0;
        gpu::Buffer grid_levels, grid_splat, grid_cells, grid_scratch[2], smooth_table, grid_bounds;
        gpu::Buffer grid_dispatch;  // a deforming mesh's: a GridAxisDispatch per axis pass (grid_boxes.comp)
        gpu::TexelView smooth_table_texels, grid_splat_texels, grid_cell_texels, grid_scratch_texels[2];
        uint32_t grid_level_count() const { return uint32_t(grid_plan_levels.size()); }
        TmMethod method() const { return exact ? TmMethod::Exact : grid ? TmMethod::Grid : TmMethod::Clustered; }
        uint64_t tm_bytes() const
        {
            uint64_t b = 0;
            for (const gpu::Buffer* x :
                 {&profiles, &point_order, &points, &nodes, &node_levels, &tm, &normal_sum, &partial_sum, &partial_comp,
                  &resume, &near_offsets, &near_disks, &near_indices, &grid_levels, &grid_splat, &grid_cells,
                  &grid_scratch[0], &grid_scratch[1], &smooth_table})
                b += *x ? x->size() : 0;
            return b;
        }
    };

    // Buffers bound whole as storage buffers must fit one binding; say so before the GPU is touched.
    void check_storage_range(VkDeviceSize bytes, const char* what) const
    {
        if (bytes > ctx.limits().maxStorageBufferRange)
            throw Error(std::string(what) + ": " + std::to_string(bytes) +
                        " bytes exceed the device's maxStorageBufferRange (" +
                        std::to_string(ctx.limits().maxStorageBufferRange) +
                        "): the mesh has too many vertices for this device");
    }

    void upload_mesh(MeshState& m, const PreparedMesh& mesh, VkBufferUsageFlags extra_usage = 0)
    {
        m.vertex_count = uint32_t(mesh.vertex_count());
        m.diagonal = mesh.diagonal;
        m.positions = gpu::Buffer::from(ctx, mesh.positions, kStorageUsage | extra_usage, "positions");
        m.normals = gpu::Buffer::from(ctx, mesh.normals, kStorageUsage | extra_usage, "normals");
        m.areas = gpu::Buffer::from(ctx, mesh.areas, kStorageUsage | extra_usage, "areas");
    }

    // The AO pass (bake/ao.cpp): the BVH as ray items (with refit work when the mesh deforms),
    // the ray items refitted to the current positions, and the traced and resolved A_o.
    void prepare_ao(MeshState& m, const PreparedMesh& mesh, bool refittable);
    void record_ray_refit(VkCommandBuffer cmd, MeshState& m);
    // Traces the ray slices [first, first + count) of m.ao_slices (ao_trace.comp) into their
    // hit counts, then resolves A_o from the counts of every slice. `retrace_changed`, with one
    // slice of several: the vertices whose slice changed have their other slices traced too
    // (ao_changed.comp, Amortisation::retrace_changed).
    void record_ao(VkCommandBuffer cmd, MeshState& m, const AoSettings& s, uint32_t first = 0, uint32_t count = 0,
                   bool retrace_changed = false);

    // The thickness pass (bake/thickness.cpp) traces the AO pass's ray items: prepare_ao first.
    void prepare_thickness(MeshState& m, const ThicknessSettings& s);
    // Traces the thickness ray slices [first, first + count) of m.ao_slices (all by default),
    // then resolves the mean distance from the sums of every slice.
    void record_thickness(VkCommandBuffer cmd, MeshState& m, const ThicknessSettings& s, uint32_t first = 0,
                          uint32_t count = 0);

    // The t_m passes (bake/tm_passes.cpp). Sets up gather → near field → (all pairs | refit →
    // clustered | grid), reading m.ao, writing m.tm. `near_margin` (bake/near_field.hpp) covers
    // how much closer vertices may come.
    void prepare_tm(MeshState& m, const PreparedMesh& mesh, const Material& material, const BakeSettings& s,
                    float near_margin);

    // The near pass over tree slots [slot_begin, slot_end): starts every target's partial sums.
    void record_near(VkCommandBuffer cmd, MeshState& m, uint32_t slot_begin, uint32_t slot_end);

    // The grid far field (bake/tm_grid.cpp): plans and allocates the grids (before the near
    // lists, whose reach is the plan's r_cut), and records splat, blur and gather.
    void prepare_grid(MeshState& m, const bake::GridPlan& plan);
    void record_grid(VkCommandBuffer cmd, MeshState& m, gpu::GpuTimer* timer, uint32_t slot_begin, uint32_t slot_end);

    // What every static bake reads back after its one submission (baker.cpp): t_m with its
    // scattering normals, how t_m was summed, and the timings.
    static void read_tm_result(BakeResult& r, const MeshState& m, const gpu::GpuTimer& timer, double setup,
                               Clock::time_point t0);

    // Gathers every source and refits the cluster tree, then evaluates t_m for the targets in
    // tree slots [slot_begin, slot_end) (every slot by default; the all-pairs method always
    // evaluates every target).
    void record_tm(VkCommandBuffer cmd, MeshState& m, const BakeSettings& s, gpu::GpuTimer* timer,
                   uint32_t slot_begin = 0, uint32_t slot_end = ~0u);
};

}  // namespace jade
