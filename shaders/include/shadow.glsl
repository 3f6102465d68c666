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
// (kShadowOffset + kShadowSlope · sin θ) texels of the tile at the point. Over a plane at angle θ
// to the light that is a depth bias of offset / cos θ along the ray, and the filter's taps, up to
// 1.5 texels away, see the plane at most 2 · texel · tan θ nearer: kShadowSlope > 2 keeps a lit
// plane, and the lit side of a convex body (which falls away from its tangent plane), free of
// acne at every angle, and moves the shadow's edge by less than about 2.5 texels.
const float kShadowOffset = 1.0, kShadowSlope = 2.5;

// Visibility ∈ [0, 1] of the light with depth tile `tile` (+ 1) from `position` with unit
// normal n, unit direction to the light l. A point facing the light is compared with layer 0,
// the surface nearest to the light: an ordinary shadow map. A point facing away from it is
// compared with layer 1, the far side of the first part along the light: the part it belongs to
// does not shadow it, another part in front of that does. The lit side's light that wraps past
// the terminator (the curvature and t_m modes' diffuse term) is then kept, as it is without
// shadows, and Lambert is 0 there anyway.
// The filter: a 2 × 2 grid of bilinear comparisons half a texel either side of the point, as
// 3 × 3 taps with the weights of a tent (1 − f, 1, f) per axis, 9 fetches. Outside the tile, lit.
float shadow_visibility(uint tile, vec3 position, vec3 n, vec3 l)
{
    uint t = tile - 1u;
    vec4 origin = data.light_tiles[t].origin, depth = data.light_tiles[t].depth;
    float c = dot(n, l);
    float texel = depth.z * (origin.w > 0.5 ? length(position - origin.xyz) : 1.0);
    float sin_theta = sqrt(max(1.0 - c * c, 0.0));
    vec3 towards = c >= 0.0 ? n : -n;
    vec3 q = light_tile_coords(t, position + towards * (texel * (kShadowOffset + kShadowSlope * sin_theta)));
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return 1.0;
    float size = data.light_depth_map.x;
    vec2 u = q.xy * size - 1.0;  // texel centres at integers, less the half texel
    vec2 b = floor(u), f = u - b;
    vec3 wx = vec3(1.0 - f.x, 1.0, f.x), wy = vec3(1.0 - f.y, 1.0, f.y);
    int x0 = int(t) * int(size);
    ivec2 hi = ivec2(int(size) - 1);
    float lit = 0.0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            ivec2 texel_at = clamp(ivec2(b) + ivec2(i, j), ivec2(0), hi);
            vec4 layers = texelFetch(light_depth_atlas, ivec2(x0, 0) + texel_at, 0);
            float occluder = c >= 0.0 ? layers.x : layers.y;
            lit += q.z <= occluder ? wx[i] * wy[j] : 0.0;
        }
    return lit * 0.25;
}

// The Burley profile R(r) = (e^{−r/d} + e^{−r/(3d)}) / (8π d r) per channel (jade/burley_diffusion.hpp).
vec3 soft_shadow_profile(vec3 d, float r) { return (exp(-r / d) + exp(-r / (3.0 * d))) / (8.0 * JADE_PI * d * r); }

// The t_m mode's shadow, per channel: light that enters the surface beside a shadow diffuses
// under it, so what a point gets is the visibility around it weighted by the scattering profile,
// ∫ R(|x − s|) V(s) ds over the surface. Across a straight shadow edge on a plane that is the
// profile's edge response, which the screen-space peers' blur gives (tests/test_peers_separable.cpp).
// JADE_SOFT_SHADOW_TAPS points s on the tangent plane at the radii of the exact inverse CDF of
// the widest channel's Burley shape, on a golden-angle disk rotated per pixel (interleaved
// gradient noise, as the Burley mode's taps), each compared with the light's tile as
// shadow_visibility compares the point (tangent-plane points of a convex body lie outside it);
// each weighs R_c(r)/pdf(r) per channel, renormalised. Where the kernel's median radius is under
// a texel of the tile the map cannot show the softening: shadow_visibility's filter instead.
// A tap counts as shadowed only where the occluder is nearer to the light than the tap by more
// than kSoftShadowTolerance times the tap's radius: the tangent plane of a lit convex body runs
// behind the body's own silhouette as seen from the light, within about its radius of it, and the
// falling light towards the terminator is the diffuse term's already (its angular blur); what is
// left is the shadow cast by another part. 2 against 0 (every tap compared as the point is):
// bunny_jewel_front, camel_wax_front and dragon_marble_front of the fidelity set 0.129, 0.159,
// 0.188 against 0.166, 0.189, 0.213 (masked LDR FLIP; the plain filter's 0.130, 0.160, 0.210).
const float kSoftShadowTolerance = 2.0;
vec3 soft_shadow_visibility(uint tile, vec3 position, vec3 n, vec3 l)
{
    uint t = tile - 1u;
    vec4 origin = data.light_tiles[t].origin, depth = data.light_tiles[t].depth;
    float texel = depth.z * (origin.w > 0.5 ? length(position - origin.xyz) : 1.0);
    const uint kMedian = JADE_SOFT_SHADOW_TAPS / 2u;
    if (data.soft_shadow.w <= 0.0 || data.soft_shadow_radius[kMedian / 4u][kMedian % 4u] <= texel)
        return vec3(shadow_visibility(tile, position, n, l));
    float c = dot(n, l);
    float sin_theta = sqrt(max(1.0 - c * c, 0.0));
    vec3 towards = c >= 0.0 ? n : -n;
    vec3 lifted = position + towards * (texel * (kShadowOffset + kShadowSlope * sin_theta));
    // An orthonormal basis of the tangent plane (Duff et al. 2017).
    float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign_z + n.z), b = n.x * n.y * a;
    vec3 t1 = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * b, -sign_z * n.x), t2 = vec3(b, sign_z + n.y * n.y * a, -n.y);
    float rotation = 2.0 * JADE_PI * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    float size = data.light_depth_map.x;
    int x0 = int(t) * int(size);
    ivec2 hi = ivec2(int(size) - 1);
    vec3 lit = vec3(0.0), weight = vec3(0.0);
    for (uint i = 0u; i < JADE_SOFT_SHADOW_TAPS; ++i) {
        float r = data.soft_shadow_radius[i / 4u][i % 4u];
        float angle = float(i) * 2.39996322972865332 + rotation;  // the golden angle π(3 − √5)
        vec3 q = light_tile_coords(t, lifted + r * (cos(angle) * t1 + sin(angle) * t2));
        vec3 w = soft_shadow_profile(data.soft_shadow.rgb, r) / soft_shadow_profile(data.soft_shadow.www, r).x;
        weight += w;
        if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) {
            lit += w;  // outside the tile: lit
            continue;
        }
        vec4 layers = texelFetch(light_depth_atlas, ivec2(x0, 0) + clamp(ivec2(q.xy * size), ivec2(0), hi), 0);
        lit += q.z - kSoftShadowTolerance * r / depth.y <= (c >= 0.0 ? layers.x : layers.y) ? w : vec3(0.0);
    }
    return lit / max(weight, vec3(1e-30));
}

#endif
