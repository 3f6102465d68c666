// shading/lut_reference.cpp - float64 references of the translucency and curvature LUTs
// (definitions and parameterisations in jade/dev/lut.hpp).
#include "bake/disk_integral.hpp"

#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/dev/lut.hpp>

#include "lut_interface.h"  // JADE_LUT_SERIES_FROM_T, shared with lut_build.comp

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace jade {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSeriesFromT = JADE_LUT_SERIES_FROM_T;  ///< lut_interface.h, shared with lut_build.comp
constexpr double kWindow = 10.0;                         ///< direct integration over |φ| ≤ 10σ (tail < 2e-23)

double clamp_cos(double cos_theta, const char* where)
{
    if (std::isnan(cos_theta)) throw Error(std::string(where) + ": cos_theta is NaN");
    return std::clamp(cos_theta, -1.0, 1.0);
}

void check_variance(double t, const char* where)
{
    if (!(t >= 0.0)) throw Error(std::string(where) + ": variance t = " + std::to_string(t) + " must be >= 0");
}

}  // namespace

double detail::lut_reference_series(double cos_theta, double t)
{
    const double c = clamp_cos(cos_theta, "lut_reference_series");
    check_variance(t, "lut_reference_series");
    const double theta = std::acos(c);
    double sum = 0.0;
    for (int k = 1; k < 100000; ++k) {
        const double kk = double(k) * double(k);
        const double term = std::exp(-2.0 * kk * t) / (4.0 * kk - 1.0);
        if (term < 1e-18) break;
        sum += ((k % 2 == 1) ? term : -term) * std::cos(2.0 * k * theta);
    }
    return 1.0 / kPi + 0.5 * std::exp(-0.5 * t) * c + (2.0 / kPi) * sum;
}

double detail::lut_reference_direct(double cos_theta, double t)
{
    const double c = clamp_cos(cos_theta, "lut_reference_direct");
    check_variance(t, "lut_reference_direct");
    if (t == 0.0) return std::max(c, 0.0);
    // f = ∫ max(cos(θ + σz), 0) φ(z) dz with φ the standard normal density, over the pieces
    // of |z| ≤ 10 where cos(θ + σz) ≥ 0: θ + σz ∈ [2πk − π/2, 2πk + π/2].
    const double theta = std::acos(c), sigma = std::sqrt(t);
    const double inv_sqrt_2pi = 1.0 / std::sqrt(2.0 * kPi);
    auto integrand = [&](double z) {
        return std::max(std::cos(theta + sigma * z), 0.0) * inv_sqrt_2pi * std::exp(-0.5 * z * z);
    };
    const int k_lo = int(std::floor((theta - kWindow * sigma + 0.5 * kPi) / (2.0 * kPi)));
    const int k_hi = int(std::ceil((theta + kWindow * sigma - 0.5 * kPi) / (2.0 * kPi)));
    double f = 0.0;
    for (int k = k_lo; k <= k_hi; ++k) {
        const double a = std::max(-kWindow, (2.0 * kPi * k - 0.5 * kPi - theta) / sigma);
        const double b = std::min(kWindow, (2.0 * kPi * k + 0.5 * kPi - theta) / sigma);
        if (a < b) f += bake::integrate(integrand, a, b, 1e-14, 1e-16);
    }
    return f;
}

double lut_reference(double cos_theta, double t)
{
    check_variance(t, "lut_reference");
    return t >= kSeriesFromT ? detail::lut_reference_series(cos_theta, t) : detail::lut_reference_direct(cos_theta, t);
}

double curvature_lut_reference(double cos_theta, double curvature_radius, const ChannelProfile& profile)
{
    const double c = clamp_cos(cos_theta, "curvature_lut_reference");
    const double r = curvature_radius;
    if (!(r > 0.0)) throw Error("curvature_lut_reference: curvature_radius = " + std::to_string(r) + " must be > 0");
    if (std::isinf(r)) return std::max(c, 0.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - c * c));
    // E(γ(s), θ): the clamped cosine averaged over the circle of chord s about x.
    auto irradiance = [&](double s) {
        const double h = std::min(s / (2.0 * r), 1.0);  // sin(γ/2)
        const double cos_g = 1.0 - 2.0 * h * h;
        const double sin_g = 2.0 * h * std::sqrt(std::max(0.0, 1.0 - h * h));
        const double a = cos_g * c, b = sin_g * sin_theta;  // a + b cos β, b ≥ 0
        if (b <= std::abs(a)) return std::max(a, 0.0);
        const double q = -a / b;  // cos β0
        return (a * std::acos(q) + b * std::sqrt(std::max(0.0, 1.0 - q * q))) / kPi;
    };
    // Weight 2πsR(s) on [0, 2r], cut where the profile's tail is below 1e-16. Panels shrink
    // geometrically towards s = 0 so that no scale of a multi-lobe profile escapes the nodes.
    auto integrand = [&](double s) { return bake::radial_density(profile, s) * irradiance(s); };
    double hi = std::min(2.0 * r, dev::radius_for_tail(profile, 1e-16)), num = 0.0;
    for (int k = 0; k < 48; ++k, hi *= 0.5) num += bake::integrate(integrand, 0.5 * hi, hi, 1e-12, 1e-300);
    num += bake::integrate(integrand, 0.0, hi, 1e-12, 1e-300);
    return num / dev::profile_cdf(profile, 2.0 * r);
}

}  // namespace jade
