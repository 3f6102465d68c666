// transmission.glsl - light from behind through the object (jade/material.hpp Transmission), in
// two parts:
//   forward: A_b(t) · (n+1)/(2π) max(V·(−L), 0)^n · ((1 − m) + m max(−N·L, 0)) · E, with A_b the
//     forward attenuation along the path t inside the object (attenuation.glsl), per fragment;
//   diffused: the light that entered where the light meets the object and diffused to here, a
//     gather of the dipole over the light's depth tile (diffused_light), per vertex (mesh.vert).
// The lobe is smooth over the surface and per vertex. The path t (the longer of the local thickness
// and the path inside the medium from where the light enters, from the light's depth layers) is
// per vertex on a fine mesh and per fragment on a coarse one (PATH_PER_VERTEX): it is not smooth
// where the body shadows a part from the light, and per vertex it lost a fifth of a thumb tip's
// glow on the coarse hand of tests/test_fidelity.cpp; A_b(t) is read from the table of
// transmission_table.comp (a fetch, not three exponentials).
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

layout(binding = 5) uniform usamplerBuffer transmission_table;  // A_b(t_i), A_b(t_{i+1}) as halves

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

// Transmitter k's light path to `position` (light_path), 0 for a light without a depth tile.
float transmitter_light_path(uint k, vec3 position)
{
    uint tile = uint(data.transmitters[k].color.w);
    return tile != 0u ? light_path(tile, position) : 0.0;
}

// Transmitter k's path t: the longer of the local thickness and `along`, the path from where the
// light enters (transmitter_light_path; a thin part that the body shadows from the light is dark).
float transmitter_path(float thickness, float along) { return max(thickness, along); }

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

// The forward attenuation at t, interpolated from the table (the last entry, ~0, beyond it; a NaN t
// reads an end).
vec3 attenuation_at(float t)
{
    float x = clamp(t * data.transmission_table_map.x, 0.0, data.transmission_table_map.y);
    float i = min(floor(x), data.transmission_table_map.z);
    uvec4 q = texelFetch(transmission_table, int(i));
    vec2 rg = unpackHalf2x16(q.x), ba = unpackHalf2x16(q.y), gb = unpackHalf2x16(q.z);
    return mix(vec3(rg, ba.x), vec3(ba.y, gb), x - i);
}

// Transmitter k's forward light at `position` with normal n (unit), forward lobe `lobe` and path t
// along the light, short of the crossing out to the eye (the same for every light): in through
// the far side (this normal standing in for the entry's), then along the line, e^{−σ_t t}, out in
// the forward lobe, the share at this normal transmitter_follow's.
vec3 transmitted_light(uint k, vec3 position, vec3 n, float lobe, float t)
{
    vec3 l, e;
    transmitter_at(k, position, l, e);
    float n_dot_l = dot(n, l);
    float entry = boundary_crossed() ? boundary_transmittance(-n_dot_l) : 1.0;
    return entry * transmitter_follow(n_dot_l) * lobe * attenuation_at(t) * e;
}

// The flux through the surface at x (normal n) of a point source q = base + along · depth (per
// channel), per unit power, with x's tangent plane as an extrapolated boundary (q's image 2 z_b
// beyond it), in a medium of extinction σ: a (1 + σr)e^{−σr}/r³ for q at distance a inside the
// plane and r from x, plus the image's (Jensen et al. 2001's dipole, x's plane for the surface).
vec3 plane_flux(vec3 x, vec3 n, vec3 base, vec3 along, vec3 depth, vec3 zb, vec3 sigma)
{
    vec3 d0 = x - base;
    float nd = dot(n, d0), na = dot(n, along), da = dot(d0, along), dd = dot(d0, d0);
    vec3 r2 = max(vec3(dd) - 2.0 * depth * da + depth * depth, vec3(1e-30));
    vec3 a = max(vec3(nd) - depth * na, vec3(0.0));
    vec3 av = a + 2.0 * zb;
    vec3 v2 = r2 - a * a + av * av;
    vec3 r = sqrt(r2), v = sqrt(v2);
    return a * (1.0 + sigma * r) * exp(-sigma * r) / (r2 * r) + av * (1.0 + sigma * v) * exp(-sigma * v) / (v2 * v);
}

// What enters at s (the light travelling along `along`, unit) and leaves through the surface at
// x, per unit flux, 1/mesh unit²: the diffusion dipole with both boundaries, the entry's and x's
// (Donner & Jensen 2005's multipole cut to its first pairs): the source z_r inside along the light
// and its negative image z_r + 2z_b outside the entry, each with its image beyond x's plane. On the
// far side of a slab of thickness h it is the slab's transmission profile.
vec3 dipole_exit(vec3 x, vec3 n, vec3 s, vec3 along, vec3 sigma)
{
    vec3 zr = data.dipole_real.rgb, zb = data.dipole_boundary.rgb;
    vec3 f = plane_flux(x, n, s, along, zr, zb, sigma) - plane_flux(x, n, s, along, -(zr + 2.0 * zb), zb, sigma);
    return data.dipole_albedo.rgb * max(f, vec3(0.0));
}

const uint kDiffusionTaps = 24;  // taps of the diffused light's gather (diffused_light)
const float kFacingCut = 0.2;    // n·l beyond which a vertex gathers nothing (diffused_light)

// Tap i of `count` of diffused_light's passes and its radius r: on the golden-angle spiral in the
// plane through `position` across the light (side, up), radii evenly spaced in ln r from `inner`
// (span = ln(reach / inner)).
vec3 gather_tap(uint i, uint count, vec3 position, float inner, float span, vec3 side, vec3 up, float turn, out float r)
{
    r = inner * exp(span * (float(i) + 0.5) / float(count));
    float angle = float(i) * 2.39996323 + turn;
    return position + r * (cos(angle) * side + sin(angle) * up);
}

