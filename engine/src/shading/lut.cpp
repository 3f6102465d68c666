#include "shading/lut.hpp"

#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/kernel.hpp"

#include <jade/dev/material.hpp>
#include <jade/dev/lut.hpp>

#include "jade_shaders.hpp"
#include "lut_interface.h"  // struct LutBuildPush, shared with lut_build.comp

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>

namespace jade {

double LutLayout::variance(uint32_t j) const
{
    const double v = double(j) / double(height - 1);
    return kMaxVariance * (v * v) * (v * v);
}

double LutLayout::x(double cos_theta) const
{
    return (std::clamp(cos_theta, -1.0, 1.0) + 1.0) * 0.5 * double(width - 1);
}

double LutLayout::y(double t) const
{
    return std::sqrt(std::sqrt(std::max(t, 0.0) / kMaxVariance)) * double(height - 1);
}

}  // namespace jade

namespace jade::shading {
namespace {

void require_format(const gpu::Context& ctx, VkFormat format, VkFormatFeatureFlags features, const char* what)
{
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), format, &p);
    if ((p.optimalTilingFeatures & features) != features)
        throw Error(std::string(what) + ": device " + ctx.info().name +
                    " cannot store/sample/linearly filter the texture format it needs (format " +
                    std::to_string(format) + ")");
}

void require_texel_format(const gpu::Context& ctx, VkFormat format, const char* what)
{
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), format, &p);
    if (!(p.bufferFeatures & VK_FORMAT_FEATURE_UNIFORM_TEXEL_BUFFER_BIT))
        throw Error(std::string(what) + ": device " + ctx.info().name + " cannot read format " +
                    std::to_string(format) + " from a uniform texel buffer");
}

void check_size(uint32_t width, uint32_t height, const char* what)
{
    if (width < 3 || width % 2 == 0 || height < 2)
        throw Error(std::string(what) + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                    " must have an odd width ≥ 3 (cos θ = 0 on a texel centre) and a height ≥ 2");
}

// A sampled image of `desc` (usage: sampled, transfer destination) holding `texels`, tightly
// packed rows, copied in through a host-visible staging buffer named `staging_name`.
template <class T>
gpu::Image upload_image(gpu::Context& ctx, const gpu::ImageDesc& desc, const std::vector<T>& texels,
                        const char* staging_name)
{
    gpu::Buffer staging(ctx, texels.size() * sizeof(T), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging_name, true);
    staging.upload(texels.data(), texels.size() * sizeof(T));
    gpu::Image image(ctx, desc);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        image.transition(cmd, gpu::use::kTransferDst);
        image.copy_from_buffer(cmd, staging.handle());
        image.transition(cmd, gpu::use::kSampled);
    });
    return image;
}

}  // namespace

gpu::OwnedSampler make_lut_sampler(const gpu::Context& ctx)
{
    return gpu::make_sampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                             "LUT sampler (linear, clamp)");
}

TranslucencyLut::TranslucencyLut(gpu::Context& ctx, const LutLayout& layout) : layout_(layout)
{
    check_size(layout.width, layout.height, "translucency LUT");
    require_format(ctx, VK_FORMAT_R32_SFLOAT,
                   VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
                   "translucency LUT");
    image_ =
        gpu::Image(ctx, {"translucency LUT", layout.width, layout.height, VK_FORMAT_R32_SFLOAT,
                         VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    // The kernel is needed once per LUT: it is not kept.
    gpu::Kernel build(
        ctx,
        {"lut_build", shaders::lut_build_comp(), {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, sizeof(LutBuildPush), 64, {}});
    LutBuildPush push{layout.width, layout.height, float(LutLayout::kMaxVariance)};
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        image_.transition(cmd, gpu::use::kComputeWrite);
        build.dispatch(cmd, uint64_t(layout.width) * layout.height, push,
                       {gpu::Binding::image(image_.view(), VK_IMAGE_LAYOUT_GENERAL)});
        image_.transition(cmd, gpu::use::kSampled);
    });

    // Until build_quads: a zero texel, so that every draw has a quads descriptor to bind.
    require_texel_format(ctx, VK_FORMAT_R32G32B32A32_SFLOAT, "translucency LUT");
    no_quads_ = gpu::Buffer::from(ctx, std::vector<glm::vec4>(1, glm::vec4(0.0f)),
                                  VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, "translucency LUT quads (none)");
    no_quads_view_ = gpu::TexelView(ctx, no_quads_, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "translucency LUT quads (none)");
    const uint32_t W = layout.width, H = layout.height;
    const std::vector<float> f = read(ctx);

    // The same texels in 16 bits for the sampler (TmEvaluation::LutFiltered): f ∈ [0, 1], so
    // UNORM steps of 1.5e-5, a tenth of what the image budget allows (docs/shading.md).
    require_format(ctx, VK_FORMAT_R16_UNORM,
                   VK_FORMAT_FEATURE_TRANSFER_DST_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
                   "translucency LUT (16 bit)");
    std::vector<uint16_t> unorm(f.size());
    for (size_t i = 0; i < f.size(); ++i) unorm[i] = uint16_t(std::lround(std::clamp(f[i], 0.0f, 1.0f) * 65535.0f));
    filtered_ = upload_image(ctx,
                             {"translucency LUT (16 bit)", W, H, VK_FORMAT_R16_UNORM,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT},
                             unorm, "translucency LUT upload");
}

void TranslucencyLut::build_quads(gpu::Context& ctx)
{
    const std::lock_guard lock(quads_mutex_);
    if (quads_built_) return;
    // TmEvaluation::Lut reads quads, not the image: on lavapipe one RGBA32F texel-buffer fetch
    // plus a bilinear blend in the shader costs a fraction of one filtered sample (docs/shading.md).
    // Packed on the host from the GPU-built texels, so both hold the same float32 values.
    const uint32_t W = layout_.width, H = layout_.height;
    const uint64_t count = uint64_t(W - 1) * (H - 1);
    const std::vector<float> f = read(ctx);
    std::vector<glm::vec4> quads(count);
    for (uint32_t j = 0; j + 1 < H; ++j)
        for (uint32_t i = 0; i + 1 < W; ++i) {
            const size_t t = size_t(j) * W + i;
            quads[size_t(j) * (W - 1) + i] = {f[t], f[t + 1], f[t + W], f[t + W + 1]};
        }
    quads_ = gpu::Buffer::from(ctx, quads, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, "translucency LUT quads");
    quads_view_ = gpu::TexelView(ctx, quads_, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "translucency LUT quads");
    quads_built_ = true;
}

glm::vec4 TranslucencyLut::shader_map() const
{
    // Continuous texel indices: column x = (cos θ + 1)/2 · (W − 1), row y = (t/t_max)^¼ · (H − 1).
    const float w = float(layout_.width), h = float(layout_.height);
    return {0.5f * (w - 1.0f), w - 1.0f, h - 1.0f, h - 2.0f};
}

std::vector<float> TranslucencyLut::read(gpu::Context& ctx)
{
    gpu::Buffer staging(ctx, image_.bytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, "translucency LUT read-back", true);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        image_.transition(cmd, gpu::use::kTransferSrc);
        image_.copy_to_buffer(cmd, staging.handle());
        image_.transition(cmd, gpu::use::kSampled);
    });
    return staging.read<float>(size_t(layout_.width) * layout_.height);
}

