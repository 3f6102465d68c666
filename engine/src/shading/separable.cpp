// shading/separable.cpp - see separable.hpp.
#include "shading/separable.hpp"

#include "gpu/context.hpp"
#include "shading/frame.hpp"

#include <jade/dev/material.hpp>
#include <jade/dev/burley_diffusion.hpp>
#include <jade/error.hpp>
#include <jade/dev/separable.hpp>

#include "jade_shaders.hpp"

#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace jade::shading {

SeparableData separable_data(const Material& material, uint32_t taps, uint32_t burley_samples)
{
    const SeparableKernel k = separable_kernel(material, taps);
    SeparableData d{};
    // The taps of a shorter kernel first; the shader reads TAPS of them.
    for (uint32_t i = 0; i < taps; ++i) d.taps[i] = glm::vec4(glm::vec3(k.weight[i]), float(k.offset[i]));
    double reach = 0.0;
    for (const ChannelProfile& p : material.profile) reach = std::max(reach, dev::radius_for_tail(p, 1e-4));
    reach = std::max(reach, 1e-30);
    for (uint32_t i = 0; i < JADE_SEPARABLE_TRANSMITTANCE_STEPS; ++i) {
        const double u = double(i) / double(JADE_SEPARABLE_TRANSMITTANCE_STEPS - 1);
        for (int c = 0; c < 3; ++c)
            d.transmittance[i][c] = float(separable_transmittance(material.profile[size_t(c)], reach * u * u));
    }
    d.params = glm::vec4(float(1.0 / reach), float(k.range), 0.0f, 0.0f);
    // Burley: the widest channel's shape is sampled (its samples reach every channel's light).
    const glm::dvec3 shape = burley_shapes(material);
    const double sampled = std::max({shape.x, shape.y, shape.z});
    d.burley = glm::vec4(glm::vec3(shape), float(sampled));
    for (uint32_t i = 0; i < burley_samples; ++i)
        d.burley_radius[i / 4][i % 4] = float(burley_sample_radius((i + 0.5) / burley_samples, sampled));
    return d;
}

VkRect2D screen_bounds(const glm::mat4& view_proj, glm::vec3 lo, glm::vec3 hi, uint32_t width, uint32_t height)
{
    const VkRect2D whole{{0, 0}, {width, height}};
    glm::vec2 a(1e30f), b(-1e30f);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
        const glm::vec4 clip = view_proj * glm::vec4(p, 1.0f);
        if (!(clip.w > 1e-6f)) return whole;  // behind the eye: the box's projection is unbounded
        const glm::vec2 px = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
        a = glm::min(a, px), b = glm::max(b, px);
    }
    const float x0 = std::clamp(std::floor(a.x) - 1.0f, 0.0f, float(width)),
                y0 = std::clamp(std::floor(a.y) - 1.0f, 0.0f, float(height));
    const float x1 = std::clamp(std::ceil(b.x) + 1.0f, 0.0f, float(width)),
                y1 = std::clamp(std::ceil(b.y) + 1.0f, 0.0f, float(height));
    return {{int32_t(x0), int32_t(y0)}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
}

VkRenderingAttachmentInfo SeparablePasses::prepare(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s,
                                                   const Material& material)
{
    if (t.keep && t.resolve)
        throw Error("render target: the separable mode adds its blurred light to the resolved image only; keep with "
                    "a multisampled target would lose it");
    if (!data_) {  // the first separable draw
        data_ =
            gpu::Buffer(ctx_, sizeof(SeparableData),
                        VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, "separable constants");
        sampler_ =
            gpu::make_sampler(ctx_, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "separable sampler");
    }
    if (!profiles_ || *profiles_ != material.profile || taps_ != s.separable_taps ||
        samples_made_ != s.burley_samples) {
        constants_ = separable_data(material, s.separable_taps, s.burley_samples);  // throws for a bad tap count
        profiles_ = material.profile, taps_ = s.separable_taps, samples_made_ = s.burley_samples;
    }
    if (width_ != s.width || height_ != s.height || samples_ != s.samples) {
        // Recorded draws may still read the old images.
        if (irradiance_)
            ctx_.release_after_gpu(std::move(irradiance_msaa_), std::move(irradiance_), std::move(horizontal_));
        constexpr VkImageUsageFlags kTarget = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        irradiance_msaa_ = s.samples > 1
                               ? gpu::Image(ctx_, {"separable irradiance (multisampled)", s.width, s.height,
                                                   kSeparableIrradianceFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                                   VkSampleCountFlagBits(s.samples)})
                               : gpu::Image();
        irradiance_ =
            gpu::Image(ctx_, {"separable irradiance", s.width, s.height, kSeparableIrradianceFormat, kTarget});
        horizontal_ =
            gpu::Image(ctx_, {"separable horizontal pass", s.width, s.height, kSeparableIrradianceFormat, kTarget});
        width_ = s.width, height_ = s.height, samples_ = s.samples;
    }
    // As the frame constants (renderer.cpp): after earlier draws' reads, visible to this one's.
    constexpr VkPipelineStageFlags2 kShaders =
        VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    gpu::memory_barrier(cmd, kShaders, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdUpdateBuffer(cmd, data_.handle(), 0, sizeof(SeparableData), &constants_);
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, kShaders,
                        VK_ACCESS_2_UNIFORM_READ_BIT);
    if (irradiance_msaa_) irradiance_msaa_.transition(cmd, gpu::use::kColorAttachment, true);
    irradiance_.transition(cmd, gpu::use::kColorAttachment, true);
    return irradiance_attachment();
}

