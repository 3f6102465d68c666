// shading_interface.h - what the draw's C++ (engine/src/shading) and mesh.vert/mesh.frag must
// agree on, written once: the push constants, the frame constants and their array sizes.
//
// Included by the shaders (through shading.glsl) and by C++ (shading/mesh_pipeline.hpp). In C++
// the structs live in jade::shading and the GLSL types are spelt with GLM. The shaders declare
//     layout(push_constant, scalar) uniform FramePushBlock { FramePush frame; };
//     layout(binding = 0, scalar) uniform FrameDataBlock { FrameData data; };
// Scalar layout places these members (vec4, mat4, a vec3 then a uint) exactly where C++ does;
// sizes are checked in C++.
#ifndef JADE_SHADING_INTERFACE_H
#define JADE_SHADING_INTERFACE_H

#define JADE_MAX_LIGHTS 64                      // lights per draw
#define JADE_MAX_TRANSMITTERS 4                 // lights drawn with transmission per draw (transmission.glsl)
#define JADE_MAX_LIGHT_DEPTH_TILES 4            // lights with a depth tile (shading/light_depth.hpp)
#define JADE_COLOR_MAP_STOPS 9                  // false-colour stops
#define JADE_SEPARABLE_MAX_TAPS 25              // taps of one 1-D pass of the separable mode (11, 17 or 25)
#define JADE_SEPARABLE_TRANSMITTANCE_STEPS 128  // entries of its transmittance profile
#define JADE_BURLEY_MAX_SAMPLES 80              // samples a pixel of the Burley mode (HDRP's high)
#define JADE_SOFT_SHADOW_TAPS 16                // taps of the t_m mode's profile-shaped shadow filter (shadow.glsl)

// Shading modes, the specialisation constant MODE of mesh.vert and mesh.frag: jade::ShadingMode's
// values (shading/mesh_pipeline.hpp asserts they match; the public enum cannot include this
// private header). 4 … 6 are the peers' modes (docs/peers.md). MODE = JADE_MODE_INPUTS + k, k <
// JADE_INPUTS_SLOTS, is the inputs pass: it writes the k-th vec4 of the rasterised shading inputs
// (Renderer::shading_inputs) instead of shading; it lies past every ShadingMode.
#define JADE_MODE_LAMBERT 0
#define JADE_MODE_CURVATURE 1
#define JADE_MODE_TM 2
#define JADE_MODE_FALSE_COLOR 3
#define JADE_MODE_FILAMENT 4
#define JADE_MODE_SEPARABLE 5
#define JADE_MODE_BURLEY 6
#define JADE_MODE_INPUTS 8
#define JADE_INPUTS_SLOTS 7

// How the Tm mode evaluates F(cos θ, t), the specialisation constant EVAL (translucency.glsl):
// jade::TmEvaluation's values (asserted in shading/mesh_pipeline.hpp).
#define JADE_EVAL_LUT 1           // the LUT as RGBA32F quads in a texel buffer
#define JADE_EVAL_LUT_FILTERED 2  // the LUT as R16_UNORM, hardware-filtered
#define JADE_EVAL_ALU 3           // no memory read: Fourier series and a closed form

