// transmission.glsl - light from behind through the object (jade/material.hpp Transmission):
//   [A_b(t) · (n+1)/(2π) max(V·(−L), 0)^n · ((1 − m) + m max(−N·L, 0)) + A_d(h) · max(−N·L, 0)/π] · E
// with A_b the ballistic attenuation along the path t inside the object and A_d the diffused
// attenuation across the slab h (attenuation.glsl; h in transmitted_light). The lobe is smooth
// over the surface and per vertex (mesh.vert). The path t (the longer of the local thickness and
// the path inside the medium from where the light enters, from the light's depth layers) is per
// vertex on a fine mesh and per fragment on a coarse one (PATH_PER_VERTEX): it is not smooth where
// the body shadows a part from the light, and per vertex it lost a fifth of a thumb tip's glow on
// the coarse hand of tests/test_fidelity.cpp; A_b(t) and A_d(t) are read from the table
// of transmission_table.comp (a fetch each, not nine exponentials).
#ifndef JADE_TRANSMISSION_GLSL
#define JADE_TRANSMISSION_GLSL

#include "attenuation.glsl"
#include "light_tile.glsl"
#include "shading.glsl"  // boundary_transmittance

// Lights drawn with transmission (data.transmitters[0 … TRANSMISSION − 1]); 0: none.
layout(constant_id = 2) const uint TRANSMISSION = 0;
// 1: transmitter_path per vertex (mesh.vert) and interpolated, 0: per fragment (jade::LightPathSampling).
layout(constant_id = 7) const uint PATH_PER_VERTEX = 0;
const uint kMaxTransmitters = JADE_MAX_TRANSMITTERS;  // shading_interface.h

layout(binding = 5) uniform usamplerBuffer transmission_table;  // per part (ballistic, then diffused): A(t_i), A(t_{i+1}) as halves

// The path inside the medium up to depth z along the light, from the depths of the first four
// surfaces at one texel (1 where there is none): [layer 0, layer 1] and [layer 2, layer 3] are
// inside a closed mesh, the gap between them is air. Beyond layer 3 the rest counts as medium
// (the path is then at least as long as it is). Continuous in z; 0 where no surface is.
float medium_path(vec4 layers, float z)
{
    return (clamp(z, layers.x, layers.y) - layers.x) + (clamp(z, layers.z, layers.w) - layers.z) +
           max(z - layers.w, 0.0);
}

// How far light from transmitter k travels inside the object before it reaches `position`, mesh
// units: the medium's share of the light's line from where it enters (medium_path), per texel
// of its tile (atlas column `tile` − 1) and bilinear between the four nearest (per texel: a
// texel beside a part's edge as the light sees it must not lend its layers to the next). The
// tile's own matrix and depth mapping (perspective for a point light: the layers and the
// fragment's depth are distances from the light, so the path is a length along its ray).
float light_path(uint tile, vec3 position)
{
    uint t = max(tile, 1u) - 1u;
    vec3 p = light_tile_coords(t, position);
    float size = data.light_depth_map.x;
    vec2 xy = clamp(p.xy, 0.0, 1.0) * size - 0.5;
    vec2 f = fract(xy);
    ivec2 base = ivec2(floor(xy)), lo = ivec2(0), hi = ivec2(int(size) - 1);
    int x0 = int(t) * int(size);
    float t00 = medium_path(texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base, lo, hi), 0), p.z);
    float t10 = medium_path(texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base + ivec2(1, 0), lo, hi), 0), p.z);
    float t01 = medium_path(texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base + ivec2(0, 1), lo, hi), 0), p.z);
    float t11 = medium_path(texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(base + ivec2(1, 1), lo, hi), 0), p.z);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y) * data.light_tiles[t].depth.y;
}

// Transmitter k's path t at `position`: the longer of the local thickness and the path from
// where the light enters (a thin part that the body shadows from the light is dark).
float transmitter_path(uint k, vec3 position, float thickness)
{
    uint tile = uint(data.transmitters[k].color.w);
    return tile != 0u ? max(thickness, light_path(tile, position)) : thickness;
}

