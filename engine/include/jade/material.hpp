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
/// bake never point-samples it there but integrates it with its closed-form cdf (R, cdf and the
/// radius of a tail: jade/dev/material.hpp).
struct ChannelProfile {
    static constexpr int kMaxGaussians = 6;

    ProfileKind kind = ProfileKind::Burley;
    double d = 1.0;                         ///< Burley shape, mesh units
    double sigma_tr = 0, z_r = 0, z_v = 0;  ///< Dipole, in 1/mesh units and mesh units
    double dipole_total = 1;      ///< Dipole: output, the unnormalised total reflectance R_d (reported, not used)
    uint32_t gaussian_count = 0;  ///< Gaussians: how many of weight/variance are used
    std::array<double, kMaxGaussians> weight{}, variance{};  ///< Gaussians: Σ weight = 1; variance in units²

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

    ChannelProfile scaled(double factor) const;  ///< the same profile for a mesh scaled by factor
    bool operator==(const ChannelProfile&) const = default;
};

/// A homogeneous scattering medium behind a dielectric boundary, the physical description that
/// Material::from_medium turns into the renderer's parameters. Coefficients are linear RGB, per
/// mesh unit (multiply coefficients per millimetre by mm_per_unit, the millimetres one mesh unit
/// stands for). The boundary is a rough dielectric: GGX with α = roughness², as in glTF.
struct Medium {
    glm::dvec3 sigma_s{0.0};  ///< scattering coefficient σ_s ≥ 0, 1/mesh unit
    glm::dvec3 sigma_a{0.0};  ///< absorption coefficient σ_a ≥ 0, 1/mesh unit
    double g = 0.0;           ///< Henyey–Greenstein mean cosine, (−1, 1)
    double ior = 1.5;         ///< relative index of refraction of the boundary, > 0
    double roughness = 0.6;   ///< perceptual GGX roughness of the boundary, [0, 1]

    /// The same medium for a mesh unit `factor` times longer (coefficients × factor).
    Medium scaled(double factor) const;
};

/// The medium an artist describes by its look (glTF's KHR_materials_volume and
/// diffuse_transmission map here): the diffuse colour `albedo` ∈ [0, 1] that
/// Material::from_medium(result) gives back exactly (up to the fitted albedo scale s · 1, the
/// largest reachable), and the mean free path ℓ (mesh units) of the extinction, σ_t = 1/ℓ. The
/// reduced albedo α' solves s · R_d(α', η) = albedo (bisection; R_d the diffuse reflectance of
/// from_medium); σ_s = α'σ_t, σ_a = (1 − α')σ_t, g = 0. Throws jade::Error naming the value for
/// an albedo outside [0, 1] or a non-positive mean free path. The fitted constants (s =
/// MediumFit::albedo_scale) and R_d are jade/dev/material.hpp's.
Medium medium_from_appearance(glm::dvec3 albedo, glm::dvec3 mean_free_path, double ior, double roughness);

/// Light that crosses the object from a light behind it (thin parts glowing, a flank lighting the
/// face beside it), in two parts (shaders/include/transmission.glsl; docs/fidelity.md):
/// - forward, per fragment, from the path length t inside the object (mesh units): the longer of
///   the per-vertex thickness t̄ (jade/bake.hpp ThicknessSettings) and the light's path inside the
///   medium from where it enters (the first four surfaces along each light behind the object, so
///   parts the body shadows stay dark and the air between two parts does not count):
///     L_f = weight · e^{−σ_t·t} · lobe(μ) · ((1 − normal_mix) + normal_mix·max(−N·L, 0)) · E
///     lobe(μ) = (n + 1)/(2π) · max(μ, 0)^n,  μ = V·(−L),  n = `lobe`
///   the low-order light of σ_t = k·(σ_s + σ_a), k = MediumFit::forward_extinction: grey when
///   σ_s + σ_a is grey, so thin parts of a grey-σ_t medium glow white-grey whatever its colour;
/// - diffused, per vertex: the light that entered wherever the light first meets the object (its
///   depth tile's first layer) and diffused to this point, a gather of the diffusion dipole of
///   Jensen et al. 2001 with both boundaries (the entry's and this surface's), the part's width
///   across the light in a transverse buckling, of which the share max(n·(x − s), 0)/|x − s|
///   leaves here; it leaves as a Lambertian emitter (1/π), coloured (red crosses skin furthest):
///     L_d = diffusion_weight · Σ_taps [share · dipole(x, s)] · T̄_in · E / π
///   Its inputs are σ_s' (sigma_s_reduced), σ_tr, z_r = source_depth − extrapolation = 1/σ_t'
///   and z_b = extrapolation.
/// Both cross the boundary (Material::boundary_transmittance). weight = diffusion_weight = 0 turns
/// the term off. Material::from_medium fills every field: sigma_tr, source_depth and
/// extrapolation are outputs derived from the medium (set them only together, as from_medium
/// does); weight, lobe and normal_mix are fitted knobs, diffusion_weight is 1 (derived: the
/// dipole's own flux).
struct Transmission {
    glm::vec3 sigma_t{0.0f};          ///< extinction σ_s + σ_a, 1/mesh unit
    glm::vec3 sigma_s_reduced{0.0f};  ///< σ_s' = σ_s(1 − g), 1/mesh unit
    glm::vec3 sigma_tr{0.0f};         ///< output: √(3σ_a(σ_a + σ_s')), 1/mesh unit
    glm::vec3 source_depth{0.0f};     ///< output: z_s = z_r + z_b, z_r = 1/σ_t' the dipole's source depth, mesh units
    glm::vec3 extrapolation{0.0f};    ///< output: z_b = 2A/(3σ_t'), the extrapolated boundary's distance, mesh units
    float weight = 0.0f;              ///< forward part (the boundary's crossings: Material::boundary_transmittance)
    float diffusion_weight = 0.0f;    ///< diffused part (the same; from_medium: 1)
    float lobe = 2.0f;                ///< exponent n of the forward lobe, ≥ 0
    float normal_mix = 0.3f;          ///< how much the term follows max(−N·L, 0), [0, 1]
    bool enabled() const { return weight > 0.0f || diffusion_weight > 0.0f; }
};

