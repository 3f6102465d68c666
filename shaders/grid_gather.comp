#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
// The smooth part of t_m, step 3 of 3: at each target, every grid's blurred value with the
// same cubic B-spline as the splat, weighted per channel, added to the near pass's partial sums
// (which hold the short part). One thread per tree slot in [slot_begin, slot_begin + count).
#include "common.glsl"
#include "grid.glsl"
#include "tm_common.glsl"

#include "bake_interface.h"  // struct GridGatherPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { GridGatherPush pc; };

layout(binding = 1, scalar) readonly buffer Levels { GridLevel levels[]; };
layout(binding = 2, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 3, scalar) readonly buffer Order { uint order[]; };  // slot → bake vertex
// Per cell: (1 − A_o)·area, and times n.x, n.y, n.z (grid_splat_body.glsl), blurred.
layout(binding = 4) uniform samplerBuffer blurred;

layout(binding = 9, scalar) readonly buffer Bounds { uvec3 bounds_lo, bounds_hi; };  // grid_bounds.comp

#define TM_STATE_BINDING 5
#include "tm_state.glsl"

void main()
{
    uint t = jade_thread_index();
    if (t >= pc.slot_count) return;
    uint k = pc.slot_begin + t;
    uint v = order[k];
    vec3 x = positions[v];
    vec3 sum = partial_sum[k], comp = partial_comp[k];
    vec3 normal[3] = vec3[3](vec3(0.0), vec3(0.0), vec3(0.0));
    vec3 corner = cube_corner(pc.cube_side, bounds_lo, bounds_hi);
    for (uint g = 0u; g < pc.level_count; ++g) {
        GridLevel l = levels[g];
        if (l.weight == vec3(0.0)) continue;  // a grid kept only to restrict the next ones from
        ivec3 base;
        vec4 wx, wy, wz;
        bspline_footprint(l, level_origin(l, pc.cube_side, corner), x, base, wx, wy, wz);
        vec4 value = vec4(0.0);
        [[unroll]] for (int c = 0; c < 4; ++c)
            [[unroll]] for (int j = 0; j < 4; ++j) {
                int at = int(grid_cell(l, base + ivec3(0, j, c)));
                float w = wy[j] * wz[c];
                value += w * (wx.x * texelFetch(blurred, at) + wx.y * texelFetch(blurred, at + 1) + wx.z * texelFetch(blurred, at + 2) +
                              wx.w * texelFetch(blurred, at + 3));
            }
        compensated_add(sum, comp, value.x * l.weight);
        add_weighted(normal, l.weight, value.yzw);
    }
    save_partial(k, v, sum, comp);
    add_normal_sums(v, normal);
}
