// bake/gpu_profile.hpp - ChannelProfile in the layout of `Profile` in shaders/include/profile_interface.h.
#pragma once

#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/material.hpp>

#include "profile_interface.h"  // struct Profile, shared with the shaders

#include <array>
#include <cmath>
#include <cstdint>

namespace jade::bake {

/// A channel's profile as the shaders read it: Profile of profile_interface.h.
using GpuProfile = Profile;
static_assert(JADE_PROFILE_BURLEY == uint32_t(ProfileKind::Burley) &&
              JADE_PROFILE_DIPOLE == uint32_t(ProfileKind::Dipole) &&
              JADE_PROFILE_GAUSSIANS == uint32_t(ProfileKind::Gaussians));
static_assert(JADE_PROFILE_MAX_GAUSSIANS == ChannelProfile::kMaxGaussians);

/// The smallest r with R(r)·total_weight ≤ threshold (R decreases with r for every kind), by
/// bisection in float64: the clustered pass then tests distances instead of evaluating R.
inline float faint_radius(const ChannelProfile& p, double total_weight, double threshold, double scale)
{
    auto faint = [&](double r) { return dev::profile_value(p, r) * total_weight <= threshold; };
    double lo = 1e-12 * scale, hi = 1e12 * scale;
    if (faint(lo)) return 0.0f;
    if (!faint(hi)) return 3.0e38f;
    for (int k = 0; k < 200 && hi > lo * (1 + 1e-7); ++k) {
        const double mid = std::sqrt(lo * hi);  // bisection in log r: the bracket spans 24 decades
        (faint(mid) ? hi : lo) = mid;
    }
    return float(hi);
}

inline GpuProfile to_gpu(const ChannelProfile& p)
{
    GpuProfile g{};
    g.faint_radius = 3.0e38f;  // none: set by the far pass's setup (tm_passes.cpp)
    g.kind = uint32_t(p.kind);
    switch (p.kind) {
    case ProfileKind::Burley: g.a = float(p.d); break;
    case ProfileKind::Dipole: g.a = float(p.sigma_tr), g.b = float(p.z_r), g.c = float(p.z_v); break;
    case ProfileKind::Gaussians:
        g.count = p.gaussian_count;
        for (uint32_t k = 0; k < p.gaussian_count; ++k) g.w[k] = float(p.weight[k]), g.v[k] = float(p.variance[k]);
        break;
    }
    // float32 has ~1e±38: profiles are meant for meshes in sane units, but say so clearly.
    for (float x : {g.a, g.b, g.c})
        if (!std::isfinite(x) || (x != 0 && std::fabs(x) < 1e-30f))
            throw Error("material: profile parameter out of float32 range for the GPU bake (rescale the mesh units)");
    return g;
}

inline std::array<GpuProfile, 3> to_gpu(const Material& m)
{
    return {to_gpu(m.profile[0]), to_gpu(m.profile[1]), to_gpu(m.profile[2])};
}

}  // namespace jade::bake
