// grid_splat_body.glsl - grid_splat.comp and grid_splat_int64.comp.
// The smooth part of t_m, step 1 of 3: every source's (1 − A_o)·area into every Gaussian's grid
// with cubic B-spline weights (engine/src/bake/grid_field.hpp). Integer atomics on fixed-point
// values: the sums do not depend on the order threads run in, so a bake is reproducible bit for
// bit. One thread per vertex. Four fields per cell, interleaved (4·cell + f): the weight itself
// (unsigned fixed point), then the weight times the normal's x, y, z, the normal sums of
// tm_state.glsl (signed, two's complement at half the scale, so their sums stay within ±2^31).
// With JADE_SPLAT_INT64 (shaderInt64 and shaderBufferInt64Atomics) the four fields go in as two
// 64-bit atomics, (weight, n.x) and (n.y, n.z): a 64-bit sum of lo + 2^32·hi is the pair of
// 32-bit sums, the low one's carry or borrow moved into the high one, which grid_axis.comp
// (FIXED = 2) takes back out. Half the atomics; the same integers, so the same bake.
#include "common.glsl"
#include "grid.glsl"

#include "bake_interface.h"  // struct GridSplatPush, shared with engine/src/bake
layout(push_constant, scalar) uniform Push { GridSplatPush pc; };

layout(binding = 0, scalar) readonly buffer Levels { GridLevel levels[]; };
layout(binding = 1, scalar) readonly buffer Positions { vec3 positions[]; };
layout(binding = 2, scalar) readonly buffer Areas { float areas[]; };
layout(binding = 3, scalar) readonly buffer Ao { float ao[]; };
#ifdef JADE_SPLAT_INT64
layout(binding = 4, scalar) buffer Cells { uint64_t cells[]; };  // 2 per cell: (weight, n.x), (n.y, n.z)
#else
layout(binding = 4, scalar) buffer Cells { uint cells[]; };  // 4 per cell: field f at 4·cell + f
#endif
layout(binding = 5, scalar) readonly buffer Bounds { uvec3 bounds_lo, bounds_hi; };  // grid_bounds.comp
layout(binding = 6, scalar) readonly buffer Normals { vec3 normals[]; };

void main()
{
    uint v = jade_thread_index();
    if (v >= pc.vertex_count) return;
    vec3 x = positions[v];
    float weight = max(areas[v], 0.0) * (1.0 - ao[v]);
    vec3 weight_n = 0.5 * weight * normals[v];
    vec3 corner = cube_corner(pc.cube_side, bounds_lo, bounds_hi);
    for (uint g = 0u; g < pc.level_count; ++g) {
        GridLevel l = levels[g];
        ivec3 base;
        vec4 wx, wy, wz;
        bspline_footprint(l, level_origin(l, pc.cube_side, corner), x, base, wx, wy, wz);
        float w = weight * l.splat_scale;
        vec3 wn = weight_n * l.splat_scale;
        [[unroll]] for (int k = 0; k < 4; ++k)
            [[unroll]] for (int j = 0; j < 4; ++j) {
                float b_jk = wy[j] * wz[k];
                uint row = grid_cell(l, base + ivec3(0, j, k));
                [[unroll]] for (int i = 0; i < 4; ++i) {
                    float b = b_jk * wx[i];
                    uint weight_fixed = uint(w * b + 0.5);
                    ivec3 n = ivec3(floor(wn * b + 0.5));
#ifdef JADE_SPLAT_INT64
                    uint at = 2u * (row + uint(i));
                    atomicAdd(cells[at], uint64_t(weight_fixed) + (uint64_t(int64_t(n.x)) << 32));
                    atomicAdd(cells[at + 1u], uint64_t(int64_t(n.y)) + (uint64_t(int64_t(n.z)) << 32));
#else
                    uint at = 4u * (row + uint(i));
                    atomicAdd(cells[at], weight_fixed);
                    atomicAdd(cells[at + 1u], uint(n.x));
                    atomicAdd(cells[at + 2u], uint(n.y));
                    atomicAdd(cells[at + 3u], uint(n.z));
#endif
                }
            }
    }
}
