// translucency.glsl - F(cos θ, t) = {max(cos, 0) ∗ G_t}(θ) of jade/lut.hpp, per colour channel,
// evaluated one of three ways (specialisation constant EVAL; docs/shading.md has the costs and
// which device takes which):
//   kEvalQuads     the LUT as RGBA32F quads in a texel buffer, bilinear in the shader
//   kEvalFiltered  the LUT as R16_UNORM, one hardware-filtered sample per read (texture units)
//   kEvalAlu       no memory read: the Fourier series in cos θ, plus a closed form for small t
// Split in two: translucency_setup() once per fragment (everything that depends only on t, per
// channel, shared by the lights) and translucency() once per light (cos θ, shared by the channels).
#ifndef JADE_TRANSLUCENCY_GLSL
#define JADE_TRANSLUCENCY_GLSL

const uint kEvalQuads = JADE_EVAL_LUT, kEvalFiltered = JADE_EVAL_LUT_FILTERED, kEvalAlu = JADE_EVAL_ALU;  // shading_interface.h
layout(constant_id = 3) const uint EVAL = JADE_EVAL_LUT;
// ALU: Fourier terms summed (1 … 6), and whether the closed form for small t is needed at all.
// The renderer picks the fewest terms that stay within its error budget at the smallest t of
// the mesh (choose_terms, shading/mesh_pipeline.cpp); a mesh with smaller t than kSmallSigma² somewhere
// gets the closed form too (both are evaluated: lavapipe runs both sides of every branch).
layout(constant_id = 4) const uint TERMS = 6;
layout(constant_id = 5) const uint SMALL_T = 1;
layout(constant_id = 6) const float SMALL_SIGMA = 0.3;  // closed form where √t is below this

// f(θ, t) as (W − 1) × (H − 1) quads: cell (i, j) = texels (i, j), (i+1, j), (i, j+1), (i+1, j+1).
layout(binding = 1) uniform samplerBuffer translucency_quads;
layout(binding = 4) uniform sampler2D translucency_lut;  // R16_UNORM, linear filter, clamp

const uint kMaxTerms = 6;

// What one fragment needs of t, per channel.
struct Translucency {
    vec3 row_first, row_weight;  // quads: first quad of the row, weight of the upper row
    vec3 v;                      // filtered: texture coordinate of the row
    vec3 half_decay;             // ALU: ½e^{−t/2}, the coefficient of cos θ
    vec3 decay[kMaxTerms];       // ALU: e^{−2k²t}, k = 1 … TERMS
    vec3 t, sigma, inv_sigma;    // ALU, closed form: t, √t, 1/√t
};

// t = variance(t_m, spread) (shading.glsl), interpolated from the vertices.
Translucency translucency_setup(vec3 t)
{
    // Under MSAA a pixel's centre can lie outside the triangle it shades, and the interpolated t
    // is then extrapolated: below 0 it would make e^{−2k²t} grow without bound (a white line
    // along a silhouette where t changes fast).
    t = clamp(t, vec3(0.0), vec3(1.0 / data.params.x));
    Translucency r;
    if (EVAL == kEvalQuads || EVAL == kEvalFiltered) {
        // Row y = (t / t_max)^¼ · (H − 1): docs/shading.md says why the fourth root.
        vec3 y = sqrt(sqrt(t * data.params.x)) * data.lut_map.z;
        vec3 row = min(floor(y), vec3(data.lut_map.w));
        r.row_first = row * data.lut_map.y;
        r.row_weight = y - row;
        r.v = (y + 0.5) / (data.lut_map.z + 1.0);
    }
    if (EVAL == kEvalAlu) {
        // One exp gives every e^{−2k²t} as powers of q = e^{−2t}: q^{(k+1)²} = q^{k²}·q^{2k+1}.
        vec3 q = exp(-2.0 * t), q2 = q * q, odd = q, power = q;
        for (uint k = 0; k < TERMS; ++k) {
            r.decay[k] = power;
            odd *= q2;
            power *= odd;
        }
        r.half_decay = 0.5 * sqrt(sqrt(q));
        if (SMALL_T == 1u) {
            r.t = t;
            r.sigma = sqrt(t);
            r.inv_sigma = 1.0 / max(r.sigma, 1e-12);
        }
    }
    return r;
}

float quad_read(float first_of_row, float column, float column_weight, float row_weight)
{
    vec4 q = texelFetch(translucency_quads, int(first_of_row + column));
    return mix(mix(q.x, q.y, column_weight), mix(q.z, q.w, column_weight), row_weight);
}

// Φ(−|z|) = ½·erfc(|z|/√2) from Abramowitz–Stegun 7.1.26 (1.5e-7) in z/√2 (p = 0.3275911/√2),
// given e = e^{−z²/2}, which the callers need for φ too.
vec3 normal_tail(vec3 z, vec3 e)
{
    vec3 s = 1.0 / (1.0 + 0.2316419 * abs(z));
    vec3 poly = s * (0.254829592 + s * (-0.284496736 + s * (1.421413741 + s * (-1.453152027 + s * 1.061405429))));
    return 0.5 * poly * e;
}

