// bake/gpu_profile.hpp - ChannelProfile in the layout of `Profile` in shaders/include/profile.glsl.
#pragma once

#include <jade/error.hpp>
#include <jade/material.hpp>

#include <array>
#include <cmath>
#include <cstdint>

namespace jade::bake {

struct GpuProfile {
    uint32_t kind = 0, count = 0;
    float a = 0, b = 0, c = 0;
    float w[6] = {}, v[6] = {};
    /// Beyond this distance a cluster is faint (tm_cluster.comp); set by the far pass's setup.
    float faint_radius = 3.0e38f;
};
static_assert(sizeof(GpuProfile) == 72);

/// The smallest r with R(r)·total_weight ≤ threshold (R decreases with r for every kind), by
/// bisection in float64: the clustered pass then tests distances instead of evaluating R.
inline float faint_radius(const ChannelProfile& p, double total_weight, double threshold, double scale)
{
    auto faint = [&](double r) { return p.R(r) * total_weight <= threshold; };
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
    GpuProfile g;
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
