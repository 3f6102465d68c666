// bake/far_field.hpp - which far field sums t_m on a mesh (TmMethod::Auto's rule, docs/bake.md
// "Choosing the far field"), and the grid's plan when it is the grid: one function that the
// bake's set-up (prepare_tm) and the estimate of its buffers (buffer_estimate.cpp) both call.
#pragma once

#include "bake/bvh.hpp"
#include "bake/grid_field.hpp"

#include <jade/bake.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>

#include <cstdint>
#include <optional>

namespace jade::bake {

struct FarField {
    TmMethod method = TmMethod::Exact;  // what the bake runs: Exact, Clustered or Grid
    /// The grid's plan: set when method is Grid, and when Grid was asked for but cannot run
    /// (not feasible, or long_lists), for the bake's error message.
    std::optional<GridPlan> grid;
    uint64_t near_entries = 0;  // the grid's near lists, sampled on the mesh (0 without a plan)
    bool long_lists = false;    // those lists would pass kGridMaxNearBytes
};

/// A t_m buffer of a fixed size per vertex: its name and bytes per vertex, written once for
/// prepare_tm, which allocates it, and estimate_buffers, which counts it.
struct PerVertexBuffer {
    const char* name;
    uint64_t bytes_per_vertex;
};
inline constexpr PerVertexBuffer kTmValues{"t_m", 12};                                       // float3
inline constexpr PerVertexBuffer kTmNormalSums{"scattering normal sums (per channel)", 36};  // float3 per channel
inline constexpr PerVertexBuffer kTmPartialSums{"t_m partial sums", 12};
inline constexpr PerVertexBuffer kTmPartialCompensation{"t_m partial compensation", 12};
inline constexpr PerVertexBuffer kTmSources{"t_m sources", 32};  // two RGBA32F texels (gather_sources.comp)
inline constexpr PerVertexBuffer kTmResume{"t_m traversal resume state", 12};  // clustered pass

/// The point tree the choice samples the near lists with (and the clustered pass walks).
Bvh build_point_tree(const PreparedMesh& mesh);

/// The far field of a bake with these settings; `near_margin` is the near lists' margin
/// (kStaticNearMargin, or kDynamicNearMargin for a deforming mesh). Auto takes the all-pairs
/// sum below kExactBelow vertices, else the grid unless its grids had to be coarsened to fit in
/// memory or its near lists would be long (a mesh whose bounds are vast for its vertex spacing,
/// or dense in patches: more than 4 × the plan's estimate, or past kGridMaxNearBytes).
FarField choose_far_field(const PreparedMesh& mesh, const Material& material, const BakeSettings& settings,
                          const Bvh& point_tree, float near_margin);

}  // namespace jade::bake
