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

// The profiles in registers: read once per thread, not once per pair.
Profile[3] load_profiles()
{
    return Profile[3](profiles[0], profiles[1], profiles[2]);
}

// Point value A_j·R(r) of source j for a target at distance r, or 0 when the target lies
// within NEAR_FACTOR disk radii (the near pass, tm_near.comp, integrates those pairs over the
// disk, and the self disk). Also 0 for the target itself (r = 0).
float far_pair(Profile p, float r, float area)
{
    bool far = r * r >= (NEAR_FACTOR * NEAR_FACTOR / JADE_PI) * area;
    float value = area * profile_r(p, max(r, 1e-30));
    return far ? value : 0.0;
}

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
