// bake/medium.cpp - materials from a physical medium (Material::from_medium): the diffuse albedo
// behind a dielectric boundary, the Burley profile, strength and the transmission term.
// Formulas and sources are in jade/material.hpp and jade/dev/material.hpp; the fitted constants in
// docs/fidelity.md.
#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/material.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace jade {
namespace {

std::string fmt(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

void check_eta(const char* where, double eta)
{
    if (!(eta > 0.2 && eta < 5.0)) throw Error(std::string(where) + ": ior = " + fmt(eta) + " must be in (0.2, 5)");
}

/// Egan and Hilgeman's fit of the internal diffuse Fresnel reflectance (Jensen et al. 2001).
double internal_diffuse_fresnel(double eta) { return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta; }

// The dipole's boundary term A = (1 + F_dr)/(1 − F_dr) (Jensen et al. 2001): how much further the
// boundary reflects diffuse light back in; F_dr < 0.9 on η ∈ (0.2, 5).
double boundary_term(double eta)
{
    const double f_dr = internal_diffuse_fresnel(eta);
    return (1.0 + f_dr) / (1.0 - f_dr);
}

// Mean free paths beyond these are not representable in the bake's float32 profile
// evaluation; a medium that clear is, for t_m, no medium (and the clamp is documented).
constexpr double kMinPath = 1e-12, kMaxPath = 1e12;

}  // namespace

Medium Medium::scaled(double factor) const
{
    if (!(std::isfinite(factor) && factor > 0.0))
        throw Error("Medium::scaled: factor = " + fmt(factor) + " must be finite and > 0");
    Medium m = *this;
    m.sigma_s *= factor;
    m.sigma_a *= factor;
    return m;
}

double dev::diffuse_reflectance(double reduced_albedo, double eta)
{
    if (!(reduced_albedo >= 0.0 && reduced_albedo <= 1.0))
        throw Error("diffuse_reflectance: reduced albedo = " + fmt(reduced_albedo) + " must be in [0, 1]");
    check_eta("diffuse_reflectance", eta);
    const double a = boundary_term(eta);
    const double root = std::sqrt(3.0 * (1.0 - reduced_albedo));
    return std::clamp(0.5 * reduced_albedo * (1.0 + std::exp(-4.0 / 3.0 * a * root)) * std::exp(-root), 0.0, 1.0);
}

Medium dev::medium_from_appearance(glm::dvec3 albedo, glm::dvec3 mean_free_path, double ior, double roughness,
                                   const MediumFit& fit)
{
    check_eta("medium_from_appearance", ior);
    Medium m;
    m.ior = ior, m.roughness = roughness;
    for (int c = 0; c < 3; ++c) {
        if (!(albedo[c] >= 0.0 && albedo[c] <= 1.0))
            throw Error("medium_from_appearance: albedo[" + std::to_string(c) + "] = " + fmt(albedo[c]) +
                        " must be in [0, 1]");
        if (!(mean_free_path[c] > 0.0 && std::isfinite(mean_free_path[c])))
            throw Error("medium_from_appearance: mean free path[" + std::to_string(c) +
                        "] = " + fmt(mean_free_path[c]) + " must be finite and > 0");
        const double target = fit.albedo_scale > 0.0 ? std::min(albedo[c] / fit.albedo_scale, 1.0) : 0.0;
        double lo = 0.0, hi = 1.0;  // diffuse_reflectance rises monotonically in α'
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (lo + hi);
            (diffuse_reflectance(mid, ior) < target ? lo : hi) = mid;
        }
        const double sigma_t = 1.0 / mean_free_path[c];
        m.sigma_s[c] = hi * sigma_t;
        m.sigma_a[c] = (1.0 - hi) * sigma_t;
    }
    return m;
}

Medium medium_from_appearance(glm::dvec3 albedo, glm::dvec3 mean_free_path, double ior, double roughness)
{
    return dev::medium_from_appearance(albedo, mean_free_path, ior, roughness, dev::MediumFit{});
}

Material Material::from_medium(const Medium& medium, std::string name)
{
    return dev::from_medium(medium, dev::MediumFit{}, std::move(name));
}

