// jade/dev/separable.hpp - the kernel and transmittance of the Separable shading mode: Jimenez's
// separable subsurface scattering (Jimenez, Zsolnai, Jarabo, Freude, Auzinger, Wu, von der Pahlen,
// Wimmer, Gutierrez 2015, "Separable Subsurface Scattering"; the screen-space version of Jimenez,
// Sundstedt, Gutierrez 2009/2012, reference code iryoku/separable-sss), fitted to a material's own
// profiles R(r) instead of the skin constant (docs/peers_separable.md).
//
// Units: offsets and distances in mesh units; weights and transmittances unitless. float64
// throughout; the renderer uploads these values as float. Pure functions, thread-safe, no GPU.
#pragma once

#include <jade/material.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace jade {

/// The share of a profile's light that lands in the half-plane {x' < x} from a unit point source
/// at the origin: E(x) = ∫_{−∞}^x M(s) ds, M the 1-D marginal ∫ R(√(s² + y²)) dy. It is the
/// exact response of the profile to a straight edge of light (lit for x' < 0, dark beyond) at
/// distance x into the dark side; E(−∞) = 0, E(0) = ½, E(∞) = 1. Evaluated as
/// E(x) = 1 − H(x) for x ≥ 0, H(−x) for x < 0, with H(x) = (1/π) ∫_0^{π/2} (1 − cdf(x / cos φ)) dφ
/// (the half-plane's mass in polar coordinates, integrated by parts: bounded integrand, no R(0)
/// singularity), composite Simpson with 2048 intervals.
double profile_edge_response(const ChannelProfile& profile, double x);

/// One 1-D pass of the separable kernel: `taps` taps at offsets x_i (mesh units, ascending,
/// symmetric, x at the middle tap 0) distributed as Jimenez's reference code does,
/// x_i = range · t_i · |t_i|, t_i = −1 + 2i/(taps − 1) (denser near the centre); per channel c
/// the weight of tap i is the marginal's mass between the midpoints to its neighbours,
/// w_i,c = E_c(m_i) − E_c(m_{i−1}), the outermost taps taking the tails (m_{−1} = −∞,
/// m_{taps−1} = ∞), so each channel's weights sum to 1. Applied along x and then y, a straight
/// edge along either axis gets exactly E sampled at the taps. `range` is where the widest
/// channel's tail H(range) falls to kSeparableKernelTail.
struct SeparableKernel {
    std::vector<double> offset;      ///< mesh units
    std::vector<glm::dvec3> weight;  ///< per tap, per channel (linear RGB)
    double range = 0;                ///< the outermost tap's offset, mesh units
};
inline constexpr double kSeparableKernelTail = 0.005;
/// Throws jade::Error unless taps is 11, 17 or 25 (the counts the shader is built for).
SeparableKernel separable_kernel(const Material& material, uint32_t taps);

/// SSSSTransmittance's profile of the distance d (mesh units) that light crossed inside the
/// object (Jimenez, Whelan, Sundstedt, Gutierrez 2010, "Real-Time Realistic Skin Translucency"):
/// for skin they sum the profile's Gaussians as Σ w_i e^{−d²/v_i}, which is the share of a
/// Gaussian sum's light that travels farther than d, 1 − cdf(d) (with d'Eon's variances:
/// Σ w_i e^{−d²/(2v_i)}). For any profile: T(d) = 1 − cdf(d) ∈ [0, 1], T(0) = 1.
double separable_transmittance(const ChannelProfile& profile, double d);

}  // namespace jade
