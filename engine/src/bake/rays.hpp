// bake/rays.hpp - the AO ray set, shared bit for bit by the GPU pass (GLSL mirror) and the
// float64 reference. Everything up to the two 24-bit fixed-point sample coordinates is uint32
// arithmetic (uint64 only for the exact k·2^24/N, which GLSL reproduces with umulExtended and
// a long division), so both sides draw identical u1, u2 ∈ [0, 1) (multiples of 2^-24).
//
// Per vertex i:    h0 = pcg_hash(seed ^ pcg_hash(i)), h1 = pcg_hash(h0)
// Low discrepancy: ray k of N is the Hammersley point (k/N, radical inverse of k), truncated to
//                  24 bits, Cranley–Patterson rotated by (h0 >> 8, h1 >> 8) modulo 2^24:
//                    U1 = ((k·2^24)/N + (h0 >> 8)) & 0xFFFFFF
//                    U2 = ((bitfieldReverse(k) >> 8) + (h1 >> 8)) & 0xFFFFFF
// i.i.d.:          U1 = pcg_hash(h0 + 2k) >> 8, U2 = pcg_hash(h1 + 2k + 1) >> 8 (wrapping)
// Direction:       cosine-weighted about the unit normal n: rr = √u1, φ = 2π·u2,
//                  local = (rr cos φ, rr sin φ, √max(0, 1 − u1)), in the frame of Duff et al.
//                  2017 ("Building an orthonormal basis, revisited").
#pragma once

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace jade::bake {

/// PCG-RXS-M-XS 32-bit hash (Jarzynski & Olano 2020).
inline uint32_t pcg_hash(uint32_t v)
{
    const uint32_t state = v * 747796405u + 2891336453u;
    const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// A 24-bit fixed-point value as a float in [0, 1); exact.
inline float fixed24_to_float(uint32_t u) { return float(u & 0xFFFFFFu) * (1.0f / 16777216.0f); }

/// The top 24 bits of a hash as a float in [0, 1); exact.
inline float to_unit(uint32_t h) { return fixed24_to_float(h >> 8); }

/// GLSL bitfieldReverse.
inline uint32_t bit_reverse(uint32_t v)
{
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0F0F0F0Fu) | ((v & 0x0F0F0F0Fu) << 4);
    v = ((v >> 8) & 0x00FF00FFu) | ((v & 0x00FF00FFu) << 8);
    return (v >> 16) | (v << 16);
}

/// The per-vertex hashes h0, h1 (the rotation of the low-discrepancy set, the seeds of i.i.d.).
struct VertexHashes {
    uint32_t h0, h1;
};

inline VertexHashes vertex_hashes(uint32_t seed, uint32_t vertex)
{
    const uint32_t h0 = pcg_hash(seed ^ pcg_hash(vertex));
    return {h0, pcg_hash(h0)};
}

/// The sample (u1, u2) of ray k of n (k < n) of a vertex; both multiples of 2^-24 in [0, 1).
struct RaySample {
    float u1, u2;
};

inline RaySample ray_sample(VertexHashes h, uint32_t k, uint32_t n, bool low_discrepancy)
{
    uint32_t U1, U2;
    if (low_discrepancy) {
        const uint32_t u1_fixed = uint32_t((uint64_t(k) << 24) / n);  // floor(k·2^24 / n) < 2^24
        const uint32_t u2_fixed = bit_reverse(k) >> 8;
        U1 = (u1_fixed + (h.h0 >> 8)) & 0xFFFFFFu;
        U2 = (u2_fixed + (h.h1 >> 8)) & 0xFFFFFFu;
    } else {
        U1 = pcg_hash(h.h0 + 2u * k) >> 8;
        U2 = pcg_hash(h.h1 + 2u * k + 1u) >> 8;
    }
    return {fixed24_to_float(U1), fixed24_to_float(U2)};
}

/// `local` (z along the unit vector n) in n's frame (Duff et al. 2017), in double.
inline glm::dvec3 in_frame(glm::dvec3 n, double lx, double ly, double lz)
{
    const double s = std::copysign(1.0, n.z);
    const double a = -1.0 / (s + n.z);
    const double b = n.x * n.y * a;
    const glm::dvec3 t(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    const glm::dvec3 bt(b, s + n.y * n.y * a, -n.y);
    return lx * t + ly * bt + lz * n;
}

/// The cosine-weighted direction of sample (u1, u2) about the unit normal n (the AO rays).
inline glm::dvec3 cosine_direction(glm::dvec3 n, double u1, double u2)
{
    const double rr = std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
    return in_frame(n, rr * std::cos(phi), rr * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1)));
}

/// Uniform in solid angle in the cone of half-angle acos(cos_cone) about the unit axis (the
/// thickness rays): cos θ = 1 − u1·(1 − cos_cone), φ = 2π·u2.
inline glm::dvec3 cone_direction(glm::dvec3 axis, double u1, double u2, double cos_cone)
{
    const double c = 1.0 - u1 * (1.0 - cos_cone), sn = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = 2.0 * std::numbers::pi * u2;
    return in_frame(axis, sn * std::cos(phi), sn * std::sin(phi), c);
}

}  // namespace jade::bake
