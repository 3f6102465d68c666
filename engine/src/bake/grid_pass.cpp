// bake/grid_pass.cpp - the grid far field of t_m (bake/grid_pass.hpp).
#include "bake/grid_pass.hpp"

namespace jade::bake {

// A grid cell: four floats (or fixed-point integers), the fields of grid_splat_body.glsl.
constexpr uint32_t kCellBytes = 4 * kGridFields;

uint64_t GridPass::Buffers::bytes() const
{
    uint64_t b = 0;
    for (const gpu::Buffer* x : {&levels, &splat, &cells, &scratch[0], &scratch[1], &smooth_table})
        b += *x ? x->size() : 0;
    return b;
}

void GridPass::prepare_placeholder(Buffers& b) const
{
    b.smooth_table = gpu::Buffer(ctx_, 16, kTexelUsage, "smooth-part table (unused)");
    b.smooth_table_texels =
        gpu::TexelView(ctx_, b.smooth_table, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "smooth-part table");
}

void GridPass::prepare(Buffers& b, const GridPlan& plan) const
{
    b.r_cut = plan.r_cut;
    b.cube_side = float(plan.cube_side);
    b.bounds = gpu::Buffer(ctx_, 24, kStorageUsage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, "t_m grid bounds");
    b.cut2 = float(plan.r_cut * plan.r_cut);
    b.table_scale = float((kGridTableSize - 1) / plan.table_range);
    b.plan_levels = plan.levels;
    b.splat_levels = std::min<uint32_t>(uint32_t(plan.levels.size()), plan.per_octave);
    std::vector<glm::vec4> table(plan.table.size());
    for (size_t k = 0; k < table.size(); ++k) table[k] = glm::vec4(plan.table[k], 0.0f);
    b.smooth_table = gpu::Buffer(ctx_, table.size() * 16, kTexelUsage, "t_m smooth-part table");
    b.smooth_table.upload(table.data(), table.size() * 16);
    b.smooth_table_texels =
        gpu::TexelView(ctx_, b.smooth_table, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "t_m smooth-part table");
    if (plan.levels.empty()) return;  // the profile is within r_cut: the near pass is all of t_m
    b.levels = gpu::Buffer::from(ctx_, plan.levels, kStorageUsage, "t_m grid levels");
    check_storage_range(ctx_, plan.cells * kCellBytes, "t_m grid cells");
    uint64_t splat_cells = 0;
    for (uint32_t g = 0; g < b.splat_levels; ++g)
        splat_cells += uint64_t(plan.levels[g].dims.x) * plan.levels[g].dims.y * plan.levels[g].dims.z;
    // The fixed-point splats, then each grid's sources (restricted) and in place its blurred
    // values: the four fields of a cell in one texel (grid_splat_body.glsl).
    b.splat =
        gpu::Buffer(ctx_, splat_cells * kCellBytes, kTexelUsage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, "t_m grid splats");
    b.splat_texels = gpu::TexelView(ctx_, b.splat, VK_FORMAT_R32G32B32A32_UINT, kCellBytes, "t_m grid splats (texels)");
    b.cells = gpu::Buffer(ctx_, plan.cells * kCellBytes, kTexelUsage, "t_m grid cells");
    b.cell_texels = gpu::TexelView(ctx_, b.cells, VK_FORMAT_R32G32B32A32_SFLOAT, kCellBytes, "t_m grid cells (texels)");
    if (plan.cube_side > 0) {  // three axis passes per restricted grid and per blurred grid
        uint32_t passes = 3 * (uint32_t(plan.levels.size()) - b.splat_levels);
        for (const auto& l : plan.levels) passes += l.weight != glm::vec3(0) ? 3 : 0;
        b.dispatch = gpu::Buffer(ctx_, std::max<uint32_t>(passes, 1) * sizeof(GridAxisDispatch),
                                 kStorageUsage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, "t_m grid pass dispatches");
    }
    for (int i = 0; i < 2; ++i) {
        b.scratch[i] = gpu::Buffer(ctx_, plan.max_level_cells * kCellBytes, kTexelUsage, "t_m grid pass scratch");
        b.scratch_texels[i] = gpu::TexelView(ctx_, b.scratch[i], VK_FORMAT_R32G32B32A32_SFLOAT, kCellBytes,
                                             "t_m grid pass scratch (texels)");
    }
}

namespace {

constexpr uint32_t kAxisRun = JADE_GRID_AXIS_RUN;  // bake_interface.h: grid_axis.comp's output cells per thread
// Threads per group of grid_axis.comp, along x: rows of a coarse grid are short, and a group
// wider than a row idles its other lanes.
constexpr uint32_t kAxisGroup = 8;

glm::uvec3 dims_of(const GpuGridLevel& l) { return l.dims; }

}  // namespace

void GridPass::record(VkCommandBuffer cmd, Buffers& grids, const MeshState& m, gpu::GpuTimer* timer,
                      uint32_t slot_begin, uint32_t slot_end)
{
    const uint32_t levels = grids.level_count();
    if (levels == 0) return;
    auto mark = [&](const char* stage) {
        if (timer) timer->mark(cmd, stage);
    };
    // Two 64-bit atomics a tap where the device has them, else four of 32 bits (the same sums).
    const bool int64_splat = ctx_.info().int64_atomics;
    const auto& splat = lazy_kernel(ctx_, splat_,
                                    {"grid_splat",
                                     int64_splat ? shaders::grid_splat_int64_comp() : shaders::grid_splat_comp(),
                                     gpu::storage_bindings(7),
                                     sizeof(GridSplatPush),
                                     64,
                                     {}});
    const uint32_t splat_format = int64_splat ? 2u : 1u;  // FIXED in grid_axis.comp
    auto axis_kernel = [&](uint32_t half_width, uint32_t step, bool fixed) -> const gpu::Kernel& {
        return lazy_kernel(ctx_, axis_[fixed][step - 1][half_width],
                           {"grid_axis",
                            shaders::grid_axis_comp(),
                            {kTexels, kTexels, kStorage, kStorage},
                            sizeof(GridAxisPush),
                            kAxisGroup,
                            {half_width, step, fixed ? splat_format : 0u}});
    };
    const auto& gather = lazy_kernel(
        ctx_, gather_,
        {"grid_gather",
         shaders::grid_gather_comp(),
         {kStorage, kStorage, kStorage, kStorage, kTexels, kStorage, kStorage, kStorage, kStorage, kStorage},
         sizeof(GridGatherPush),
         64,
         tm_constants(m.variant)});
    const auto& L = grids.plan_levels;
    vkCmdFillBuffer(cmd, grids.splat.handle(), 0, VK_WHOLE_SIZE, 0);
    if (grids.cube_side > 0) {  // the current bounds, for grids that follow the mesh
        vkCmdFillBuffer(cmd, grids.bounds.handle(), 0, 12, ~0u);
        vkCmdFillBuffer(cmd, grids.bounds.handle(), 12, 12, 0);
        gpu::compute_barrier(cmd);
        lazy_kernel(ctx_, bounds_,
                    {"grid_bounds", shaders::grid_bounds_comp(), gpu::storage_bindings(2), sizeof(GatherPush), 64, {}})
            .dispatch(cmd, m.vertex_count, GatherPush{m.vertex_count}, {m.positions, grids.bounds});
    }
    gpu::compute_barrier(cmd);
    splat.dispatch(cmd, m.vertex_count, GridSplatPush{m.vertex_count, grids.splat_levels, grids.cube_side},
                   {grids.levels, m.positions, m.areas, m.ao, grids.splat, grids.bounds, m.normals});
    gpu::compute_barrier(cmd);
    mark("t_m grid splat");

    // Three passes x, y, z from level `from` (its cells, or its fixed-point splat) into level
    // `to` of the cell buffer, through the two scratch buffers.
    struct AxisPass {
        const gpu::Kernel* kernel;
        GridAxisPush push;
        glm::uvec3 runs;  // threads: runs of kAxisRun cells along the axis, cells along the others
        const gpu::TexelView* source;
        const gpu::Buffer* target;
    };
    std::vector<AxisPass> passes;
    auto separable =
        [&](uint32_t from, uint32_t to, uint32_t step, int32_t shift, uint32_t half_width, const float* w) {
        const GpuGridLevel& src = L[from];
        const bool fixed = from < grids.splat_levels;
        glm::uvec3 in = dims_of(src);
        for (uint32_t axis = 0; axis < 3; ++axis) {
            glm::uvec3 out = in;
            out[axis] = dims_of(L[to])[axis];
            GridAxisPush p{in, out, axis, shift, 0, 0, 1.0f, from, to, grids.cube_side, uint32_t(passes.size()), {}};
            std::copy(w, w + half_width + 1, p.w);
            const gpu::TexelView* source = &grids.scratch_texels[(axis + 1) % 2];
            const gpu::Buffer* target = &grids.scratch[axis % 2];
            if (axis == 0) {
                source = &grids.cell_texels;
                p.in_offset = src.offset;
                p.inv_scale = 1.0f / src.splat_scale;
            }
            if (axis == 2) target = &grids.cells, p.out_offset = L[to].offset;
            glm::uvec3 runs = out;
            runs[axis] = (out[axis] + kAxisRun - 1) / kAxisRun;
            passes.push_back({&axis_kernel(half_width, step, fixed && axis == 0), p, runs, source, target});
            in = out;
        }
    };
    static constexpr float kTwoScale[3] = {6.0f / 8, 4.0f / 8, 1.0f / 8};
    for (uint32_t g = grids.splat_levels; g < levels; ++g) separable(g - grids.splat_levels, g, 2, -2, 2, kTwoScale);
    const size_t restrict_passes = passes.size();
    for (uint32_t g = 0; g < levels; ++g)
        if (L[g].weight != glm::vec3(0)) separable(g, g, 1, 0, L[g].half_width, L[g].blur);
    // A deforming mesh's passes run over this frame's active boxes only (grid_boxes.comp).
    const bool boxed = grids.cube_side > 0;
    if (boxed) {
        const auto& boxes = lazy_kernel(ctx_, boxes_,
                                        {"grid_boxes",
                                         shaders::grid_boxes_comp(),
                                         gpu::storage_bindings(3),
                                         sizeof(GridAxisPush),
                                         1,
                                         {kAxisGroup, kAxisRun}});
        for (const AxisPass& pass : passes)
            boxes.dispatch(cmd, 1, pass.push, {grids.levels, grids.bounds, grids.dispatch});
        gpu::indirect_barrier(cmd);
    }
    if (restrict_passes == 0) mark("t_m grid restrict");
    for (size_t i = 0; i < passes.size(); ++i) {
        const AxisPass& pass = passes[i];
        // A static mesh's passes read no boxes: any storage buffer stands in.
        const gpu::Buffer& boxes = boxed ? grids.dispatch : grids.levels;
        const std::initializer_list<gpu::Binding> bindings{grids.splat_texels, *pass.source, *pass.target, boxes};
        if (boxed)
            pass.kernel->dispatch_indirect(cmd, grids.dispatch, i * sizeof(GridAxisDispatch), pass.push, bindings);
        else
            pass.kernel->dispatch_3d(cmd, pass.runs, pass.push, bindings);
        gpu::compute_barrier(cmd);
        if (i + 1 == restrict_passes) mark("t_m grid restrict");
    }
    mark("t_m grid blur");
    gather.dispatch(cmd, slot_end - slot_begin,
                    GridGatherPush{levels, slot_begin, slot_end - slot_begin, grids.cube_side},
                    {m.profiles, grids.levels, m.positions, m.point_order, grids.cell_texels, m.partial_sum,
                     m.partial_comp, m.tm, m.normal_sum, grids.bounds});
    gpu::compute_barrier(cmd);
    mark("t_m grid gather");
}

}  // namespace jade::bake
