// jade/dev/lut.hpp - the translucency LUT's layout (dev::RendererStudy sets its size) and the
// float64 reference functions of the shading look-up tables.
//
// Translucency LUT (the poster's f_r / k_d):
//   f(θ, t) = ∫_ℝ max(cos(θ − φ), 0) · G_t(φ) dφ,   G_t(φ) = e^{−φ²/2t} / √(2πt)
// θ is the angle between the normal and the light (rad), t the Gaussian variance in rad²
// (the shader uses t = strength · t_m). Since max(cos, 0) is 2π-periodic, f is its circular
// convolution with the wrapped Gaussian, with the Fourier series
//   f = 1/π + ½e^{−t/2} cos θ + (2/π) Σ_{k≥1} (−1)^{k+1} e^{−2k²t} / (4k² − 1) · cos 2kθ.
// Properties: f(θ, 0) = max(cos θ, 0); f → 1/π as t → ∞; ∫_{−π}^{π} f dθ = 2 for every t;
// f ≥ 0; f is even in θ.
//
// Curvature LUT (pre-integrated skin style, Penner 2011 / Kubo et al. 2010), on a sphere:
//   D(θ, r) = ∫_{S_r} max(n(s)·L, 0) R(|x − s|) dS / ∫_{S_r} R(|x − s|) dS
// for a point x on a sphere of radius r (mesh units) lit from a distant light L at angle θ to
// the normal at x, with the material's profile R. With the chord s = |x − s| = 2r sin(γ/2)
// (γ the polar angle of the surface point about x) the area element is dS = s ds dβ, the
// same measure as on the plane, so
//   D = ∫_0^{2r} 2πs R(s) · E(γ(s), θ) ds / cdf(2r),
//   E(γ, θ) = (1/2π) ∫_0^{2π} max(cos γ cos θ + sin γ sin θ cos β, 0) dβ   (closed form).
// The ring form ∫ max(cos(θ + x), 0) R(2r sin(|x|/2)) dx of Penner's paper diverges for a
// Burley profile (R ~ 1/r is not integrable along a line), the sphere form is finite for every
// profile. Properties: D → max(cos θ, 0) as r → ∞; ½∫_{−1}^{1} D d(cos θ) = ¼ for every r
// (uniform lighting); for a profile finite at 0 (dipole, Gaussians) D → ¼ as r → 0.
#pragma once

#include <jade/material.hpp>

#include <cstdint>

namespace jade {

/// The translucency LUT's parameterisation (texel i, j of a W × H R32_SFLOAT texture):
///   cos θ_i = −1 + 2i/(W − 1)                 (cos θ = 0 exactly on texel (W − 1)/2)
///   t_j     = t_max · (j/(H − 1))⁴            (t = 0 exactly on row 0; t > t_max clamps)
/// sampled with linear filtering and clamp-to-edge at x = (cos θ + 1)/2 · (W − 1),
/// y = (t/t_max)^¼ · (H − 1), texture coordinates ((x + ½)/W, (y + ½)/H). The fourth root
/// (rather than √t) spaces rows like the Gaussian's σ² ∝ v⁴, i.e. σ ∝ v²: near t = 0, f(θ, t)
/// has a kink whose smoothing scales with σ, and the interpolation error of a uniform σ grid
/// stays above 1e-4 up to thousands of rows (see docs/shading.md for the measured table).
struct LutLayout {
    static constexpr double kMaxVariance = 25.0;  ///< t_max, rad²: f(θ, 25) is within 2e-6 of 1/π
    uint32_t width = 1537, height = 161;
    double cos_theta(uint32_t i) const { return -1.0 + 2.0 * double(i) / double(width - 1); }
    double variance(uint32_t j) const;  ///< t_j above, rad²
    /// Continuous texel coordinates (x, y) of (cos θ, t) before the +½ and division.
    double x(double cos_theta) const;
    double y(double t) const;
};

/// f(θ, t) above, accurate to about 1e-12 absolute. cos_theta is clamped to [−1, 1];
/// t ≥ 0 in rad² (Fourier series for t ≥ 0.1, direct Gauss–Kronrod integration below).
/// Throws jade::Error for a NaN cos_theta or a negative or NaN t.
double lut_reference(double cos_theta, double t);

/// D(θ, r) above for a sphere of radius `curvature_radius` > 0 (mesh units, +∞ allowed: the
/// plane) and the profile `profile`; accurate to about 1e-10. cos_theta is clamped to [−1, 1].
double curvature_lut_reference(double cos_theta, double curvature_radius, const ChannelProfile& profile);

namespace detail {
/// The two evaluation branches of lut_reference, exposed for tests. The series needs t > 0
/// (it is summed until the terms are below 1e-18); the direct integration is valid for every
/// t > 0 but used for t < 0.1.
double lut_reference_series(double cos_theta, double t);
double lut_reference_direct(double cos_theta, double t);
}  // namespace detail

}  // namespace jade
