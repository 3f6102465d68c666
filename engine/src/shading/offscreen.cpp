// shading/offscreen.cpp - see offscreen.hpp.
#include "shading/offscreen.hpp"

#include "gpu/context.hpp"
#include "shading/frame.hpp"

#include <cstdint>

namespace jade::shading {

void OffscreenTarget::ensure(gpu::Context& ctx, const RenderSettings& s, VkFormat color_format, const std::string& name)
{
    if (width_ == s.width && height_ == s.height && samples_ == s.samples && format_ == color_format) return;
    *this = OffscreenTarget{};
    // The names are read only while the objects are made (debug names, error messages).
    const std::string color = name + " colour", resolve = name + " resolve", depth = name + " depth",
                      readback = name + " read-back";
    const auto msaa = VkSampleCountFlagBits(s.samples);
    const VkImageUsageFlags attachment = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    // The single-sampled colour is copied out itself; a multisampled one through its resolve.
    const VkImageUsageFlags copied = s.samples == 1 ? VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_SRC_BIT) : 0u;
    color_ = gpu::Image(ctx, {color.c_str(), s.width, s.height, color_format, attachment | copied, msaa});
    if (s.samples > 1)
        resolve_ = gpu::Image(
            ctx, {resolve.c_str(), s.width, s.height, color_format, attachment | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    depth_ = gpu::Image(ctx, {depth.c_str(), s.width, s.height, VK_FORMAT_D32_SFLOAT,
                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, msaa});
    readback_ = gpu::Buffer(ctx, color_.bytes(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, readback.c_str(), true);
    width_ = s.width, height_ = s.height, samples_ = s.samples, format_ = color_format;
}

void OffscreenTarget::begin(VkCommandBuffer cmd)
{
    color_.transition(cmd, gpu::use::kColorAttachment, true);
    depth_.transition(cmd, gpu::use::kDepthAttachment, true);
    if (resolve_) resolve_.transition(cmd, gpu::use::kColorAttachment, true);
}

RenderTarget OffscreenTarget::target(bool load, bool keep) const
{
    return {color_.view(), resolve_ ? resolve_.view() : VK_NULL_HANDLE, depth_.view(), width_, height_, load, keep};
}

void OffscreenTarget::copy_out(VkCommandBuffer cmd)
{
    gpu::Image& result = resolve_ ? resolve_ : color_;
    result.transition(cmd, gpu::use::kTransferSrc);
    result.copy_to_buffer(cmd, readback_.handle());
}

std::vector<float> OffscreenTarget::read_rgba() const
{
    const size_t n = size_t(width_) * height_ * 4;
    if (format_ == VK_FORMAT_R32G32B32A32_SFLOAT) return readback_.read<float>(n);
    std::vector<float> rgba(n);
    const std::vector<uint16_t> half = readback_.read<uint16_t>(n);
    for (size_t i = 0; i < n; ++i) rgba[i] = half_to_float(half[i]);
    return rgba;
}

}  // namespace jade::shading
