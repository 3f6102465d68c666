// Scattering profiles, materials and presets (engine/src/bake/profile.cpp): closed-form cdfs
// against numerical integration, limits, numerical robustness, validation, scaling, presets.
#include "../engine/src/bake/disk_integral.hpp"

#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/material.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using jade::ChannelProfile;
using jade::Material;
namespace dev = jade::dev;

namespace {

constexpr double kPi = std::numbers::pi;

struct Named {
    std::string name;
    ChannelProfile p;
};

/// One profile of every kind and the edge cases (σ_a = 0 dipole, zero Gaussian weights).
std::vector<Named> profiles()
{
    const double w[3] = {0.2, 0.0, 0.8}, v[3] = {0.01, 1.0, 0.3};
    const double w1[1] = {1.0}, v1[1] = {2.5};
    return {
        {"burley", ChannelProfile::burley(0.7)},
        {"burley-tiny", ChannelProfile::burley(1e-5)},
        {"dipole-marble-red", ChannelProfile::dipole(2.19, 0.0021, 1.3)},
        {"dipole-ketchup-blue", ChannelProfile::dipole(0.03, 1.45, 1.3)},
        {"dipole-no-absorption", ChannelProfile::dipole(1.0, 0.0, 1.3)},
        {"gaussians-3", ChannelProfile::gaussians(w, v)},
        {"gaussian-1", ChannelProfile::gaussians(w1, v1)},
    };
}

/// 2π∫_0^r R(s) s ds by adaptive Gauss–Kronrod on the public R (nodes never touch 0).
double numeric_cdf(const ChannelProfile& p, double r)
{
    return jade::bake::integrate([&](double s) { return 2.0 * kPi * s * dev::profile_value(p, s); }, 0.0, r, 1e-13,
                                 1e-300);
}

/// A typical length of the profile: the median scattering radius.
double median(const ChannelProfile& p) { return dev::radius_for_tail(p, 0.5); }

}  // namespace

TEST(Profiles, CdfEqualsNumericalIntegral)
{
    for (const auto& [name, p] : profiles()) {
        const double m = median(p);
        for (double f : {1e-4, 1e-2, 0.3, 1.0, 3.0, 20.0}) {
            const double r = f * m;
            const double exact = dev::profile_cdf(p, r), numeric = numeric_cdf(p, r);
            EXPECT_NEAR(exact, numeric, 1e-9 * numeric) << name << " r = " << r;
        }
    }
}

TEST(Profiles, CdfLimitsAndMonotone)
{
    for (const auto& [name, p] : profiles()) {
        EXPECT_EQ(dev::profile_cdf(p, 0.0), 0.0) << name;
        EXPECT_EQ(dev::profile_cdf(p, std::numeric_limits<double>::infinity()), 1.0) << name;
        EXPECT_NEAR(dev::profile_cdf(p, 1e12), 1.0, 1e-9) << name;
        EXPECT_LE(dev::profile_cdf(p, 1e300), 1.0) << name;
        double previous = 0.0;
        for (double r = 1e-6 * median(p); r < 1e3 * median(p); r *= 1.5) {
            const double c = dev::profile_cdf(p, r);
            EXPECT_GE(c, previous) << name << " r = " << r;
            EXPECT_LE(c, 1.0) << name;
            previous = c;
        }
        EXPECT_GT(previous, 1.0 - 1e-3) << name;  // the σ_a = 0 dipole's tail falls off like 1/r
    }
}

TEST(Profiles, NoNanAnywhere)
{
    for (const auto& [name, p] : profiles()) {
        for (double r : {0.0, 1e-300, 1e-12, 1.0, 1e12, 1e300, std::numeric_limits<double>::infinity()}) {
            const double R = dev::profile_value(p, r), c = dev::profile_cdf(p, r), g = jade::bake::radial_density(p, r);
            EXPECT_FALSE(std::isnan(R)) << name << " R(" << r << ")";
            EXPECT_GE(R, 0.0) << name << " R(" << r << ")";
            EXPECT_TRUE(std::isfinite(c) && c >= 0.0 && c <= 1.0) << name << " cdf(" << r << ") = " << c;
            EXPECT_TRUE(std::isfinite(g) && g >= 0.0) << name << " radial_density(" << r << ") = " << g;
            if (r > 0.0 || p.kind != jade::ProfileKind::Burley) {
                EXPECT_TRUE(std::isfinite(R)) << name << " R(" << r << ")";
            }
        }
        if (p.kind == jade::ProfileKind::Burley) {
            EXPECT_EQ(dev::profile_value(p, 0.0), std::numeric_limits<double>::infinity()) << name;
        }
        EXPECT_THROW(dev::profile_value(p, -1e-9), jade::Error) << name;
        EXPECT_THROW(dev::profile_cdf(p, -1.0), jade::Error) << name;
        EXPECT_THROW(dev::profile_cdf(p, std::nan("")), jade::Error) << name;
    }
}