Material dev::from_medium(const Medium& medium, const MediumFit& fit, std::string name)
{
    const std::string where = "material '" + name + "' from a medium";
    auto check_rgb = [&](const char* field, const glm::dvec3& v) {
        for (int c = 0; c < 3; ++c)
            if (!(std::isfinite(v[c]) && v[c] >= 0.0))
                throw Error(where + ": " + field + "[" + std::to_string(c) + "] = " + fmt(v[c]) +
                            " must be finite and >= 0 (1/mesh unit)");
    };
    check_rgb("sigma_s", medium.sigma_s);
    check_rgb("sigma_a", medium.sigma_a);
    if (!(medium.g > -1.0 && medium.g < 1.0)) throw Error(where + ": g = " + fmt(medium.g) + " must be in (-1, 1)");
    check_eta(where.c_str(), medium.ior);
    if (!(medium.roughness >= 0.0 && medium.roughness <= 1.0))
        throw Error(where + ": roughness = " + fmt(medium.roughness) + " must be in [0, 1]");
    auto check_fit = [&](const char* field, double v, double lo, double hi) {
        if (!(v >= lo && v <= hi))
            throw Error(where + ": fit." + field + " = " + fmt(v) + " must be in [" + fmt(lo) + ", " + fmt(hi) + "]");
    };
    check_fit("albedo_scale", fit.albedo_scale, 0.0, 1.0);
    check_fit("strength", fit.strength, 0.0, 1e6);
    check_fit("spread_strength", fit.spread_strength, 0.0, 1e6);
    check_fit("transmission_weight", fit.transmission_weight, 0.0, 1e3);
    check_fit("diffusion_weight", fit.diffusion_weight, 0.0, 1e3);
    check_fit("lobe", fit.lobe, 0.0, 1e3);
    check_fit("normal_mix", fit.normal_mix, 0.0, 1.0);
    check_fit("forward_extinction", fit.forward_extinction, 1e-3, 1.0);

    Material m;
    m.name = std::move(name);
    const double boundary_a = boundary_term(medium.ior);
    for (int c = 0; c < 3; ++c) {
        const double s_reduced = medium.sigma_s[c] * (1.0 - medium.g);
        const double t_reduced = s_reduced + medium.sigma_a[c];
        const double alpha = t_reduced > 0.0 ? s_reduced / t_reduced : 0.0;  // a clear medium scatters nothing
        const double reflectance = diffuse_reflectance(alpha, medium.ior);
        m.albedo[c] = float(fit.albedo_scale * reflectance);
        const double path = t_reduced > 0.0 ? std::clamp(1.0 / t_reduced, kMinPath, kMaxPath) : kMaxPath;
        m.profile[c] = ChannelProfile::burley_from_albedo(reflectance, path);
        m.transmission.sigma_t[c] =
            float(std::min(fit.forward_extinction * (medium.sigma_s[c] + medium.sigma_a[c]), 3.0e38));
        m.transmission.sigma_s_reduced[c] = float(std::min(s_reduced, 3.0e38));
        m.transmission.sigma_tr[c] = float(std::min(std::sqrt(3.0 * medium.sigma_a[c] * t_reduced), 3.0e38));
        // The diffusion dipole's source depth and extrapolated boundary (the diffused part of the
        // transmission, transmission.glsl); 0 where nothing scatters (that part is 0 there anyway).
        if (s_reduced > 0.0) {
            const double z0 = 1.0 / t_reduced, zb = 2.0 * boundary_a / (3.0 * t_reduced);
            m.transmission.source_depth[c] = float(std::min(z0 + zb, 3.0e38));
            m.transmission.extrapolation[c] = float(std::min(zb, 3.0e38));
        }
    }
    m.strength = float(fit.strength);
    m.spread_strength = float(fit.spread_strength);
    // The two crossings of the boundary are boundary_transmittance's, at the angles of the light.
    m.transmission.weight = float(fit.transmission_weight);
    m.transmission.diffusion_weight = float(fit.diffusion_weight);
    m.transmission.lobe = float(fit.lobe);
    m.transmission.normal_mix = float(fit.normal_mix);
    m.ior = float(medium.ior);
    m.roughness = float(medium.roughness);
    m.boundary_transmittance = true;
    return m;
}

}  // namespace jade
