// bake/grid_pass.hpp - the grid far field of t_m (the maths and the plan: bake/grid_field.hpp):
// splat every source into every Gaussian's grid, blur each grid along x, y and z, gather at
// the targets into the near pass's partial sums. Recorded by the static bake and by DynamicBake
// (which re-splats and re-blurs every frame, and gathers its t_m slice). Private to
// engine/src/bake.
#pragma once

#include "bake/grid_field.hpp"
#include "bake/mesh_state.hpp"

namespace jade::bake {

// The pass's kernels, made on first use; one per Baker, shared by every mesh it bakes.
class GridPass {
public:
    // One mesh's grids: its plan's sizes, cells (fixed-point splats, blurred values; four fields
    // per cell, grid_splat_body.glsl: the weight, then times n.x, n.y, n.z), two blur buffers
    // for the largest grid, the levels and the S(r) table, which the near pass reads too (a
    // placeholder for the other far fields: the near pass always binds one).
    struct Buffers {
        float cut2 = 0, table_scale = 0, cube_side = 0;
        uint32_t splat_levels = 0;  // the finest grids, splatted into; the others restricted
        std::vector<GpuGridLevel> plan_levels;
        double r_cut = 0;
        gpu::Buffer levels, splat, cells, scratch[2], smooth_table, bounds;
        gpu::Buffer dispatch;  // a deforming mesh's: a GridAxisDispatch per axis pass (grid_boxes.comp)
        gpu::TexelView smooth_table_texels, splat_texels, cell_texels, scratch_texels[2];
        uint32_t level_count() const { return uint32_t(plan_levels.size()); }
        uint64_t bytes() const;  // what BakeResult::tm_bytes counts of them
    };

    explicit GridPass(gpu::Context& ctx) : ctx_(ctx) {}

    // Allocates the grids of `plan` (before the near lists, whose reach is the plan's r_cut).
    void prepare(Buffers& b, const GridPlan& plan) const;
    // The smooth-part table the near pass binds when t_m has another far field.
    void prepare_placeholder(Buffers& b) const;
    // Splat, blur and gather into the targets in tree slots [slot_begin, slot_end).
    void record(VkCommandBuffer cmd, Buffers& b, const MeshState& m, gpu::GpuTimer* timer, uint32_t slot_begin,
                uint32_t slot_end);

private:
    gpu::Context& ctx_;
    std::optional<gpu::Kernel> splat_, gather_, bounds_, boxes_;
    std::optional<gpu::Kernel> axis_[2][2][kGridMaxHalfWidth + 1];  // [fixed-point input][blur, restrict][half-width]
};

}  // namespace jade::bake