TEST(Profiles, CdfIsRelativelyAccurateForTinyRadii)
{
    // Leading terms: Burley cdf ≈ r/(2d); dipole ≈ πR(0)r²; Gaussians ≈ Σ w r²/(2v).
    const auto burley = ChannelProfile::burley(0.7);
    for (double r : {1e-300, 1e-200, 1e-12})
        EXPECT_NEAR(dev::profile_cdf(burley, r) / (r / (2.0 * 0.7)), 1.0, 1e-9) << r;
    const auto dipole = ChannelProfile::dipole(2.19, 0.0021, 1.3);
    for (double r : {1e-150, 1e-12})
        EXPECT_NEAR(dev::profile_cdf(dipole, r) / (kPi * dev::profile_value(dipole, 0.0) * r * r), 1.0, 1e-9) << r;
    const double w[2] = {0.25, 0.75}, v[2] = {0.5, 2.0};
    const auto g = ChannelProfile::gaussians(w, v);
    const double leading = 0.25 / (2 * 0.5) + 0.75 / (2 * 2.0);
    for (double r : {1e-150, 1e-12}) EXPECT_NEAR(dev::profile_cdf(g, r) / (leading * r * r), 1.0, 1e-9) << r;
}

TEST(Profiles, RadiusForTail)
{
    for (const auto& [name, p] : profiles()) {
        for (double tail : {0.5, 1e-3, 1e-8}) {
            const double r = dev::radius_for_tail(p, tail);
            EXPECT_NEAR(1.0 - dev::profile_cdf(p, r), tail, 1e-6 * tail) << name << " tail " << tail;
        }
        EXPECT_EQ(dev::radius_for_tail(p, 1.0), 0.0);
        EXPECT_THROW(dev::radius_for_tail(p, 0.0), jade::Error);
    }
}

TEST(Profiles, DipoleMatchesJensenFormulaAndIsNormalised)
{
    // Independent transcription of Jensen et al. 2001, eq. (4)-(5), unnormalised.
    const double ss = 2.19, sa = 0.0021, eta = 1.3;
    const double st = ss + sa, alpha = ss / st, str = std::sqrt(3 * sa * st);
    const double fdr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    const double A = (1 + fdr) / (1 - fdr), zr = 1 / st, zv = zr * (1 + 4 * A / 3);
    auto Rd = [&](double r) {
        const double dr = std::sqrt(r * r + zr * zr), dv = std::sqrt(r * r + zv * zv);
        return alpha / (4 * kPi) *
               (zr * (1 + str * dr) * std::exp(-str * dr) / (dr * dr * dr) +
                zv * (1 + str * dv) * std::exp(-str * dv) / (dv * dv * dv));
    };
    const auto p = ChannelProfile::dipole(ss, sa, eta);
    EXPECT_NEAR(p.z_r, zr, 1e-15 * zr);
    EXPECT_NEAR(p.z_v, zv, 1e-15 * zv);
    EXPECT_NEAR(p.sigma_tr, str, 1e-15 * str);
    for (double r : {0.0, 0.01, 0.5, 3.0, 40.0})
        EXPECT_NEAR(dev::profile_value(p, r) * p.dipole_total, Rd(r), 1e-12 * Rd(r)) << r;
    // The total reflectance by quadrature (substitution r = u/(1−u) maps [0, ∞) to [0, 1)).
    const double total = jade::bake::integrate(
        [&](double u) {
        const double r = u / (1 - u);
        return 2 * kPi * r * Rd(r) / ((1 - u) * (1 - u));
        },
        0.0, 1.0, 1e-13);
    EXPECT_NEAR(p.dipole_total, total, 1e-9 * total);
    // Jensen's closed form R_d = α'/2 (1 + e^{−4/3 A √(3(1−α'))}) e^{−√(3(1−α'))}.
    const double s3 = std::sqrt(3 * (1 - alpha));
    EXPECT_NEAR(p.dipole_total, 0.5 * alpha * (1 + std::exp(-4.0 / 3.0 * A * s3)) * std::exp(-s3), 1e-12);
}

