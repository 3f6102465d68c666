// shading/mesh_pipeline.hpp - what the renderer's draw hands the GPU (the host mirrors of
// shaders/include/shading.glsl), and which mesh.vert/mesh.frag pipeline variant a draw takes:
// the specialisation constants (mode, channels, transmission slots, evaluation path, Fourier
// terms) and the rules that pick them (docs/shading.md, "Evaluation paths").
#pragma once

#include "gpu/pipeline.hpp"
#include "shading/buffer_estimate.hpp"  // kRendererVertexBytes, kRendererFrameDataBytes
#include "shading/light_depth.hpp"

#include <jade/dev/renderer.hpp>
#include <jade/render.hpp>

#include "shading_interface.h"  // FramePush, GpuLight, FrameData, shared with the shaders

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <map>

namespace jade::shading {

inline constexpr uint32_t kMaxLights = JADE_MAX_LIGHTS;
/// Mode constant of the inputs pass: kInputsMode + k writes the k-th vec4 of the inputs (shading_interface.h).
inline constexpr uint32_t kInputsMode = JADE_MODE_INPUTS, kInputsSlots = JADE_INPUTS_SLOTS;
// The public enums cannot include shading_interface.h: their values are checked against it here.
static_assert(uint32_t(ShadingMode::Lambert) == JADE_MODE_LAMBERT &&
              uint32_t(ShadingMode::Curvature) == JADE_MODE_CURVATURE && uint32_t(ShadingMode::Tm) == JADE_MODE_TM &&
              uint32_t(ShadingMode::TmFalseColor) == JADE_MODE_FALSE_COLOR &&
              uint32_t(ShadingMode::Filament) == JADE_MODE_FILAMENT &&
              uint32_t(ShadingMode::Separable) == JADE_MODE_SEPARABLE &&
              uint32_t(ShadingMode::Burley) == JADE_MODE_BURLEY);
static_assert(uint32_t(TmEvaluation::Lut) == JADE_EVAL_LUT &&
              uint32_t(TmEvaluation::LutFiltered) == JADE_EVAL_LUT_FILTERED &&
              uint32_t(TmEvaluation::Alu) == JADE_EVAL_ALU);
/// Lights drawn with transmission per draw: the first that may shine through (transmission.glsl).
inline constexpr uint32_t kMaxTransmitters = JADE_MAX_TRANSMITTERS;

// Vertex, FramePush, GpuLight and FrameData: shaders/include/shading_interface.h.
static_assert(sizeof(Vertex) == kRendererVertexBytes && sizeof(FrameData) == kRendererFrameDataBytes);

/// The specialisation constants of one mesh pipeline.
struct MeshVariant {
    uint32_t mode = 0;          ///< ShadingMode, or kInputsMode + k
    uint32_t channels = 3;      ///< 1: grey material
    uint32_t transmission = 0;  ///< lights drawn with transmission (FrameData::transmitters)
    TmEvaluation evaluation = TmEvaluation::Lut;
    uint32_t terms = 5;            ///< Alu: Fourier terms
    bool small_t = true;           ///< Alu: the closed form for √t < kSmallSigma is needed
    bool path_per_vertex = false;  ///< transmission: the light's path in mesh.vert (LightPathSampling)
    bool shadows = false;          ///< the lights' diffuse and specular light is shadowed (shadow.glsl)
    uint64_t key(VkFormat format, uint32_t samples) const;
};

/// Alu: the closed form is used where √t is below this; above it the series with kMaxTerms
/// terms errs by at most 7e-6, below it the closed form by at most 4e-5 (docs/shading.md).
inline constexpr float kSmallSigma = 0.3f;
inline constexpr uint32_t kMaxTerms = 5;
/// Alu: the fewest Fourier terms whose first omitted term stays below 2e-5 for every t ≥ t_min
/// (and whether t_min needs the closed form too). t_min = 0 when not known (a GPU-updated mesh).
void choose_terms(double t_min, MeshVariant& variant);

/// What TmEvaluation::Auto means on a device of this type: Alu on a CPU (lavapipe: every memory
/// read is a gather of its own, arithmetic is SIMD), LutFiltered wherever there are texture units.
TmEvaluation resolve_evaluation(TmEvaluation requested, VkPhysicalDeviceType type);
TmEvaluation resolve_evaluation(TmEvaluation requested, const gpu::Context& ctx);  ///< for ctx's device

/// LightPathSampling::Auto: per vertex where the mesh's median edge spans at most this many
/// texels of a light's depth tile. Measured (docs/shading.md): the fidelity scenes' meshes of
/// 2.1 … 6.8 texels gave the same FLIP (±0.001) and thin-region radiance (±1 %) either way; the
/// fist, 14 texels, lost a fifth of its thumb tip's glow per vertex.
inline constexpr double kLightPathVertexTexels = 8.0;
/// What `requested` means for a mesh with this median edge length and bounding radius (mesh
/// units) and depth tiles of `tile_size` texels (2·LightDepth::kMargin radii across).
dev::LightPathSampling resolve_light_path(dev::LightPathSampling requested, double median_edge, double radius,
                                          uint32_t tile_size);

/// A light as the shaders read it; w of the colour as given (the transmitters' depth tile).
inline GpuLight gpu_light(const Light& l, float w)
{
    return {glm::vec4(l.vector, l.type == Light::Type::Point ? 1.0f : 0.0f), glm::vec4(l.color, w)};
}

/// The pipelines of one renderer, made on first use per (variant, colour format, samples).
class MeshPipelines {
public:
    explicit MeshPipelines(gpu::Context& ctx) : ctx_(ctx) {}
    const gpu::GraphicsPipeline& get(const MeshVariant& variant, VkFormat format, uint32_t samples);

private:
    gpu::Context& ctx_;
    std::map<uint64_t, gpu::GraphicsPipeline> pipelines_;
};

}  // namespace jade::shading
