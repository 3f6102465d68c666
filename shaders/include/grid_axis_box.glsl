// grid_axis_box.glsl - which cells one pass of grid_axis.comp works on (engine/src/bake/
// tm_grid.cpp). A deforming mesh's grids are cubes that hold any pose, several times the cells
// its sources reach in one frame: there a pass works on the box of cells this frame's sources
// reach (footprint_box, from the bounds of grid_bounds.comp). The gather reads nothing outside
// it, and the cells outside it are zero in the splat and in every pass's exact result.
// grid_boxes.comp sizes each pass's dispatch to that box; grid_axis.comp skips what rounding adds.
#ifndef JADE_GRID_AXIS_BOX_GLSL
#define JADE_GRID_AXIS_BOX_GLSL

#include "grid.glsl"
#include "bake_interface.h"  // struct GridAxisPush

// The cells [first, last] of a level (inverse spacing inv_h, `dims` cells) that the sources in
// [lo, hi] reach: all of a static mesh's grids (cube_side 0), which fit its bounds.
void active_box(float cube_side, float inv_h, uvec3 dims, vec3 corner, vec3 lo, vec3 hi, out ivec3 first,
                out ivec3 last)
{
    first = ivec3(0), last = ivec3(dims) - 1;
    if (cube_side > 0.0) {
        GridLevel l;
        l.inv_h = inv_h, l.dims = dims;
        footprint_box(l, level_origin(l, cube_side, corner), lo, hi, first, last);
    }
}

// The input's and the output's boxes of pass `p` (levels of inverse spacing inv_h_in and
// inv_h_out; bounds as grid_bounds.comp writes them): on the axes already filtered the input is
// the output level's, on the others its own (the push constants' dims are the levels' own on
// every axis used).
void axis_pass_boxes(GridAxisPush p, float inv_h_in, float inv_h_out, uvec3 lo_bits, uvec3 hi_bits,
                     out ivec3 in_first, out ivec3 in_last, out ivec3 out_first, out ivec3 out_last)
{
    vec3 corner = cube_corner(p.cube_side, lo_bits, hi_bits);
    vec3 lo = from_ordered_bits(lo_bits), hi = from_ordered_bits(hi_bits);
    active_box(p.cube_side, inv_h_in, p.in_dims, corner, lo, hi, in_first, in_last);
    active_box(p.cube_side, inv_h_out, p.out_dims, corner, lo, hi, out_first, out_last);
    [[unroll]] for (uint a = 0u; a < 3u; ++a)
        if (a < p.axis) in_first[a] = out_first[a], in_last[a] = out_last[a];
}

#endif
