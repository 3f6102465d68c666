// profile.glsl - scattering profiles R(r) in float32, normalised to 1 over the plane
// (engine/include/jade/material.hpp has the float64 originals and the formulas' sources).
// Everything is written so that tiny and huge radii neither cancel nor overflow: expm1 forms
// for the radial CDFs, and R(t)·t (finite at t = 0) where the integrals need it.
#ifndef JADE_PROFILE_GLSL
#define JADE_PROFILE_GLSL

#include "profile_interface.h"  // struct Profile and the kinds, shared with engine/src/bake

const uint PROFILE_BURLEY = JADE_PROFILE_BURLEY;
const uint PROFILE_DIPOLE = JADE_PROFILE_DIPOLE;
const uint PROFILE_GAUSSIANS = JADE_PROFILE_GAUSSIANS;
const uint PROFILE_MIXED = JADE_PROFILE_MIXED;

// The kind of every channel's profile, a specialisation constant (PROFILE_MIXED: read each
// profile's own kind at run time). Lavapipe executes both sides of every branch (docs/
// lavapipe.md), so a shader compiled for one kind skips the other kinds' arithmetic.
layout(constant_id = 2) const uint PROFILE_KIND = PROFILE_MIXED;

uint profile_kind(uint runtime_kind) { return PROFILE_KIND == PROFILE_MIXED ? runtime_kind : PROFILE_KIND; }

// The Gaussian sums run over all PROFILE_MAX_GAUSSIANS slots, unrolled, the unused ones
// weighing 0 (gaussian_weight): a loop to `count` would cost lavapipe a loop back-edge per term,
// and its budget of 65,535 back-edges per invocation (docs/lavapipe.md) then ran out inside
// the all-pairs pass of a 10,000-vertex mesh, which silently left out most of the sources.
const uint PROFILE_MAX_GAUSSIANS = JADE_PROFILE_MAX_GAUSSIANS;

// e^x − 1 without cancellation for small |x|.
float expm1_accurate(float x)
{
    if (abs(x) < 1e-2) return x * (1.0 + x * (0.5 + x * (1.0 / 6.0 + x * (1.0 / 24.0))));
    return exp(x) - 1.0;
}

// One dipole source at depth z: its R_d·t term (unnormalised by 1/(2π·total)).
float dipole_source_rt(float sigma, float z, float t)
{
    float d = sqrt(t * t + z * z);
    return t * z * (1.0 + sigma * d) * exp(-sigma * d) / (d * d * d);
}

// One dipole source's share of the radial CDF: e^{−σz} − z·e^{−σd}/d in a form stable for r ≪ z.
float dipole_source_cdf(float sigma, float z, float r)
{
    float d = sqrt(r * r + z * z);
    float delta = r * r / (d + z);  // d − z without cancellation
    return exp(-sigma * z) * (delta - z * expm1_accurate(-sigma * delta)) / d;
}

// Slot k's weight and variance; an unused slot weighs 0 with variance 1, so every sum over the
// slots adds an exact 0 for it.
float gaussian_weight(Profile p, uint k) { return k < p.count ? p.w[k] : 0.0; }
float gaussian_variance(Profile p, uint k) { return k < p.count ? p.v[k] : 1.0; }

// w/(2πv)·e^{−t²/2v}, the plane-normalised Gaussian of slot k.
float gaussian_term(Profile p, uint k, float t2)
{
    float v = gaussian_variance(p, k);
    return gaussian_weight(p, k) / (2.0 * JADE_PI * v) * exp(-t2 / (2.0 * v));
}

float dipole_total(Profile p) { return exp(-p.a * p.b) + exp(-p.a * p.c); }

// R(t)·t, finite at t = 0 for every profile.
float profile_rt(Profile p, float t)
{
    if (profile_kind(p.kind) == PROFILE_BURLEY) {
        float d = p.a;
        float slow = exp(-t / (3.0 * d));  // e^{-t/d} = (e^{-t/3d})³: one exp instead of two
        return (slow * slow * slow + slow) / (8.0 * JADE_PI * d);
    }
    if (profile_kind(p.kind) == PROFILE_DIPOLE)
        return (dipole_source_rt(p.a, p.b, t) + dipole_source_rt(p.a, p.c, t)) / (2.0 * JADE_PI * dipole_total(p));
    float s = 0.0;
    [[unroll]] for (uint k = 0u; k < PROFILE_MAX_GAUSSIANS; ++k) s += gaussian_term(p, k, t * t);
    return s * t;
}

// R(t), t > 0.
float profile_r(Profile p, float t)
{
    if (profile_kind(p.kind) == PROFILE_GAUSSIANS) {
        float s = 0.0;
        [[unroll]] for (uint k = 0u; k < PROFILE_MAX_GAUSSIANS; ++k) s += gaussian_term(p, k, t * t);
        return s;
    }
    return profile_rt(p, t) / t;
}

