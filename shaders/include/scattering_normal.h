// scattering_normal.h - BakeResult::scattering_normal and normal_spread (jade/bake.hpp) from the
// per-channel normal sums N_c (tm_state.glsl) and t_m, written once in the words that C++ (GLM)
// and GLSL share: the static bake's read-back (bake/bake_common.hpp) and a deforming mesh's
// pack_vertices.comp both call these.
#ifndef JADE_SCATTERING_NORMAL_H
#define JADE_SCATTERING_NORMAL_H

#ifdef __cplusplus
#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

namespace jade::bake::scattering {
using namespace glm;  // only in here: the functions below are written in GLSL's words
#define JADE_INLINE inline
#else
#define JADE_INLINE
#endif

// The direction of N_0 + N_1 + N_2, or 0 where the sum is too short to have one (nothing within
// the profile's reach is lit) or not finite: the caller then takes the vertex normal.
JADE_INLINE vec3 scattering_direction(vec3 n0, vec3 n1, vec3 n2)
{
    vec3 s = n0 + n1 + n2;
    float len2 = dot(s, s);
    return len2 > 1e-30f && len2 < 3e38f ? s / sqrt(len2) : vec3(0.0f);
}

// Per channel 1 − |N_c|/t_m,c clamped to [0, 1]; 0 where t_m,c is not positive or |N_c| not finite.
JADE_INLINE vec3 normal_spread(vec3 n0, vec3 n1, vec3 n2, vec3 tm)
{
    vec3 len = vec3(length(n0), length(n1), length(n2));
    vec3 ratio = mix(vec3(1.0f), len / max(tm, vec3(1e-30f)), greaterThan(tm, vec3(0.0f)));
    return clamp(1.0f - mix(ratio, vec3(1.0f), isnan(ratio)), vec3(0.0f), vec3(1.0f));
}

#undef JADE_INLINE
#ifdef __cplusplus
}  // namespace jade::bake::scattering
#endif

#endif  // JADE_SCATTERING_NORMAL_H
