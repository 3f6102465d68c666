// GLSL of Jade's default (tm) shading, for three.js. Each block follows the Jade shader
// function named in its comment (shaders/mesh.frag, mesh.vert, shaders/include/*.glsl): the same
// formulas and constants, written for WebGL2 (GLSL ES 3.00) and three.js's light uniforms.
// Positions and directions are in three.js's view space (the eye at the origin): every quantity
// the shading reads is a dot product or a length, the same in any rigid frame.
import { diffusionChunk } from './jadeDiffusionChunk.js';

// What both stages share: the material's constants and the lights. The lights are three.js's own
// (DirectionalLight: colour × intensity is the irradiance E on a surface facing it, as in Jade;
// PointLight: colour × intensity / d², Jade's inverse-square falloff; three.js's distance and
// decay are not used).
export const commonChunk = /* glsl */ `
#define JADE_PI 3.14159265358979323846
uniform vec4 jadeAlbedoStrength;      // k_d (linear RGB), strength
uniform vec4 jadeSpecular;            // F0, alpha = roughness^2, weight, spreadStrength
uniform vec4 jadeExtinction;          // sigma_t, w_b
// The diffused transmission's dipole (FrameData dipole_*, shading/frame.cpp material_constants):
uniform vec4 jadeDipoleAlbedo;        // alpha'/(4 pi), w: diffusion weight (0: no gather)
uniform vec4 jadeDipoleSigma;         // sigma_tr, w: the gather's reach past the light's path, 3/min sigma_tr
uniform vec3 jadeDipoleReal;          // z_r = 1/sigma_t', the source's depth
uniform vec3 jadeDipoleBoundary;      // z_b = 2AD, the extrapolated boundary's distance
uniform vec4 jadeShape;               // lobe n, (n + 1)/(2 pi), normalMix, boundary transmittance (1/0)
uniform vec4 jadeBounds;              // bounding sphere of the mesh (object space): centre, radius
uniform float jadeTransmission;       // 1: the transmission term is drawn (the file has _THICKNESS)

#if NUM_DIR_LIGHTS > 0
struct DirectionalLight { vec3 direction; vec3 color; };
uniform DirectionalLight directionalLights[NUM_DIR_LIGHTS];
#endif
#if NUM_POINT_LIGHTS > 0
struct PointLight { vec3 position; vec3 color; float distance; float decay; };
uniform PointLight pointLights[NUM_POINT_LIGHTS];
#endif

// The lights' depth tiles (JadeLightDepth.js, Jade's atlas columns and LightTile), one slot a
// light: the directional lights', then the point lights'. Layers: the first four surfaces along
// the light, 1 where there is none.
#define JADE_TILE_SLOTS (NUM_DIR_LIGHTS + NUM_POINT_LIGHTS)
#if JADE_TILE_SLOTS > 0
uniform sampler2D jadeTileLayers[JADE_TILE_SLOTS];
uniform mat4 jadeTileMatrix[JADE_TILE_SLOTS];   // view space -> the tile's clip space
uniform vec4 jadeTileInfo[JADE_TILE_SLOTS];     // texels across, unused, 0 none | 1 orthographic | 2 perspective
uniform vec4 jadeTileDepth[JADE_TILE_SLOTS];    // LightTile::depth: near, range, texel (a point light's: per unit distance)
uniform vec3 jadeTileOrigin[JADE_TILE_SLOTS];   // a point light's position, view space
#endif
struct JadeTile { mat4 m; vec4 info; vec4 depth; vec3 origin; };

// light_tile_coords (light_tile.glsl): xy in [0, 1] over the tile, z its depth in the units the
// layers hold (the window depth of an orthographic tile, the distance from a point light).
vec3 jadeTileCoords(JadeTile t, vec3 p)
{
    vec4 c = t.m * vec4(p, 1.0);
    float z = t.info.z > 1.5 ? (length(p - t.origin) - t.depth.x) / t.depth.y : c.z / c.w * 0.5 + 0.5;
    return vec3(c.xy / c.w * 0.5 + 0.5, z);
}

// medium_path (transmission.glsl): the path inside the medium up to depth z at one texel.
float jadeMediumPath(vec4 layers, float z)
{
    return (clamp(z, layers.x, layers.y) - layers.x) + (clamp(z, layers.z, layers.w) - layers.z) +
           max(z - layers.w, 0.0);
}

// light_path (transmission.glsl): the medium's share of the light's line up to p (view space),
// bilinear between the four nearest texels, in length units. Per fragment, or per vertex
// (JADE_PATH_PER_VERTEX) as Jade picks.
float jadeLightPath(sampler2D layers, JadeTile t, vec3 p)
{
    vec3 q = jadeTileCoords(t, p);
    float size = t.info.x;
    vec2 xy = clamp(q.xy, 0.0, 1.0) * size - 0.5;
    vec2 f = fract(xy);
    ivec2 base = ivec2(floor(xy)), lo = ivec2(0), hi = ivec2(int(size) - 1);
    float t00 = jadeMediumPath(texelFetch(layers, clamp(base, lo, hi), 0), q.z);
    float t10 = jadeMediumPath(texelFetch(layers, clamp(base + ivec2(1, 0), lo, hi), 0), q.z);
    float t01 = jadeMediumPath(texelFetch(layers, clamp(base + ivec2(0, 1), lo, hi), 0), q.z);
    float t11 = jadeMediumPath(texelFetch(layers, clamp(base + ivec2(1, 1), lo, hi), 0), q.z);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y) * t.depth.y;
}

// shadow_visibility (shadow.glsl): a 3 x 3 tent of depth comparisons, of the point moved off
// the surface along its normal by (1 + 2.5 sin theta) texels of the tile at the point; against
// layer 0 where the surface faces the light, layer 1 where it faces away. Outside the tile, lit.
float jadeShadowVisibility(sampler2D layers, JadeTile t, vec3 position, vec3 n, vec3 l)
{
    float c = dot(n, l), size = t.info.x;
    float texel = t.depth.z * (t.info.z > 1.5 ? length(position - t.origin) : 1.0);
    float sin_theta = sqrt(max(1.0 - c * c, 0.0));
    vec3 towards = c >= 0.0 ? n : -n;
    vec3 q = jadeTileCoords(t, position + towards * (texel * (1.0 + 2.5 * sin_theta)));
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return 1.0;
    vec2 u = q.xy * size - 1.0;
    vec2 b = floor(u), f = u - b;
    vec3 wx = vec3(1.0 - f.x, 1.0, f.x), wy = vec3(1.0 - f.y, 1.0, f.y);
    ivec2 hi = ivec2(int(size) - 1);
    float lit = 0.0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            ivec2 at = clamp(ivec2(b) + ivec2(i, j), ivec2(0), hi);
            vec4 depths = texelFetch(layers, at, 0);
            float occluder = c >= 0.0 ? depths.x : depths.y;
            lit += q.z <= occluder ? wx[i] * wy[j] : 0.0;
        }
    return lit * 0.25;
}

// soft_shadow_visibility (shadow.glsl): the visibility on the tangent plane weighted by the
// profile, per channel: 16 taps at the radii of the widest channel's Burley inverse CDF
// (jadeSoftShadowRadius, view-space units) on a golden-angle disk rotated per pixel, each
// weighing R_c(r)/pdf(r); an occluder counts only when nearer than twice the tap's radius. Where
// the kernel's median radius is under a texel, the kernel widened to a texel (its weights kept).
uniform vec4 jadeSoftShadow;              // Burley d per channel, w the sampled d (0: off)
uniform float jadeSoftShadowRadius[16];
uniform float jadeSoftShadowMedian;       // the sampled shape's median radius
vec3 jadeSoftShadowProfile(vec3 d, float r) { return (exp(-r / d) + exp(-r / (3.0 * d))) / (8.0 * JADE_PI * d * r); }
bool jadeSoftShadowTapVisible(sampler2D layers, JadeTile t, vec3 lifted, float r, float angle, vec3 t1, vec3 t2, bool front)
{
    vec3 q = jadeTileCoords(t, lifted + r * (cos(angle) * t1 + sin(angle) * t2));
    if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return true;
    vec4 depths = texelFetch(layers, clamp(ivec2(q.xy * t.info.x), ivec2(0), ivec2(int(t.info.x) - 1)), 0);
    return q.z - 2.0 * r / t.depth.y <= (front ? depths.x : depths.y);
}
// pixel: gl_FragCoord.xy (a parameter: the vertex shader compiles this chunk too).
vec3 jadeSoftShadowVisibility(sampler2D layers, JadeTile t, vec3 position, vec3 n, vec3 l, vec2 pixel)
{
    float texel = t.depth.z * (t.info.z > 1.5 ? length(position - t.origin) : 1.0);
    if (jadeSoftShadow.w <= 0.0) return vec3(jadeShadowVisibility(layers, t, position, n, l));
    float widen = max(texel / jadeSoftShadowMedian, 1.0);
    float c = dot(n, l);
    float sin_theta = sqrt(max(1.0 - c * c, 0.0));
    vec3 towards = c >= 0.0 ? n : -n;
    vec3 lifted = position + towards * (texel * (1.0 + 2.5 * sin_theta));
    float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sign_z + n.z), b = n.x * n.y * a;
    vec3 t1 = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * b, -sign_z * n.x), t2 = vec3(b, sign_z + n.y * n.y * a, -n.y);
    float rotation = 2.0 * JADE_PI * fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
    // As Jade: where the centre and the four outermost taps agree, so does the kernel.
    bool front = c >= 0.0;
    bool first = jadeSoftShadowTapVisible(layers, t, lifted, 0.0, 0.0, t1, t2, front), agree = true;
    for (int i = 12; i < 16; ++i) {
        float angle = float(i) * 2.39996322972865332 + rotation;
        agree = agree && jadeSoftShadowTapVisible(layers, t, lifted, widen * jadeSoftShadowRadius[i], angle, t1, t2, front) == first;
    }
    if (agree) return vec3(first ? 1.0 : 0.0);
    vec3 lit = vec3(0.0), weight = vec3(0.0);
    for (int i = 0; i < 16; ++i) {
        float r = jadeSoftShadowRadius[i];
        float angle = float(i) * 2.39996322972865332 + rotation;
        vec3 w = jadeSoftShadowProfile(jadeSoftShadow.rgb, r) / jadeSoftShadowProfile(jadeSoftShadow.www, r).x;
        weight += w;
        if (jadeSoftShadowTapVisible(layers, t, lifted, widen * r, angle, t1, t2, front)) lit += w;
    }
    return lit / max(weight, vec3(1e-30));
}

// light_at (mesh.frag) / transmitter_at (transmission.glsl): towards the light, unit, and its
// irradiance at p.
void jadeDirectional(vec3 direction, vec3 color, out vec3 l, out vec3 e) { l = normalize(direction); e = color; }
void jadePoint(vec3 position, vec3 color, vec3 p, out vec3 l, out vec3 e)
{
    l = position - p;
    e = color / max(dot(l, l), 1e-20);
    l = normalize(l);
}

// LightDepth::may_transmit (engine/src/shading/light_depth.cpp): whether the light can shine
// through the object towards the eye: a point light always, a directional one when the cone of
// view directions from the bounding sphere reaches its forward lobe. Jade draws the
// transmission term for these lights only.
// centre: the bounding sphere's centre in view space (vJadeCentre).
bool jadeMayTransmit(vec3 direction, bool point, vec3 centre)
{
    float distance = length(centre), radius = jadeBounds.w;
    if (!(distance > radius) || point) return true;
    return dot(-centre / distance, -normalize(direction)) > -radius / distance;
}
`;