// R and its first three derivatives at t > 0, analytic for Burley and Gaussians. The dipole
// returns has_derivatives = false: callers fall back to finite differences.
struct ProfileDerivatives {
    float r0, r1, r2, r3;
    bool has_derivatives;
};

ProfileDerivatives profile_derivatives(Profile p, float t)
{
    ProfileDerivatives o;
    o.has_derivatives = profile_kind(p.kind) != PROFILE_DIPOLE;
    o.r0 = profile_r(p, t);
    o.r1 = 0.0, o.r2 = 0.0, o.r3 = 0.0;
    if (profile_kind(p.kind) == PROFILE_BURLEY) {
        // R = k·f·g with f = e^{-t/d} + e^{-t/3d}, g = 1/t, k = 1/(8πd)
        float d = p.a, k = 1.0 / (8.0 * JADE_PI * d);
        float e3 = exp(-t / (3.0 * d)), e1 = e3 * e3 * e3;
        float f0 = e1 + e3, f1 = -(e1 + e3 / 3.0) / d, f2 = (e1 + e3 / 9.0) / (d * d), f3 = -(e1 + e3 / 27.0) / (d * d * d);
        float g0 = 1.0 / t, g1 = -g0 * g0, g2 = 2.0 * g0 * g0 * g0, g3 = -6.0 * g0 * g0 * g0 * g0;
        o.r1 = k * (f1 * g0 + f0 * g1);
        o.r2 = k * (f2 * g0 + 2.0 * f1 * g1 + f0 * g2);
        o.r3 = k * (f3 * g0 + 3.0 * f2 * g1 + 3.0 * f1 * g2 + f0 * g3);
    } else if (profile_kind(p.kind) == PROFILE_GAUSSIANS) {
        [[unroll]] for (uint k = 0u; k < PROFILE_MAX_GAUSSIANS; ++k) {
            float v = gaussian_variance(p, k);
            float g = gaussian_term(p, k, t * t);
            o.r1 -= t / v * g;
            o.r2 += (t * t / (v * v) - 1.0 / v) * g;
            o.r3 += (3.0 * t / (v * v) - t * t * t / (v * v * v)) * g;
        }
    }
    return o;
}

// 2π ∫_0^r R(ρ) ρ dρ, the share of the profile inside radius r.
float profile_cdf(Profile p, float r)
{
    if (profile_kind(p.kind) == PROFILE_BURLEY) {
        float x = r / p.a;
        return -0.25 * expm1_accurate(-x) - 0.75 * expm1_accurate(-x / 3.0);
    }
    if (profile_kind(p.kind) == PROFILE_DIPOLE)
        return (dipole_source_cdf(p.a, p.b, r) + dipole_source_cdf(p.a, p.c, r)) / dipole_total(p);
    float s = 0.0;
    [[unroll]] for (uint k = 0u; k < PROFILE_MAX_GAUSSIANS; ++k)
        s -= gaussian_weight(p, k) * expm1_accurate(-r * r / (2.0 * gaussian_variance(p, k)));
    return s;
}

// ∫ R over a flat disk of radius rho whose centre lies at distance r (the vertex-disk rule of
// jade/bake.hpp): cdf(max(ρ − r, 0)) + ∫_{|r−ρ|}^{r+ρ} R(t)·2t·α(t) dt, 8-point Gauss–Legendre
// in φ with t = c − h·cos φ, which makes the integrand smooth at both ends.
// 8-point Gauss–Legendre nodes and weights on [−1, 1].
const float GAUSS_LEGENDRE_8_X[8] = float[8](-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                                            0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363);
const float GAUSS_LEGENDRE_8_W[8] = float[8](0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                                            0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763);

float disk_integral(Profile p, float r, float rho)
{
    // Seen from (almost) its own centre the disk integral tends to cdf(ρ) continuously; no
    // early return: lavapipe mis-handles returns inside divergent loops.
    r = max(r, 1e-6 * rho);
    float lo = abs(r - rho), hi = r + rho;
    float c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    float sum = 0.0;
    [[unroll]] for (int k = 0; k < 8; ++k) {
        float phi = (GAUSS_LEGENDRE_8_X[k] + 1.0) * (0.5 * JADE_PI);
        float t = c - h * cos(phi);
        // α = acos((t² + r² − ρ²)/(2tr)), as 2·atan(√(1−cos α), √(1+cos α)) with both factored:
        // no cancellation near α = 0 or π, where GPU acos approximations are poor.
        float one_minus = max((rho - t + r) * (rho + t - r), 0.0);
        float one_plus = max((t + r - rho) * (t + r + rho), 0.0);
        float alpha = 2.0 * atan(sqrt(one_minus), sqrt(one_plus));
        sum += GAUSS_LEGENDRE_8_W[k] * profile_rt(p, t) * alpha * sin(phi);
    }
    // Σ w·(π/2)·R(t)·2t·α·h·sin φ
    return profile_cdf(p, max(rho - r, 0.0)) + sum * JADE_PI * h;
}

#endif