// Where the light of tile t that passes `tap` (a point in the plane through x across the light)
// first meets the object: that layer's depth (1 where the line meets nothing) and the point.
float light_entry(uint t, vec3 tap, vec3 l, out vec3 entry)
{
    float size = data.light_depth_map.x;
    vec3 p = light_tile_coords(t, tap);
    ivec2 texel = ivec2(int(t) * int(size), 0) + clamp(ivec2(p.xy * size), ivec2(0), ivec2(int(size) - 1));
    bool inside = all(greaterThanEqual(p.xy, vec2(0.0))) && all(lessThan(p.xy, vec2(1.0)));
    float first = inside ? texelFetch(light_depth_atlas, texel, 0).x : 1.0;
    entry = tap + l * ((p.z - first) * data.light_tiles[t].depth.y);
    return first;
}

// The light of transmitter k that entered the object where the light first meets it and diffused
// to `position` (normal n, unit): its exitance there (the radiance is it / π times the crossing
// out). A translucent shadow map (Dachsbacher & Stamminger 2003): the first layer of the light's
// depth tile is where light enters, each texel taking the light's irradiance over its projected
// area whatever the surface's slope (with the crossing in averaged over the slopes,
// mean_boundary_transmittance); what enters at s reaches x through dipole_exit, of which the
// share leaving here is max(n·(x − s), 0)/|x − s|: 1 through a thin part, ~0 from this surface's
// own neighbourhood (that light is the diffuse term's). Taps on a golden-angle spiral in the plane
// through x across the light, at radii spaced evenly in ln r from a twentieth of the light's path
// to x (the kernel is as wide as the part is deep; inside, ρ·T(ρ) → 0) out to that path plus three
// diffusion lengths (1/σ_tr of the channel reaching furthest): tap i stands for 2π r² Δ(ln r).
// A part is not an endless slab: light that diffuses sideways leaves through its sides. The
// diffusion equation's transverse buckling B² = 2(π/(W + 2z_b))² adds to σ_tr², W the part's
// width across the light, the disk whose area is the share of the gather's disk that the light
// meets (found in the pass that reads the taps; 8 taps for it put the ear's red at 0.72 of the
// path tracer's instead of 0.84).
// turn: the spiral's turn for this vertex; path: the light's path to it (transmitter_light_path).
vec3 diffused_light(uint k, vec3 position, vec3 n, float turn, float path)
{
    uint tile = uint(data.transmitters[k].color.w);
    if (tile == 0u) return vec3(0.0);
    uint t = tile - 1u;
    vec3 l, e, s;
    transmitter_at(k, position, l, e);
    // A surface facing the light takes its light from the diffuse term, whose blur already carries
    // what enters around it: the gather fades out from n·l = 0 to kFacingCut (0.2: held-out side
    // light 0.157 → 0.145 with the cut, committed scenes within 0.002), and is skipped beyond.
    float facing = clamp(1.0 - dot(n, l) / kFacingCut, 0.0, 1.0);
    if (facing == 0.0) return vec3(0.0);
    vec3 side = normalize(abs(l.y) < 0.9 ? cross(l, vec3(0.0, 1.0, 0.0)) : cross(l, vec3(1.0, 0.0, 0.0)));
    vec3 up = cross(l, side);
    // The tile's width at this point (mesh units): the gather stays inside it.
    LightTile tl = data.light_tiles[t];
    float width = tl.depth.z * data.light_depth_map.x * (tl.origin.w > 0.5 ? length(position - tl.origin.xyz) : 1.0);
    float reach = max(min(path + data.dipole_sigma.w, 0.5 * width), 1e-30);
    float inner = max(0.05 * path, 1e-3 * reach), span = log(reach / inner);
    // One pass over the taps: where each enters (xyz) and its ring's weight r² (w; 0 where the
    // light meets nothing), kept for the gather once the width is known.
    vec4 entries[kDiffusionTaps];
    float covered = 0.0, total = 0.0, r;
    for (uint i = 0; i < kDiffusionTaps; ++i) {
        float first = light_entry(t, gather_tap(i, kDiffusionTaps, position, inner, span, side, up, turn, r), l, s);
        entries[i] = vec4(s, first < 1.0 ? r * r : 0.0);
        covered += entries[i].w;
        total += r * r;
    }
    vec3 zb = data.dipole_boundary.rgb;
    vec3 buckling = min(JADE_PI / max(vec3(2.0 * reach * sqrt(covered / total)) + 2.0 * zb, vec3(1e-30)), vec3(1e18));
    vec3 sigma_tr = min(data.dipole_sigma.rgb, vec3(1e18));
    vec3 sigma = sqrt(sigma_tr * sigma_tr + 2.0 * buckling * buckling);
    vec3 sum = vec3(0.0);
    for (uint i = 0; i < kDiffusionTaps; ++i) {
        vec3 d = position - entries[i].xyz;
        float out_share = max(dot(n, d), 0.0) * inversesqrt(max(dot(d, d), 1e-30));
        sum += (out_share * entries[i].w) * dipole_exit(position, n, entries[i].xyz, -l, sigma);
    }
    float entry = boundary_crossed() ? mean_boundary_transmittance() : 1.0;
    return (2.0 * JADE_PI * span / float(kDiffusionTaps) * entry * data.dipole_albedo.w * facing) * sum * e;
}

#endif
