// jade/dev/burley_diffusion.hpp - the sampling of the Burley shading mode: screen-space Burley
// diffusion as Unity HDRP does it (Golubev 2018, "Efficient Screen-Space Subsurface Scattering
// Using Burley's Normalized Diffusion in Real-Time", SIGGRAPH course; read, not copied). Each pixel
// draws its samples by the exact inverse CDF of the Burley profile of the material's widest
// channel, on a golden-angle disk in world units at the pixel's depth, rotated per pixel; a sample
// weighs R_c(√(r² + Δz²)) / pdf(r) per channel, and the sums are renormalised per channel.
//
// Units: radii and shapes d in mesh units; pdf per unit area (1/mesh units²). float64, pure.
#pragma once

#include <jade/material.hpp>

#include <glm/vec3.hpp>

namespace jade {

/// The radius r with cdf(r) = u of the Burley profile of shape d > 0, u ∈ [0, 1):
/// cdf(r) = 1 − ¼e^{−r/d} − ¾e^{−r/(3d)}. With x = e^{−r/(3d)} that is the cubic
/// x³ + 3x − 4(1 − u) = 0, whose one real root is Cardano's
/// x = ∛(2(1 − u) + √(4(1 − u)² + 1)) + ∛(2(1 − u) − √(4(1 − u)² + 1)); r = −3d ln x.
double burley_sample_radius(double u, double d);
/// The density of those samples per unit area of the plane at radius r: the profile itself,
/// R(r) = (e^{−r/d} + e^{−r/(3d)}) / (8π d r) (its radial density 2πr R(r) is cdf′(r)).
double burley_sample_pdf(double r, double d);
/// The Burley shape d per channel that the mode uses: the profile's own d for a Burley channel;
/// otherwise the d whose Burley profile has the same median radius (cdf = ½).
glm::dvec3 burley_shapes(const Material& material);

}  // namespace jade
