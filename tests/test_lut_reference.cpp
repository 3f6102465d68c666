// float64 LUT references (engine/src/shading/lut_reference.cpp, jade/dev/lut.hpp): exact limits,
// normalisation, agreement of the two evaluation branches, the curvature LUT's limits; and the
// Gauss–Kronrod integrator they rely on.
#include "../engine/src/bake/disk_integral.hpp"

#include <jade/error.hpp>
#include <jade/dev/lut.hpp>
#include <jade/material.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace {

constexpr double kPi = std::numbers::pi;

/// ∫_{−π}^{π} g(θ) dθ for an even g given as a function of cos θ. For small t, f has a feature
/// of width √t at the terminator θ = π/2 that a quadrature node may never see: split there
/// at π/2 ± 10^−k.
template <class G> double integrate_over_angle(G&& g)
{
    std::vector<double> breaks = {0.0, kPi};
    for (double e = 1e-1; e > 1e-8; e *= 0.1) breaks.insert(breaks.end(), {kPi / 2 - e, kPi / 2 + e});
    breaks.push_back(kPi / 2);
    std::sort(breaks.begin(), breaks.end());
    double sum = 0.0;
    for (size_t k = 0; k + 1 < breaks.size(); ++k)
        sum += jade::bake::integrate([&](double theta) { return g(std::cos(theta)); }, breaks[k], breaks[k + 1], 1e-13,
                                     1e-16);
    return 2.0 * sum;
}

}  // namespace

TEST(Quadrature, GaussKronrodConstantsAndAdaptivity)
{
    // One GK15 panel integrates polynomials up to degree 22 exactly.
    for (int degree = 0; degree <= 22; ++degree) {
        const double v = jade::bake::integrate([&](double x) { return std::pow(x, degree); }, 0.0, 1.0, 1.0, 0.0, 1);
        EXPECT_NEAR(v, 1.0 / (degree + 1), 1e-15) << degree;
    }
    // Adaptive: endpoint singularity and a narrow peak.
    EXPECT_NEAR(jade::bake::integrate([](double x) { return std::sqrt(x); }, 0.0, 1.0), 2.0 / 3.0, 1e-13);
    EXPECT_NEAR(jade::bake::integrate([](double x) { return 1.0 / std::sqrt(x); }, 0.0, 1.0, 1e-10), 2.0, 1e-9);
    EXPECT_NEAR(jade::bake::integrate([](double x) { return std::exp(-1e6 * (x - 0.3) * (x - 0.3)); }, 0.0, 1.0),
                std::sqrt(kPi / 1e6), 1e-13);
}

TEST(LutReference, ZeroVarianceIsClampedCosine)
{
    for (double c = -1.0; c <= 1.0; c += 0.0625) EXPECT_EQ(jade::lut_reference(c, 0.0), std::max(c, 0.0)) << c;
    // Small t approaches it continuously (error ~ t near θ = π/2, ~ e^{−…} elsewhere).
    for (double c : {-0.9, -0.3, 0.0, 0.2, 0.7, 1.0})
        EXPECT_NEAR(jade::lut_reference(c, 1e-10), std::max(c, 0.0), 1e-5) << c;
    EXPECT_NEAR(jade::lut_reference(0.0, 1e-12), std::sqrt(1e-12 / (2 * kPi)), 1e-12);  // E[max(σz,0)] = σ/√(2π)
}

TEST(LutReference, LargeVarianceIsUniform)
{
    for (double c : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
        EXPECT_NEAR(jade::lut_reference(c, 100.0), 1.0 / kPi, 1e-12) << c;
        EXPECT_NEAR(jade::lut_reference(c, 40.0), 1.0 / kPi, 1e-6) << c;
    }
}

TEST(LutReference, NormalisedAndNonNegative)
{
    for (double t : {1e-6, 1e-3, 0.05, 0.0999, 0.1, 0.3, 1.0, 5.0}) {
        EXPECT_NEAR(integrate_over_angle([&](double c) { return jade::lut_reference(c, t); }), 2.0, 1e-9) << t;
        for (double c = -1.0; c <= 1.0; c += 0.125) EXPECT_GE(jade::lut_reference(c, t), 0.0) << c << " " << t;
    }
}

