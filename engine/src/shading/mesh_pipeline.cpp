// shading/mesh_pipeline.cpp - the mesh pipeline variants and the rules that choose them
// (mesh_pipeline.hpp).
#include "shading/mesh_pipeline.hpp"

#include "gpu/context.hpp"
#include "shading/separable.hpp"

#include <jade/dev/names.hpp>
#include <jade/dev/renderer.hpp>
#include <jade/error.hpp>

#include "jade_shaders.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>

namespace jade {

std::string_view tm_evaluation_name(TmEvaluation evaluation)
{
    switch (evaluation) {
    case TmEvaluation::Auto: return "auto";
    case TmEvaluation::Lut: return "lut";
    case TmEvaluation::LutFiltered: return "lut16";
    case TmEvaluation::Alu: return "alu";
    }
    return "unknown";
}

TmEvaluation parse_tm_evaluation(std::string_view name)
{
    for (TmEvaluation e : {TmEvaluation::Auto, TmEvaluation::Lut, TmEvaluation::LutFiltered, TmEvaluation::Alu})
        if (name == tm_evaluation_name(e)) return e;
    throw Error("unknown t_m evaluation '" + std::string(name) + "' (known: auto, lut, lut16, alu)");
}

std::string_view dev::light_path_sampling_name(LightPathSampling sampling)
{
    switch (sampling) {
    case dev::LightPathSampling::Auto: return "auto";
    case dev::LightPathSampling::PerVertex: return "vertex";
    case dev::LightPathSampling::PerFragment: return "fragment";
    }
    return "unknown";
}

dev::LightPathSampling dev::parse_light_path_sampling(std::string_view name)
{
    for (LightPathSampling s :
         {dev::LightPathSampling::Auto, dev::LightPathSampling::PerVertex, dev::LightPathSampling::PerFragment})
        if (name == dev::light_path_sampling_name(s)) return s;
    throw Error("unknown light path sampling '" + std::string(name) + "' (known: auto, vertex, fragment)");
}

}  // namespace jade

namespace jade::shading {

uint64_t MeshVariant::key(VkFormat format, uint32_t samples) const
{
    return uint64_t(mode) | uint64_t(channels) << 4 | uint64_t(transmission) << 6 | uint64_t(evaluation) << 11 |
           uint64_t(terms) << 14 | uint64_t(small_t) << 18 | uint64_t(path_per_vertex) << 19 | uint64_t(samples) << 20 |
           uint64_t(shadows) << 28 | uint64_t(format) << 32;
}

void choose_terms(double t_min, MeshVariant& variant)
{
    // The series' error is about its first omitted term, (2/π) e^{−2(K+1)²t} / (4(K+1)² − 1),
    // largest at the smallest t (measured against jade::lut_reference, docs/shading.md).
    constexpr double kBudget = 2e-5;
    const double t = std::max(t_min, 0.0);
    variant.small_t = t < double(kSmallSigma) * double(kSmallSigma);
    variant.terms = kMaxTerms;
    if (variant.small_t) return;
    for (uint32_t k = 1; k < kMaxTerms; ++k) {
        const double next = double(k + 1) * double(k + 1);
        if (2.0 / std::numbers::pi * std::exp(-2.0 * next * t) / (4.0 * next - 1.0) <= kBudget) {
            variant.terms = k;
            return;
        }
    }
}

TmEvaluation resolve_evaluation(TmEvaluation requested, VkPhysicalDeviceType type)
{
    if (requested != TmEvaluation::Auto) return requested;
    return type == VK_PHYSICAL_DEVICE_TYPE_CPU ? TmEvaluation::Alu : TmEvaluation::LutFiltered;
}

TmEvaluation resolve_evaluation(TmEvaluation requested, const gpu::Context& ctx)
{
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(ctx.physical_device(), &p);
    return resolve_evaluation(requested, p.deviceType);
}

dev::LightPathSampling resolve_light_path(dev::LightPathSampling requested, double median_edge, double radius,
                                          uint32_t tile_size)
{
    if (requested != dev::LightPathSampling::Auto) return requested;
    const double texel = 2.0 * double(LightDepth::kMargin) * radius / double(std::max(tile_size, 1u));
    return median_edge <= kLightPathVertexTexels * texel ? dev::LightPathSampling::PerVertex
                                                         : dev::LightPathSampling::PerFragment;
}

const gpu::GraphicsPipeline& MeshPipelines::get(const MeshVariant& v, VkFormat format, uint32_t samples)
{
    auto [it, inserted] = pipelines_.try_emplace(v.key(format, samples));
    if (!inserted) return it->second;
    try {
        gpu::GraphicsPipelineDesc d;
        d.name = "mesh";
        d.vertex_spirv = shaders::mesh_vert();
        d.fragment_spirv = shaders::mesh_frag();
        d.color_formats = {format};
        if (v.mode == uint32_t(ShadingMode::Separable) || v.mode == uint32_t(ShadingMode::Burley))
            d.color_formats.push_back(kSeparableIrradianceFormat);
        d.depth_format = VK_FORMAT_D32_SFLOAT;
        d.samples = VkSampleCountFlagBits(samples);
        d.vertex_stride = sizeof(Vertex);
        d.attributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                        {1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                        {2, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, tm)},
                        {3, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, curvature)},
                        {4, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, thickness)},
                        {5, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, scattering_normal)},
                        {6, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal_spread)}};
        d.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,         VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER,
                      VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER};  // 6: SeparableData
        d.push_size = sizeof(FramePush);
        // constant_id 0 … 8 of mesh.vert/mesh.frag (shading.glsl, transmission.glsl, translucency.glsl,
        // shadow.glsl).
        d.constants = {v.mode,
                       v.channels,
                       v.transmission,
                       uint32_t(v.evaluation),
                       v.terms,
                       v.small_t ? 1u : 0u,
                       std::bit_cast<uint32_t>(kSmallSigma),
                       v.path_per_vertex ? 1u : 0u,
                       v.shadows ? 1u : 0u};
        it->second = gpu::GraphicsPipeline(ctx_, d);
    } catch (...) {
        pipelines_.erase(it);
        throw;
    }
    return it->second;
}

}  // namespace jade::shading
