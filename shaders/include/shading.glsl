// shading.glsl - what mesh.vert and mesh.frag share: the push and frame constants (their layout,
// shared with C++, is shading_interface.h), the shading modes and the light count.
#ifndef JADE_SHADING_GLSL
#define JADE_SHADING_GLSL

#extension GL_EXT_scalar_block_layout : require

#include "pi.glsl"  // JADE_PI

#include "shading_interface.h"  // FramePush, GpuLight, FrameData, the array sizes

layout(push_constant, scalar) uniform FramePushBlock { FramePush frame; };

const uint kColorMapStops = JADE_COLOR_MAP_STOPS;

// Shading modes (specialisation constant MODE of both stages) and the inputs pass:
// shading_interface.h says what each is.
const uint kLambert = JADE_MODE_LAMBERT, kCurvature = JADE_MODE_CURVATURE, kTm = JADE_MODE_TM,
           kFalseColor = JADE_MODE_FALSE_COLOR, kFilament = JADE_MODE_FILAMENT, kSeparable = JADE_MODE_SEPARABLE,
           kBurley = JADE_MODE_BURLEY, kInputs = JADE_MODE_INPUTS;

const uint kMaxLights = JADE_MAX_LIGHTS;

layout(binding = 0, scalar) uniform FrameDataBlock { FrameData data; };

// t = t_m · (strength + spread_strength · spread) per channel (jade/material.hpp), clamped to the
// LUT's range t_max (past it f is 1/π within 2e-6). strength alone is the poster's model: a blur
// whose angle does not depend on how far light travels under the surface. The spread (≈ ⟨θ²⟩/2
// of the normals within the profile's reach, ≈ the variance of the angle that light crosses on
// its way under a curved surface) gives the blur the scale of the medium against the shape:
// a head of skin (reach ~1 mm, curvature radius ~80 mm) blurs by a few degrees, a jade bunny by
// tens; t_m scales it by how much light arrives (occlusion lowers it, a thin part raises it).
// t_m is capped below +Inf first, since 0 · Inf would be NaN (tests/test_stability.cpp renders
// t_m = 3e38 with strength 0 and 1e30); the product itself may overflow to +Inf, which the clamp
// takes. The spread is in [0, 1]. Evaluated per vertex (mesh.vert): t is smooth over a triangle,
// as the poster's interpolated t_m, with three varyings fewer; the clamps hold under
// interpolation.
vec3 variance(vec3 tm, vec3 spread)
{
    tm = min(max(tm, vec3(0.0)), vec3(3.0e38));
    vec3 t = tm * (data.albedo_strength.w + data.specular.w * clamp(spread, 0.0, 1.0));
    return min(t * data.params.x, vec3(1.0)) * (1.0 / data.params.x);
}

// The share of light that crosses the rough dielectric boundary at cos θ (entering from the light,
// leaving towards the eye: the F_t(η, ω) factors of Jensen et al. 2001's BSSRDF): 1 − Schlick's
// Fresnel with the roughness-damped grazing value max(1 − α, F0). (1 − μ)⁵ by multiplication:
// pow() is a log and an exp.
float boundary_transmittance(float cos_theta)
{
    float f0 = data.specular.x, grazing = max(1.0 - data.specular.y, f0);
    float m = 1.0 - clamp(cos_theta, 0.0, 1.0), m2 = m * m;
    return 1.0 - (f0 + (grazing - f0) * (m2 * m2 * m));
}

// boundary_transmittance averaged over the light's projected area, ∫ T(μ) 2μ dμ (∫ 2μ(1 − μ)⁵ dμ =
// 1/21): the share that enters where the light falls on a surface of every orientation alike.
float mean_boundary_transmittance()
{
    float f0 = data.specular.x, grazing = max(1.0 - data.specular.y, f0);
    return 1.0 - f0 - (grazing - f0) * (1.0 / 21.0);
}

// Whether the t_m mode's light pays the boundary's crossings (Material::boundary_transmittance).
bool boundary_crossed() { return data.transmission_shape.w > 0.0; }

#endif
