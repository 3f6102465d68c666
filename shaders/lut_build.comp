#version 460
#extension GL_GOOGLE_include_directive : require
// lut_build.comp - the translucency LUT f(θ, t) = {max(cos θ, 0) ∗ G_t}(θ) in float32, one
// thread per texel (parameterisation: jade::LutLayout in jade/render.hpp).
//   t ≥ 0.1: the Fourier series of the circular convolution, cos 2kθ as the Chebyshev
//            polynomial T_2k(cos θ) (a stable recurrence, no acos);
//   t < 0.1: Gauss–Legendre quadrature of ∫ max(cos(θ − φ), 0) G_t(φ) dφ over |φ| ≤ 8σ, cut at
//            the kinks φ = θ ± π/2 (mod 2π) and at 0, ±4σ, so each piece is smooth and at most
//            4σ wide; 16 nodes per piece integrate it to float precision.
// The texel's cos θ = (2i − (W − 1))/(W − 1) is one rounding of an exact integer ratio, so
// row 0 holds max(cos θ, 0) correctly rounded and the centre texel exactly 0.
#include "common.glsl"

layout(binding = 0, r32f) uniform writeonly image2D lut;

#include "lut_interface.h"  // struct LutBuildPush, JADE_LUT_SERIES_FROM_T, shared with engine/src/shading
layout(push_constant, scalar) uniform Push { LutBuildPush push; };

const float kSeriesFrom = JADE_LUT_SERIES_FROM_T;

// 16-point Gauss–Legendre nodes (positive half) and weights on [−1, 1].
const float kNode[8] = float[](0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                               0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499);
const float kWeight[8] = float[](0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                 0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541);

float series(float c, float t)
{
    float f = 1.0 / JADE_PI + 0.5 * exp(-0.5 * t) * c;
    float t_prev = c, t_cur = 2.0 * c * c - 1.0;  // T_1, T_2
    float sum = 0.0, sign = 1.0;
    for (int k = 1; k <= 32; ++k) {
        float kk = float(k * k);
        float damp = exp(-2.0 * kk * t);
        if (damp < 1e-10) break;
        sum += sign * damp / (4.0 * kk - 1.0) * t_cur;  // t_cur = T_2k(c)
        sign = -sign;
        // Advance two orders: T_{n+1} = 2c T_n − T_{n−1}.
        float t_next = 2.0 * c * t_cur - t_prev;
        t_prev = t_next;
        t_cur = 2.0 * c * t_next - t_cur;
    }
    return f + (2.0 / JADE_PI) * sum;
}

float quadrature(float c, float t)
{
    float s = sqrt(max(0.0, 1.0 - c * c));      // sin θ, θ ∈ [0, π]
    float theta = acos(c);
    float sigma = sqrt(t), inv_2t = 0.5 / t;
    // cos(θ − φ) ≥ 0 exactly on the intervals φ ∈ θ + [−π/2, π/2] + 2πk. Intersecting them
    // with four 4σ-wide quarters of the window gives pieces on which the integrand is smooth
    // and a Gaussian at most 4σ wide; |φ| ≤ 8σ < 2.6 needs k ∈ {−1, 0, 1} only.
    float f = 0.0;
    for (int quarter = 0; quarter < 4; ++quarter) {
        float a = (float(quarter) - 2.0) * 4.0 * sigma, b = a + 4.0 * sigma;
        for (int k = -1; k <= 1; ++k) {
            float centre = theta + 2.0 * JADE_PI * float(k);
            float lo = max(a, centre - 0.5 * JADE_PI), hi = min(b, centre + 0.5 * JADE_PI);
            if (lo >= hi) continue;
            float mid = 0.5 * (lo + hi), half_width = 0.5 * (hi - lo), piece = 0.0;
            for (int q = 0; q < 8; ++q)
                for (int side = -1; side <= 1; side += 2) {
                    float phi = mid + float(side) * half_width * kNode[q];
                    piece += kWeight[q] * max(c * cos(phi) + s * sin(phi), 0.0) * exp(-phi * phi * inv_2t);
                }
            f += half_width * piece;
        }
    }
    return f / sqrt(2.0 * JADE_PI * t);
}

void main()
{
    uint index = jade_thread_index();
    if (index >= push.width * push.height) return;
    uint i = index % push.width, j = index / push.width;
    float c = float(int(2 * i) - int(push.width - 1)) / float(push.width - 1);
    float v = float(j) / float(push.height - 1);
    float t = push.t_max * (v * v) * (v * v);
    float f = t == 0.0 ? max(c, 0.0) : t >= kSeriesFrom ? series(c, t) : quadrature(c, t);
    imageStore(lut, ivec2(i, j), vec4(f));
}
