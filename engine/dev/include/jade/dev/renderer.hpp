// jade/dev/renderer.hpp - the renderer's study knobs and introspection, for the CLI, tools and
// tests (an embedder needs none of it): the LUT sizes, Tm evaluation paths and light path
// sampling a Renderer is built with (RendererStudy), what its shading reads per pixel, its LUT and curvature as built, the
// mean curvature, the Filament peer's parameters and the back-light preset of `jade bench`.
// Declared for jade::dev, defined in jade::jade.
#pragma once

#include <jade/dev/lut.hpp>
#include <jade/render.hpp>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace jade {

/// How the Tm mode evaluates F(cos θ, t) (docs/shading.md: costs, errors, the rule of Auto).
/// Every path keeps the final 8-bit sRGB image within 0.5 of a level (99th percentile) and 1
/// level (max) of a float64 evaluation of the same shading (tests/test_shading_error.cpp).
enum class TmEvaluation : uint32_t {
    Auto = 0,         ///< by the device: Alu on a CPU device (lavapipe), LutFiltered on any other
    Lut = 1,          ///< the LUT as RGBA32F quads in a texel buffer, bilinear in the shader, 1 fetch a read
    LutFiltered = 2,  ///< the LUT in R16_UNORM, one hardware-filtered sample a read (texture units)
    Alu = 3,          ///< no memory read: Fourier series in cos θ and a closed form for small t
};
/// "auto", "lut", "lut16", "alu".
std::string_view tm_evaluation_name(TmEvaluation evaluation);
/// The inverse of tm_evaluation_name; throws jade::Error listing the names.
TmEvaluation parse_tm_evaluation(std::string_view name);

/// What the Tm shading of each pixel reads, as rasterised with one sample per pixel at its
/// centre (dev::shading_inputs): to check the shader against an independent evaluation.
/// Per pixel, rows top to bottom; `path` is light-major (light k's pixel p at k·w·h + p).
struct ShadingInputs {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> position;           ///< xyz: mesh units; w: 1 where the mesh covers the pixel, 0 elsewhere
    std::vector<glm::vec4> normal;             ///< xyz: interpolated vertex normal (not unit); w: thickness
    std::vector<glm::vec4> tm;                 ///< rgb: interpolated t_m; w: curvature
    std::vector<glm::vec4> scattering_normal;  ///< xyz: interpolated scattering normal (not unit); w: 0
    std::vector<glm::vec4> normal_spread;      ///< rgb: interpolated normal spread; w: 0
    std::vector<glm::vec4> diffused;           ///< rgb: the transmitting lights' diffused exitance, summed (its
                                               ///< radiance is it / π times the crossing out); w: 0
    std::vector<float> path;                   ///< the path t (mesh units) of each transmitting light's attenuation
    std::vector<uint8_t> transmits;            ///< per light: 1 when the draw adds its transmission
};

/// What ShadingMode::Filament feeds Filament's subsurface model (shaders/include/filament.glsl),
/// derived from the material's medium (Material::transmission.sigma_tr, docs/peers.md):
/// - thickness = min(t̄ · thickness_per_unit, 1), t̄ the baked thickness (mesh units) and
///   thickness_per_unit = σ_min / 2, σ_min the smallest positive σ_tr,c: Filament's BTDF falls
///   as (1 − thickness), and a ramp 1 − t/L carries the same total ∫ dt as the diffusion's
///   transmittance e^{−σ_min t} for L = 2/σ_min;
/// - subsurfaceColor_c = (1 − k_d,c) · σ_min / σ_tr,c (σ_min/σ_tr,c = 1 where σ_tr,c = 0): the
///   share of the light that the surface does not reflect diffusely (k_d = Material::albedo, the
///   medium's diffuse albedo), the only light there is to cross the part (Filament adds its BTDF
///   to the BRDF, so without it a slab would return more than it receives), with the colour of
///   the ramp matched per channel, ∫ (σ_min/σ_tr,c)(1 − t/L) dt = ∫ e^{−σ_tr,c t} dt;
/// - subsurfacePower = 12.234, Filament's default (nothing in a medium sets a lobe's width).
/// A material without σ_tr (not made from a medium) gets 1 − k_d and thickness_per_unit 0, which
/// the renderer reads as Filament's default constant thickness 0.5.
struct FilamentSubsurface {
    glm::vec3 color{1.0f};
    float power = 12.234f;
    float thickness_per_unit = 0.0f;  ///< 1/mesh unit
};
FilamentSubsurface filament_subsurface(const Material& material);

