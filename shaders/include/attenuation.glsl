// attenuation.glsl - the transmittance of the transmission term along a path t inside the
// object (jade/material.hpp Transmission): ballistic and diffused,
//   A(t) = w_b e^{−σ_t t} + w_d (1 − e^{−σ_s' t}) e^{−σ_tr t}.
// One home for the formula: transmission_table.comp tabulates it for mesh.frag.
#ifndef JADE_ATTENUATION_GLSL
#define JADE_ATTENUATION_GLSL

// extinction: σ_t, w_b; diffusion: σ_tr, w_d; scatter: σ_s' (1/mesh unit). σ ≤ 3e38 and t > 0:
// the products are finite or +Inf, never NaN, and e^{−Inf} = 0. A zero (or NaN) t transmits
// fully without the product: lavapipe turned 3e38 · 0 into a NaN there (tests/test_thickness.cpp).
vec3 transmission_attenuation(float t, vec4 extinction, vec4 diffusion, vec3 scatter)
{
    vec3 ballistic = t > 0.0 ? exp(-extinction.rgb * t) : vec3(1.0);
    vec3 diffused = t > 0.0 ? (1.0 - exp(-scatter * t)) * exp(-diffusion.rgb * t) : vec3(0.0);
    return extinction.w * ballistic + diffusion.w * diffused;
}

#endif
