// bake_interface.h - what the bake's C++ (engine/src/bake) and its compute shaders must agree
// on, written once: the push constants of every bake pass and the constants both sides read.
//
// Included by the shaders (glslang's include directive) and by C++ (bake/bake_common.hpp,
// bake/disk_integral.hpp, bake/grid_field.hpp). In C++ the structs live in jade::bake and the
// GLSL types are spelt with std::uint32_t and GLM. A shader declares its push constants as
//     layout(push_constant, scalar) uniform Push { AoPush pc; };
// and reads pc.rays as before. Scalar layout places these members (4-byte scalars, uvec3 and
// float arrays at 4-byte alignment) exactly where C++ does; sizes are checked in C++ below.
#ifndef JADE_BAKE_INTERFACE_H
#define JADE_BAKE_INTERFACE_H

// A neighbour's disk never reaches past DISK_CAP·r towards the target (bake/disk_integral.hpp
// explains why): the near pass (tm_near.comp) and the float64 reference use the same cap.
#define JADE_DISK_CAP 0.6
// Blur taps on each side of a grid cell, at most (bake/grid_field.hpp, shaders/include/grid.glsl).
#define JADE_GRID_MAX_HALF_WIDTH 16
// A source is integrated over its disk within NEAR_FACTOR disk radii ρ_j = √(A_j/π) of a target
// and counts as a point beyond (bake/near_field.hpp; tm_common.glsl, gather_sources.comp,
// cluster_refit.comp).
#define JADE_NEAR_FACTOR 4.0
// Samples of S(r), then of (R − S)·r, in the grid far field's table for the near pass
// (bake/grid_field.hpp, tm_near.comp).
#define JADE_GRID_TABLE_SIZE 1024
// grid_axis.comp's output cells per thread along the axis (bake/grid_pass.cpp sizes its dispatches
// and hands it to grid_boxes.comp as a specialisation constant).
#define JADE_GRID_AXIS_RUN 8
// Fixed-point steps per max_distance of the thickness sums: 2^22, so ≤ 1023 rays fit in 32 bits
// (thickness_trace.comp, thickness_resolve.comp).
#define JADE_THICKNESS_QUANTUM 4194304.0

#ifdef __cplusplus
#include <glm/vec3.hpp>

#include <cstdint>

