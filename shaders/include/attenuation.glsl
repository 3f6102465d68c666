// attenuation.glsl - the transmittance of the transmission term's forward part along a path t
// inside the object (jade/material.hpp Transmission): A_b(t) = w_b e^{−σ_t t}.
// One home for the formula: transmission_table.comp tabulates it for mesh.frag.
#ifndef JADE_ATTENUATION_GLSL
#define JADE_ATTENUATION_GLSL

// extinction: σ_t (1/mesh unit), w_b. σ ≤ 3e38 and t > 0: the product is finite or +Inf, never
// NaN, and e^{−Inf} = 0. A zero (or NaN) t transmits fully without the product: lavapipe turned
// 3e38 · 0 into a NaN there (tests/test_thickness.cpp).
vec3 forward_attenuation(float t, vec4 extinction)
{
    return extinction.w * (t > 0.0 ? exp(-extinction.rgb * t) : vec3(1.0));
}

#endif
