// transmission.glsl - light from behind through the object (jade/material.hpp Transmission), in
// two parts: what depends on the path t inside the object only (the attenuation, smooth over the
// surface: mesh.vert evaluates it per vertex) and what depends on the eye and the normal (the
// lobe, per fragment in mesh.frag). Their product is the transmitted() of docs/shading.md:
//   [w_b e^{−σ_t t} + w_d (1 − e^{−σ_s' t}) e^{−σ_tr t}] · (n+1)/(2π) max(V·(−L), 0)^n ·
//   ((1 − m) + m max(−N·L, 0))
#ifndef JADE_TRANSMISSION_GLSL
#define JADE_TRANSMISSION_GLSL

// Bit s: attenuation slot s is drawn; slot 0 is the local thickness alone (point lights and
// lights without a depth tile), slot s ≥ 1 the path of depth tile s. 0: no transmission.
layout(constant_id = 2) const uint TRANSMISSION = 0;
const uint kAttenuationSlots = 5;  // 1 + shading::LightDepth::kMaxLights

layout(binding = 3) uniform sampler2D light_depth_atlas;  // D32: depth nearest to each light, one tile per light

// How far light from directional light `tile` (1-based) travels inside the object before it
// reaches `position`, mesh units: its depth along the light minus the depth of the surface
// nearest to the light, bilinear between the four nearest texels of its tile.
float light_path(uint tile, vec3 position)
{
    vec4 p = data.light_depth[tile - 1u] * vec4(position, 1.0);
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

// The path of slot s: the longer of the local thickness and the path from where the light
// enters (a thin part that the body shadows from the light is dark).
float transmission_path(uint slot, float thickness, vec3 position)
{
    return slot == 0u ? thickness : max(thickness, light_path(slot, position));
}

// Ballistic and diffused transmittance along the path t. σ_t ≤ 3e38 and t > 0: the product is
// finite or +Inf, never NaN, and e^{−Inf} = 0. A zero (or NaN) thickness transmits fully without
// the product: lavapipe turned 3e38 · 0 into a NaN there (tests/test_thickness.cpp).
vec3 transmission_attenuation(float t)
{
    vec3 ballistic = t > 0.0 ? exp(-data.transmission.rgb * t) : vec3(1.0);
    vec3 diffused = t > 0.0 ? (1.0 - exp(-data.transmission_scatter.rgb * t)) * exp(-data.transmission_diffusion.rgb * t) : vec3(0.0);
    return data.transmission.w * ballistic + data.transmission_diffusion.w * diffused;
}

// The forward lobe (n + 1)/(2π)·max(V·(−L), 0)^n, following −N·L by normal_mix.
float transmission_lobe(vec3 v, vec3 l, float n_dot_l)
{
    float mu = max(-dot(v, l), 0.0);
    vec4 shape = data.transmission_shape;
    float lobe = mu > 0.0 ? shape.y * pow(mu, shape.x) : 0.0;
    return lobe * ((1.0 - shape.z) + shape.z * max(-n_dot_l, 0.0));
}

#endif
