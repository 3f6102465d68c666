// profile_interface.h - a channel's scattering profile as the bake's shaders read it, written
// once for C++ (bake/gpu_profile.hpp fills it from jade::ChannelProfile) and GLSL (profile.glsl).
// Scalar layout: 4-byte members in order, as C++ places them; the size is checked in C++.
#ifndef JADE_PROFILE_INTERFACE_H
#define JADE_PROFILE_INTERFACE_H

// Profile kinds: jade::ProfileKind's values (bake/gpu_profile.hpp asserts they match; the public
// enum cannot include this private header), and MIXED for a kernel that reads each profile's own
// kind at run time (the specialisation constant PROFILE_KIND, profile.glsl).
#define JADE_PROFILE_BURLEY 0
#define JADE_PROFILE_DIPOLE 1
#define JADE_PROFILE_GAUSSIANS 2
#define JADE_PROFILE_MIXED 3
// Gaussian terms of a profile, at most (= ChannelProfile::kMaxGaussians, asserted in C++).
#define JADE_PROFILE_MAX_GAUSSIANS 6

#ifdef __cplusplus
#include <cstdint>

namespace jade::bake {
namespace glsl {
using uint = std::uint32_t;
}  // namespace glsl
using namespace glsl;  // only this name: the struct below is written in GLSL's words
#endif

struct Profile {
    uint kind;                            // JADE_PROFILE_*
    uint count;                           // Gaussians: number of terms
    float a;                              // Burley: d.  Dipole: σ_tr
    float b;                              // Dipole: z_r
    float c;                              // Dipole: z_v
    float w[JADE_PROFILE_MAX_GAUSSIANS];  // Gaussians: weights (sum 1)
    float v[JADE_PROFILE_MAX_GAUSSIANS];  // Gaussians: variances, units²
    float faint_radius;                   // tm_cluster.comp: clusters farther than this are faint
};

#ifdef __cplusplus
static_assert(sizeof(Profile) == 4 * (6 + 2 * JADE_PROFILE_MAX_GAUSSIANS), "scalar layout packs Profile so");
}  // namespace jade::bake
#endif

#endif  // JADE_PROFILE_INTERFACE_H
