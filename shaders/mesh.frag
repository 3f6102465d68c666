#version 460
#extension GL_GOOGLE_include_directive : require
// mesh.frag - diffuse from the translucency magnitude (or Lambert, or the curvature LUT) plus a
// GGX specular lobe, summed over the lights and shadowed by the mesh, and the light transmitted
// through thin parts. Mode, channel count, evaluation path, transmission slots and shadows are
// specialisation constants:
// each pipeline holds only its path. Lavapipe runs both sides of every branch (docs/lavapipe.md),
// so what a light does not need sits in a loop of its own, not behind an if.
#include "shading.glsl"
#include "translucency.glsl"
#include "transmission.glsl"
#include "shadow.glsl"
#include "filament.glsl"

layout(constant_id = 0) const uint MODE = JADE_MODE_TM;  // kLambert … kBurley (shading.glsl), kInputs + k
layout(constant_id = 1) const uint CHANNELS = 3;  // 1: grey material, one evaluation per light

layout(binding = 2) uniform sampler2D curvature_lut;  // RGBA32F, D_c(cos θ, κ) per channel

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec3 in_tm;
layout(location = 3) in float in_curvature;
layout(location = 4) in float in_thickness;  // mesh units; the Filament mode: its thickness in [0, 1] (mesh.vert)
layout(location = 5) in float in_lobe[kMaxTransmitters];
layout(location = 9) in vec3 in_scattering_normal;
layout(location = 10) in vec3 in_normal_spread;
layout(location = 11) in vec3 in_variance;
layout(location = 12) in float in_path[kMaxTransmitters];
layout(location = 16) in vec3 in_diffused;  // the transmitting lights' diffused exitance (mesh.vert)

layout(location = 0) out vec4 out_color;
// kSeparable, kBurley (shading/separable.hpp): the diffuse light, blurred after this pass, in a
// target of its own with the linear depth in alpha; out_color keeps the specular light.
layout(location = 1) out vec4 out_irradiance;
layout(binding = 6, scalar) uniform SeparableBlock { SeparableData sep; };