/// Mean curvature per bake vertex from the cotangent Laplacian: H = −(Δx · n)/2 with
/// Δx_i = 1/(2A_i) Σ_j (cot α_ij + cot β_ij)(x_j − x_i), A_i the vertex area. 1/mesh units,
/// positive where convex (1/R on a sphere of radius R), then `smoothing` iterations of
/// area-weighted 1-ring averaging (scanned meshes are noisy at the scale of one edge).
std::vector<float> mean_curvature(const PreparedMesh& mesh, uint32_t smoothing = 2);

/// Two lights, one behind the object: the key of default_lights (E = 2.5) and the back light of
/// figure1_lights (E = 6), so that the transmission term is drawn (`jade bench render --lights back`).
std::vector<Light> back_lights(const Camera& camera);

namespace dev {

/// Where the Tm mode reads a back light's path inside the object (Transmission: the medium along
/// the light's line, from its depth tile; docs/shading.md "Transmission"). Per vertex saves four
/// gathers per fragment and transmitting light; on a coarse mesh it loses the edges of what the
/// body shadows from the light within a triangle.
enum class LightPathSampling : uint32_t {
    Auto = 0,         ///< PerVertex where the mesh's median edge spans ≤ 8 texels of the tile, else PerFragment
    PerVertex = 1,    ///< in the vertex shader, interpolated
    PerFragment = 2,  ///< per fragment, bilinear between the four nearest texels
};
/// "auto", "vertex", "fragment".
std::string_view light_path_sampling_name(LightPathSampling sampling);
/// The inverse of light_path_sampling_name; throws jade::Error listing the names.
LightPathSampling parse_light_path_sampling(std::string_view name);

/// What RendererOptions::study holds: settings for measuring the renderer's alternatives.
struct RendererStudy {
    LutLayout lut;                                           ///< translucency LUT size (odd width, ≥ 3 × 2)
    TmEvaluation tm_evaluation = TmEvaluation::Auto;         ///< dev::tm_evaluation(renderer) says what Auto chose
    LightPathSampling light_path = LightPathSampling::Auto;  ///< dev::light_path(renderer) says what Auto chose
    uint32_t curvature_lut_width = 129, curvature_lut_height = 64;
};
/// options.study, or the defaults when it is null.
const RendererStudy& study_of(const RendererOptions& options);
/// Sets options.study to a copy of `study`.
void set_study(RendererOptions& options, const RendererStudy& study);

/// The per-pixel inputs of the draw renderer.render(camera, lights, settings) would make, with
/// one sample per pixel (settings.samples is ignored): see ShadingInputs. Submits and waits.
ShadingInputs shading_inputs(Renderer& renderer, const Camera& camera, std::span<const Light> lights,
                             const RenderSettings& settings);
/// The path RendererStudy::tm_evaluation resolved to on this device (never Auto).
TmEvaluation tm_evaluation(const Renderer& renderer);
/// Where RendererStudy::light_path resolved to for the current mesh (never Auto; PerFragment
/// before set_mesh).
LightPathSampling light_path(const Renderer& renderer);
const LutLayout& lut_layout(const Renderer& renderer);  ///< as given in RendererStudy
/// The translucency LUT as the GPU built it, width × height floats, row j = variance(j).
/// Reads back from the GPU (submits and waits).
std::vector<float> read_lut(Renderer& renderer);
/// Signed mean curvature per bake vertex of the current mesh (1/mesh units, > 0 convex).
const std::vector<float>& curvature(const Renderer& renderer);
/// The curvature LUT's length scale d̄ (mesh units): rows are at κ·d̄ = v/(1 − v), v = j/(H − 1).
/// Throws jade::Error before set_material.
double curvature_scale(const Renderer& renderer);

}  // namespace dev
}  // namespace jade
