// gpu/image.hpp - one 2-D VkImage with its own memory and a view, layout transitions
// (synchronization2), and copies to and from buffers.
#pragma once

#include "gpu/vk.hpp"

#include <cstdint>

namespace jade::gpu {

class Context;

/// Where an image is used: the layout it must be in and the stage/access of that use. A
/// transition goes from one use to the next; the presets below cover Jade's passes.
struct ImageUse {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

namespace use {
/// Contents are discarded (first use, or the old contents no longer matter).
inline constexpr ImageUse kDiscard{VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE};
inline constexpr ImageUse kComputeWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
// Vertex shaders sample too: mesh.vert reads the light-depth atlas.
inline constexpr ImageUse kSampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                   VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
inline constexpr ImageUse kColorAttachment{
    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
inline constexpr ImageUse kDepthAttachment{
    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
inline constexpr ImageUse kTransferSrc{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                       VK_ACCESS_2_TRANSFER_READ_BIT};
inline constexpr ImageUse kTransferDst{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                       VK_ACCESS_2_TRANSFER_WRITE_BIT};
}  // namespace use

/// Records one image barrier from `from` to `to` over the whole image (all mips and layers of
/// `aspect`). Works on any image, including ones Jade does not own.
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, const ImageUse& from,
                   const ImageUse& to);

struct ImageDesc {
    const char* name = "image";
    uint32_t width = 1, height = 1;
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

/// A 2-D image (one mip, one layer) in device-local memory, with a view of its whole
/// aspect (colour, or depth for depth formats). It remembers the use it was last transitioned
/// to, so `transition(cmd, to)` needs only the new use; that bookkeeping is on the host and
/// assumes command buffers run in the order they were recorded (true for Jade's one queue).
class Image {
public:
    Image() = default;
    Image(Context& ctx, const ImageDesc& desc);

    /// Barrier from the last use to `to`. With `discard`, the old contents are dropped (old
    /// layout UNDEFINED), still ordered after the last use.
    void transition(VkCommandBuffer cmd, const ImageUse& to, bool discard = false);
    /// Copies the image (which must be in use::kTransferSrc) into `buffer` at `offset`, rows
    /// tightly packed.
    void copy_to_buffer(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset = 0) const;
    /// Copies tightly packed rows from `buffer` into the image (which must be in use::kTransferDst).
    void copy_from_buffer(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset = 0) const;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    VkFormat format() const { return format_; }
    VkImageAspectFlags aspect() const { return aspect_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    VkDeviceSize bytes() const;  ///< width × height × texel size (tightly packed)
    const ImageUse& current_use() const { return use_; }
    explicit operator bool() const { return bool(image_); }

private:
    uint32_t width_ = 0, height_ = 0;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkImageAspectFlags aspect_ = VK_IMAGE_ASPECT_COLOR_BIT;
    ImageUse use_;
    // Destroyed in reverse order: view, image, then the memory they live in.
    OwnedMemory memory_;
    OwnedImage image_;
    OwnedImageView view_;
};

/// Bytes per texel of the formats Jade uses (asserts on others).
uint32_t texel_bytes(VkFormat format);

/// A sampler with the given filter and address mode, no mipmaps, no anisotropy.
OwnedSampler make_sampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode address, const char* name);

}  // namespace jade::gpu
