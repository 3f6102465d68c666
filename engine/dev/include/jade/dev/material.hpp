// jade/dev/material.hpp - the arithmetic behind jade/material.hpp, for the float64 references,
// the fidelity tools and tests: a profile's value R(r), its cdf and the radius of a tail; the
// dipole's diffuse reflectance and the slab's diffusion transmittance that Material::from_medium
// is built on; and the constants fitted to a path tracer (MediumFit), which `jade fidelity` and
// tools/groundtruth vary (a host gets the fitted defaults from the core). Declared for jade::dev,
// defined in jade::jade.
#pragma once

#include <jade/material.hpp>

#include <glm/vec3.hpp>

#include <string>

namespace jade::dev {

/// R(r): the profile's value at distance r ≥ 0 (mesh units), 1/units²; +∞ at r = 0 for Burley.
/// Throws jade::Error for a negative or NaN r.
double profile_value(const ChannelProfile& profile, double r);
/// 2π∫_0^r R(ρ)ρ dρ ∈ [0, 1], exact closed form (1 at r = ∞). Throws as profile_value.
double profile_cdf(const ChannelProfile& profile, double r);
/// The smallest r with 1 − cdf(r) ≤ tail (0 for tail ≥ 1). Throws jade::Error for tail ≤ 0.
double radius_for_tail(const ChannelProfile& profile, double tail);

/// True when the three channels have the same profile: one channel is baked and fetched (the
/// renderer's and the bake's choice; docs/scene.md "grey materials").
inline bool is_grey(const Material& material)
{
    return material.profile[0] == material.profile[1] && material.profile[1] == material.profile[2];
}

/// The constants of Material::from_medium that the model leaves free, fitted to a volumetric path
/// tracer (Mitsuba 3) on the training scenes of tools/groundtruth (27 scenes: bunny, dragon, camel
/// × jewel, marble, wax × front, side, back light; fit and validation: docs/fidelity.md). The
/// defaults are the fitted values; the validation scenes (hand, elephant) and the held-out
/// regimes (skin at a head's scale, Jensen et al.'s media in millimetres, point lights) never
/// took part in choosing them.
struct MediumFit {
    /// k_d = albedo_scale · R_d(α', η): fitted (stage 1, front and side light); the dipole's R_d
    /// alone overestimates what leaves a rough dielectric.
    double albedo_scale = 0.9;
    /// Material::strength, rad² per unit t_m: the poster's scale-free blur. 0: the default's blur
    /// comes from the spread alone, whose angle follows the medium's reach against the shape (a
    /// scale-free one lit a back-lit head's face, where the path tracer has nothing).
    double strength = 0.0;
    /// Material::spread_strength, rad² per unit t_m · normal spread: fitted (front and side light,
    /// 4.5 against 3, 6 and 12); the spread ≈ ⟨θ²⟩/2 of the normals within the profile's reach.
    double spread_strength = 4.5;
    double transmission_weight = 0.35;  ///< Transmission::weight: fitted (stage 2, back light, w_d = 1)
    /// Transmission::diffusion_weight: derived, 1: the diffused part is the diffusion dipole's own
    /// flux, with the part's sides in its transverse buckling (transmission.glsl). A free weight
    /// fitted on the training scenes' back light would be 0.78 (tools/groundtruth/STUDIES.md,
    /// "The diffused light as a gather").
    double diffusion_weight = 1.0;
    double lobe = 16.0;        ///< Transmission::lobe: fitted (stage 2)
    double normal_mix = 0.25;  ///< Transmission::normal_mix: fitted (stage 2)
    /// Transmission::sigma_t = forward_extinction · (σ_s + σ_a), in (0, 1]: the forward light falls
    /// slower than the unscattered light, since light scattered a little still leaves in the lobe
    /// (fitted: 0.5, 0.6, 0.7, 0.85, 1).
    double forward_extinction = 0.7;
};

/// Material::from_medium with other constants than the fitted defaults (MediumFit{} gives the
/// same material as Material::from_medium). Also throws jade::Error naming a constant of `fit`
/// out of range.
Material from_medium(const Medium& medium, const MediumFit& fit, std::string name = "medium");

/// medium_from_appearance (jade/material.hpp) with the albedo scale of `fit`: the reduced albedo
/// α' solves fit.albedo_scale · diffuse_reflectance(α', η) = albedo.
Medium medium_from_appearance(glm::dvec3 albedo, glm::dvec3 mean_free_path, double ior, double roughness,
                              const MediumFit& fit);

/// The multiple-scattering (diffuse) reflectance of a semi-infinite medium behind a boundary of
/// relative IOR η, from the reduced albedo α' = σ_s'/(σ_s' + σ_a), σ_s' = σ_s(1 − g): the
/// classical dipole's total diffuse reflectance (Jensen et al. 2001, eq. 13, with the boundary
/// term A = (1 + F_dr)/(1 − F_dr) and Egan–Hilgeman's F_dr):
///   R_d = (α'/2) (1 + e^{−(4/3)A·√(3(1−α'))}) e^{−√(3(1−α'))}
/// in [0, 1]; 0 for α' = 0, 1 for α' = 1 (no absorption). Throws jade::Error for α' ∉ [0, 1] or
/// η out of (0.2, 5).
double diffuse_reflectance(double reduced_albedo, double eta);

}  // namespace jade::dev
