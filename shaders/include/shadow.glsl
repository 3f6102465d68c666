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

// The t_m mode's shadow, per channel: light that enters the surface beside a shadow diffuses
// under it, so what a point gets is the visibility around it weighted by the scattering profile,
// ∫ R(|x − s|) V(s) ds over the surface. Across a straight shadow edge on a plane that is the
// profile's edge response, which the screen-space peers' blur gives (tests/test_peers_separable.cpp).
// JADE_SOFT_SHADOW_TAPS points s on the tangent plane at the radii of the exact inverse CDF of
// the widest channel's Burley shape, on a golden-angle disk rotated per pixel (interleaved
// gradient noise, as the Burley mode's taps), each compared with the light's tile as
// shadow_visibility compares the point, and weighted per channel by R_c(r)/pdf(r), normalised:
// offsets and weights are the material's, computed once (shading::soft_shadow_kernel). The
// points are projected into the tile through its derivative at the point (exact for a
// directional light's orthographic tile, to first order in r/distance for a point light's).
// Where the kernel's median radius is under a texel of the tile, the map cannot show the
// softening: the kernel is widened to a median radius of one texel, a filter of about the width
// of shadow_visibility's, so that no branch picks between two filters (see the loop below).
// A tap counts as shadowed only where the occluder is nearer to the light than the tap by more
// than kSoftShadowTolerance times the tap's radius: the tangent plane of a lit convex body runs
// behind the body's own silhouette as seen from the light, within about its radius of it, and the
// falling light towards the terminator is the diffuse term's already (its angular blur); what is
// left is the shadow cast by another part. 2 against 0 (every tap compared as the point is):
// bunny_jewel_front, camel_wax_front and dragon_marble_front of the fidelity set 0.129, 0.159,
// 0.188 against 0.166, 0.189, 0.213 (masked LDR FLIP; the plain filter's 0.130, 0.160, 0.210).
const float kSoftShadowTolerance = 2.0;

// Whether the light reaches tap (xy: its offset on the disk before the pixel's turn, z: its
// radius, in median radii of the kernel) of the kernel centred at q0 of tile t, whose tangent
// axes map to q1 and q2 per median radius; `tolerance`: the occluder's, per median radius of the
// tap's radius; front: the point faces the light (layer 0), else layer 1. Outside the tile, lit.
bool soft_shadow_tap_visible(vec4 tap, vec3 q0, vec3 q1, vec3 q2, vec2 turn, float tolerance, uint t, bool front)
{
    vec3 q = q0 + (turn.x * tap.x - turn.y * tap.y) * q1 + (turn.y * tap.x + turn.x * tap.y) * q2;
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return true;
    float size = data.light_depth_map.x;
    ivec2 texel = clamp(ivec2(q.xy * size), ivec2(0), ivec2(int(size) - 1)) + ivec2(int(t) * int(size), 0);
    vec4 layers = texelFetch(light_depth_atlas, texel, 0);
    return q.z - tolerance * tap.z <= (front ? layers.x : layers.y);
}

vec3 soft_shadow_visibility(uint tile, vec3 position, vec3 n, vec3 l)
{
    uint t = tile - 1u;
    vec4 origin = data.light_tiles[t].origin, depth = data.light_tiles[t].depth;
    float texel = depth.z * (origin.w > 0.5 ? length(position - origin.xyz) : 1.0);
    float c = dot(n, l);
    float sin_theta = sqrt(max(1.0 - c * c, 0.0));
    vec3 towards = c >= 0.0 ? n : -n;
    vec3 lifted = position + towards * (texel * (kShadowOffset + kShadowSlope * sin_theta));
    // An orthonormal basis of the tangent plane (Duff et al. 2017), and its image in the tile per
    // median radius of the kernel, widened to a texel where it is narrower.
    float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign_z + n.z), b = n.x * n.y * a;
    vec3 t1 = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * b, -sign_z * n.x), t2 = vec3(b, sign_z + n.y * n.y * a, -n.y);
    float reach = max(data.soft_shadow.x, texel);
    vec3 q0 = light_tile_coords(t, lifted);
    vec3 q1 = light_tile_coords(t, lifted + reach * t1) - q0;
    vec3 q2 = light_tile_coords(t, lifted + reach * t2) - q0;
    float rotation = 2.0 * JADE_PI * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
    vec2 turn = vec2(cos(rotation), sin(rotation));
    float tolerance = kSoftShadowTolerance * reach / depth.y;
    bool front = c >= 0.0;
    // Most points lie far from any shadow's edge: where the centre and the four outermost taps
    // (the largest radii, spread round the disk by the golden angle) agree, so does the kernel.
    const uint kOuter = JADE_SOFT_SHADOW_TAPS - 4u;
    bool first = soft_shadow_tap_visible(vec4(0.0), q0, q1, q2, turn, tolerance, t, front), agree = true;
    vec3 lit = vec3(0.0);  // the outer taps' share, then the rest's
    for (uint i = kOuter; i < JADE_SOFT_SHADOW_TAPS; ++i) {
        bool visible = soft_shadow_tap_visible(data.soft_shadow_taps[i], q0, q1, q2, turn, tolerance, t, front);
        agree = agree && visible == first;
        if (visible) lit += data.soft_shadow_weights[i].rgb;
    }
    // The other taps in a loop that runs no step where those agree, not after an early return:
    // lavapipe (llvmpipe) shades fragments in SIMD lanes and runs the body of every `if` for the
    // whole group, masked, even when no lane takes it, but it leaves a loop as soon as no lane
    // goes on. (A GPU skips a branch that no thread of a wave takes, and runs this loop alike.)
    for (uint i = 0u, inner = agree ? 0u : kOuter; i < inner; ++i)
        if (soft_shadow_tap_visible(data.soft_shadow_taps[i], q0, q1, q2, turn, tolerance, t, front))
            lit += data.soft_shadow_weights[i].rgb;
    return agree ? vec3(first ? 1.0 : 0.0) : lit;
}

#endif
