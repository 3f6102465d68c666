// bake/grid_field.hpp - the grid far field of t_m: the profile split into a short part, summed
// exactly over each vertex's neighbourhood, and a smooth part, summed on 3-D grids.
//
//   R(r) = R_short(r) + S(r),   S(r) = Σ_g a_g · 1/(2πσ_g²) · e^{−r²/2σ_g²}   (per channel)
//
// S is fitted (non-negative least squares) to R over [r_cut, r_max], weighted by 2πr², the
// share of t_m per unit of ln r, so R_short = R − S is negligible beyond r_cut. The near pass
// (tm_near.comp) sums R_short exactly over every source within r_cut (disk pairs over their
// disk), the grid passes sum S over every source:
//   splat  (grid_splat_body.glsl):  sources (1 − A_o)·area into the one or two finest grids with cubic
//                              B-spline weights, fixed-point integer atomics (deterministic);
//   restrict (grid_axis.comp): each coarser grid from the one of half its spacing, exactly
//                              (the B-spline's two-scale relation);
//   blur   (grid_axis.comp):   three 1-D passes of a sampled Gaussian of variance σ² − 2h²/3
//                              (splat and gather each add h²/3, the B-spline's variance);
//   gather (grid_gather.comp): the same B-spline at each target, weighted per channel.
// Gaussian g has its own grid of spacing h_g = σ_g / resolution over the mesh's bounds; the
// σ_g are 2 apart (√2 at the high resolutions: levels_per_octave), from σ_min = r_cut /
// resolution, so the grids shrink by 8 (2^{3/2}) each and the finest one sets the memory. r_cut = 2.5·resolution mean vertex spacings √(area/n).
// Private to engine/src/bake.
#pragma once

#include <jade/material.hpp>
#include <jade/mesh.hpp>

#include "bake_interface.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace jade::bake {

constexpr uint32_t kGridMaxHalfWidth = JADE_GRID_MAX_HALF_WIDTH;  // bake_interface.h, shared with grid.glsl
constexpr uint32_t kGridTableSize = JADE_GRID_TABLE_SIZE;  // samples of S(r) for the near pass, over [0, table_range]
constexpr uint64_t kGridMaxCells =
    1ull << 23;  // all grids together (16 B a cell: one binding); past it r_cut grows (see plan_grid)
constexpr double kGridMaxCoarsening = 1.5;  // ... by at most this factor (the near lists by its square)
// The Gaussians' σ are 2^{1/L} apart, L the levels per octave: 1 below this resolution, 2 from
// it. The sources are splatted into the L finest grids, and grid g ≥ L is restricted from grid
// g − L, which has half its spacing. Two levels an octave fit the profile ~10× closer (max
// relative error ~5e-4 against ~3e-3 at resolution 2), one costs half the splat, blur and gather.
constexpr double kTwoLevelsPerOctaveFrom = 3.0;
uint32_t levels_per_octave(double resolution);
// Fields splatted and blurred per grid: (1 − A_o)·area, and times n.x, n.y, n.z for the
// scattering normal (shaders/include/grid_splat_body.glsl).
constexpr uint32_t kGridFields = 4;
constexpr double kDeformingCube = 1.1;  // a deforming mesh's grids: cubes of this × the rest pose's bounding sphere

/// One Gaussian's grid, as the grid shaders read it: GridLevel of bake_interface.h.
using GpuGridLevel = GridLevel;

/// The smooth part S of a material's profiles: Gaussians shared by the channels.
struct SmoothFit {
    std::vector<double> sigma;       // mesh units, ascending
    std::vector<glm::dvec3> weight;  // a_g per channel (≥ 0)
    glm::dvec3 residual{0};          // ∫_{r_cut}^{r_max} |R − S| 2πr dr per channel
    double S(int channel, double r) const;
};

/// Fits S to the profiles over [r_cut, r_max] with Gaussians σ_min·2^{g/per_octave} (σ_min = r_cut/resolution)
/// up to the profile's extent or 2·r_max; `channels` 1 fits channel 0 only (grey).
SmoothFit fit_smooth_part(const Material& material, int channels, double r_cut, double r_max, double resolution,
                          uint32_t per_octave);

/// Everything the grid passes need for one mesh.
struct GridPlan {
    double r_cut = 0;        // mesh units: the near pass's exact radius
    double table_range = 0;  // S is tabulated over [0, table_range] (≥ every near-list reach)
    SmoothFit fit;
    uint32_t per_octave = 1;           // levels_per_octave: the grids splatted into
    std::vector<GpuGridLevel> levels;  // one per Gaussian with a non-zero weight
    // Per channel at r_k = k·table_range/(kGridTableSize − 1): S(r_k), then (R − S)(r_k)·r_k
    // (the near pass's point pairs, with no exponential per pair).
    std::vector<glm::vec3> table;
    double cube_side = 0;  // > 0: a deforming mesh's grids (plan_grid)
    uint64_t cells = 0, max_level_cells = 0;
    bool coarsened = false;     // r_cut grew past its rule to fit kGridMaxCells
    bool feasible = true;       // false: it would have to grow past kGridMaxCoarsening
    uint64_t cells_needed = 0;  // the grids at r_cut's rule
    double spacing = 0;         // the mesh's mean vertex spacing
    uint64_t bytes() const;     // device memory of the grid passes
    uint64_t near_entries(size_t vertices, double margin) const;  // the near lists' length, estimated
};

/// Plans the grids over the mesh's bounds, for pairs up to the diagonal apart. A deforming
/// mesh's grids are cubes of side kDeformingCube × the diameter of the rest pose's bounding
/// sphere, placed each frame about its current bounds (grid_bounds.comp): they hold the rest
/// pose turned any way, and stretches of 10 %; a vertex beyond counts at the cube's face. When the grids would exceed
/// kGridMaxCells, r_cut grows until they fit (`coarsened`): fewer, coarser grids and longer
/// near lists; past kGridMaxCoarsening the plan is not `feasible` (no levels). Never a silent
/// error. `near_margin`: the near lists' (bake/near_field.hpp); the table covers their reach.
GridPlan plan_grid(const PreparedMesh& mesh, const Material& material, int channels, double resolution, bool deforming,
                   double near_margin);

/// Solves min ‖A·x − b‖ subject to x ≥ 0 (Lawson–Hanson), A row-major rows × cols.
std::vector<double> nnls(const std::vector<double>& A, const std::vector<double>& b, size_t rows, size_t cols);

}  // namespace jade::bake
