// Materials from a physical medium (Material::from_medium) against independent numbers: the
// diffuse reflectance against a float64 integral of the dipole's radial profile, the transmission
// lobe's normalisation, limits and extreme media, and the errors bad values give.
#include "test_support.hpp"

#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/material.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <vector>

using namespace jade;

namespace {

constexpr double kPi = std::numbers::pi;

// 2π ∫_0^∞ R_d(r) r dr of the classical dipole (Jensen et al. 2001, eq. 5) with σ_t' = 1,
// by the trapezoidal rule on r = e^u (the integrand spans many decades), float64.
double dipole_integral(double reduced_albedo, double eta)
{
    const double sigma_t = 1.0, sigma_a = (1.0 - reduced_albedo) * sigma_t;
    const double sigma_tr = std::sqrt(3.0 * sigma_a * sigma_t);
    const double f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    const double a = (1.0 + f_dr) / (1.0 - f_dr);
    const double z_r = 1.0 / sigma_t, z_v = z_r * (1.0 + 4.0 * a / 3.0);
    auto pole = [&](double z, double r) {
        const double d = std::sqrt(r * r + z * z);
        return z * (sigma_tr * d + 1.0) * std::exp(-sigma_tr * d) / (d * d * d);
    };
    double sum = 0.0;
    const double u0 = std::log(1e-7), u1 = std::log(1e4), du = 1e-4;
    for (double u = u0; u <= u1; u += du) {
        const double r = std::exp(u);
        const double rd = reduced_albedo / (4.0 * kPi) * (pole(z_r, r) + pole(z_v, r));
        sum += 2.0 * kPi * rd * r * r * du;  // r dr = r² du
    }
    return sum;
}

}  // namespace

TEST(Medium, DiffuseReflectanceIsTheIntegralOfTheDipoleProfile)
{
    for (double eta : {1.0, 1.3, 1.5, 2.0})
        for (double alpha : {0.05, 0.3, 0.7, 0.9, 0.99, 0.999}) {
            const double closed = dev::diffuse_reflectance(alpha, eta), integral = dipole_integral(alpha, eta);
            EXPECT_NEAR(closed, integral, 2e-5 * std::max(integral, 1e-3)) << "alpha' " << alpha << ", eta " << eta;
        }
    EXPECT_EQ(dev::diffuse_reflectance(0.0, 1.5), 0.0);
    EXPECT_NEAR(dev::diffuse_reflectance(1.0, 1.5), 1.0, 1e-12);  // nothing absorbed: all light returns
    // Monotone in the albedo.
    double last = -1.0;
    for (double alpha = 0.0; alpha <= 1.0; alpha += 0.01) {
        const double r = dev::diffuse_reflectance(alpha, 1.4);
        EXPECT_GT(r, last);
        last = r;
    }
}