double CurvatureLut::length_scale(const Material& material)
{
    double sum = 0;
    for (const auto& p : material.profile) sum += dev::radius_for_tail(p, 0.5);
    return sum / 3.0;
}

std::vector<glm::vec4> CurvatureLut::evaluate(const Material& material, uint32_t width, uint32_t height)
{
    check_size(width, height, "curvature LUT");
    const double scale = length_scale(material);
    const bool grey = dev::is_grey(material);
    std::vector<glm::vec4> texels(size_t(width) * height);
    auto row = [&](uint32_t j) {
        const double v = double(j) / double(height - 1);
        // κ·d̄ = v/(1 − v): r = 1/κ = d̄(1 − v)/v; row 0 is the plane, the last row a sphere of
        // radius d̄/1000 (κ → ∞ would be r = 0, outside the reference's domain).
        const double r =
            j == 0 ? std::numeric_limits<double>::infinity() : std::max(scale * (1.0 - v) / v, scale * 1e-3);
        for (uint32_t i = 0; i < width; ++i) {
            const double c = -1.0 + 2.0 * double(i) / double(width - 1);
            glm::vec4& t = texels[size_t(j) * width + i];
            for (int ch = 0; ch < 3; ++ch)
                t[ch] = (grey && ch > 0) ? t[0] : float(curvature_lut_reference(c, r, material.profile[ch]));
            t[3] = 1.0f;
        }
    };
    // Rows are independent: spread them over the CPU's threads (the reference is adaptive
    // quadrature, ~10 µs a texel).
    const uint32_t threads = std::clamp<uint32_t>(std::thread::hardware_concurrency(), 1, height);
    std::vector<std::thread> pool;
    std::exception_ptr failure;
    std::mutex failure_mutex;
    for (uint32_t k = 0; k < threads; ++k)
        pool.emplace_back([&, k] {
            try {
                for (uint32_t j = k; j < height; j += threads) row(j);
            } catch (...) {
                std::lock_guard lock(failure_mutex);
                failure = std::current_exception();
            }
        });
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    return texels;
}

CurvatureLut::CurvatureLut(gpu::Context& ctx, const Material& material, uint32_t width, uint32_t height)
    : scale_(length_scale(material))
{
    require_format(ctx, VK_FORMAT_R32G32B32A32_SFLOAT,
                   VK_FORMAT_FEATURE_TRANSFER_DST_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
                   "curvature LUT");
    std::vector<glm::vec4> texels = evaluate(material, width, height);
    image_ = upload_image(ctx,
                          {"curvature LUT", width, height, VK_FORMAT_R32G32B32A32_SFLOAT,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT},
                          texels, "curvature LUT upload");
}

glm::vec4 CurvatureLut::shader_map() const
{
    const uint32_t w = image_.width();
    glm::vec2 v = texel_centre_map(image_.height());
    return {float(w - 1) / float(2 * w), 0.5f, v.x, v.y};
}

std::shared_ptr<TranslucencyLut> shared_translucency_lut(gpu::Context& ctx, const LutLayout& layout)
{
    // Weak entries: the registry never keeps a LUT alive, the Renderers do. Keyed by the device
    // handle, so Contexts adopting the same device share too.
    static std::mutex mutex;
    static std::map<std::tuple<VkDevice, uint32_t, uint32_t>, std::weak_ptr<TranslucencyLut>> registry;
    const std::lock_guard lock(mutex);
    std::erase_if(registry, [](const auto& entry) { return entry.second.expired(); });  // devices long gone
    auto& slot = registry[{ctx.device(), layout.width, layout.height}];
    if (auto lut = slot.lock()) return lut;
    auto lut = std::make_shared<TranslucencyLut>(ctx, layout);
    slot = lut;
    return lut;
}

}  // namespace jade::shading
