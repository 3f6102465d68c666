// bake/profile.cpp - scattering profiles R(r) (Burley, dipole, sums of Gaussians), materials
// and presets. Every profile is normalised to 2π∫R(r) r dr = 1; r in mesh units.
//
// Numerics: cdf uses −expm1 forms so that it is accurate relative to itself for tiny r, and
// the tail 1 − cdf is evaluated directly (never as 1 − cdf) where it matters.
#include "disk_integral.hpp"

#include <jade/dev/material.hpp>
#include <jade/error.hpp>
#include <jade/material.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace jade {
namespace {

constexpr double kPi = std::numbers::pi;

std::string fmt(double v)
{
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

/// Throws unless v is finite and v > 0 (or ≥ 0 when allow_zero).
void check_param(const char* where, const char* name, double v, bool allow_zero = false)
{
    if (std::isfinite(v) && (v > 0.0 || (allow_zero && v == 0.0))) return;
    throw Error(std::string(where) + ": " + name + " = " + fmt(v) + " must be finite and " +
                (allow_zero ? ">= 0" : "> 0"));
}

void check_radius(const char* where, double r)
{
    if (!(r >= 0.0)) throw Error(std::string("ChannelProfile::") + where + ": radius r = " + fmt(r) + " must be >= 0");
}

// Dipole helpers. One pole at depth z: its contribution to the cdf (×e^{σz}) is
//   1 − (z/d)·e^{−σ(d − z)},  d = √(r² + z²),
// written as −expm1(−(σ(d − z) + ½·log1p(r²/z²))) with d − z = r²/(d + z) (no cancellation).
double pole_cdf(double sigma, double z, double r)
{
    const double d = std::hypot(r, z);
    const double q = r / (d + z);  // ≤ 1, so r·q = d − z never overflows
    const double rz = r / z;
    return -std::expm1(-(sigma * r * q + 0.5 * std::log1p(rz * rz)));
}

/// z·(1 + σd)·e^{−σ(d − z0)} / d³ with d = √(r² + z²): the pole's R (up to 1/(2π·norm)),
/// exponent shifted by the real pole's depth z0 so that nothing underflows needlessly.
double pole_R(double sigma, double z, double z0, double r)
{
    const double d = std::hypot(r, z);
    return z * (1.0 + sigma * d) * std::exp(-sigma * (d - z0)) / (d * d * d);
}

/// Σ over poles of e^{−σ(z − z_r)}: the normalisation of the dipole (× e^{σ z_r}).
double dipole_norm(const ChannelProfile& p) { return 1.0 + std::exp(-p.sigma_tr * (p.z_v - p.z_r)); }

/// 1 − cdf(r), evaluated directly.
double tail(const ChannelProfile& p, double r)
{
    switch (p.kind) {
    case ProfileKind::Burley: {
        const double x = r / p.d;
        return 0.25 * std::exp(-x) + 0.75 * std::exp(-x / 3.0);
    }
    case ProfileKind::Dipole: {
        // [z_r e^{−σ d_r}/d_r + z_v e^{−σ d_v}/d_v] / (e^{−σ z_r} + e^{−σ z_v})
        const double s = p.sigma_tr, dr = std::hypot(r, p.z_r), dv = std::hypot(r, p.z_v);
        return (p.z_r / dr * std::exp(-s * (dr - p.z_r)) + p.z_v / dv * std::exp(-s * (dv - p.z_r))) / dipole_norm(p);
    }
    case ProfileKind::Gaussians: {
        double t = 0.0;
        for (uint32_t k = 0; k < p.gaussian_count; ++k)
            if (p.weight[k] > 0.0) t += p.weight[k] * std::exp(-r * r / (2.0 * p.variance[k]));
        return t;
    }
    }
    return 0.0;
}

/// A length on which the profile varies: the start of the search in radius_for_tail.
double length_scale(const ChannelProfile& p)
{
    switch (p.kind) {
    case ProfileKind::Burley: return p.d;
    case ProfileKind::Dipole: return p.z_v;
    case ProfileKind::Gaussians: {
        double v = 0.0;
        for (uint32_t k = 0; k < p.gaussian_count; ++k) v = std::max(v, p.variance[k]);
        return std::sqrt(v);
    }
    }
    return 1.0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// ChannelProfile

ChannelProfile ChannelProfile::burley(double d)
{
    check_param("ChannelProfile::burley", "d", d);
    ChannelProfile p;
    p.kind = ProfileKind::Burley;
    p.d = d;
    return p;
}

ChannelProfile ChannelProfile::burley_from_albedo(double albedo, double mean_free_path)
{
    if (!(albedo >= 0.0 && albedo <= 1.0))
        throw Error("ChannelProfile::burley_from_albedo: albedo = " + fmt(albedo) + " must be in [0, 1]");
    check_param("ChannelProfile::burley_from_albedo", "mean_free_path", mean_free_path);
    const double a = std::abs(albedo - 0.8);
    const double s = 1.85 - albedo + 7.0 * a * a * a;  // ≥ 0.85 on [0, 1]
    return burley(mean_free_path / s);
}

ChannelProfile ChannelProfile::dipole(double sigma_s_prime, double sigma_a, double eta)
{
    const char* where = "ChannelProfile::dipole";
    check_param(where, "sigma_s_prime", sigma_s_prime);
    check_param(where, "sigma_a", sigma_a, /*allow_zero=*/true);
    check_param(where, "eta", eta);
    const double sigma_t = sigma_s_prime + sigma_a;  // σ_t', 1/units
    const double alpha = sigma_s_prime / sigma_t;    // α'
    const double f_dr = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    if (!(f_dr < 1.0)) throw Error(std::string(where) + ": eta = " + fmt(eta) + " gives F_dr >= 1");
    const double a = (1.0 + f_dr) / (1.0 - f_dr);
    ChannelProfile p;
    p.kind = ProfileKind::Dipole;
    p.sigma_tr = std::sqrt(3.0 * sigma_a * sigma_t);
    p.z_r = 1.0 / sigma_t;
    p.z_v = p.z_r * (1.0 + 4.0 * a / 3.0);
    p.dipole_total = 0.5 * alpha * (std::exp(-p.sigma_tr * p.z_r) + std::exp(-p.sigma_tr * p.z_v));
    if (!(p.z_v > 0.0 && std::isfinite(p.z_v)))
        throw Error(std::string(where) + ": eta = " + fmt(eta) + " gives no valid virtual source");
    return p;
}

ChannelProfile ChannelProfile::gaussians(std::span<const double> weights, std::span<const double> variances)
{
    const char* where = "ChannelProfile::gaussians";
    if (weights.size() != variances.size() || weights.empty() || weights.size() > size_t(kMaxGaussians))
        throw Error(std::string(where) + ": need 1 to 6 weights and as many variances, got " +
                    std::to_string(weights.size()) + " weights and " + std::to_string(variances.size()) + " variances");
    ChannelProfile p;
    p.kind = ProfileKind::Gaussians;
    p.gaussian_count = uint32_t(weights.size());
    double sum = 0.0;
    for (size_t k = 0; k < weights.size(); ++k) {
        const std::string index = std::to_string(k);
        check_param(where, (std::string("weight[") + index + "]").c_str(), weights[k], /*allow_zero=*/true);
        check_param(where, (std::string("variance[") + index + "]").c_str(), variances[k]);
        p.weight[k] = weights[k];
        p.variance[k] = variances[k];
        sum += weights[k];
    }
    if (!(sum > 0.0)) throw Error(std::string(where) + ": all weights are zero");
    for (size_t k = 0; k < weights.size(); ++k) p.weight[k] /= sum;
    return p;
}

double dev::profile_value(const ChannelProfile& p, double r)
{
    check_radius("R", r);
    if (std::isinf(r)) return 0.0;
    switch (p.kind) {
    case ProfileKind::Burley:  // (e^{−r/d} + e^{−r/3d}) / (8π d r); +inf at r = 0
        return (std::exp(-r / p.d) + std::exp(-r / (3.0 * p.d))) / (8.0 * kPi * p.d * r);
    case ProfileKind::Dipole:
        return (pole_R(p.sigma_tr, p.z_r, p.z_r, r) + pole_R(p.sigma_tr, p.z_v, p.z_r, r)) /
               (2.0 * kPi * dipole_norm(p));
    case ProfileKind::Gaussians: {
        double v = 0.0;
        for (uint32_t k = 0; k < p.gaussian_count; ++k)
            if (p.weight[k] > 0.0)
                v += p.weight[k] / (2.0 * kPi * p.variance[k]) * std::exp(-r * r / (2.0 * p.variance[k]));
        return v;
    }
    }
    return 0.0;
}

double dev::profile_cdf(const ChannelProfile& p, double r)
{
    check_radius("cdf", r);
    if (std::isinf(r)) return 1.0;
    switch (p.kind) {
    case ProfileKind::Burley: {  // 1 − ¼e^{−x} − ¾e^{−x/3}, x = r/d
        const double x = r / p.d;
        return -0.25 * std::expm1(-x) - 0.75 * std::expm1(-x / 3.0);
    }
    case ProfileKind::Dipole: {
        const double v = (pole_cdf(p.sigma_tr, p.z_r, r) +
                          std::exp(-p.sigma_tr * (p.z_v - p.z_r)) * pole_cdf(p.sigma_tr, p.z_v, r)) /
                         dipole_norm(p);
        return std::min(v, 1.0);
    }
    case ProfileKind::Gaussians: {
        double c = 0.0;
        for (uint32_t k = 0; k < p.gaussian_count; ++k)
            if (p.weight[k] > 0.0) c -= p.weight[k] * std::expm1(-r * r / (2.0 * p.variance[k]));
        return std::min(c, 1.0);
    }
    }
    return 0.0;
}

double dev::radius_for_tail(const ChannelProfile& p, double t)
{
    if (!(t > 0.0)) throw Error("ChannelProfile::radius_for_tail: tail = " + fmt(t) + " must be > 0");
    if (t >= 1.0) return 0.0;
    double lo = 0.0, hi = length_scale(p);
    while (tail(p, hi) > t) {  // tail → 0 monotonically (at least like 1/r), so this ends
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (tail(p, mid) > t ? lo : hi) = mid;
    }
    return hi;
}

ChannelProfile ChannelProfile::scaled(double f) const
{
    check_param("ChannelProfile::scaled", "factor", f);
    ChannelProfile p = *this;
    p.d *= f;
    p.sigma_tr /= f;
    p.z_r *= f;
    p.z_v *= f;
    for (uint32_t k = 0; k < gaussian_count; ++k) p.variance[k] *= f * f;
    return p;
}

double bake::radial_density(const ChannelProfile& p, double t)
{
    if (std::isinf(t)) return 0.0;
    switch (p.kind) {
    case ProfileKind::Burley: {  // 2πtR(t) = (e^{−t/d} + e^{−t/3d}) / 4d, finite at 0
        const double x = t / p.d;
        return (std::exp(-x) + std::exp(-x / 3.0)) / (4.0 * p.d);
    }
    case ProfileKind::Dipole:
    case ProfileKind::Gaussians: return 2.0 * kPi * t * dev::profile_value(p, t);
    }
    return 0.0;
}

// ---------------------------------------------------------------------------------------------
// Materials and presets

Material Material::scaled(double factor) const
{
    Material m = *this;
    for (auto& p : m.profile) p = p.scaled(factor);
    m.transmission.sigma_t /= float(factor);
    m.transmission.sigma_s_reduced /= float(factor);
    m.transmission.sigma_tr /= float(factor);  // 1/mesh unit: the mesh grows, the same medium per unit thins
    return m;
}

Material burley_material(glm::dvec3 d, glm::vec3 albedo, std::string name)
{
    Material m;
    m.name = std::move(name);
    for (int c = 0; c < 3; ++c) m.profile[c] = ChannelProfile::burley(d[c]);
    m.albedo = albedo;
    return m;
}

namespace {

struct JensenEntry {
    const char* name;
    double sigma_s_prime[3], sigma_a[3];  // mm^-1, RGB
};

// Jensen, Marschner, Levoy, Hanrahan 2001, table 2 (η = 1.3).
constexpr JensenEntry kJensen[] = {
    {"apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}},
    {"chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}},
    {"chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}},
    {"cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}},
    {"ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}},
    {"marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}},
    {"potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}},
    {"skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}},
    {"skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}},
    {"skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}},
    {"wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}},
};
constexpr double kJensenEta = 1.3;

// Media of Jade's own presets, per millimetre (an object of ~100 mm: σ_t ≈ 20 per object size
// for the jewel, the medium of the path-traced references in tools/groundtruth/scenes.json).
struct MediumEntry {
    const char* name;
    double sigma_s[3], sigma_a[3];  // mm^-1, RGB
    double g, ior, roughness;
};

constexpr MediumEntry kMedia[] = {
    {"jade", {0.10, 0.16, 0.11}, {0.06, 0.01, 0.04}, 0.3, 1.66, 0.25},
    {"blue-jewel", {0.12, 0.15, 0.196}, {0.08, 0.05, 0.004}, 0.0, 1.6, 0.08},
    {"wax", {0.30, 0.26, 0.22}, {0.006, 0.025, 0.07}, 0.0, 1.45, 0.35},
};

// d'Eon, Luebke, Enderton 2007: six Gaussians for skin; variances in mm², weights per RGB.
constexpr double kSkinVariance[6] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
constexpr double kSkinWeight[3][6] = {
    {0.233, 0.100, 0.118, 0.113, 0.358, 0.078},
    {0.455, 0.336, 0.198, 0.007, 0.004, 0.0},
    {0.649, 0.344, 0.0, 0.007, 0.0, 0.0},
};

}  // namespace

std::vector<std::string> material_preset_names()
{
    std::vector<std::string> names;
    for (const auto& e : kMedia) names.emplace_back(e.name);
    for (const auto& e : kJensen) names.emplace_back(e.name);
    names.emplace_back("skin");
    names.emplace_back("opaque");
    return names;
}

Material material_preset(std::string_view name, double mm_per_unit)
{
    if (!(std::isfinite(mm_per_unit) && mm_per_unit > 0.0))
        throw Error("material_preset: mm_per_unit = " + fmt(mm_per_unit) + " must be finite and > 0");
    Material m;
    m.name = std::string(name);
    for (const auto& e : kMedia) {
        if (name != e.name) continue;
        Medium medium;
        for (int c = 0; c < 3; ++c) medium.sigma_s[c] = e.sigma_s[c], medium.sigma_a[c] = e.sigma_a[c];
        medium.g = e.g, medium.ior = e.ior, medium.roughness = e.roughness;
        return Material::from_medium(medium.scaled(mm_per_unit), std::string(name));  // mm^-1 × mm/unit
    }
    for (const auto& e : kJensen) {
        if (name != e.name) continue;
        // The measured reduced coefficients, with g = 0 (σ_s' is all the table gives); the
        // dipole profile of the same coefficients replaces from_medium's Burley fit.
        Medium medium;
        for (int c = 0; c < 3; ++c) medium.sigma_s[c] = e.sigma_s_prime[c], medium.sigma_a[c] = e.sigma_a[c];
        medium.ior = kJensenEta, medium.roughness = 0.25;
        m = Material::from_medium(medium.scaled(mm_per_unit), std::string(name));
        for (int c = 0; c < 3; ++c)
            m.profile[c] =
                ChannelProfile::dipole(e.sigma_s_prime[c] * mm_per_unit, e.sigma_a[c] * mm_per_unit, kJensenEta);
        return m;
    }
    if (name == "skin") {
        double variance[6];
        for (int k = 0; k < 6; ++k) variance[k] = kSkinVariance[k] / (mm_per_unit * mm_per_unit);  // mm² → units²
        for (int c = 0; c < 3; ++c) m.profile[c] = ChannelProfile::gaussians(kSkinWeight[c], variance);
        m.albedo = {0.75f, 0.52f, 0.42f};
        m.ior = 1.4f;
        m.roughness = 0.35f;
        return m;
    }
    if (name == "opaque") {
        m.opaque = true;  // profiles are unused (default Burley, grey)
        m.albedo = glm::vec3(0.8f);
        return m;
    }
    std::string list;
    for (const auto& n : material_preset_names()) list += (list.empty() ? "" : ", ") + n;
    throw Error("material preset '" + std::string(name) + "' is unknown; valid names: " + list);
}

}  // namespace jade