/// A translucent (or opaque) material.
struct Material {
    std::string name;                       ///< preset or user name, used in messages and reports
    std::array<ChannelProfile, 3> profile;  ///< linear RGB
    glm::vec3 albedo{0.8f};                 ///< diffuse albedo k_d, linear RGB
    float strength = 1.0f;  ///< Gaussian variance (rad²) = t_m · (strength + spread_strength · spread)
    /// Blur that follows the surface's shape within the profile's reach: rad² per unit of t_m ·
    /// BakeResult::normal_spread (≈ ⟨θ²⟩/2 of the normals there, per channel): a medium whose
    /// light travels far against the surface's curvature blurs more. Above 0 the blur also stops
    /// at the terminator, past which the light falls off over an angle of variance spread (its
    /// own reach, not the fitted blur's: docs/shading.md). 0 is the poster's model, blurred all
    /// the way round; from_medium sets it from the fit.
    float spread_strength = 0.0f;
    float ior = 1.5f;           ///< for the specular Fresnel term
    float roughness = 0.25f;    ///< GGX roughness (perceptual, squared in the shader)
    float specular = 1.0f;      ///< specular weight (0 turns the lobe off)
    bool opaque = false;        ///< true: no bake, Lambert shading
    Transmission transmission;  ///< light through thin parts (off unless set)
    /// Tm shading: the diffuse light enters and leaves through the dielectric boundary, so it is
    /// multiplied by T(N·L)·T(N·V), T = 1 − Schlick's Fresnel (F0 from ior, grazing value
    /// max(1 − α, F0), α = roughness²): the F_t factors of Jensen et al. 2001's BSSRDF. Dims the
    /// terminator and the silhouettes as a rough dielectric does. The light transmitted through
    /// the object crosses the boundary twice too: it is multiplied by T(max(−N·L, 0))·T(N·V), the
    /// exit point's normal standing in for the entry's (exact for a slab facing the light; at a
    /// rim where the light grazes the surface both crossings are near the grazing value, so a
    /// thin rim does not glow white, as it does not in the path tracer). from_medium sets it.
    bool boundary_transmittance = false;

    /// Every parameter the renderer uses, derived from a physical medium (per mesh unit), with
    /// the constants `fit` fitted to a path tracer (MediumFit and R_d = diffuse_reflectance, the
    /// dipole's diffuse reflectance: jade/dev/material.hpp, which takes other constants too):
    /// - albedo k_d = fit.albedo_scale · diffuse_reflectance(α', η) per channel;
    /// - profile: Burley per channel with d = ℓ/s(A), ℓ = 1/σ_t' the reduced mean free path,
    ///   A = diffuse_reflectance(α', η), s(A) = 1.85 − A + 7|A − 0.8|³ (Christensen & Burley
    ///   2015, searchlight configuration; ℓ is clamped to [1e-12, 1e12] mesh units);
    /// - strength = fit.strength, spread_strength = fit.spread_strength (fitted on the training
    ///   scenes' front and side light); with spread_strength > 0 the light past the terminator
    ///   falls off over an angle of variance BakeResult::normal_spread (derived: the profile's
    ///   reach against the curvature; docs/shading.md);
    /// - transmission: σ_t = fit.forward_extinction · (σ_s + σ_a) (fitted), σ_s', σ_tr (derived);
    ///   the dipole's z_r = 1/σ_t' and z_b = 2A/(3σ_t') (derived; A as in diffuse_reflectance;
    ///   both 0 where σ_s' = 0); weight = fit.transmission_weight, lobe and normal_mix (fitted on
    ///   the training scenes' back light), diffusion_weight = fit.diffusion_weight (derived: 1);
    ///   the boundary's two crossings are boundary_transmittance's;
    /// - ior and roughness of the specular lobe from the boundary, and boundary_transmittance on.
    /// Limits (all finite): σ_s = 0 gives k_d = 0 and only transmission; σ_a = 0 gives R_d = 1;
    /// σ_s = σ_a = 0 is a clear medium (k_d = 0, transmittance 1). Throws jade::Error naming the
    /// field for negative or non-finite coefficients, |g| ≥ 1, an IOR outside (0.2, 5) or a
    /// roughness outside [0, 1].
    static Material from_medium(const Medium& medium, std::string name = "medium");

    Material scaled(double factor) const;  ///< profiles for a mesh scaled by factor
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