TEST(Profiles, ValidationNamesTheParameter)
{
    auto message = [](auto&& f) {
        try {
            f();
        } catch (const jade::Error& e) {
            return std::string(e.what());
        }
        return std::string("<no error>");
    };
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    EXPECT_NE(message([&] { ChannelProfile::dipole(-1, 0.1, 1.3); }).find("sigma_s_prime"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::dipole(0, 0.1, 1.3); }).find("sigma_s_prime"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::dipole(1, nan, 1.3); }).find("sigma_a"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::dipole(1, -0.1, 1.3); }).find("sigma_a"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::dipole(1, 0.1, inf); }).find("eta"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::dipole(1, 0.1, 0.0); }).find("eta"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::burley(0.0); }).find("d ="), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::burley(nan); }).find("d ="), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::burley_from_albedo(1.5, 1.0); }).find("albedo"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::burley_from_albedo(0.5, -1.0); }).find("mean_free_path"),
              std::string::npos);
    const double zero[2] = {0.0, 0.0}, neg[2] = {1.0, -0.5}, v[2] = {1.0, 2.0}, badv[2] = {1.0, 0.0};
    EXPECT_NE(message([&] { ChannelProfile::gaussians(zero, v); }).find("zero"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::gaussians(neg, v); }).find("weight[1]"), std::string::npos);
    EXPECT_NE(message([&] { ChannelProfile::gaussians(v, badv); }).find("variance[1]"), std::string::npos);
    EXPECT_THROW(ChannelProfile::gaussians(std::span<const double>(v, 2), std::span<const double>(v, 1)), jade::Error);
    EXPECT_THROW(ChannelProfile::burley(1.0).scaled(0.0), jade::Error);
}

TEST(Profiles, BurleyFromAlbedoAndGaussianWeights)
{
    // s(0.8) = 1.05, s(0.3) = 1.85 − 0.3 + 7·0.125 = 2.425
    EXPECT_DOUBLE_EQ(ChannelProfile::burley_from_albedo(0.8, 2.1).d, 2.0);
    EXPECT_DOUBLE_EQ(ChannelProfile::burley_from_albedo(0.3, 2.425).d, 1.0);
    const double w[3] = {1.0, 0.0, 3.0}, v[3] = {1.0, 1.0, 1.0};
    const auto g = ChannelProfile::gaussians(w, v);
    EXPECT_DOUBLE_EQ(g.weight[0], 0.25);
    EXPECT_DOUBLE_EQ(g.weight[2], 0.75);
    EXPECT_EQ(g.gaussian_count, 3u);
}

TEST(Profiles, ScaledProfileMatchesScaledMesh)
{
    for (const auto& [name, p] : profiles()) {
        for (double f : {1e-4, 0.37, 8.0, 1e4}) {
            const ChannelProfile q = p.scaled(f);
            for (double r : {0.01, 0.5, 2.0}) {
                const double rr = r * median(p);
                EXPECT_NEAR(dev::profile_cdf(q, f * rr), dev::profile_cdf(p, rr), 1e-13) << name << " f " << f;
                EXPECT_NEAR(dev::profile_value(q, f * rr) * f * f, dev::profile_value(p, rr),
                            1e-12 * dev::profile_value(p, rr))
                    << name << " f " << f;
            }
        }
    }
}

