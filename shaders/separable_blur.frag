#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// separable_blur.frag - one 1-D pass of Jimenez's separable subsurface scattering (Jimenez et al.
// 2015; the pass as in iryoku/separable-sss's SSSSBlurPS, written anew): the diffuse light of the
// pixel's neighbours along one axis, weighted per channel by the kernel that jade/separable.hpp
// fits to the material's profiles, the taps' world offsets turned into pixels at the pixel's own
// linear depth (taps along the screen's axes, as the reference: no slope correction).
// Follow-surface: a tap whose depth differs from the centre's is replaced by the centre's light,
// the more the larger the difference (fully at 1 / push.texel.w mesh units), which keeps the
// weights' sum 1 and stops light bleeding across depth edges (a silhouette, the background).
#include "shading_interface.h"

layout(constant_id = 0) const uint TAPS = 17;     // 11, 17 or 25
layout(constant_id = 1) const uint VERTICAL = 0;  // 0: along x, 1: along y

layout(push_constant, scalar) uniform SeparablePushBlock { SeparablePush push; };
layout(binding = 0, scalar) uniform SeparableBlock { SeparableData sep; };
// rgb: the diffuse light (k_d applied), a: the linear depth (mesh units; 0: no translucent surface).
layout(binding = 1) uniform sampler2D source;

layout(location = 0) out vec4 out_color;

void main()
{
    vec2 uv = gl_FragCoord.xy * push.texel.xy;
    vec4 centre = textureLod(source, uv, 0.0);
    if (centre.a <= 0.0) discard;  // not a translucent pixel: it pays nothing more
    // Texture coordinates per mesh unit along the axis at this depth.
    vec2 axis = VERTICAL == 1u ? vec2(0.0, push.texel.y) : vec2(push.texel.x, 0.0);
    axis *= push.texel.z / centre.a;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < TAPS; ++i) {
        vec4 tap = sep.taps[i];
        vec4 s = textureLod(source, uv + axis * tap.w, 0.0);
        float away = clamp(abs(s.a - centre.a) * push.texel.w, 0.0, 1.0);
        sum += tap.rgb * mix(s.rgb, centre.rgb, away);
    }
    // The horizontal pass keeps the centre's depth for the vertical one; the vertical pass adds
    // its rgb to the image (alpha kept by the blend).
    out_color = vec4(sum, VERTICAL == 1u ? 0.0 : centre.a);
}
