// attenuation.glsl - the transmittance of the transmission term along a path t inside the
// object (jade/material.hpp Transmission), in two parts, ballistic and diffused:
//   A_b(t) = w_b e^{−σ_t t},  A_d(t) = w_d (1 − e^{−σ_s' t}) T_d(t),
//   T_d(t) = min(1, sinh(σ_tr z_s) cosh(σ_tr z_b) / sinh(σ_tr (t + 2 z_b))), z_s = z_0 + z_b,
// the diffusion approximation's transmittance through a slab of thickness t
// (jade::slab_diffusion_transmittance, its float64 home).
// One home for the formula: transmission_table.comp tabulates it for mesh.frag.
#ifndef JADE_ATTENUATION_GLSL
#define JADE_ATTENUATION_GLSL

// 1 − e^{−x} for x ≥ 0 without the cancellation of small x (a series below 1e-3).
vec3 one_minus_exp(vec3 x) { return mix(1.0 - exp(-x), x * (1.0 - x * (0.5 - x / 6.0)), lessThan(x, vec3(1e-3))); }

// T_d(t) per channel; source: z_s (mesh units), boundary: z_b. Written as
//   e^{σ(z_0 − t)} · (1 − e^{−2σz_s})(1 + e^{−2σz_b}) / (2(1 − e^{−2σ(t + 2z_b)}))
// so that no exponential overflows, and the ratio of the two 1 − e^{−x} as its limit
// z_s/(t + 2z_b) where σ(t + 2z_b) is tiny (σ_a = 0: no absorption, 1/t decay).
vec3 slab_diffusion(float t, vec3 sigma_tr, vec3 source, vec3 boundary)
{
    vec3 width = vec3(t) + 2.0 * boundary;
    vec3 w = 2.0 * sigma_tr * width;
    vec3 ratio = mix(one_minus_exp(2.0 * sigma_tr * source) / max(one_minus_exp(w), vec3(1e-30)),
                     source / max(width, vec3(1e-30)) * (1.0 - sigma_tr * (source - width)), lessThan(w, vec3(1e-6)));
    vec3 decay = exp(min(sigma_tr * (source - boundary - vec3(t)), vec3(20.0)));
    vec3 edge = 0.5 * (1.0 + exp(-2.0 * sigma_tr * boundary));
    vec3 r = min(ratio * decay * edge, vec3(1.0));
    return mix(r, vec3(0.0), isnan(r));  // a capped σ of 3e38 times a zero distance
}

// The two parts of the transmittance along t, weighted: `part` 0 is the forward (ballistic) part
// w_b e^{−σ_t t}, which leaves in the forward lobe; 1 is the diffused part
// w_d (1 − e^{−σ_s' t}) T_d(t), which leaves the far side diffusely (transmission.glsl).
// extinction: σ_t, w_b; diffusion: σ_tr, w_d; scatter: σ_s' (1/mesh unit); source: z_s, boundary:
// z_b (mesh units). σ ≤ 3e38 and t > 0: the products are finite or +Inf, never NaN, and
// e^{−Inf} = 0. A zero (or NaN) t transmits fully without the product: lavapipe turned 3e38 · 0
// into a NaN there (tests/test_thickness.cpp).
vec3 transmission_attenuation(uint part, float t, vec4 extinction, vec4 diffusion, vec3 scatter, vec3 source,
                              vec3 boundary)
{
    if (part == 0u) return extinction.w * (t > 0.0 ? exp(-extinction.rgb * t) : vec3(1.0));
    return diffusion.w *
           (t > 0.0 ? one_minus_exp(scatter * t) * slab_diffusion(t, diffusion.rgb, source, boundary) : vec3(0.0));
}

#endif