TEST(LutReference, BranchesAgree)
{
    // The Fourier series and the direct integration are independent evaluations of f.
    double worst = 0.0;
    for (double t : {0.01, 0.03, 0.1, 0.3, 1.0})
        for (double c = -1.0; c <= 1.0; c += 1.0 / 32) {
            const double a = jade::detail::lut_reference_series(c, t), b = jade::detail::lut_reference_direct(c, t);
            worst = std::max(worst, std::abs(a - b));
        }
    EXPECT_LT(worst, 1e-12);
    // Continuity across the switch at t = 0.1.
    for (double c : {-0.8, -0.1, 0.0, 0.4, 1.0})
        EXPECT_NEAR(jade::lut_reference(c, 0.1 - 1e-15), jade::lut_reference(c, 0.1), 1e-10) << c;
}

TEST(LutReference, MonotoneInAngle)
{
    for (double t : {1e-4, 0.02, 0.5}) {
        double previous = -1.0;
        for (double c = -1.0; c <= 1.0; c += 1.0 / 64) {
            const double f = jade::lut_reference(c, t);
            EXPECT_GE(f, previous - 1e-15) << c << " " << t;
            previous = f;
        }
    }
}

TEST(LutReference, Errors)
{
    EXPECT_THROW(jade::lut_reference(0.5, -1e-9), jade::Error);
    EXPECT_THROW(jade::lut_reference(0.5, std::nan("")), jade::Error);
    EXPECT_THROW(jade::lut_reference(std::nan(""), 0.5), jade::Error);
    EXPECT_EQ(jade::lut_reference(2.0, 0.0), 1.0);  // clamped
}

TEST(CurvatureLut, FlatLimitIsClampedCosine)
{
    const auto burley = jade::ChannelProfile::burley(0.5);
    for (double c = -1.0; c <= 1.0; c += 0.125) {
        EXPECT_NEAR(jade::curvature_lut_reference(c, 5e5, burley), std::max(c, 0.0), 1e-5) << c;
        EXPECT_EQ(jade::curvature_lut_reference(c, std::numeric_limits<double>::infinity(), burley), std::max(c, 0.0));
    }
}

TEST(CurvatureLut, UniformLightingIsAQuarter)
{
    // ½∫ D d(cos θ) = ¼ for any radius and profile: the average of max(n·L, 0) over all L.
    const double w[2] = {0.3, 0.7}, v[2] = {0.05, 0.8};
    const jade::ChannelProfile skin_red = jade::material_preset("skin", 1.0).profile[0];  // six lobes, σ 0.08..2.7
    for (const auto& p : {jade::ChannelProfile::burley(0.5), jade::ChannelProfile::dipole(1.0, 0.05, 1.3),
                          jade::ChannelProfile::gaussians(w, v), skin_red})
        for (double r : {0.05, 0.5, 3.0}) {
            const double avg =
                0.5 * jade::bake::integrate([&](double c) { return jade::curvature_lut_reference(c, r, p); }, -1.0, 1.0,
                                            1e-11);
            EXPECT_NEAR(avg, 0.25, 1e-9) << r;
        }
}

TEST(CurvatureLut, SmallSphereWithFiniteProfileIsUniform)
{
    // R finite at 0: the weight becomes uniform over the sphere, D → ¼ for every θ.
    const double w[1] = {1.0}, v[1] = {1.0};
    const auto g = jade::ChannelProfile::gaussians(w, v);
    for (double c : {-1.0, 0.0, 1.0}) EXPECT_NEAR(jade::curvature_lut_reference(c, 1e-4, g), 0.25, 1e-6) << c;
}

TEST(CurvatureLut, WrapsLightAroundCurvedSurfaces)
{
    const auto p = jade::ChannelProfile::burley(1.0);
    const double c = std::cos(kPi / 2 + 0.3);  // back-lit
    const double small = jade::curvature_lut_reference(c, 1.0, p), large = jade::curvature_lut_reference(c, 10.0, p);
    EXPECT_GT(small, 0.01);
    EXPECT_GT(small, large);
    EXPECT_GT(large, 0.0);
    EXPECT_LT(jade::curvature_lut_reference(1.0, 1.0, p), 1.0);  // front-lit: darker than Lambert
    EXPECT_THROW(jade::curvature_lut_reference(0.5, 0.0, p), jade::Error);
}