VkRenderingAttachmentInfo SeparablePasses::irradiance_attachment() const
{
    VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    a.imageView = irradiance_msaa_ ? irradiance_msaa_.view() : irradiance_.view();
    a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // alpha 0: no surface, the blur passes skip the pixel
    a.storeOp = irradiance_msaa_ ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    a.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    if (irradiance_msaa_) {
        a.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        a.resolveImageView = irradiance_.view();
        a.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    return a;
}

const gpu::GraphicsPipeline& SeparablePasses::pass_pipeline(Pass pass, uint32_t count, VkFormat format)
{
    auto [it, inserted] = pipelines_.try_emplace(uint64_t(count) | uint64_t(pass) << 8 | uint64_t(format) << 16);
    if (!inserted) return it->second;
    try {
        gpu::GraphicsPipelineDesc d;
        d.name = pass == Pass::Horizontal ? "separable horizontal pass"
                 : pass == Pass::Vertical ? "separable vertical pass"
                                          : "burley pass";
        d.vertex_spirv = shaders::fullscreen_vert();
        d.fragment_spirv = pass == Pass::Burley ? shaders::burley_blur_frag() : shaders::separable_blur_frag();
        d.color_formats = {format};
        d.depth_format = VK_FORMAT_UNDEFINED;
        d.samples = VK_SAMPLE_COUNT_1_BIT;
        d.cull = VK_CULL_MODE_NONE;
        // The last pass adds the blurred light to the image.
        d.blend = pass == Pass::Horizontal ? gpu::Blend::None : gpu::Blend::AddColor;
        d.bindings = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
        d.push_size = sizeof(SeparablePush);
        // separable_blur.frag: constant_id 0 TAPS, 1 VERTICAL; burley_blur.frag: 0 SAMPLES.
        d.constants = {count, pass == Pass::Vertical ? 1u : 0u};
        it->second = gpu::GraphicsPipeline(ctx_, d);
    } catch (...) {
        pipelines_.erase(it);
        throw;
    }
    return it->second;
}

void SeparablePasses::record_blur(VkCommandBuffer cmd, const RenderTarget& t, const RenderSettings& s,
                                  VkFormat color_format, const Camera& camera, const glm::mat4& view_proj, glm::vec3 lo,
                                  glm::vec3 hi)
{
    const float focal = 0.5f * float(s.height) / std::tan(0.5f * glm::radians(camera.fov_y_degrees));
    const VkRect2D area = screen_bounds(view_proj, lo, hi, s.width, s.height);
    // The follow-surface scale: a tap whose depth differs from the centre's by the kernel's
    // range or more is replaced by the centre (Jimenez's lerp towards the centre colour).
    const float range = std::max(constants_.params.y, 1e-30f);
    const SeparablePush push{glm::vec4(1.0f / float(s.width), 1.0f / float(s.height), focal, 1.0f / range)};
    const VkExtent2D extent{s.width, s.height};
    // `vertical` (or burley): the last pass, which adds its light to the image.
    auto pass = [&](const gpu::Image& source, VkImageView target, bool vertical, bool burley, VkFormat format) {
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = target;
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = vertical ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;  // horizontal: alpha 0 outside
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        if (!vertical) a.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, extent};
        ri.layerCount = 1;
        ri.colorAttachmentCount = 1;
        ri.pColorAttachments = &a;
        vkCmdBeginRendering(cmd, &ri);
        const Pass kind = burley ? Pass::Burley : vertical ? Pass::Vertical : Pass::Horizontal;
        pass_pipeline(kind, burley ? s.burley_samples : s.separable_taps, format)
            .bind(cmd, extent, push,
                  {data_, gpu::Binding::image(source.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_)});
        vkCmdSetScissor(cmd, 0, 1, &area);  // only the mesh's pixels pay
        vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
    };
    const bool burley = s.mode == ShadingMode::Burley;
    irradiance_.transition(cmd, gpu::use::kSampled);
    if (!burley) {
        horizontal_.transition(cmd, gpu::use::kColorAttachment, true);
        pass(irradiance_, horizontal_.view(), false, false, kSeparableIrradianceFormat);
        horizontal_.transition(cmd, gpu::use::kSampled);
    }
    // The mesh pass's resolve (or single-sample colour) write, before the last pass adds to it.
    const VkImageView final_view = t.resolve ? t.resolve : t.color;
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    pass(burley ? irradiance_ : horizontal_, final_view, true, burley, color_format);
}

}  // namespace jade::shading