// Towards transmitter k from `position`, unit, and its irradiance there (e: the colour, times
// the inverse-square falloff of a point light).
void transmitter_at(uint k, vec3 position, out vec3 l, out vec3 e)
{
    GpuLight light = data.transmitters[k];
    l = light.vector.xyz;
    e = light.color.rgb;
    if (light.vector.w != 0.0) {
        l -= position;
        e /= max(dot(l, l), 1e-20);
    }
    l = normalize(l);
}

// The forward lobe (n + 1)/(2π)·max(V·(−L), 0)^n of transmitter k: smooth over the surface (V
// and L change little across a triangle), per vertex.
float transmitter_lobe(uint k, vec3 position, vec3 v)
{
    vec3 l, e;
    transmitter_at(k, position, l, e);
    float mu = max(-dot(v, l), 0.0);
    return mu > 0.0 ? data.transmission_shape.y * pow(mu, data.transmission_shape.x) : 0.0;
}

// How much of the lobe goes out at this normal: following −N·L by normal_mix (per fragment:
// the kink at N·L = 0 is not smooth).
float transmitter_follow(float n_dot_l)
{
    return (1.0 - data.transmission_shape.z) + data.transmission_shape.z * max(-n_dot_l, 0.0);
}

// A part of the attenuation at t (0: ballistic, 1: diffused; attenuation.glsl), interpolated
// from the table (the last entry, ~0, beyond it; a NaN t reads an end).
vec3 attenuation_at(uint part, float t)
{
    float x = clamp(t * data.transmission_table_map.x, 0.0, data.transmission_table_map.y);
    float i = min(floor(x), data.transmission_table_map.z);
    uvec4 q = texelFetch(transmission_table, int(i) + int(part) * int(data.transmission_table_map.w));
    vec2 rg = unpackHalf2x16(q.x), ba = unpackHalf2x16(q.y), gb = unpackHalf2x16(q.z);
    return mix(vec3(rg, ba.x), vec3(ba.y, gb), x - i);
}

// The mean inward-cone thickness t̄ (ThicknessSettings: rays in the 60° cone about −n) of a flat
// slab of thickness h is h · ln 4: ∫ h/cos θ dΩ over the cone / its solid angle.
const float kSlabPerConeThickness = 0.72134752;  // 1 / ln 4

// Transmitter k's light at `position` with normal n (unit), forward lobe `lobe`, path t along
// the light and local thickness t̄, short of the crossing out to the eye (the same for every
// light): in through the far side (this normal standing in for the entry's), then the two parts.
// The ballistic light travels the line, e^{−σ_t t}, and leaves in the forward lobe, the share at
// this normal transmitter_follow's. The diffused light enters the slab's far side with the
// irradiance E·max(−N·L, 0) (none on a surface that faces the light: that light is the diffuse
// term's), and has forgotten its direction: it crosses the slab between where
// it entered and here, whose thickness is the path's depth along the normal, t·(−N·L) (exact for
// a flat slab lit at any angle), and never less than the slab that the local thickness stands
// for, t̄/ln 4; it leaves as a Lambertian emitter, 1/π of its flux per steradian (the exit flux
// of the diffusion approximation's slab, T_d). A back-facing surface of a thick body gets ~0.
vec3 transmitted_light(uint k, vec3 position, vec3 n, float lobe, float t, float thickness)
{
    vec3 l, e;
    transmitter_at(k, position, l, e);
    float n_dot_l = dot(n, l);
    float entry = boundary_crossed() ? boundary_transmittance(-n_dot_l) : 1.0;
    float behind = max(-n_dot_l, 0.0);
    float slab = min(max(kSlabPerConeThickness * thickness, t * behind), t);
    vec3 a = transmitter_follow(n_dot_l) * lobe * attenuation_at(0u, t) +
             (behind / JADE_PI) * attenuation_at(1u, slab);
    return entry * a * e;
}

#endif
