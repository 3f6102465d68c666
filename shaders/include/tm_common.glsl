// tm_common.glsl - what the t_m kernels share: channel count, the source layout, the
// vertex-disk rule for one (target, source) pair, and compensated summation.
#ifndef JADE_TM_COMMON_GLSL
#define JADE_TM_COMMON_GLSL

#include "bake_interface.h"  // JADE_NEAR_FACTOR
#include "direction.glsl"
#include "profile.glsl"

// 1 for grey materials (one profile baked, copied to RGB), else 3.
layout(constant_id = 1) const uint CHANNELS = 3u;

// Sources within NEAR_FACTOR disk radii are integrated over their disk, farther ones are
// points (jade/bake.hpp). 4 keeps the point approximation's error below 0.2 % of the pair.
const float NEAR_FACTOR = JADE_NEAR_FACTOR;  // bake_interface.h

layout(binding = 0, scalar) readonly buffer Profiles { Profile profiles[3]; };

// The profiles in registers: read once per thread, not once per pair.
Profile[3] load_profiles()
{
    return Profile[3](profiles[0], profiles[1], profiles[2]);
}

// The far passes read the sources in tree order (exact pass: bake order) from a texel buffer
// written by gather_sources.comp, two RGBA32F texels per source:
//   2j:     position.xyz, weight = area·(1 − A_o)
//   2j + 1: near radius² = NEAR_FACTOR²·area/π, area, 1 − A_o, normal (direction.glsl)
// Within the near radius a pair is the near pass's (tm_near.comp, integrated over the disk).
const float NEAR_RADIUS2_PER_AREA = NEAR_FACTOR * NEAR_FACTOR / JADE_PI;

// Point value weight·R(r) of a source at squared distance r2 from the target with near radius²
// near_r2, or 0 when the pair is the near pass's, or the target itself (r2 = 0).
float far_pair(Profile p, float r2, float near_r2, float weight)
{
    float value = weight * profile_r(p, sqrt(max(r2, 1e-30)));
    return (r2 >= near_r2 && r2 > 0.0) ? value : 0.0;
}

// The point sums of a group of up to 8 sources, fetched cooperatively: lane m of the subgroup
// has fetched source m's texels (pw, extra); each lane adds the first `count` sources to its
// own target x, and per channel their normals with the same weights to `normal`. One texel
// fetch per lane serves 8 targets × 8 sources: lavapipe's loads cost far more than its
// arithmetic (docs/lavapipe.md). Needs a subgroup of at least 8 lanes with all lanes active.
vec3 far_group(Profile prof[3], vec3 x, vec4 pw, vec4 extra, uint count, inout vec3 normal[3])
{
    vec3 total = vec3(0.0);
    [[unroll]] for (uint m = 0u; m < 8u; ++m) {
        vec4 s = subgroupBroadcast(pw, m);
        vec4 e = subgroupBroadcast(extra, m);
        vec3 d = s.xyz - x;
        float r2 = dot(d, d);
        float w = m < count ? s.w : 0.0;
        vec3 n = decode_direction(e.w);
        [[unroll]] for (uint c = 0u; c < CHANNELS; ++c) {
            float v = far_pair(prof[c], r2, e.x, w);
            total[c] += v;
            normal[c] += v * n;
        }
    }
    return total;
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
