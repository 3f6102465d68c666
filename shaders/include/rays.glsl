// rays.glsl - the AO ray set. Bit-for-bit the integer part of engine/src/bake/rays.hpp, so the
// GPU pass and the float64 reference (reference_ao) trace the same rays.
#ifndef JADE_RAYS_GLSL
#define JADE_RAYS_GLSL

uint pcg_hash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// floor(k · 2^24 / n) for k < n, by long division (no 64-bit integers needed).
uint fixed_fraction(uint k, uint n)
{
    uint q = 0u, r = k;
    for (int b = 0; b < 24; ++b) {
        r <<= 1u;
        q <<= 1u;
        if (r >= n) { r -= n; q |= 1u; }
    }
    return q;
}

// The two 24-bit sample coordinates of ray k of `vertex`, as exact floats in [0, 1).
vec2 ray_sample(uint vertex, uint k, uint n, uint seed, bool low_discrepancy)
{
    uint h0 = pcg_hash(seed ^ pcg_hash(vertex));
    uint h1 = pcg_hash(h0);
    uint a, b;
    if (low_discrepancy) {
        // Hammersley point k of n, shifted by the vertex's Cranley–Patterson rotation.
        a = (fixed_fraction(k, n) + (h0 >> 8u)) & 0xFFFFFFu;
        b = ((bitfieldReverse(k) >> 8u) + (h1 >> 8u)) & 0xFFFFFFu;
    } else {
        a = pcg_hash(h0 + 2u * k) >> 8u;
        b = pcg_hash(h1 + 2u * k + 1u) >> 8u;
    }
    return vec2(float(a), float(b)) * (1.0 / 16777216.0);
}

// `local` (z along n) in the orthonormal frame of the unit vector n (Duff et al. 2017).
vec3 in_frame(vec3 n, vec3 local)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
    vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
    return normalize(local.x * t + local.y * bt + local.z * n);
}

// Cosine-weighted direction about the unit normal n (the AO rays).
vec3 ray_direction(vec3 n, vec2 u)
{
    float rr = sqrt(u.x);
    float phi = 2.0 * JADE_PI * u.y;
    return in_frame(n, vec3(rr * cos(phi), rr * sin(phi), sqrt(max(0.0, 1.0 - u.x))));
}

// Uniform in solid angle in the cone of half-angle acos(cos_cone) about the unit axis (the
// thickness rays): cos θ = 1 − u1·(1 − cos_cone), φ = 2π·u2.
vec3 cone_direction(vec3 axis, vec2 u, float cos_cone)
{
    float c = 1.0 - u.x * (1.0 - cos_cone);
    float s = sqrt(max(0.0, 1.0 - c * c));
    float phi = 2.0 * JADE_PI * u.y;
    return in_frame(axis, vec3(s * cos(phi), s * sin(phi), c));
}

#endif