// Small t: Φ and φ of z = asin(c)/σ, to second order in σ (the O(σ²) terms of the expansion of
// the exact e^{−t/2} Re{e^{iθ}[1 − Φ(z' + iσ)]} about the window edge); within 4e-5 of the
// float64 reference for σ ≤ 0.3, 5e-6 for σ ≤ 0.2.
vec3 translucency_small_t(float c, Translucency r)
{
    float a = c * (1.0 + c * c * (1.0 / 6.0 + c * c * (3.0 / 40.0)));  // asin(c) where it matters
    vec3 z = clamp(a * r.inv_sigma, -8.0, 8.0);
    vec3 e = exp(-0.5 * z * z);
    vec3 tail = normal_tail(z, e);  // Φ(−|z|)
    vec3 cdf = mix(tail, 1.0 - tail, step(0.0, z));
    vec3 pdf = 0.3989422804 * e;
    float sine = sqrt(max(1.0 - c * c, 0.0));
    return 2.0 * r.half_decay *
           (c * (cdf + 0.5 * r.t * z * pdf) + sine * r.sigma * pdf * (1.0 - r.t * (1.0 / 6.0) * (z * z - 1.0)));
}

// How the diffuse light falls off past the terminator, relative to its value there, when the
// blur follows the surface (Material::spread_strength > 0). The fitted blur sets how much light
// reaches the terminator (F(0, t)); how far it goes past it is the light's own reach against
// the curvature: an angle whose variance is the normal spread (≈ ⟨θ²⟩/2, the variance of the
// angle along one axis between the normals within the profile's reach), derived, not fitted.
// The clamped cosine blurred by that narrow Gaussian, normalised to 1 at the terminator:
// g(z) = √(2π)·[φ(z) − z·Φ(−z)], z = (θ − π/2)/σ, σ² = spread. A head of skin (spread ~1e-3,
// σ ≈ 2°) goes dark within a few degrees, as in the path tracer; a jade bunny (~0.05, σ ≈ 13°)
// keeps a wide wrap, and a thin part, whose normals within reach cancel (up to 1), wider still.
// c = cos θ < 0; spread per channel in [0, 1].
vec3 terminator_falloff(float c, vec3 spread)
{
    vec3 z = min(asin(min(-c, 1.0)) * inversesqrt(max(spread, vec3(1e-8))), vec3(12.0));
    vec3 e = exp(-0.5 * z * z);
    return max(e - 2.5066283 * z * normal_tail(z, e), vec3(0.0));
}

// F(c, t) per channel. c = cos θ, any value (clamped).
vec3 translucency(float c, Translucency r)
{
    c = clamp(c, -1.0, 1.0);
    if (EVAL == kEvalQuads || EVAL == kEvalFiltered) {
        // The LUT's u axis is cos θ itself (no acos): column x ∈ [0, W − 1], texel i on cos θ_i.
        float x = c * data.lut_map.x + data.lut_map.x;
        if (EVAL == kEvalFiltered) {
            float u = (x + 0.5) / (data.lut_map.y + 1.0);
            return vec3(textureLod(translucency_lut, vec2(u, r.v.r), 0.0).r, textureLod(translucency_lut, vec2(u, r.v.g), 0.0).r,
                        textureLod(translucency_lut, vec2(u, r.v.b), 0.0).r);
        }
        float column = min(floor(x), data.lut_map.y - 1.0);
        float w = x - column;
        return vec3(quad_read(r.row_first.r, column, w, r.row_weight.r), quad_read(r.row_first.g, column, w, r.row_weight.g),
                    quad_read(r.row_first.b, column, w, r.row_weight.b));
    }
    // f = 1/π + ½e^{−t/2}c + (2/π) Σ_k (−1)^{k+1} e^{−2k²t} T_2k(c)/(4k² − 1), with
    // T_2k(c) = T_k(u), u = 2c² − 1 = T_2(c): one recursion per light, shared by the channels.
    float u = 2.0 * c * c - 1.0, previous = 1.0, current = u;
    vec3 f = 1.0 / JADE_PI + r.half_decay * c;
    for (uint k = 1; k <= TERMS; ++k) {
        float kk = float(k * k);
        float weight = (k % 2u == 1u ? 2.0 : -2.0) / (JADE_PI * (4.0 * kk - 1.0));
        f += (weight * current) * r.decay[k - 1u];
        float next = 2.0 * u * current - previous;
        previous = current;
        current = next;
    }
    if (SMALL_T == 1u) f = mix(f, translucency_small_t(c, r), lessThan(r.sigma, vec3(SMALL_SIGMA)));
    return f;
}

#endif
