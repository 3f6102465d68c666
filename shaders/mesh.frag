#version 460
#extension GL_GOOGLE_include_directive : require
// mesh.frag - diffuse from the translucency LUT (or Lambert, or the curvature LUT) plus a
// GGX specular lobe, summed over the lights. Mode and channel count are specialisation
// constants: the pipeline for one (mode, channels) holds only that path, with no branch.
#include "shading.glsl"

layout(constant_id = 0) const uint MODE = 2;      // 0 Lambert, 1 curvature, 2 t_m, 3 t_m false colour
layout(constant_id = 1) const uint CHANNELS = 3;  // 1: grey material, one LUT fetch per light
layout(constant_id = 2) const uint TRANSMISSION = 0;  // 1: light through thin parts (t_m mode only)

const uint kLambert = 0, kCurvature = 1, kTm = 2, kFalseColor = 3;

// f(cos θ, t) as (W − 1) × (H − 1) quads: cell (i, j) = texels (i, j), (i+1, j), (i, j+1), (i+1, j+1).
layout(binding = 1) uniform samplerBuffer translucency_quads;
layout(binding = 2) uniform sampler2D curvature_lut;     // RGBA32F, D_c(cos θ, κ) per channel
layout(binding = 3) uniform sampler2D light_depth_atlas; // D32: depth nearest to each light, one tile per light

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_tm;
layout(location = 3) in float in_curvature;
layout(location = 4) in float in_thickness;
layout(location = 5) in vec3 in_scattering_normal;
layout(location = 6) in vec3 in_normal_spread;

layout(location = 0) out vec4 out_color;

// Where a fragment reads the translucency LUT in t, per channel and the same for every light:
// the first quad of its row of quads, and the weight of the upper row.
struct LutRows {
    vec3 first;
    vec3 weight;
};

// Bilinear interpolation done here, not by the sampler: one fetch of the quad around (x, y)
// instead of a filtered sample, which on lavapipe costs several times more (docs/shading.md).
// Weights in full float precision; row and column indices are exact in float (< 2^24).
float translucency(float first_of_row, float column, float column_weight, float row_weight)
{
    vec4 q = texelFetch(translucency_quads, int(first_of_row + column));
    return mix(mix(q.x, q.y, column_weight), mix(q.z, q.w, column_weight), row_weight);
}

// The diffuse response per channel, F in (k_d/π) F E.
vec3 diffuse_response(float c, LutRows rows, float kappa_scaled)
{
    if (MODE == kCurvature) {
        vec4 m = data.curvature_map;
        float v = kappa_scaled / (1.0 + kappa_scaled);
        return textureLod(curvature_lut, vec2(c * m.x + m.y, v * m.z + m.w), 0.0).rgb;
    }
    if (MODE == kTm) {
        // The LUT's u axis is cos θ itself (no acos): column x ∈ [0, W − 1], texel i on cos θ_i.
        float x = clamp(c, -1.0, 1.0) * data.lut_map.x + data.lut_map.x;
        float column = min(floor(x), data.lut_map.y - 1.0);
        float w = x - column;
        if (CHANNELS == 1) return vec3(translucency(rows.first.r, column, w, rows.weight.r));
        return vec3(translucency(rows.first.r, column, w, rows.weight.r), translucency(rows.first.g, column, w, rows.weight.g),
                    translucency(rows.first.b, column, w, rows.weight.b));
    }
    return vec3(max(c, 0.0));
}

// GGX (Trowbridge–Reitz) D · Smith height-correlated V · Schlick F, times cos θ_l.
float specular_lobe(vec3 n, vec3 v, vec3 l, float n_dot_l)
{
    float alpha = data.specular.y, f0 = data.specular.x;
    vec3 h = normalize(v + l);
    float n_dot_v = max(dot(n, v), 1e-4), n_dot_h = max(dot(n, h), 0.0), v_dot_h = max(dot(v, h), 0.0);
    float a2 = alpha * alpha;
    float denom = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    float d = a2 / (JADE_PI * denom * denom);
    float vis = 0.5 / (n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2) + n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2));
    float f = f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0);
    return d * vis * f * n_dot_l;
}

// How far light from directional light `tile` (1-based) travels inside the object before it
// reaches this point, mesh units: this point's depth along the light minus the depth of the
// surface nearest to the light, bilinear between the four nearest texels of its tile.
float light_path(uint tile)
{
    vec4 p = data.light_depth[tile - 1u] * vec4(in_position, 1.0);
    float size = data.light_depth_map.x;
    vec2 xy = clamp(p.xy * 0.5 + 0.5, 0.0, 1.0) * size - 0.5;
    vec2 f = fract(xy);
    ivec2 base = ivec2(floor(xy)), lo = ivec2(0), hi = ivec2(int(size) - 1);
    int x0 = int(tile - 1u) * int(size);
    float d00 = texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base, lo, hi), 0).r;
    float d10 = texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base + ivec2(1, 0), lo, hi), 0).r;
    float d01 = texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base + ivec2(0, 1), lo, hi), 0).r;
    float d11 = texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base + ivec2(1, 1), lo, hi), 0).r;
    float entry = mix(mix(d00, d10, f.x), mix(d01, d11, f.x), f.y);
    return max(p.z - entry, 0.0) * data.light_depth_map.z;
}