// What the vertex shader hands the fragment shader, declared once for both.
const varyings = /* glsl */ `
varying vec3 vJadePosition;
varying vec3 vJadeNormal;
varying vec3 vJadeScatteringNormal;
varying vec3 vJadeVariance;
varying vec3 vJadeNormalSpread;
varying float vJadeThickness;
varying vec3 vJadeCentre;  // the bounding sphere's centre, view space (the same at every vertex)
varying vec3 vJadeDiffused;  // mesh.vert's out_diffused: the transmitting lights' diffused exitance, summed
#if NUM_DIR_LIGHTS > 0
varying float vJadeLobeDir[NUM_DIR_LIGHTS];
varying float vJadePathDir[NUM_DIR_LIGHTS];  // JADE_PATH_PER_VERTEX: transmitter_path per vertex
#endif
#if NUM_POINT_LIGHTS > 0
varying float vJadeLobePoint[NUM_POINT_LIGHTS];
varying float vJadePathPoint[NUM_POINT_LIGHTS];
#endif
`;

export const vertexShader = /* glsl */ `
#include <common>
${commonChunk}
attribute vec3 jadeTm;
attribute float jadeThickness;
attribute vec3 jadeScatteringNormal;
attribute vec3 jadeNormalSpread;
${varyings}
// variance (shading.glsl): t = t_m (strength + spreadStrength spread), clamped to the LUT's
// range t_max = 25 rad^2 (LutLayout::kMaxVariance).
vec3 jadeVariance(vec3 tm, vec3 spread)
{
    tm = min(max(tm, vec3(0.0)), vec3(3.0e38));
    vec3 t = tm * (jadeAlbedoStrength.w + jadeSpecular.w * clamp(spread, 0.0, 1.0));
    return min(t * (1.0 / 25.0), vec3(1.0)) * 25.0;
}

// transmitter_lobe (transmission.glsl): (n + 1)/(2 pi) max(V.(-L), 0)^n, per vertex as in mesh.vert.
float jadeLobe(vec3 l, vec3 v)
{
    float mu = max(-dot(v, l), 0.0);
    return mu > 0.0 ? jadeShape.y * pow(mu, jadeShape.x) : 0.0;
}

${diffusionChunk}
void main()
{
    vec4 p = modelViewMatrix * vec4(position, 1.0);
    vJadePosition = p.xyz;
    vJadeNormal = normalMatrix * normal;
    vJadeScatteringNormal = normalMatrix * jadeScatteringNormal;
    vJadeVariance = jadeVariance(jadeTm, jadeNormalSpread);
    vJadeNormalSpread = jadeNormalSpread;
    vJadeThickness = jadeThickness;
    vJadeCentre = (modelViewMatrix * vec4(jadeBounds.xyz, 1.0)).xyz;
    vec3 v = normalize(-p.xyz), l, e;
    // mesh.vert's out_diffused: diffused_light summed over the transmitting lights with a tile.
    vJadeDiffused = vec3(0.0);
    // mesh.vert's turn of the gather's spiral: the golden-ratio sequence of the vertex's index.
    float turn = 6.28318531 * fract(float(gl_VertexID) * 0.61803399);
    bool diffused = jadeTransmission > 0.5 && jadeDipoleAlbedo.w > 0.0;
    vec3 n = normalize(vJadeNormal);
    JadeTile tile;
    float along;
#if NUM_DIR_LIGHTS > 0
#pragma unroll_loop_start
    for (int i = 0; i < NUM_DIR_LIGHTS; i++) {
        jadeDirectional(directionalLights[i].direction, directionalLights[i].color, l, e);
        vJadeLobeDir[i] = jadeLobe(l, v);
        tile = JadeTile(jadeTileMatrix[i], jadeTileInfo[i], jadeTileDepth[i], jadeTileOrigin[i]);
        // mesh.vert's out_path (PATH_PER_VERTEX): transmitter_path per vertex, interpolated.
        // The light's path to this vertex, read once for its path t and its gather.
        along = tile.info.z > 0.5 ? jadeLightPath(jadeTileLayers[i], tile, p.xyz) : 0.0;
#if JADE_PATH_PER_VERTEX == 1
        vJadePathDir[i] = max(jadeThickness, along);
#else
        vJadePathDir[i] = 0.0;
#endif
        if (diffused && tile.info.z > 0.5 && jadeMayTransmit(directionalLights[i].direction, false, vJadeCentre))
            vJadeDiffused += jadeDiffusedLight(jadeTileLayers[i], tile, l, e, p.xyz, n, turn, along);
    }
#pragma unroll_loop_end
#endif
#if NUM_POINT_LIGHTS > 0
#pragma unroll_loop_start
    for (int i = 0; i < NUM_POINT_LIGHTS; i++) {
        jadePoint(pointLights[i].position, pointLights[i].color, p.xyz, l, e);
        vJadeLobePoint[i] = jadeLobe(l, v);
        tile = JadeTile(jadeTileMatrix[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], jadeTileInfo[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX],
                        jadeTileDepth[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], jadeTileOrigin[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX]);
        along = tile.info.z > 0.5 ? jadeLightPath(jadeTileLayers[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], tile, p.xyz) : 0.0;
#if JADE_PATH_PER_VERTEX == 1
        vJadePathPoint[i] = max(jadeThickness, along);
#else
        vJadePathPoint[i] = 0.0;
#endif
        if (diffused && tile.info.z > 0.5)
            vJadeDiffused += jadeDiffusedLight(jadeTileLayers[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], tile, l, e, p.xyz, n, turn, along);
    }
#pragma unroll_loop_end
#endif
    gl_Position = projectionMatrix * p;
}
`;

