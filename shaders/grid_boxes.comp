#version 460
#extension GL_GOOGLE_include_directive : require
// The dispatch of one pass of grid_axis.comp over a deforming mesh's grids: the threads whose
// output lies in this frame's active box (grid_axis_box.glsl), as a VkDispatchIndirectCommand and
// the box's first thread. On lavapipe a thread that returns at once still costs its share of a
// work group, and the cube's cells outside the box are most of them. One thread, one pass.
#include "common.glsl"
#include "grid_axis_box.glsl"

layout(constant_id = 1) const uint GROUP = 8;  // grid_axis.comp's threads per group along x
layout(constant_id = 2) const uint RUN = 8;    // grid_axis.comp's output cells per thread

layout(push_constant, scalar) uniform Push { GridAxisPush pc; };

layout(binding = 0, scalar) readonly buffer Levels { GridLevel levels[]; };
layout(binding = 1, scalar) readonly buffer Bounds { uvec3 bounds_lo, bounds_hi; };  // grid_bounds.comp
layout(binding = 2, scalar) writeonly buffer Dispatches { GridAxisDispatch dispatches[]; };

void main()
{
    ivec3 in_first, in_last, out_first, out_last;
    axis_pass_boxes(pc, levels[pc.level_in].inv_h, levels[pc.level_out].inv_h, bounds_lo, bounds_hi, in_first,
                    in_last, out_first, out_last);
    // Threads count runs of RUN cells along the axis, cells along the others (grid_axis.comp).
    ivec3 first = max(in_first, ivec3(0)), last = min(in_last, ivec3(pc.out_dims) - 1);
    uint a = pc.axis;
    first[a] = max(out_first[a], 0) / int(RUN);
    last[a] = min(out_last[a], int(pc.out_dims[a]) - 1);
    last[a] = last[a] < 0 ? -1 : last[a] / int(RUN);
    uvec3 count = uvec3(max(last - first + 1, ivec3(0)));
    GridAxisDispatch d;
    d.groups = uvec3((count.x + GROUP - 1u) / GROUP, count.y, count.z);
    d.first = uvec3(first);
    d.pad0 = d.pad1 = 0u;
    dispatches[pc.pass] = d;
}
