#include "gpu/image.hpp"

#include "gpu/buffer.hpp"
#include "gpu/context.hpp"

#include <cassert>
#include <string>

namespace jade::gpu {

uint32_t texel_bytes(VkFormat format)
{
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: assert(!"texel_bytes: format not used by Jade"); return 0;
    }
}

static VkImageAspectFlags aspect_of(VkFormat format)
{
    return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM ? VK_IMAGE_ASPECT_DEPTH_BIT
                                                                           : VK_IMAGE_ASPECT_COLOR_BIT;
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, const ImageUse& from,
                   const ImageUse& to)
{
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = from.stage;
    // Only writes need making available; listing reads in srcAccessMask is legal but pointless.
    b.srcAccessMask = from.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
                                     VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    b.dstStageMask = to.stage;
    b.dstAccessMask = to.access;
    b.oldLayout = from.layout;
    b.newLayout = to.layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

Image::Image(Context& ctx, const ImageDesc& desc)
    : width_(desc.width), height_(desc.height), format_(desc.format), aspect_(aspect_of(desc.format))
{
    if (desc.width == 0 || desc.height == 0 || desc.width > ctx.limits().maxImageDimension2D ||
        desc.height > ctx.limits().maxImageDimension2D)
        throw Error(std::string(desc.name) + ": image size " + std::to_string(desc.width) + "x" +
                    std::to_string(desc.height) + " is outside 1.." + std::to_string(ctx.limits().maxImageDimension2D));
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = desc.format;
    ci.extent = {desc.width, desc.height, 1};
    ci.mipLevels = 1;
    ci.arrayLayers = 1;
    ci.samples = desc.samples;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = desc.usage;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image;
    check(vkCreateImage(ctx.device(), &ci, nullptr, &image), (std::string("vkCreateImage ") + desc.name).c_str());
    OwnedImage owned(ctx.device(), image);
    ctx.set_name(image, VK_OBJECT_TYPE_IMAGE, desc.name);
    ctx.count_created(VK_OBJECT_TYPE_IMAGE);

    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device(), image, &req);
    memory_ = allocate_memory(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0, nullptr, desc.name);
    check(vkBindImageMemory(ctx.device(), image, memory_, 0), "vkBindImageMemory");
    image_ = std::move(owned);

    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = desc.format;
    vi.subresourceRange = {aspect_, 0, 1, 0, 1};
    VkImageView view;
    check(vkCreateImageView(ctx.device(), &vi, nullptr, &view),
          (std::string("vkCreateImageView ") + desc.name).c_str());
    view_ = OwnedImageView(ctx.device(), view);
    ctx.set_name(view, VK_OBJECT_TYPE_IMAGE_VIEW, desc.name);
}

VkDeviceSize Image::bytes() const { return VkDeviceSize(width_) * height_ * texel_bytes(format_); }

void Image::transition(VkCommandBuffer cmd, const ImageUse& to, bool discard)
{
    ImageUse from = use_;
    if (discard) from.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    image_barrier(cmd, image_, aspect_, from, to);
    use_ = to;
}

static VkBufferImageCopy whole_image(VkImageAspectFlags aspect, uint32_t w, uint32_t h, VkDeviceSize offset)
{
    VkBufferImageCopy r{};
    r.bufferOffset = offset;
    r.imageSubresource = {aspect, 0, 0, 1};
    r.imageExtent = {w, h, 1};
    return r;
}

void Image::copy_to_buffer(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) const
{
    assert(use_.layout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy r = whole_image(aspect_, width_, height_, offset);
    vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &r);
}

void Image::copy_from_buffer(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) const
{
    assert(use_.layout == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy r = whole_image(aspect_, width_, height_, offset);
    vkCmdCopyBufferToImage(cmd, buffer, image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &r);
}

OwnedSampler make_sampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode address, const char* name)
{
    VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    ci.magFilter = ci.minFilter = filter;
    ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    ci.addressModeU = ci.addressModeV = ci.addressModeW = address;
    ci.maxLod = 0.0f;  // one mip: never minify into a level that does not exist
    VkSampler s;
    check(vkCreateSampler(ctx.device(), &ci, nullptr, &s), (std::string("vkCreateSampler ") + name).c_str());
    ctx.set_name(s, VK_OBJECT_TYPE_SAMPLER, name);
    return OwnedSampler(ctx.device(), s);
}

}  // namespace jade::gpu
