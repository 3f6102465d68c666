#version 460
#extension GL_GOOGLE_include_directive : require
// Which threads one pass of grid_axis.comp runs over a deforming mesh's grids. Those grids are
// cubes that hold any pose (grid_field.hpp), several times the cells its sources reach in one
// frame: a pass works on the box of cells this frame's sources reach (footprint_box, from the
// bounds of grid_bounds.comp). The gather reads nothing outside it, and the cells outside it are
// zero in the splat and in every pass's exact result. On lavapipe a thread that returns at once
// still costs its share of a work group, so the pass is dispatched over the box alone: its
// VkDispatchIndirectCommand, its first and last thread, and the input cells its taps may read
// along the axis. One thread, one pass.
#include "common.glsl"
#include "grid.glsl"

layout(constant_id = 1) const uint GROUP = 8;  // grid_axis.comp's threads per group along x
layout(constant_id = 2) const uint RUN = JADE_GRID_AXIS_RUN;    // grid_axis.comp's output cells per thread

#include "bake_interface.h"  // structs GridAxisPush, GridAxisDispatch, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { GridAxisPush pc; };

layout(binding = 0, scalar) readonly buffer Levels { GridLevel levels[]; };
layout(binding = 1, scalar) readonly buffer Bounds { uvec3 bounds_lo, bounds_hi; };  // grid_bounds.comp
layout(binding = 2, scalar) writeonly buffer Dispatches { GridAxisDispatch dispatches[]; };

// The cells [first, last] of `level` (of `dims` cells) that this frame's sources reach.
void active_box(uint level, uvec3 dims, out ivec3 first, out ivec3 last)
{
    GridLevel l;
    l.inv_h = levels[level].inv_h, l.dims = dims;
    footprint_box(l, level_origin(l, pc.cube_side, cube_corner(pc.cube_side, bounds_lo, bounds_hi)),
                  from_ordered_bits(bounds_lo), from_ordered_bits(bounds_hi), first, last);
}

void main()
{
    // The input's box: axes already filtered are the output level's, the others the input's
    // (so the push constants' dims are the levels' own on every axis used).
    ivec3 in_first, in_last, out_first, out_last;
    active_box(pc.level_in, pc.in_dims, in_first, in_last);
    active_box(pc.level_out, pc.out_dims, out_first, out_last);
    [[unroll]] for (uint a = 0u; a < 3u; ++a)
        if (a < pc.axis) in_first[a] = out_first[a], in_last[a] = out_last[a];
    // Threads count runs of RUN cells along the axis, cells along the others (grid_axis.comp).
    uint a = pc.axis;
    ivec3 dims = ivec3(pc.out_dims);
    ivec3 first = max(in_first, ivec3(0)), last = min(in_last, dims - 1);
    first[a] = max(out_first[a], 0) / int(RUN);
    last[a] = min(out_last[a], dims[a] - 1);
    last[a] = last[a] < 0 ? -1 : last[a] / int(RUN);
    uvec3 count = uvec3(max(last - first + 1, ivec3(0)));
    GridAxisDispatch d;
    d.groups = uvec3((count.x + GROUP - 1u) / GROUP, count.y, count.z);
    d.first = first;
    d.last = last;
    d.tap_first = max(in_first[a], 0);
    d.tap_last = min(in_last[a], int(pc.in_dims[a]) - 1);
    dispatches[pc.pass] = d;
}