export const fragmentShader = /* glsl */ `
#include <common>
${commonChunk}
${varyings}
// Translucency (translucency.glsl, EVAL = kEvalAlu, SMALL_SIGMA = 0.3): what one fragment needs
// of t, per channel. JADE_TERMS Fourier terms and JADE_SMALL_T (the closed form for small t) are
// chosen per mesh as Jade's choose_terms does (JadeTranslucentMaterial.setSmallestVariance).
struct JadeTranslucency {
    vec3 half_decay;  // e^{-t/2}/2, the coefficient of cos
    vec3 decay[6];    // e^{-2k^2 t}, k = 1 ... 6
    vec3 t, sigma, inv_sigma;
};

// translucency_setup (translucency.glsl), the ALU path.
JadeTranslucency jadeTranslucencySetup(vec3 t)
{
    t = clamp(t, vec3(0.0), vec3(25.0));
    JadeTranslucency r;
    vec3 q = exp(-2.0 * t), q2 = q * q, odd = q, power = q;
    for (int k = 0; k < JADE_TERMS; ++k) {
        r.decay[k] = power;
        odd *= q2;
        power *= odd;
    }
    r.half_decay = 0.5 * sqrt(sqrt(q));
    r.t = t;
    r.sigma = sqrt(t);
    r.inv_sigma = 1.0 / max(r.sigma, 1e-12);
    return r;
}

// normal_tail (translucency.glsl): Phi(-|z|) from Abramowitz-Stegun 7.1.26, given e = e^{-z^2/2}.
vec3 jadeNormalTail(vec3 z, vec3 e)
{
    vec3 s = 1.0 / (1.0 + 0.2316419 * abs(z));
    vec3 poly = s * (0.254829592 + s * (-0.284496736 + s * (1.421413741 + s * (-1.453152027 + s * 1.061405429))));
    return 0.5 * poly * e;
}

// translucency_small_t (translucency.glsl): the closed form of {max(cos, 0) * G_t} for small t.
vec3 jadeTranslucencySmallT(float c, JadeTranslucency r)
{
    float a = c * (1.0 + c * c * (1.0 / 6.0 + c * c * (3.0 / 40.0)));
    vec3 z = clamp(a * r.inv_sigma, -8.0, 8.0);
    vec3 e = exp(-0.5 * z * z);
    vec3 tail = jadeNormalTail(z, e);
    vec3 cdf = mix(tail, 1.0 - tail, step(0.0, z));
    vec3 pdf = 0.3989422804 * e;
    float sine = sqrt(max(1.0 - c * c, 0.0));
    return 2.0 * r.half_decay *
           (c * (cdf + 0.5 * r.t * z * pdf) + sine * r.sigma * pdf * (1.0 - r.t * (1.0 / 6.0) * (z * z - 1.0)));
}

// terminator_falloff (translucency.glsl): past the terminator (c < 0) the diffuse light, relative
// to its value there, falls off as the clamped cosine under a Gaussian of variance spread.
vec3 jadeTerminatorFalloff(float c, vec3 spread)
{
    vec3 z = min(asin(min(-c, 1.0)) * inversesqrt(max(spread, vec3(1e-8))), vec3(12.0));
    vec3 e = exp(-0.5 * z * z);
    return max(e - 2.5066283 * z * jadeNormalTail(z, e), vec3(0.0));
}

// translucency (translucency.glsl), the ALU path: F(cos, t) = {max(cos, 0) * G_t}(theta) per
// channel, the Fourier series in cos (Chebyshev recursion), the closed form where sqrt(t) < 0.3.
vec3 jadeTranslucency(float c, JadeTranslucency r)
{
    c = clamp(c, -1.0, 1.0);
    float u = 2.0 * c * c - 1.0, previous = 1.0, current = u;
    vec3 f = 1.0 / JADE_PI + r.half_decay * c;
    for (int k = 1; k <= JADE_TERMS; ++k) {
        float kk = float(k * k);
        float weight = ((k % 2) == 1 ? 2.0 : -2.0) / (JADE_PI * (4.0 * kk - 1.0));
        f += (weight * current) * r.decay[k - 1];
        float next = 2.0 * u * current - previous;
        previous = current;
        current = next;
    }
#if JADE_SMALL_T == 1
    f = mix(f, jadeTranslucencySmallT(c, r), lessThan(r.sigma, vec3(0.3)));
#endif
    return f;
}

// boundary_transmittance (shading.glsl): 1 - Schlick's Fresnel, grazing value max(1 - alpha, F0).
float jadeBoundaryTransmittance(float cos_theta)
{
    float f0 = jadeSpecular.x, grazing = max(1.0 - jadeSpecular.y, f0);
    float m = 1.0 - clamp(cos_theta, 0.0, 1.0), m2 = m * m;
    return 1.0 - (f0 + (grazing - f0) * (m2 * m2 * m));
}

// specular_lobe (mesh.frag): GGX D, Smith height-correlated V, Schlick F, times cos theta_l.
float jadeSpecularLobe(vec3 n, vec3 v, vec3 l, float n_dot_l)
{
    float alpha = jadeSpecular.y, f0 = jadeSpecular.x;
    vec3 h = normalize(v + l);
    float n_dot_v = max(dot(n, v), 1e-4), n_dot_h = max(dot(n, h), 0.0), v_dot_h = max(dot(v, h), 0.0);
    float a2 = alpha * alpha;
    float denom = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    float d = a2 / (JADE_PI * denom * denom);
    float vis = 0.5 / (n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2) + n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2));
    float f = f0 + (1.0 - f0) * pow(1.0 - v_dot_h, 5.0);
    return d * vis * f * n_dot_l;
}

// forward_attenuation (attenuation.glsl): the forward part's attenuation along a path t,
// computed here rather than read from Jade's table of it (transmission_table.comp tabulates the
// same formula).
vec3 jadeForwardAttenuation(float t) { return jadeExtinction.w * (t > 0.0 ? exp(-jadeExtinction.rgb * t) : vec3(1.0)); }

// transmitted_light (transmission.glsl): the forward part; t is the path along the light
// (transmitter_path: the longer of the thickness and jadeLightPath for the light with layers,
// else the thickness). The diffused part is per vertex (jadeDiffusedLight, vJadeDiffused).
vec3 jadeTransmittedLight(vec3 l, vec3 e, vec3 n, float lobe, float t)
{
    float n_dot_l = dot(n, l);
    float entry = jadeShape.w > 0.0 ? jadeBoundaryTransmittance(-n_dot_l) : 1.0;
    float follow = (1.0 - jadeShape.z) + jadeShape.z * max(-n_dot_l, 0.0);  // transmitter_follow
    return entry * follow * lobe * jadeForwardAttenuation(t) * e;
}

// main (mesh.frag), MODE = kTm: one light's diffuse and specular light, and its transmission.
// visibility: the light's shadow (1: none); path: its path through the object (transmitter_path).
void jadeAddLight(vec3 l, vec3 e, bool transmits, vec3 visibility, float path, float lobe, vec3 n, vec3 n_diffuse,
                  vec3 v, float exit_transmittance, JadeTranslucency tr, inout vec3 color)
{
    float c = dot(n, l), c_diffuse = dot(n_diffuse, l);
    vec3 unshadowed = e;  // the transmitted light crossed the occluder: not shadowed
    e *= visibility;
    // diffuse_response (mesh.frag): with the spread model the blur stops at the terminator.
    bool falloff = c_diffuse < 0.0 && jadeSpecular.w > 0.0;
    vec3 f = jadeTranslucency(falloff ? 0.0 : c_diffuse, tr);
    if (falloff) f *= jadeTerminatorFalloff(c_diffuse, vJadeNormalSpread);
    vec3 diffuse = jadeAlbedoStrength.rgb * (1.0 / JADE_PI) * f * e;
    if (jadeShape.w > 0.0) diffuse *= jadeBoundaryTransmittance(c_diffuse) * exit_transmittance;
    color += diffuse;
    if (c > 0.0 && jadeSpecular.z > 0.0) color += jadeSpecular.z * jadeSpecularLobe(n, v, l, c) * e;
    if (transmits && jadeTransmission > 0.5)
        color += exit_transmittance * jadeTransmittedLight(l, unshadowed, n, lobe, path);
}

void main()
{
    vec3 n = normalize(vJadeNormal);
    vec3 sn = vJadeScatteringNormal;
    vec3 n_diffuse = dot(sn, sn) > 1e-12 ? normalize(sn) : n;
    vec3 v = normalize(-vJadePosition);
    float exit_transmittance = jadeShape.w > 0.0 ? jadeBoundaryTransmittance(dot(n, v)) : 1.0;
    JadeTranslucency tr = jadeTranslucencySetup(vJadeVariance);
    vec3 color = vec3(0.0), l, e;
    vec3 visibility = vec3(1.0);
    float path;
    bool tiled;
    JadeTile tile;
#if NUM_DIR_LIGHTS > 0
#pragma unroll_loop_start
    for (int i = 0; i < NUM_DIR_LIGHTS; i++) {
        jadeDirectional(directionalLights[i].direction, directionalLights[i].color, l, e);
        tile = JadeTile(jadeTileMatrix[i], jadeTileInfo[i], jadeTileDepth[i], jadeTileOrigin[i]);
        tiled = tile.info.z > 0.5;
#if JADE_SHADOWS == 1
        visibility = tiled ? jadeSoftShadowVisibility(jadeTileLayers[i], tile, vJadePosition, n, l, gl_FragCoord.xy) : vec3(1.0);
#endif
#if JADE_PATH_PER_VERTEX == 1
        path = tiled ? vJadePathDir[i] : vJadeThickness;
#else
        path = tiled ? max(vJadeThickness, jadeLightPath(jadeTileLayers[i], tile, vJadePosition)) : vJadeThickness;
#endif
        jadeAddLight(l, e, jadeMayTransmit(directionalLights[i].direction, false, vJadeCentre), visibility, path,
                     vJadeLobeDir[i], n, n_diffuse, v, exit_transmittance, tr, color);
    }
#pragma unroll_loop_end
#endif
#if NUM_POINT_LIGHTS > 0
#pragma unroll_loop_start
    for (int i = 0; i < NUM_POINT_LIGHTS; i++) {
        jadePoint(pointLights[i].position, pointLights[i].color, vJadePosition, l, e);
        tile = JadeTile(jadeTileMatrix[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], jadeTileInfo[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX],
                        jadeTileDepth[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], jadeTileOrigin[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX]);
        tiled = tile.info.z > 0.5;
        visibility = vec3(1.0);
#if JADE_SHADOWS == 1
        if (tiled) visibility = jadeSoftShadowVisibility(jadeTileLayers[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], tile, vJadePosition, n, l,
                                                 gl_FragCoord.xy);
#endif
#if JADE_PATH_PER_VERTEX == 1
        path = tiled ? vJadePathPoint[i] : vJadeThickness;
#else
        path = tiled ? max(vJadeThickness, jadeLightPath(jadeTileLayers[NUM_DIR_LIGHTS + UNROLLED_LOOP_INDEX], tile, vJadePosition))
                     : vJadeThickness;
#endif
        jadeAddLight(l, e, true, visibility, path, vJadeLobePoint[i], n, n_diffuse, v, exit_transmittance, tr, color);
    }
#pragma unroll_loop_end
#endif
    // The diffused light leaves as a Lambertian emitter: its exitance / pi (mesh.frag).
    if (jadeTransmission > 0.5) color += exit_transmittance * (1.0 / JADE_PI) * vJadeDiffused;
    gl_FragColor = vec4(color, 1.0);
#include <tonemapping_fragment>
#include <colorspace_fragment>
}
`;
