// shading/separable_kernel.cpp - jade/dev/separable.hpp: the separable kernel and the transmittance
// profile fitted to a material's profiles, in float64.
#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/dev/separable.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace jade {

namespace {

// H(x) = (1/π) ∫_0^{π/2} (1 − cdf(x / cos φ)) dφ, x ≥ 0: the profile's mass in the half-plane
// beyond the line at distance x (the points at radius r beyond it span the angle 2 acos(x/r);
// integrating 2 acos(x/r) R(r) r dr by parts and putting r = x / cos φ gives this form).
double half_plane_beyond(const ChannelProfile& p, double x)
{
    if (x <= 0.0) return 0.5;
    constexpr int kIntervals = 2048;  // even: composite Simpson
    const double h = 0.5 * std::numbers::pi / kIntervals;
    auto f = [&](int k) {
        const double c = std::cos(h * k);
        return c <= 0.0 ? 0.0 : 1.0 - dev::profile_cdf(p, x / c);  // φ = π/2: the line's far end, nothing beyond
    };
    double sum = f(0) + f(kIntervals);
    for (int k = 1; k < kIntervals; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(k);
    return std::clamp(sum * h / 3.0 / std::numbers::pi, 0.0, 0.5);
}

}  // namespace

double profile_edge_response(const ChannelProfile& profile, double x)
{
    return x >= 0.0 ? 1.0 - half_plane_beyond(profile, x) : half_plane_beyond(profile, -x);
}

double separable_transmittance(const ChannelProfile& profile, double d)
{
    return std::clamp(1.0 - dev::profile_cdf(profile, std::max(d, 0.0)), 0.0, 1.0);
}

SeparableKernel separable_kernel(const Material& material, uint32_t taps)
{
    if (taps != 11 && taps != 17 && taps != 25)
        throw Error("separable kernel: taps must be 11, 17 or 25 (got " + std::to_string(taps) + ")");
    // The range: where the widest channel's half-plane tail falls to kSeparableKernelTail
    // (bisection; H decreases with x). Start from the profile's own scale.
    double range = 0.0;
    for (const ChannelProfile& p : material.profile) {
        double lo = 0.0, hi = std::max(dev::radius_for_tail(p, 1e-3), 1e-30);
        while (half_plane_beyond(p, hi) > kSeparableKernelTail) lo = hi, hi *= 2.0;
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (lo + hi);
            (half_plane_beyond(p, mid) > kSeparableKernelTail ? lo : hi) = mid;
        }
        range = std::max(range, hi);
    }
    SeparableKernel k;
    k.range = range;
    k.offset.resize(taps);
    for (uint32_t i = 0; i < taps; ++i) {
        const double t = -1.0 + 2.0 * double(i) / double(taps - 1);
        k.offset[i] = range * t * std::fabs(t);  // Jimenez's EXPONENT 2: denser near the centre
    }
    k.offset[taps / 2] = 0.0;
    k.weight.assign(taps, glm::dvec3(0.0));
    for (int c = 0; c < 3; ++c) {
        const ChannelProfile& p = material.profile[size_t(c)];
        double below = 0.0;  // E at the lower midpoint, E(−∞) = 0
        for (uint32_t i = 0; i < taps; ++i) {
            const double above = i + 1 < taps ? profile_edge_response(p, 0.5 * (k.offset[i] + k.offset[i + 1])) : 1.0;
            k.weight[i][c] = above - below;
            below = above;
        }
    }
    return k;
}

}  // namespace jade