// The diffuse response per channel, F in (k_d/π) F E.
vec3 diffuse_response(float c, Translucency tr, float kappa_scaled)
{
    if (MODE == kCurvature) {
        vec4 m = data.curvature_map;
        float v = kappa_scaled / (1.0 + kappa_scaled);
        return textureLod(curvature_lut, vec2(c * m.x + m.y, v * m.z + m.w), 0.0).rgb;
    }
    if (MODE == kTm) {
        // With the spread model the blur stops at the terminator and the light falls off past it
        // over the profile's own angle (terminator_falloff); the poster's model blurs all round.
        bool falloff = c < 0.0 && data.specular.w > 0.0;
        vec3 f = translucency(falloff ? 0.0 : c, tr);
        if (falloff) f *= terminator_falloff(c, CHANNELS == 1 ? in_normal_spread.rrr : in_normal_spread);
        return CHANNELS == 1 ? f.rrr : f;
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

vec3 false_color(float x)
{
    float s = clamp(x, 0.0, 1.0) * float(kColorMapStops - 1);
    uint i = min(uint(s), kColorMapStops - 2);
    return mix(data.color_map[i].rgb, data.color_map[i + 1].rgb, s - float(i));
}

// Transmitter k's path t at this fragment: interpolated from the vertices, or its own.
float path_at(uint k)
{
    return PATH_PER_VERTEX == 1u ? in_path[k] : transmitter_path(in_thickness, transmitter_light_path(k, in_position));
}

// The inputs pass: what the shading of this fragment reads, as rasterised.
vec4 shading_input(uint k)
{
    if (k == 0u) return vec4(in_position, 1.0);
    if (k == 1u) return vec4(in_normal, in_thickness);
    if (k == 2u) return vec4(in_tm, in_curvature);
    if (k == 4u) return vec4(in_scattering_normal, 0.0);
    if (k == 5u) return vec4(in_normal_spread, 0.0);
    if (k == 6u) return vec4(in_diffused, 0.0);
    vec4 path = vec4(0.0);
    for (uint j = 0; j < kMaxTransmitters; ++j)
        if (j < TRANSMISSION) path[j] = path_at(j);
    return path;
}

// SSSSTransmittance (Jimenez, Whelan, Sundstedt, Gutierrez 2010; iryoku/separable-sss), with the
// material's profile for the skin's Gaussians: the distance d that the light crossed inside the
// object, from the light's first surface (layer 0 of its depth tile, the shadow map) to this
// point moved in along the normal (by a texel of the tile, the reference's "shrinked" position),
// run through T(d) = 1 − cdf(d) per channel (jade/separable.hpp), times the reference's
// saturate(0.3 + N·(−L)). kBurley: HDRP's thick mode, the same T(d) (for a Burley profile it is
// HDRP's ¼(e^{−d/s} + 3e^{−d/3s})) lit by max(N·(−L), 0).
vec3 separable_transmittance(uint tile, vec3 n, vec3 l)
{
    uint t = tile - 1u;
    vec4 origin = data.light_tiles[t].origin, depth = data.light_tiles[t].depth;
    float texel = depth.z * (origin.w > 0.5 ? length(in_position - origin.xyz) : 1.0);
    vec3 q = light_tile_coords(t, in_position - n * texel);
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return vec3(0.0);
    float size = data.light_depth_map.x;
    ivec2 at = clamp(ivec2(q.xy * size), ivec2(0), ivec2(int(size) - 1));
    float first = texelFetch(light_depth_atlas, ivec2(int(t) * int(size), 0) + at, 0).x;
    // d (mesh units) → the table's index: d = reach · (x / (STEPS − 1))².
    float x = sqrt(max(q.z - first, 0.0) * depth.y * sep.params.x) * float(JADE_SEPARABLE_TRANSMITTANCE_STEPS - 1);
    uint i = min(uint(x), uint(JADE_SEPARABLE_TRANSMITTANCE_STEPS) - 2u);
    vec3 profile = mix(sep.transmittance[i].rgb, sep.transmittance[i + 1u].rgb, clamp(x - float(i), 0.0, 1.0));
    return profile * clamp((MODE == kBurley ? 0.0 : 0.3) + dot(l, -n), 0.0, 1.0);
}

// Towards light `light` from this fragment, unit, and its irradiance here.
void light_at(GpuLight light, out vec3 l, out vec3 e)
{
    l = light.vector.xyz;
    e = light.color.rgb;
    if (light.vector.w != 0.0) {  // point light: inverse-square falloff
        l -= in_position;
        e /= max(dot(l, l), 1e-20);
    }
    l = normalize(l);
}

void main()
{
    if (MODE >= kInputs) {
        out_color = shading_input(MODE - kInputs);
        return;
    }
    if (MODE == kFalseColor) {
        out_color = vec4(false_color((dot(in_tm, vec3(1.0 / 3.0)) - data.params.z) * data.params.w), 1.0);
        return;
    }
    vec3 n = normalize(in_normal);
    // The t_m modes light the diffuse term along the scattering normal (BakeResult::
    // scattering_normal: bumps within the profile's reach smoothed out), the rest along n.
    // Interpolated across a thin part's rim, where the vertices' scattering normals point apart,
    // the sum can vanish: the vertex normal stands in there (no NaN from normalize).
    vec3 sn = in_scattering_normal;
    vec3 n_diffuse = MODE == kTm && dot(sn, sn) > 1e-12 ? normalize(sn) : n;
    vec3 v = normalize(frame.eye - in_position);
    // Leaving towards the eye: the same for every light.
    bool boundary = MODE == kTm && boundary_crossed();
    float exit_transmittance = boundary ? boundary_transmittance(dot(n, v)) : 1.0;
    vec3 albedo = data.albedo_strength.rgb;
    // t = strength · t_m + spread_strength · normal spread per channel, interpolated (linear in
    // t_m, so the poster's interpolated t_m): interpolating a function of t instead (the LUT row,
    // e^{−2t}) leaves the image budget where t_m is noisy.
    Translucency tr;
    if (MODE == kTm) tr = translucency_setup(CHANNELS == 1 ? in_variance.rrr : in_variance);
    float kappa_scaled = max(in_curvature, 0.0) * data.params.y;  // concave: treated as flat

    vec3 color = vec3(0.0), irradiance = vec3(0.0);
    for (uint k = 0; k < frame.light_count; ++k) {
        vec3 l, e;
        light_at(data.lights[k], l, e);
        float c = dot(n, l), c_diffuse = dot(n_diffuse, l);
        uint tile = uint(data.lights[k].color.w);
        // Filament's BTDF is not shadowed (filament.glsl): it takes the light before the shadow.
        if (MODE == kFilament) color += filament_subsurface(n, v, l, in_thickness) * e;
        // Jimenez's transmittance: k_d/π as the diffuse term's (the reference's albedo · light),
        // not shadowed (it is the light that crossed the occluder).
        if ((MODE == kSeparable || MODE == kBurley) && tile != 0u)
            irradiance += albedo * (1.0 / JADE_PI) * separable_transmittance(tile, n, l) * e;
        // The mesh's shadow (shadow.glsl) dims this light's diffuse and specular light alike; the
        // t_m modes' is softened by the scattering profile, per channel.
        if (SHADOWS == 1u && tile != 0u)
            e *= MODE == kTm ? soft_shadow_visibility(tile, in_position, n, l)
                             : vec3(shadow_visibility(tile, in_position, n, l));
        vec3 diffuse = albedo * (1.0 / JADE_PI) * diffuse_response(c_diffuse, tr, kappa_scaled) * e;
        if (boundary) diffuse *= boundary_transmittance(c_diffuse) * exit_transmittance;
        if (MODE == kSeparable || MODE == kBurley)
            irradiance += diffuse;  // k_d before the blur (pre-scatter), Lambert's irradiance
        else
            color += diffuse;
        if (c > 0.0 && data.specular.z > 0.0) color += data.specular.z * specular_lobe(n, v, l, c) * e;
    }
    // Only the lights that may shine through the object towards the eye, each in its own
    // unrolled step (constant indices: a loop over a list would cost more than the term).
    if (MODE == kTm) {
        for (uint k = 0; k < TRANSMISSION; ++k)
            color += exit_transmittance * transmitted_light(k, in_position, n, in_lobe[k], path_at(k));
        // Diffused light leaves as a Lambertian emitter: its exitance / π.
        if (TRANSMISSION > 0u) color += exit_transmittance * (1.0 / JADE_PI) * in_diffused;
    }
    out_color = vec4(color, 1.0);
    // Linear depth: clip w is the distance along the view axis (perspective), 1 / gl_FragCoord.w.
    if (MODE == kSeparable || MODE == kBurley) out_irradiance = vec4(irradiance, 1.0 / gl_FragCoord.w);
}
