#version 460
#extension GL_GOOGLE_include_directive : require
// The smooth part of t_m, step 2 of 3: one axis of a separable filter over one grid
// (engine/src/bake/grid_field.hpp), either
//   blur:     a sampled Gaussian of variance σ² − 2h²/3 (splat and gather each add the
//             B-spline's h²/3), STEP 1: out[o] = Σ_k w[|k|]·in[o + k];
//   restrict: the cubic B-spline's two-scale filter (1 4 6 4 1)/8 onto the grid of twice the
//             spacing, STEP 2: out[o] = Σ_k w[|k|]·in[2o − 2 + k]. Exact: splatting into the
//             coarse grid gives the same cells, so only the two finest grids take atomics.
// Cells outside the input grid are zero (every source lies two cells or more inside).
// A deforming mesh's grids are cubes that hold any pose (grid_field.hpp). There a pass works on
// the box of cells this frame's sources reach, dispatched over that box's threads alone
// (grid_boxes.comp): its taps read only inside it (the buffers hold earlier frames' values out
// there), and threads that rounding adds return at once.
// One thread per RUN consecutive output cells along the axis: it fetches the inputs they share
// once (lavapipe pays per fetch, not per multiply-add). The half-width and step are
// specialisation constants, so the taps unroll with constant indices.
#include "common.glsl"

layout(constant_id = 1) const int HALF_WIDTH = 8;
layout(constant_id = 2) const int STEP = 1;
// The input: 0 floats; the fixed-point splat (inv_scale: area per unit; the weight unsigned, the
// normal's xyz signed at half the scale) as 1: four 32-bit sums, 2: two 64-bit sums of pairs
// (grid_splat_body.glsl), whose high halves carry the low halves' borrows.
layout(constant_id = 3) const uint FIXED = 0u;
#include "bake_interface.h"  // structs GridAxisPush, GridAxisDispatch, JADE_GRID_AXIS_RUN, shared with engine/src/bake
const int RUN = JADE_GRID_AXIS_RUN;
const int INPUTS = STEP * (RUN - 1) + 2 * HALF_WIDTH + 1;
layout(push_constant, scalar) uniform Push { GridAxisPush pc; };

// Four fields per cell, one RGBA texel (grid_splat_body.glsl): one fetch serves them all, and
// lavapipe pays per fetch, not per multiply-add.
layout(binding = 0) uniform usamplerBuffer splat;  // texel fetches: lavapipe's storage loads are per-lane loops
layout(binding = 1) uniform samplerBuffer source;
layout(binding = 2, scalar) writeonly buffer Target { vec4 target[]; };
layout(binding = 3, scalar) readonly buffer Dispatches { GridAxisDispatch dispatches[]; };  // grid_boxes.comp

vec4 fetch(int texel)
{
    if (FIXED != 0u) {
        uvec4 u = texelFetch(splat, texel);
        ivec3 n = ivec3(u.yzw);
        // 64-bit pairs: (weight, n.x) has no borrow (the weight is never negative); (n.y, n.z)
        // borrowed one from n.z where the sum of n.y is negative.
        if (FIXED == 2u && n.y < 0) n.z += 1;
        return vec4(float(u.x), vec3(n) * 2.0) * pc.inv_scale;
    }
    return texelFetch(source, texel);
}

void main()
{
    // gl_GlobalInvocationID counts runs along the axis, cells along the others (from the active
    // box's first thread when there is one). The taps read input cells [lo, hi] along the axis.
    uvec3 id = pc.in_dims;
    ivec3 thread = ivec3(gl_GlobalInvocationID);
    int lo = 0, hi = int(id[pc.axis]) - 1;
    if (pc.cube_side > 0.0) {
        GridAxisDispatch box = dispatches[pc.pass];
        thread += box.first;
        if (any(greaterThan(thread, box.last))) return;
        lo = box.tap_first, hi = box.tap_last;
    }
    uvec3 o = uvec3(thread);
    uvec3 od = pc.out_dims;
    o[pc.axis] *= uint(RUN);
    if (o.x >= od.x || o.y >= od.y || o.z >= od.z) return;
    int stride = pc.axis == 0u ? 1 : pc.axis == 1u ? int(id.x) : int(id.x * id.y);
    uvec3 at = o;
    at[pc.axis] = 0u;
    int row = int(pc.in_offset + (at.z * id.y + at.y) * id.x + at.x);  // the input row's first cell
    int first = STEP * int(o[pc.axis]) + pc.shift - HALF_WIDTH;
    vec4 inputs[INPUTS];
    [[unroll]] for (int i = 0; i < INPUTS; ++i) {
        int at_i = first + i;
        inputs[i] = at_i >= lo && at_i <= hi ? fetch(row + clamp(at_i, lo, hi) * stride) : vec4(0.0);
    }
    int out_stride = pc.axis == 0u ? 1 : pc.axis == 1u ? int(od.x) : int(od.x * od.y);
    int out_at = int(pc.out_offset + (o.z * od.y + o.y) * od.x + o.x);
    int count = min(RUN, int(od[pc.axis] - o[pc.axis]));
    [[unroll]] for (int r = 0; r < RUN; ++r) {
        vec4 sum = vec4(0.0);
        [[unroll]] for (int k = -HALF_WIDTH; k <= HALF_WIDTH; ++k) sum += pc.w[k < 0 ? -k : k] * inputs[STEP * r + HALF_WIDTH + k];
        if (r < count) target[out_at + r * out_stride] = sum;
    }
}
