#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// burley_blur.frag - screen-space Burley diffusion as Unity HDRP does it (Golubev 2018; read, not
// copied): SAMPLES taps at the radii of the exact inverse CDF of the Burley profile of the widest
// channel (jade/burley_diffusion.hpp, float64 on the host), on a golden-angle disk in world units
// at the pixel's depth, rotated per pixel (interleaved gradient noise, Jimenez 2014); each tap
// weighs R_c(√(r² + Δz²)) / pdf(r) per channel, Δz its depth against the centre's, and the sum is
// renormalised per channel. Taps on no translucent surface (depth 0) weigh nothing.
#include "shading_interface.h"

layout(constant_id = 0) const uint SAMPLES = 40;  // 1 … JADE_BURLEY_MAX_SAMPLES

layout(push_constant, scalar) uniform SeparablePushBlock { SeparablePush push; };
layout(binding = 0, scalar) uniform SeparableBlock { SeparableData sep; };
// rgb: the diffuse light (k_d applied), a: the linear depth (mesh units; 0: no translucent surface).
layout(binding = 1) uniform sampler2D source;

layout(location = 0) out vec4 out_color;

#include "pi.glsl"  // JADE_PI
const float kGoldenAngle = 2.39996322972865332;  // π (3 − √5)

// The Burley profile R(r) = (e^{−r/d} + e^{−r/(3d)}) / (8π d r) per channel.
vec3 burley(vec3 d, float r)
{
    return (exp(-r / d) + exp(-r / (3.0 * d))) / (8.0 * JADE_PI * d * r);
}

void main()
{
    vec2 uv = gl_FragCoord.xy * push.texel.xy;
    vec4 centre = textureLod(source, uv, 0.0);
    if (centre.a <= 0.0) discard;  // not a translucent pixel: it pays nothing more
    vec2 per_unit = push.texel.xy * (push.texel.z / centre.a);  // texture coordinates per mesh unit
    float rotation = 2.0 * JADE_PI * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    vec3 shape = sep.burley.rgb;
    float sampled = sep.burley.a;
    vec3 sum = vec3(0.0), weight = vec3(0.0);
    for (uint i = 0u; i < SAMPLES; ++i) {
        float r = sep.burley_radius[i / 4u][i % 4u];
        float angle = float(i) * kGoldenAngle + rotation;
        vec4 s = textureLod(source, uv + per_unit * r * vec2(cos(angle), sin(angle)), 0.0);
        float dz = s.a - centre.a;
        // pdf(r): the sampled profile itself per unit area (its radial density is cdf′).
        vec3 w = burley(shape, sqrt(r * r + dz * dz)) / burley(vec3(sampled), r).x;
        w *= s.a > 0.0 ? 1.0 : 0.0;
        sum += w * s.rgb;
        weight += w;
    }
    // Every tap off the surface (an isolated pixel): its own light, unblurred.
    vec3 result = mix(centre.rgb, sum / max(weight, vec3(1e-30)), step(vec3(1e-30), weight));
    out_color = vec4(result, 0.0);
}