TEST(Medium, DerivesEveryParameterFromTheCoefficients)
{
    Medium m;
    m.sigma_s = {12.0, 15.0, 19.6};
    m.sigma_a = {8.0, 5.0, 0.4};
    m.g = 0.0, m.ior = 1.5, m.roughness = 0.6;
    dev::MediumFit fit;
    const Material mat = dev::from_medium(m, fit, "jewel");
    for (int c = 0; c < 3; ++c) {
        const double alpha = m.sigma_s[c] / (m.sigma_s[c] + m.sigma_a[c]);
        const double rd = dev::diffuse_reflectance(alpha, 1.5);
        EXPECT_NEAR(mat.albedo[c], fit.albedo_scale * rd, 1e-6);
        const double s = 1.85 - rd + 7.0 * std::pow(std::abs(rd - 0.8), 3.0);
        EXPECT_EQ(mat.profile[c].kind, ProfileKind::Burley);
        EXPECT_NEAR(mat.profile[c].d, 1.0 / (m.sigma_s[c] + m.sigma_a[c]) / s, 1e-12);
        EXPECT_FLOAT_EQ(mat.transmission.sigma_t[c], float(fit.forward_extinction * (m.sigma_s[c] + m.sigma_a[c])));
        // The slab's source depth z_0 + z_b and extrapolation z_b = 2A/(3σ_t'), Egan–Hilgeman F_dr.
        const double f_dr = -1.440 / 2.25 + 0.710 / 1.5 + 0.668 + 0.0636 * 1.5;
        const double zb = 2.0 * (1.0 + f_dr) / (1.0 - f_dr) / (3.0 * (m.sigma_s[c] + m.sigma_a[c]));
        EXPECT_NEAR(mat.transmission.extrapolation[c], zb, 1e-6 * zb);
        EXPECT_NEAR(mat.transmission.source_depth[c], 1.0 / (m.sigma_s[c] + m.sigma_a[c]) + zb, 1e-6 * zb);
    }
    EXPECT_GT(mat.albedo.b, mat.albedo.r);  // a saturated blue: red and green are absorbed
    EXPECT_FLOAT_EQ(mat.strength, float(fit.strength));
    EXPECT_NEAR(mat.transmission.weight, fit.transmission_weight, 1e-6);
    EXPECT_FLOAT_EQ(mat.ior, 1.5f);
    EXPECT_FLOAT_EQ(mat.roughness, 0.6f);
    // Anisotropy enters through the reduced coefficients: forward scattering, lower albedo.
    Medium forward = m;
    forward.g = 0.8;
    EXPECT_LT(Material::from_medium(forward).albedo.b, Material::from_medium(m).albedo.b);
    // Per millimetre × millimetres per unit = per unit.
    EXPECT_DOUBLE_EQ(m.scaled(10.0).sigma_s.x, 120.0);
}

TEST(Medium, TransmissionLobeIsNormalisedOverTheHemisphere)
{
    // (n + 1)/(2π) ∫_hemisphere μ^n dω = 1 for the lobe of jade/material.hpp, float64 midpoint rule.
    for (double n : {0.0, 1.0, 2.0, 4.5, 16.0}) {
        double sum = 0.0;
        const int steps = 200000;
        for (int k = 0; k < steps; ++k) {
            const double mu = (k + 0.5) / steps;
            sum += (n + 1.0) / (2.0 * kPi) * std::pow(mu, n) * 2.0 * kPi / steps;
        }
        EXPECT_NEAR(sum, 1.0, 1e-6) << "n = " << n;
    }
}

TEST(Medium, ExtremeMediaGiveFiniteDocumentedResults)
{
    auto finite = [](const Material& mat) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(mat.albedo[c]) && mat.albedo[c] >= 0.0f && mat.albedo[c] <= 1.0f);
            EXPECT_TRUE(std::isfinite(mat.profile[c].d) && mat.profile[c].d > 0.0);
            EXPECT_TRUE(std::isfinite(mat.transmission.sigma_t[c]) && mat.transmission.sigma_t[c] >= 0.0f);
            EXPECT_TRUE(std::isfinite(mat.transmission.source_depth[c]) && mat.transmission.source_depth[c] >= 0.0f);
            EXPECT_TRUE(std::isfinite(mat.transmission.extrapolation[c]) && mat.transmission.extrapolation[c] >= 0.0f);
        }
    };
    Medium m;
    m.sigma_s = glm::dvec3(5.0), m.sigma_a = glm::dvec3(0.0);  // no absorption: albedo 1 behind the boundary
    Material a = dev::from_medium(m, {1.0});
    finite(a);
    EXPECT_NEAR(a.albedo.r, 1.0f, 1e-6f);
    m.sigma_s = glm::dvec3(0.0), m.sigma_a = glm::dvec3(5.0);  // no scattering: black diffuse, only transmission
    Material b = Material::from_medium(m);
    finite(b);
    EXPECT_EQ(b.albedo.r, 0.0f);
    m.sigma_s = glm::dvec3(0.0), m.sigma_a = glm::dvec3(0.0);  // clear: transmittance 1, path clamped
    Material c = Material::from_medium(m);
    finite(c);
    EXPECT_EQ(c.transmission.sigma_t.r, 0.0f);
    EXPECT_LE(c.profile[0].d, 1e12);
    for (double k : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
        m.sigma_s = glm::dvec3(k), m.sigma_a = glm::dvec3(0.1 * k);
        const Material mat = Material::from_medium(m);
        finite(mat);
        EXPECT_NEAR(mat.profile[0].d * k, Material::from_medium(m.scaled(1.0 / k)).profile[0].d,
                    1e-9 * mat.profile[0].d * k)
            << "the profile scales with the mean free path at " << k;
    }
}