// Light from behind through the object (jade/material.hpp Transmission): ballistic and diffused
// transmittance along the path t into the forward lobe (n + 1)/(2π)·max(V·(−L), 0)^n, following
// −N·L by normal_mix.
vec3 transmitted(vec3 n, vec3 v, vec3 l, float n_dot_l, uint tile)
{
    float mu = -dot(v, l);
    if (mu <= 0.0) return vec3(0.0);
    // The longer of the local thickness and the path from where the light enters: a thin part
    // that the body shadows from the light is dark. σ_t ≤ 3e38 and t > 0: the product is finite
    // or +Inf, never NaN, and e^{−Inf} = 0. A zero (or, extrapolated at a multisample edge, NaN)
    // thickness transmits fully without the product: lavapipe turned 3e38 · 0 into a NaN there
    // (tests/test_thickness.cpp).
    float t = tile != 0u ? max(in_thickness, light_path(tile)) : in_thickness;
    vec3 ballistic = t > 0.0 ? exp(-data.transmission.rgb * t) : vec3(1.0);
    vec3 diffused = t > 0.0 ? (1.0 - exp(-data.transmission_scatter.rgb * t)) * exp(-data.transmission_diffusion.rgb * t) : vec3(0.0);
    vec3 attenuation = data.transmission.w * ballistic + data.transmission_diffusion.w * diffused;
    vec4 shape = data.transmission_shape;
    float lobe = shape.y * pow(mu, shape.x);
    float follow = (1.0 - shape.z) + shape.z * max(-n_dot_l, 0.0);
    return lobe * follow * attenuation;
}

// The share of light that crosses the rough dielectric boundary at cos θ (entering from the light,
// leaving towards the eye: the F_t(η, ω) factors of Jensen et al. 2001's BSSRDF): 1 − Schlick's
// Fresnel with the roughness-damped grazing value max(1 − α, F0).
float boundary_transmittance(float cos_theta)
{
    float f0 = data.specular.x, grazing = max(1.0 - data.specular.y, f0);
    return 1.0 - (f0 + (grazing - f0) * pow(1.0 - clamp(cos_theta, 0.0, 1.0), 5.0));
}

vec3 false_color(float x)
{
    float s = clamp(x, 0.0, 1.0) * float(kColorMapStops - 1);
    uint i = min(uint(s), kColorMapStops - 2);
    return mix(data.color_map[i].rgb, data.color_map[i + 1].rgb, s - float(i));
}

void main()
{
    if (MODE == kFalseColor) {
        out_color = vec4(false_color((dot(in_tm, vec3(1.0 / 3.0)) - data.params.z) * data.params.w), 1.0);
        return;
    }
    vec3 n = normalize(in_normal);
    // The t_m modes light the diffuse term along the scattering normal (BakeResult::
    // scattering_normal: bumps within the profile's reach smoothed out), the rest along n.
    vec3 n_diffuse = MODE == kTm ? normalize(in_scattering_normal) : n;
    vec3 v = normalize(frame.eye - in_position);
    // Leaving towards the eye: the same for every light.
    float exit_transmittance = MODE == kTm && data.transmission_shape.w > 0.0 ? boundary_transmittance(dot(n, v)) : 1.0;
    vec3 albedo = data.albedo_strength.rgb;
    // Row y = (t / t_max)^¼ · (H − 1) with t = strength · t_m, interpolated t_m as the poster
    // (not the row: docs/shading.md); past t_max the last row. t_m is capped below +Inf first,
    // since interpolating vertex values near FLT_MAX can round up to +Inf and strength 0 · Inf
    // would be NaN (tests/test_stability.cpp renders t_m = 3e38 with strength 0 and 1e30), and
    // t is clamped before the root: strength · t_m may overflow to +Inf.
    vec3 tm = min(max(in_tm, vec3(0.0)), vec3(3.0e38));
    LutRows rows;
    {
        vec3 t = data.albedo_strength.w * tm + data.specular.w * clamp(in_normal_spread, 0.0, 1.0);
        vec3 y = sqrt(sqrt(clamp(t * data.params.x, 0.0, 1.0))) * data.lut_map.z;
        vec3 row = min(floor(y), vec3(data.lut_map.w));
        rows.first = row * data.lut_map.y;
        rows.weight = y - row;
    }
    float kappa_scaled = max(in_curvature, 0.0) * data.params.y;  // concave: treated as flat

    vec3 color = vec3(0.0);
    for (uint k = 0; k < frame.light_count; ++k) {
        GpuLight light = data.lights[k];
        vec3 l = light.vector.xyz;
        vec3 e = light.color.rgb;
        if (light.vector.w != 0.0) {  // point light: inverse-square falloff
            l -= in_position;
            float d2 = max(dot(l, l), 1e-20);
            e /= d2;
        }
        l = normalize(l);
        float c = dot(n, l), c_diffuse = dot(n_diffuse, l);
        vec3 diffuse = albedo * (1.0 / JADE_PI) * diffuse_response(c_diffuse, rows, kappa_scaled) * e;
        if (MODE == kTm && data.transmission_shape.w > 0.0) diffuse *= boundary_transmittance(c_diffuse) * exit_transmittance;
        color += diffuse;
        if (c > 0.0 && data.specular.z > 0.0) color += data.specular.z * specular_lobe(n, v, l, c) * e;
        if (TRANSMISSION == 1u) color += transmitted(n, v, l, c, uint(light.color.w)) * e;
    }
    out_color = vec4(color, 1.0);
}