TEST(Presets, AllExistAndAreValid)
{
    const auto names = jade::material_preset_names();
    EXPECT_EQ(names.size(), 16u);
    for (const auto& n : names) {
        for (double mm : {0.05, 1.0, 30.0}) {
            const Material m = jade::material_preset(n, mm);
            EXPECT_EQ(m.name, n);
            // Media absorb physically: ketchup's green and blue are nearly black.
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(m.albedo[c], 0.001f) << n;
                EXPECT_LE(m.albedo[c], 0.98f) << n;
            }
            EXPECT_GT(m.ior, 1.0f) << n;
            EXPECT_GT(m.roughness, 0.0f) << n;
            if (m.opaque) continue;
            EXPECT_FALSE(dev::is_grey(m)) << n;
            for (int c = 0; c < 3; ++c) {
                const ChannelProfile& p = m.profile[c];
                // Scattering radii are physical: between 1 µm and 1 m in millimetres.
                const double median_mm = dev::radius_for_tail(p, 0.5) * mm;
                EXPECT_GT(median_mm, 1e-3) << n << " channel " << c;
                EXPECT_LT(median_mm, 1e3) << n << " channel " << c;
                EXPECT_NEAR(dev::profile_cdf(p, dev::radius_for_tail(p, 1e-3)), 1.0 - 1e-3, 1e-9) << n;
            }
        }
    }
    EXPECT_TRUE(jade::material_preset("opaque", 1.0).opaque);
}

TEST(Presets, UnitsAndKnownValues)
{
    // mm_per_unit = 2: one unit is 2 mm, so every length in units halves.
    for (const char* n : {"marble", "skin", "jade", "blue-jewel"}) {
        const Material a = jade::material_preset(n, 1.0), b = jade::material_preset(n, 2.0), c = a.scaled(0.5);
        for (int ch = 0; ch < 3; ++ch)
            for (double r : {0.05, 0.3, 1.0, 4.0})
                EXPECT_NEAR(dev::profile_cdf(b.profile[ch], r), dev::profile_cdf(c.profile[ch], r), 1e-14) << n;
    }
    // jade, red: σ_s = 0.10/mm, σ_a = 0.06/mm, g = 0.3 → ℓ = 1/σ_t' = 1/0.13 mm, A = R_d(0.07/0.13, 1.66),
    // d = ℓ / (1.85 − A + 7|A − 0.8|³)
    const double a_red = jade::dev::diffuse_reflectance(0.07 / 0.13, 1.66);
    EXPECT_NEAR(jade::material_preset("jade", 1.0).profile[0].d,
                (1.0 / 0.13) / (1.85 - a_red + 7.0 * std::pow(std::abs(a_red - 0.8), 3.0)), 1e-9);
    const Material bj = jade::material_preset("blue-jewel", 1.0);
    EXPECT_FLOAT_EQ(bj.roughness, 0.08f);
    EXPECT_FLOAT_EQ(bj.ior, 1.6f);
    // Jensen marble, mm_per_unit = 10: σ' = 21.9 / unit.
    const Material marble = jade::material_preset("marble", 10.0);
    EXPECT_NEAR(marble.profile[0].z_r, 1.0 / (21.9 + 0.021), 1e-15);
    EXPECT_NEAR(marble.albedo[0], jade::dev::MediumFit{}.albedo_scale * marble.profile[0].dipole_total, 1e-6);
    EXPECT_FLOAT_EQ(marble.ior, 1.3f);
    // d'Eon skin, red: weights sum to 1, variances in units² = mm² / mm_per_unit².
    const Material skin = jade::material_preset("skin", 0.5);
    EXPECT_EQ(skin.profile[0].gaussian_count, 6u);
    EXPECT_NEAR(skin.profile[0].variance[5], 7.41 / 0.25, 1e-12);
    EXPECT_NEAR(skin.profile[0].weight[4], 0.358, 1e-12);
    double sum = 0.0;
    for (double w : skin.profile[2].weight) sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-15);
}

TEST(Presets, Errors)
{
    try {
        jade::material_preset("granite", 1.0);
        FAIL() << "no error";
    } catch (const jade::Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("granite"), std::string::npos);
        for (const auto& n : jade::material_preset_names()) EXPECT_NE(m.find(n), std::string::npos) << n;
    }
    for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(jade::material_preset("jade", bad), jade::Error) << bad;
}

TEST(Materials, BurleyMaterialAndGrey)
{
    const Material grey = jade::burley_material(glm::dvec3(0.5), glm::vec3(0.7f), "g");
    EXPECT_TRUE(dev::is_grey(grey));
    EXPECT_EQ(grey.name, "g");
    EXPECT_DOUBLE_EQ(grey.profile[1].d, 0.5);
    const Material coloured = jade::burley_material(glm::dvec3(0.5, 0.6, 0.7), glm::vec3(0.7f));
    EXPECT_FALSE(dev::is_grey(coloured));
    EXPECT_DOUBLE_EQ(coloured.scaled(4.0).profile[2].d, 2.8);
}