TEST(Medium, BadValuesNameTheField)
{
    auto message = [](const Medium& m, const dev::MediumFit& fit = {}) {
        try {
            dev::from_medium(m, fit, "glass");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    Medium m;
    m.sigma_s = glm::dvec3(1.0);
    Medium bad = m;
    bad.sigma_a.g = -1.0;
    EXPECT_NE(message(bad).find("sigma_a[1]"), std::string::npos) << message(bad);
    EXPECT_NE(message(bad).find("glass"), std::string::npos);
    bad = m, bad.sigma_s.r = NAN;
    EXPECT_NE(message(bad).find("sigma_s[0]"), std::string::npos);
    bad = m, bad.g = 1.0;
    EXPECT_NE(message(bad).find("g = 1"), std::string::npos);
    bad = m, bad.ior = 0.0;
    EXPECT_NE(message(bad).find("ior"), std::string::npos);
    bad = m, bad.roughness = 2.0;
    EXPECT_NE(message(bad).find("roughness"), std::string::npos);
    dev::MediumFit fit;
    fit.albedo_scale = 1.5;
    EXPECT_NE(message(m, fit).find("albedo_scale"), std::string::npos);
    EXPECT_THROW(dev::diffuse_reflectance(1.5, 1.3), Error);
}

TEST(Medium, PresetsWithAMediumHaveTransmission)
{
    for (const char* name : {"jade", "blue-jewel", "wax", "marble", "skin1"}) {
        const Material m = material_preset(name, 1.0);
        EXPECT_TRUE(m.transmission.enabled()) << name;
        EXPECT_GT(m.transmission.sigma_t.r, 0.0f) << name;
    }
    EXPECT_FALSE(material_preset("skin", 1.0).transmission.enabled());  // d'Eon's Gaussians: no medium given
    EXPECT_FALSE(material_preset("opaque", 1.0).transmission.enabled());
    // The Jensen et al. table keeps its measured dipole profile.
    EXPECT_EQ(material_preset("marble", 1.0).profile[0].kind, ProfileKind::Dipole);
}

// MediumFit's defaults are the fit's result (tools/groundtruth/fit.py writes fit_result.json;
// docs/fidelity.md): a refit that changes one must change the other.
TEST(MediumFit, DefaultsAreTheFitResult)
{
    std::ifstream file(JADE_FIT_RESULT);
    ASSERT_TRUE(file) << "cannot read " << JADE_FIT_RESULT;
    const nlohmann::json fit = nlohmann::json::parse(file);
    const dev::MediumFit defaults;
    const std::pair<const char*, double> fields[] = {
        {"albedo_scale", defaults.albedo_scale},
        {"strength", defaults.strength},
        {"spread_strength", defaults.spread_strength},
        {"transmission_weight", defaults.transmission_weight},
        {"diffusion_weight", defaults.diffusion_weight},
        {"lobe", defaults.lobe},
        {"normal_mix", defaults.normal_mix},
        {"forward_extinction", defaults.forward_extinction},
    };
    for (const auto& [name, value] : fields) {
        ASSERT_TRUE(fit.contains(name)) << JADE_FIT_RESULT << " has no " << name;
        EXPECT_EQ(fit[name].get<double>(), value) << "MediumFit::" << name << " against " << JADE_FIT_RESULT;
    }
}
