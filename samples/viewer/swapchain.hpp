// samples/viewer - the swapchain and the images Jade draws into.
//
// Jade's Renderer::record draws into RGBA16F (linear HDR) attachments the host owns; the
// viewer resolves the MSAA colour in Jade's pass, then blits the resolved image into the
// swapchain image. The swapchain has an sRGB format, so the blit does the linear → sRGB
// encoding (and clamps to [0, 1]) exactly as jade::save_image does for a PNG of render():
// the presented frame and `jade render --out X.png` agree to about one 8-bit step.
#pragma once

#include "vk_util.hpp"

#include <cstdint>
#include <vector>

namespace samples::viewer {

class VulkanHost;

class Swapchain {
public:
    /// Creates the swapchain for the surface at `extent` (clamped to the surface's limits),
    /// replacing `old` when given. vsync: FIFO, else IMMEDIATE (or MAILBOX) when available.
    Swapchain(const VulkanHost& host, VkExtent2D extent, bool vsync, Swapchain* old = nullptr);
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    uint32_t min_image_count() const { return min_image_count_; }
    uint32_t image_count() const { return uint32_t(images_.size()); }
    VkImage image(uint32_t i) const { return images_[i]; }
    VkImageView view(uint32_t i) const { return views_[i]; }
    /// Signalled by the frame that renders image i, waited on by its present: one per image,
    /// so a semaphore is only reused after its image was acquired again.
    VkSemaphore render_finished(uint32_t i) const { return render_finished_[i]; }

private:
    Owned<VkSwapchainKHR> swapchain_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    uint32_t min_image_count_ = 0;
    std::vector<VkImage> images_;  // owned by the swapchain
    std::vector<Owned<VkImageView>> views_;
    std::vector<Owned<VkSemaphore>> render_finished_;
};

/// Jade's attachments at the window's size: MSAA colour (RGBA16F), its resolve, MSAA depth.
struct RenderImages {
    static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // RenderSettings::float32 = false
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    RenderImages(const VulkanHost& host, VkExtent2D extent, VkSampleCountFlagBits samples);
    VkExtent2D extent;
    VkSampleCountFlagBits samples;
    Image color, resolve, depth;  // resolve is empty when samples = 1 (Jade draws into color)
    VkImage presented_source() const
    {
        return samples == VK_SAMPLE_COUNT_1_BIT ? color.image.get() : resolve.image.get();
    }
};

}  // namespace samples::viewer
