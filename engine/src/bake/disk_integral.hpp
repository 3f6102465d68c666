// bake/disk_integral.hpp - float64 quadrature for the CPU references: the vertex-disk integral
// D(r, ρ) of bake.hpp (8-point Gauss–Legendre, the rule the GPU bake mirrors) and a globally
// adaptive Gauss–Kronrod (7, 15) integrator for the LUT references and the tests.
//
// Units: r, ρ, t in mesh units; R(t) in 1/units²; radial_density in 1/units; D unitless.
#pragma once

#include <jade/dev/material.hpp>
#include <jade/material.hpp>

#include "bake_interface.h"  // JADE_DISK_CAP, shared with tm_near.comp

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

namespace jade::bake {

/// 2π·t·R(t) = d cdf / dt, the density of the scattering distance; finite at t = 0 for every
/// kind (Burley: (e^{−t/d} + e^{−t/3d}) / 4d). Defined in profile.cpp. t ≥ 0.
double radial_density(const ChannelProfile& p, double t);

/// 8-point Gauss–Legendre rule on [−1, 1] (nodes ±x_k, weights w_k); the GLSL bake uses the
/// same constants.
inline constexpr double kGaussLegendre8X[4] = {0.1834346424956498049394761, 0.5255324099163289858177390,
                                               0.7966664774136267395915539, 0.9602898564975362316835609};
inline constexpr double kGaussLegendre8W[4] = {0.3626837833783619829651504, 0.3137066458778872873379622,
                                               0.2223810344533744705443560, 0.1012285362903762591525314};

/// ∫ R(|x − s|) dA over a flat disk of radius ρ whose centre lies at distance r from x, x in
/// the disk's plane. Exact in the distance t from x:
///   D = cdf(max(ρ − r, 0)) + ∫_{|r−ρ|}^{r+ρ} 2π t R(t) · α(t)/π dt,
///   α(t) = acos((t² + r² − ρ²) / (2 t r))   (half-angle of the arc of radius t in the disk),
/// with t = c − h cos φ, φ ∈ [0, π] (c, h = centre and half-width of [|r−ρ|, r+ρ]), which
/// absorbs the square-root endpoint behaviour of α, and 8 Gauss–Legendre nodes in φ.
inline double disk_integral(const ChannelProfile& p, double r, double rho)
{
    if (r <= 1e-12 * rho) return dev::profile_cdf(p, rho);  // x at the centre (error O((r/ρ)²))
    const double lo = std::abs(r - rho), hi = r + rho;
    const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const double half_pi = 0.5 * std::numbers::pi;
    double sum = 0.0;
    for (int k = 0; k < 8; ++k) {
        const double x = (k < 4) ? -kGaussLegendre8X[3 - k] : kGaussLegendre8X[k - 4];
        const double w = (k < 4) ? kGaussLegendre8W[3 - k] : kGaussLegendre8W[k - 4];
        const double phi = (x + 1.0) * half_pi;
        const double t = c - h * std::cos(phi);
        if (!(t > 0.0)) continue;  // only when r = ρ and φ → 0; the integrand is 0 there
        const double cos_alpha = std::clamp((t * t + r * r - rho * rho) / (2.0 * t * r), -1.0, 1.0);
        const double alpha = std::acos(cos_alpha);
        // 2t·R(t)·α = radial_density(t)·α/π
        sum += w * half_pi * radial_density(p, t) * (alpha / std::numbers::pi) * h * std::sin(phi);
    }
    return dev::profile_cdf(p, std::max(rho - r, 0.0)) + sum;
}

/// The vertex-disk rule's neighbour term for a vertex j of area A_j (ρ_j = √(A_j/π)) at
/// distance r: the disk integral in the near field r < 4ρ_j (tested as r² < 16·A_j/π), A_j·R(r)
/// beyond. 0 for a zero area.
/// A neighbour's disk never reaches past kDiskCap·r towards the target: on irregular meshes a
/// large neighbour's disk would otherwise cover the target and, for a stiff profile, count a
/// second self term. The area beyond the capped disk (the annulus from kDiskCap·r to ρ about
/// the neighbour) is kept as a point at that annulus's RMS distance from the target,
/// √(r² + (ρ² + capped²)/2), so the neighbour's total area is kept and a neighbour (nearly) on
/// top of the target stays finite: at r = 0 its whole area sits at ρ/√2. Regular meshes
/// (ρ ≈ 0.56 r) are not affected.
inline constexpr double kDiskCap = JADE_DISK_CAP;

inline double rest_distance(double r, double rho, double capped)
{
    return std::sqrt(r * r + 0.5 * (rho * rho + capped * capped));
}

inline double vertex_disk_term(const ChannelProfile& p, double r, double area)
{
    if (!(area > 0.0)) return 0.0;
    if (r * r < 16.0 / std::numbers::pi * area) {
        const double rho = std::sqrt(area / std::numbers::pi);
        const double capped = std::min(rho, kDiskCap * r);
        const double rest = area - std::numbers::pi * capped * capped;
        return (capped > 0.0 ? disk_integral(p, r, capped) : 0.0) +
               (rest > 0.0 ? rest * dev::profile_value(p, rest_distance(r, rho, capped)) : 0.0);
    }
    return area * dev::profile_value(p, r);
}

template <class F>
double integrate(F&& f, double a, double b, double rel_tol = 1e-13, double abs_tol = 0.0, int max_intervals = 4000)
{
    static constexpr double xk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                     0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                     0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                     0.207784955007898467600689403773245, 0.0};
    static constexpr double wk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                     0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                     0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                     0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
    static constexpr double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                     0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
    struct Piece {
        double a, b, value, error;
        bool operator<(const Piece& o) const { return error < o.error; }
    };
    auto rule = [&](double lo, double hi) {
        const double c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
        const double fc = f(c);
        double k15 = wk[7] * fc, g7 = wg[3] * fc;
        for (int j = 0; j < 7; ++j) {
            const double s = f(c - h * xk[j]) + f(c + h * xk[j]);
            k15 += wk[j] * s;
            if (j % 2 == 1) g7 += wg[j / 2] * s;
        }
        return Piece{lo, hi, k15 * h, std::abs((k15 - g7) * h)};
    };
    if (!(b != a)) return 0.0;
    std::priority_queue<Piece> heap;
    heap.push(rule(a, b));
    double value = heap.top().value, error = heap.top().error;
    for (int n = 1; n < max_intervals && error > std::max(abs_tol, rel_tol * std::abs(value)); ++n) {
        const Piece worst = heap.top();
        const double mid = 0.5 * (worst.a + worst.b);
        if (!(mid > worst.a && mid < worst.b)) break;  // interval at double resolution
        heap.pop();
        const Piece left = rule(worst.a, mid), right = rule(mid, worst.b);
        value += left.value + right.value - worst.value;
        error += left.error + right.error - worst.error;
        heap.push(left);
        heap.push(right);
    }
    // Re-sum to drop the rounding of the running updates.
    double total = 0.0;
    for (; !heap.empty(); heap.pop()) total += heap.top().value;
    return total;
}

}  // namespace jade::bake
