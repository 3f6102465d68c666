// grid.glsl - the grids of the smooth part of t_m (engine/src/bake/grid_field.hpp): their
// layout and the cubic B-spline that splats sources into them and gathers values from them.
#ifndef JADE_GRID_GLSL
#define JADE_GRID_GLSL

#include "bake_interface.h"

const uint GRID_MAX_HALF_WIDTH = JADE_GRID_MAX_HALF_WIDTH;  // = bake::kGridMaxHalfWidth

// struct GridLevel (= bake::GpuGridLevel): bake_interface.h.

// Floats as unsigned integers in the same order (for atomicMin/atomicMax), and back.
uint ordered_bits(float f)
{
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float from_ordered_bits(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u); }

// Where a level's cell (0, 0, 0) is. A static bake's grids stay where the plan put them; a
// deforming mesh's (cube_side > 0) are cubes of that side centred on its current bounds
// (`corner`: the cube's lowest corner), each two cells beyond the corner as the static ones are
// beyond the mesh's bounds.
vec3 from_ordered_bits(uvec3 u) { return vec3(from_ordered_bits(u.x), from_ordered_bits(u.y), from_ordered_bits(u.z)); }

vec3 cube_corner(float cube_side, uvec3 lo_bits, uvec3 hi_bits)
{
    return 0.5 * (from_ordered_bits(lo_bits) + from_ordered_bits(hi_bits)) - 0.5 * cube_side;
}
vec3 level_origin(GridLevel l, float cube_side, vec3 corner) { return cube_side > 0.0 ? corner - 2.0 / l.inv_h : l.origin; }

// The four cubic B-spline weights of the cells floor(u) − 1 .. floor(u) + 2 at fraction t.
vec4 bspline_weights(float t)
{
    float s = 1.0 - t, t2 = t * t;
    return vec4(s * s * s, 3.0 * t2 * t - 6.0 * t2 + 4.0, -3.0 * t2 * t + 3.0 * t2 + 3.0 * t + 1.0, t2 * t) / 6.0;
}

// The first of the 4×4×4 cells a point reaches and its weights per axis. Points outside the
// grid (a deforming mesh that left the rest pose's bounds and padding) count at its boundary.
void bspline_footprint(GridLevel l, vec3 origin, vec3 x, out ivec3 base, out vec4 wx, out vec4 wy, out vec4 wz)
{
    vec3 u = clamp((x - origin) * l.inv_h, vec3(1.0), vec3(l.dims) - vec3(2.0001));
    vec3 f = floor(u);
    base = ivec3(f) - 1;
    vec3 t = u - f;
    wx = bspline_weights(t.x);
    wy = bspline_weights(t.y);
    wz = bspline_weights(t.z);
}

// The cells that the splats of points within [lo, hi] reach on level l: from the footprint of
// lo to that of hi (the footprint's first cell does not decrease as x grows).
void footprint_box(GridLevel l, vec3 origin, vec3 lo, vec3 hi, out ivec3 first, out ivec3 last)
{
    vec4 wx, wy, wz;
    bspline_footprint(l, origin, lo, first, wx, wy, wz);
    bspline_footprint(l, origin, hi, last, wx, wy, wz);
    last += ivec3(3);
}

uint grid_cell(GridLevel l, ivec3 c) { return l.offset + (uint(c.z) * l.dims.y + uint(c.y)) * l.dims.x + uint(c.x); }

#endif
