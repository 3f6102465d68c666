// shadow.glsl - how much of a light reaches a surface point past the rest of the mesh: a
// percentage-closer filter of the point's depth along the light against the light's depth tile
// (shading/light_depth.hpp, the same tiles as the transmission term's path). Multiplies each
// light's diffuse and specular light in mesh.frag; the transmitted light is not shadowed by it
// (its path already runs through the layers).
#ifndef JADE_SHADOW_GLSL
#define JADE_SHADOW_GLSL

#include "light_tile.glsl"

// 1: the lights with a tile (GpuLight::color.w) are shadowed; 0: no shadow code in the pipeline.
layout(constant_id = 8) const uint SHADOWS = 0;

// The point looked up is moved off the surface along its normal, towards the light's side, by
// (kShadowOffset + kShadowSlope · spacing · sin θ) texels of the tile at the point. Over a plane
// at angle θ to the light that is a depth bias of offset / cos θ along the ray, and the filter's
// taps, up to 1.5 · spacing texels away (and half a texel more where spacing > 1 rounds to the
// nearest texel), see the plane at most 2 · spacing · texel · tan θ nearer: kShadowSlope > 2 keeps a lit plane, and the lit side of a convex body (which falls away from
// its tangent plane), free of acne at every angle, and moves the shadow's edge by less than
// about 2.5 · spacing texels.
const float kShadowOffset = 1.0, kShadowSlope = 2.5;

// Visibility ∈ [0, 1] of the light with depth tile `tile` (+ 1) from `position` with unit
// normal n, unit direction to the light l. A point facing the light is compared with layer 0,
// the surface nearest to the light: an ordinary shadow map. A point facing away from it is
// compared with layer 1, the far side of the first part along the light: the part it belongs to
// does not shadow it, another part in front of that does. The lit side's light that wraps past
// the terminator (the curvature and t_m modes' diffuse term) is then kept, as it is without
// shadows, and Lambert is 0 there anyway.
// The filter: 3 × 3 taps `spacing` texels apart (LightTile::depth.w) with the weights of a tent
// (1 − f, 1, f) per axis; at spacing 1 that is exactly a 2 × 2 grid of bilinear comparisons half
// a texel either side of the point, 9 fetches (a 3 × 3 grid of bilinear ones took 16 and cost
// lavapipe about twice as much again). Outside the tile, lit.
float shadow_visibility(uint tile, vec3 position, vec3 n, vec3 l)
{
    uint t = tile - 1u;
    vec4 origin = data.light_tiles[t].origin, depth = data.light_tiles[t].depth;
    float c = dot(n, l), spacing = max(depth.w, 1.0);
    float texel = depth.z * (origin.w > 0.5 ? length(position - origin.xyz) : 1.0);
    float sin_theta = sqrt(max(1.0 - c * c, 0.0));
    vec3 towards = c >= 0.0 ? n : -n;
    vec3 q = light_tile_coords(t, position + towards * (texel * (kShadowOffset + kShadowSlope * spacing * sin_theta)));
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return 1.0;
    float size = data.light_depth_map.x;
    vec2 u = q.xy * (size / spacing) - 1.0;  // texel centres at integers, less the half texel
    vec2 b = floor(u), f = u - b;
    vec3 wx = vec3(1.0 - f.x, 1.0, f.x), wy = vec3(1.0 - f.y, 1.0, f.y);
    int x0 = int(t) * int(size);
    ivec2 hi = ivec2(int(size) - 1);
    float lit = 0.0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            // Tap (i, j) of the scaled grid, at the texel nearest to it.
            ivec2 texel_at = clamp(ivec2(floor((b + vec2(i, j) + 0.5) * spacing)), ivec2(0), hi);
            vec4 layers = texelFetch(light_depth_atlas, ivec2(x0, 0) + texel_at, 0);
            float occluder = c >= 0.0 ? layers.x : layers.y;
            lit += q.z <= occluder ? wx[i] * wy[j] : 0.0;
        }
    return lit * 0.25;
}

#endif
