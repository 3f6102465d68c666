// shading/burley_diffusion.cpp - jade/dev/burley_diffusion.hpp.
#include <jade/dev/material.hpp>
#include <jade/dev/burley_diffusion.hpp>
#include <jade/error.hpp>

#include <cmath>
#include <numbers>
#include <string>

namespace jade {

double burley_sample_radius(double u, double d)
{
    if (!(u >= 0.0 && u < 1.0) || !(d > 0.0))
        throw Error("burley_sample_radius: u must be in [0, 1) and d > 0 (u " + std::to_string(u) + ", d " +
                    std::to_string(d) + ")");
    const double a = 2.0 * (1.0 - u), s = std::sqrt(a * a + 1.0);
    const double x = std::cbrt(a + s) + std::cbrt(a - s);  // ∈ (0, 1]
    return -3.0 * d * std::log(std::min(x, 1.0));
}

double burley_sample_pdf(double r, double d)
{
    return (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / (8.0 * std::numbers::pi * d * r);
}

glm::dvec3 burley_shapes(const Material& material)
{
    // The Burley median is d times the root of 1 − ¼e^{−k} − ¾e^{−k/3} = ½.
    const double k = burley_sample_radius(0.5, 1.0);
    glm::dvec3 d(0.0);
    for (int c = 0; c < 3; ++c) {
        const ChannelProfile& p = material.profile[size_t(c)];
        d[c] = p.kind == ProfileKind::Burley ? p.d : dev::radius_for_tail(p, 0.5) / k;
    }
    return d;
}

}  // namespace jade