#ifdef __cplusplus
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace jade::shading {
namespace glsl {
using uint = std::uint32_t;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
}  // namespace glsl
using namespace glsl;  // only these names: the structs below are written in GLSL's words
#endif

// One vertex of the renderer's interleaved vertex buffer: mesh.vert's attributes
// (shading/mesh_pipeline.cpp gives their offsets) and what pack_vertices.comp writes.
struct Vertex {
    vec3 position;
    vec3 normal;
    vec3 tm;
    float curvature;
    float thickness;
    vec3 scattering_normal;  // BakeResult::scattering_normal: what the translucent diffuse term is lit along
    vec3 normal_spread;      // BakeResult::normal_spread, per channel
};

// transmission_table.comp's push constants (shading/transmission_table.cpp): the medium's
// coefficients as forward_attenuation() takes them, and the table's spacing and length.
struct TablePush {
    vec4 extinction;  // σ_t (1/mesh unit), w_b
    float step;       // mesh units between texels
    uint count;
};

// pack_vertices.comp's push constants (Renderer::record_vertex_update).
struct PackPush {
    uint vertex_count;
    uint has_thickness;          // 1: the thickness stream is copied too
    uint has_scattering_normal;  // 1: the scattering normal and spread come from DynamicBake's normal sums
};

struct FramePush {
    mat4 view_proj;  // world (mesh units) to clip space, y already flipped for Vulkan
    vec3 eye;        // camera position, mesh units
    uint light_count;
};

struct GpuLight {
    vec4 vector;  // xyz: towards the light (w = 0) or its position (w = 1)
    vec4 color;   // rgb: irradiance (directional) or intensity (point); w: the light's depth tile + 1, 0 none
};

// One light's depth tile (shading/light_depth.hpp): where its layers are and how to read them.
// A directional light's tile is orthographic and stores the depth in clip space (linear along the
// light); a point light's is perspective and stores the distance from the light along its ray,
// (|x − origin| − near) / range: both are lengths along the light's own rays, in units of range.
struct LightTile {
    mat4 view_proj;  // world → light clip space (x, y ∈ [−1, 1] over the tile after the divide by w)
    vec4 origin;     // xyz: the point light's position; w: 1 perspective (point), 0 orthographic
    vec4 depth;      // near (mesh units, perspective), range (mesh units per stored unit), texel (mesh units across
                     // one texel; perspective: per unit of distance from the light), w: unused
};

struct FrameData {
    vec4 albedo_strength;     // k_d (linear RGB), strength (variance per unit t_m)
    vec4 specular;            // F0, α = roughness², weight; Material::spread_strength (rad² per unit spread)
    vec4 lut_map;             // translucency LUT quads: column cos θ·x + x, x = (W−1)/2; y = W − 1 quads
                              // a row; row (t / t_max)^¼ · z, z = H − 1; w = H − 2 the last row of quads
    vec4 curvature_map;       // curvature LUT: u = cos θ · x + y, v = s / (1 + s) · z + w
    vec4 params;              // 1 / t_max, d̄ (curvature length, mesh units), false-colour min, 1 / range
    vec4 transmission_shape;  // lobe exponent n, (n + 1)/(2π), normal_mix, 1: diffuse × boundary transmittance
    vec4 light_depth_map;     // light-depth tile size (texels), tiles in the atlas, unused, unused
    vec4 subsurface;          // Filament mode: subsurfaceColor (linear RGB), subsurfacePower (filament.glsl)
    vec4
        subsurface_thickness;  // Filament mode: thickness = min(t̄ · x, 1) (x in 1/mesh unit), or y when y ≥ 0; zw unused
    LightTile light_tiles[JADE_MAX_LIGHT_DEPTH_TILES];  // per tile of the atlas (GpuLight::color.w − 1)
    vec4 color_map[JADE_COLOR_MAP_STOPS];               // false-colour stops, linear RGB
    vec4 transmission_table_map;  // 1 / step of the attenuation table (mesh units), last texel, last interval, unused
    // The diffused part of the transmission (transmission.glsl, diffused_light): the diffusion
    // dipole of Jensen et al. 2001 per channel, from Transmission (shading/frame.cpp).
    vec4 dipole_albedo;    // rgb: α'/(4π); w: Transmission::diffusion_weight (0: no gather)
    vec4 dipole_sigma;     // rgb: σ_tr (1/mesh unit); w: the gather's reach past the light's path, 3/min σ_tr
    vec4 dipole_real;      // rgb: z_r = 1/σ_t', the source's depth (mesh units); w: unused
    vec4 dipole_boundary;  // rgb: z_b = 2AD, the extrapolated boundary's distance (mesh units); w: unused
    GpuLight transmitters[JADE_MAX_TRANSMITTERS];  // the lights drawn with transmission (transmission.glsl)
    // The t_m mode's shadow filter (shadow.glsl, shading::soft_shadow_kernel): x the kernel's
    // median radius (mesh units; 0 for a material without a profile: a texel), yzw unused; per
    // tap, its offset on the golden-angle disk (xy = r (cos, sin) of i times the golden angle,
    // z = r, in median radii) and its weight per channel (rgb, R_c(r)/pdf(r), each channel
    // summing to 1).
    vec4 soft_shadow;
    vec4 soft_shadow_taps[JADE_SOFT_SHADOW_TAPS];
    vec4 soft_shadow_weights[JADE_SOFT_SHADOW_TAPS];
    GpuLight lights[JADE_MAX_LIGHTS];
};

// The Separable mode's constants (shading/separable.hpp, jade/separable.hpp): the kernel of its two
// 1-D blur passes and SSSSTransmittance's profile, both from the material's own profiles. Bound
// to every mesh pipeline (binding 6: mesh.frag reads the transmittance) and to the blur passes.
struct SeparableData {
    vec4 taps[JADE_SEPARABLE_MAX_TAPS];  // rgb: weight per channel (each channel sums to 1); w: offset, mesh units
    // rgb: 1 − cdf(d_i) per channel at d_i = reach · (i / (STEPS − 1))², denser near 0 where the
    // narrow channels fall fastest
    vec4 transmittance[JADE_SEPARABLE_TRANSMITTANCE_STEPS];
    vec4 params;  // x: 1 / the table's reach (1/mesh units); y: the kernel's range (mesh units); z, w: unused
    // The Burley mode (jade/burley_diffusion.hpp): rgb the Burley shape d per channel, w the shape
    // sampled (the widest channel's), mesh units; sample i's radius at [i / 4][i % 4], mesh units.
    vec4 burley;
    vec4 burley_radius[JADE_BURLEY_MAX_SAMPLES / 4];
};

// The push constants of the separable blur passes (separable_blur.frag).
struct SeparablePush {
    vec4 texel;  // xy: 1 / the image's size (texture coordinates of one pixel); z: pixels per mesh unit at linear
                 // depth 1, height / (2 tan(fov_y / 2)); w: 1 / the depth difference (mesh units) at which a tap
                 // is replaced by the centre (follow-surface)
};

#ifdef __cplusplus
static_assert(sizeof(SeparableData) ==
              (JADE_SEPARABLE_MAX_TAPS + JADE_SEPARABLE_TRANSMITTANCE_STEPS + 2 + JADE_BURLEY_MAX_SAMPLES / 4) * 16);
static_assert(sizeof(Vertex) == 68 && sizeof(TablePush) == 24 && sizeof(PackPush) == 12 && sizeof(FramePush) == 80 &&
              sizeof(GpuLight) == 32 && sizeof(LightTile) == 96);
static_assert(sizeof(FrameData) == 9 * 16 + JADE_MAX_LIGHT_DEPTH_TILES * 96 + JADE_COLOR_MAP_STOPS * 16 + 16 + 4 * 16 +
                                       (JADE_MAX_TRANSMITTERS + JADE_MAX_LIGHTS) * 32 +
                                       (1 + 2 * JADE_SOFT_SHADOW_TAPS) * 16,
              "FrameData must have no padding: scalar layout packs it so");
}  // namespace jade::shading
#endif

#endif
