// jade/material.hpp - translucent materials: scattering profiles R(r) per colour channel.
//
// Conventions
// - Every profile is normalised over the plane: ∫ R(|s|) dA = 2π ∫_0^∞ R(r) r dr = 1.
//   Hence t_m = 1 on an unoccluded infinite plane, t_m is unitless and does not depend on the
//   mesh's scale when the profile is scaled with it.
// - Radii r are in mesh units. Physical data (Jensen et al. 2001, d'Eon) is in millimetres;
//   presets take `mm_per_unit`, the number of millimetres one mesh unit stands for.
// - Colour channels are linear RGB, index 0 = red.
// Everything here is plain data and pure functions: thread-safe, no GPU needed. Errors are
// jade::Error naming the parameter at fault.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace jade {

/// Which analytic family a ChannelProfile is.
enum class ProfileKind : uint32_t {
    Burley = 0,     ///< Christensen–Burley normalised diffusion, shape d
    Dipole = 1,     ///< classical dipole (Jensen et al. 2001), normalised by its total reflectance
    Gaussians = 2,  ///< sum of up to 6 Gaussians (d'Eon et al. 2007), weights normalised to 1
};

/// The scattering profile of one colour channel. Singular at r = 0 for Burley (R ~ 1/r); the
/// bake never point-samples it there but integrates it with cdf().
struct ChannelProfile {
    static constexpr int kMaxGaussians = 6;

    ProfileKind kind = ProfileKind::Burley;
    double d = 1.0;                        ///< Burley shape, mesh units
    double sigma_tr = 0, z_r = 0, z_v = 0; ///< Dipole, in 1/mesh units and mesh units
    double dipole_total = 1;               ///< Dipole: unnormalised total reflectance R_d (for docs)
    uint32_t gaussian_count = 0;           ///< Gaussians: how many of weight/variance are used
    std::array<double, kMaxGaussians> weight{}, variance{}; ///< Gaussians: Σ weight = 1; variance in units²

    /// Burley with shape d > 0 (mesh units); throws jade::Error for d ≤ 0 or not finite.
    static ChannelProfile burley(double d);
    /// From reduced scattering and absorption coefficients in 1/mesh-unit and relative IOR η.
    static ChannelProfile dipole(double sigma_s_prime, double sigma_a, double eta);
    /// 1 to 6 Gaussians, weights ≥ 0 (normalised to sum 1), variances > 0 in units²; throws
    /// jade::Error for mismatched sizes or bad values.
    static ChannelProfile gaussians(std::span<const double> weights, std::span<const double> variances);
    /// Burley's fit from surface albedo A and mean free path ℓ (mesh units): d = ℓ / s(A),
    /// s = 1.85 − A + 7|A − 0.8|³ (searchlight configuration).
    static ChannelProfile burley_from_albedo(double albedo, double mean_free_path);

    double R(double r) const;       ///< profile value, 1/units²
    double cdf(double r) const;     ///< 2π∫_0^r R(ρ)ρ dρ ∈ [0,1], exact closed form
    double radius_for_tail(double tail) const; ///< smallest r with 1 − cdf(r) ≤ tail
    ChannelProfile scaled(double factor) const; ///< the same profile for a mesh scaled by factor
    bool operator==(const ChannelProfile&) const = default;
};

/// A translucent (or opaque) material.
struct Material {
    std::string name;                       ///< preset or user name, used in messages and reports
    std::array<ChannelProfile, 3> profile;  ///< linear RGB
    glm::vec3 albedo{0.8f};                 ///< diffuse albedo k_d, linear RGB
    float strength = 1.0f;                  ///< Gaussian variance (rad²) = strength · t_m
    float ior = 1.5f;                       ///< for the specular Fresnel term
    float roughness = 0.25f;                ///< GGX roughness (perceptual, squared in the shader)
    float specular = 1.0f;                  ///< specular weight (0 turns the lobe off)
    bool opaque = false;                    ///< true: no bake, Lambert shading

    /// True when the three channels have the same profile: one channel is baked and fetched.
    bool grey() const { return profile[0] == profile[1] && profile[1] == profile[2]; }
    Material scaled(double factor) const;   ///< profiles for a mesh scaled by factor
};

/// Preset names: "jade", "blue-jewel", "marble", "skimmilk", "wholemilk", "cream", "ketchup",
/// "skin1", "skin2", "apple", "potato", "chicken1", "chicken2" (Jensen et al. 2001 dipoles),
/// "skin" (d'Eon's six Gaussians), "wax", "opaque".
std::vector<std::string> material_preset_names();

/// A preset for a mesh whose unit is `mm_per_unit` millimetres. Throws jade::Error listing the
/// known names when `name` is unknown.
Material material_preset(std::string_view name, double mm_per_unit);

/// A grey or coloured Burley material with d in mesh units per channel.
Material burley_material(glm::dvec3 d, glm::vec3 albedo, std::string name = "burley");

}  // namespace jade
