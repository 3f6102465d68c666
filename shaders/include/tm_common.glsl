// tm_common.glsl - what the t_m kernels share: channel count, the source layout, the
// vertex-disk rule for one (target, source) pair, and compensated summation.
#ifndef JADE_TM_COMMON_GLSL
#define JADE_TM_COMMON_GLSL

#include "profile.glsl"

// 1 for grey materials (one profile baked, copied to RGB), else 3.
layout(constant_id = 1) const uint CHANNELS = 3u;

// Sources within NEAR_FACTOR disk radii are integrated over their disk, farther ones are
// points (jade/bake.hpp). 4 keeps the point approximation's error below 0.2 % of the pair.
const float NEAR_FACTOR = 4.0;

layout(binding = 0, scalar) readonly buffer Profiles { Profile profiles[3]; };

// Contribution of source j (position ps, area, visibility = 1 − A_o) to the target at pt,
// excluding the visibility, for one channel. Self pairs are handled by the caller.
float pair_kernel(Profile p, float r, float area, float rho)
{
    return r < NEAR_FACTOR * rho ? disk_integral(p, r, rho) : area * profile_r(p, r);
}

float self_kernel(Profile p, float rho) { return profile_cdf(p, rho); }

// Kahan–Babuška (Neumaier) summation: `precise` keeps the compiler from re-associating it away.
void compensated_add(inout vec3 sum, inout vec3 comp, vec3 x)
{
    precise vec3 t = sum + x;
    precise vec3 big = mix(x, sum, greaterThanEqual(abs(sum), abs(x)));
    precise vec3 small = mix(sum, x, greaterThanEqual(abs(sum), abs(x)));
    comp += (big - t) + small;
    sum = t;
}

#endif