namespace jade::bake {
namespace glsl {
using uint = std::uint32_t;
using vec3 = glm::vec3;
using uvec3 = glm::uvec3;
using ivec3 = glm::ivec3;
}  // namespace glsl
using namespace glsl;  // only these names: the structs below are written in GLSL's words
#endif

// ao_trace.comp: one ray slice of the AO pass; ao_changed.comp and ao_retrace.comp: the other
// slices of the vertices whose slice `slice` changed (Amortisation::retrace_changed).
struct AoPush {
    uint vertex_count;
    uint rays;
    uint seed;
    uint low_discrepancy;
    float ray_offset;    // ray origin offset along the normal, mesh units
    float max_distance;  // mesh units
    uint item_count;
    uint slices;  // divides rays
    uint slice;   // the slice traced by this dispatch
};

// ao_resolve.comp: A_o from the hit counts of every slice.
struct AoResolvePush {
    uint vertex_count;
    uint rays;
    uint slices;
};

// thickness_trace.comp: one ray slice of the thickness pass. The ray and slice members mean
// what AoPush's do, but the rays start offset against the normal (into the mesh).
struct ThicknessPush {
    uint vertex_count;
    uint rays;
    uint seed;
    float cos_cone;  // cosine of the cone's half-angle
    float ray_offset;
    float max_distance;
    uint item_count;
    uint slices;
    uint slice;
};

// thickness_resolve.comp: the mean distance from the sums of every slice.
struct ThicknessResolvePush {
    uint vertex_count;
    uint rays;
    uint slices;
    float max_distance;  // mesh units: JADE_THICKNESS_QUANTUM steps of fixed point
};

// gather_sources.comp and grid_bounds.comp: one thread per vertex.
struct GatherPush {
    uint vertex_count;
};

// cluster_refit.comp: one level of the cluster tree.
struct RefitPush {
    uint count;  // nodes in this level
    uint first;  // first entry of this level in `level_nodes`
};

// ray_refit.comp: the triangles, or one level of the BVH's nodes.
struct RayRefitPush {
    uint count;  // work entries of this dispatch
    uint first;  // first work entry
    uint mode;   // 0: triangles, 1: nodes of one level
};

// tm_near.comp: the near field over a window of tree slots.
struct NearPush {
    uint first_slot;
    uint slot_count;
    uint index_base;    // list entry at the start of the bound window of near_indices
    uint source_base;   // texel of source slot 0 in `sources`
    float cut2;         // GRID: r_cut², beyond which a point pair is the grids' alone
    float table_scale;  // GRID: table entries per unit of distance
};

// grid_splat_body.glsl: the sources into the finest grids.
struct GridSplatPush {
    uint vertex_count;
    uint level_count;
    float cube_side;  // > 0: a deforming mesh's grids follow its bounds (level_origin)
};

// grid_axis.comp: one separable pass, blur (step 1) or restriction (step 2) along `axis`.
struct GridAxisPush {
    uvec3 in_dims;
    uvec3 out_dims;  // differs from in_dims along `axis` only
    uint axis;
    int shift;  // 0 blur, −2 restrict
    uint in_offset;
    uint out_offset;
    float inv_scale;
    // A deforming mesh's grids (cube_side > 0) work only on the cells that this frame's sources
    // reach on the levels read and written (grid_axis.comp).
    uint level_in;
    uint level_out;
    float cube_side;
    uint pass;  // with cube_side > 0: this pass's slot in the GridAxisDispatch buffer (grid_boxes.comp)
    float w[JADE_GRID_MAX_HALF_WIDTH + 1];
};

// grid_boxes.comp → grid_axis.comp: a deforming mesh's pass is dispatched over the threads of its
// active box only (groups: a VkDispatchIndirectCommand); [first, last] are that box's threads
// (groups round x up) and [tap_first, tap_last] the input cells along the axis that its taps read.
struct GridAxisDispatch {
    uvec3 groups;
    int tap_first;
    ivec3 first;
    int tap_last;
    ivec3 last;
    uint pad;
};

// grid_gather.comp: the grids' values at the targets of tree slots [slot_begin, + slot_count).
struct GridGatherPush {
    uint level_count;
    uint slot_begin;
    uint slot_count;
    float cube_side;  // > 0: a deforming mesh's grids follow its bounds (level_origin)
};

// tm_exact.comp, tm_exact_f64.comp: the point pairs of sources [source_begin, source_end).
struct ExactPush {
    uint vertex_count;
    uint source_begin;
    uint source_end;
};

// tm_cluster.comp: one dispatch of the clustered far field.
struct ClusterPush {
    uint vertex_count;
    uint node_count;
    float theta;       // the opening ratio (BakeSettings::tm_opening_ratio)
    uint work_budget;  // loop iterations per dispatch (lavapipe's loop limit)
    uint first_point;  // texel of source 0, after the nodes
    uint slot_begin;   // the targets of this dispatch: tree slots [slot_begin, slot_end)
    uint slot_end;     // (all of them, or one slice of an amortised re-bake)
};

// One Gaussian's grid of the grid far field (bake/grid_field.hpp), as the grid shaders read it
// from a storage buffer (grid.glsl). C++ calls it bake::GpuGridLevel.
struct GridLevel {
    vec3 origin;        // world position of cell (0, 0, 0)'s centre
    float inv_h;        // 1 / spacing
    uvec3 dims;         // cells per axis
    uint offset;        // first cell in the shared cell buffers
    vec3 weight;        // per channel: a_g·√(2π)·(σ/h)·(A/h²) / splat_scale, A the total area
    uint half_width;    // blur taps on each side of the centre
    float splat_scale;  // fixed-point units per unit of (1 − A_o)·area
    float blur[JADE_GRID_MAX_HALF_WIDTH + 1];  // blur[|k|], the 1-D kernel, Σ over k in [−hw, hw] = 1
};

#ifdef __cplusplus
// The sizes the shaders see (scalar layout: the sum of the members).
static_assert(sizeof(AoPush) == 36 && sizeof(AoResolvePush) == 12 && sizeof(ThicknessPush) == 36 &&
              sizeof(ThicknessResolvePush) == 16 && sizeof(GatherPush) == 4 && sizeof(RefitPush) == 8 &&
              sizeof(RayRefitPush) == 12 && sizeof(NearPush) == 24 && sizeof(GridSplatPush) == 12 &&
              sizeof(GridAxisPush) == 60 + 4 * (JADE_GRID_MAX_HALF_WIDTH + 1) && sizeof(GridAxisDispatch) == 48 &&
              sizeof(GridGatherPush) == 16 && sizeof(ExactPush) == 12 && sizeof(ClusterPush) == 28 &&
              sizeof(GridLevel) == 52 + 4 * (JADE_GRID_MAX_HALF_WIDTH + 1));
}  // namespace jade::bake
#endif

#endif  // JADE_BAKE_INTERFACE_H
