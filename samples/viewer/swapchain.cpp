#include "swapchain.hpp"

#include "window.hpp"

#include <algorithm>

namespace samples::viewer {

namespace {

// An sRGB 8-bit format that the resolved RGBA16F image can be blitted into.
VkSurfaceFormatKHR choose_format(VkPhysicalDevice physical, VkSurfaceKHR surface)
{
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(n);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &n, formats.data());
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
        for (const VkSurfaceFormatKHR& f : formats)
            if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
                VkFormatProperties props;
                vkGetPhysicalDeviceFormatProperties(physical, f.format, &props);
                if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) return f;
            }
    throw std::runtime_error(
        "the window surface offers no B8G8R8A8_SRGB or R8G8B8A8_SRGB format that can be a blit destination");
}

VkPresentModeKHR choose_present_mode(VkPhysicalDevice physical, VkSurfaceKHR surface, bool vsync)
{
    if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
    uint32_t n = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &n, nullptr);
    std::vector<VkPresentModeKHR> modes(n);
    vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &n, modes.data());
    for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR})
        if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
    return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Swapchain::Swapchain(const VulkanHost& host, VkExtent2D extent, bool vsync, Swapchain* old)
{
    const VkDevice device = host.device();
    VkSurfaceCapabilitiesKHR caps;
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(host.physical(), host.surface(), &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((caps.supportedUsageFlags & usage) != usage)
        throw std::runtime_error("the window surface's images cannot be blit destinations and copy sources (needed to "
                                 "present and to take screenshots)");
    if (caps.currentExtent.width != 0xffffffffu) extent = caps.currentExtent;
    extent.width = std::clamp(extent.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(extent.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    const VkSurfaceFormatKHR format = choose_format(host.physical(), host.surface());
    min_image_count_ = caps.minImageCount + 1;
    if (caps.maxImageCount) min_image_count_ = std::min(min_image_count_, caps.maxImageCount);

    VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    ci.surface = host.surface();
    ci.minImageCount = min_image_count_;
    ci.imageFormat = format.format;
    ci.imageColorSpace = format.colorSpace;
    ci.imageExtent = extent;
    ci.imageArrayLayers = 1;
    ci.imageUsage = usage;
    ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.preTransform = caps.currentTransform;
    ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    ci.presentMode = choose_present_mode(host.physical(), host.surface(), vsync);
    ci.clipped = VK_TRUE;
    ci.oldSwapchain = old ? old->handle() : VK_NULL_HANDLE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    check(vkCreateSwapchainKHR(device, &ci, nullptr, &swapchain), "vkCreateSwapchainKHR");
    swapchain_ = own(device, swapchain, vkDestroySwapchainKHR);
    format_ = format.format;
    extent_ = extent;

    uint32_t n = 0;
    vkGetSwapchainImagesKHR(device, swapchain, &n, nullptr);
    images_.resize(n);
    vkGetSwapchainImagesKHR(device, swapchain, &n, images_.data());
    for (VkImage image : images_) {
        views_.push_back(make_view(device, image, format_, VK_IMAGE_ASPECT_COLOR_BIT));
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore semaphore = VK_NULL_HANDLE;
        check(vkCreateSemaphore(device, &si, nullptr, &semaphore), "vkCreateSemaphore");
        render_finished_.push_back(own(device, semaphore, vkDestroySemaphore));
    }
}

RenderImages::RenderImages(const VulkanHost& host, VkExtent2D extent_, VkSampleCountFlagBits samples_)
    : extent(extent_), samples(samples_)
{
    const VkPhysicalDevice pd = host.physical();
    const VkDevice device = host.device();
    const bool msaa = samples != VK_SAMPLE_COUNT_1_BIT;
    color = make_image(pd, device, kColorFormat, extent, samples,
                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (msaa ? 0 : VK_IMAGE_USAGE_TRANSFER_SRC_BIT),
                       VK_IMAGE_ASPECT_COLOR_BIT);
    if (msaa)
        resolve = make_image(pd, device, kColorFormat, extent, VK_SAMPLE_COUNT_1_BIT,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                             VK_IMAGE_ASPECT_COLOR_BIT);
    depth = make_image(pd, device, kDepthFormat, extent, samples, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                       VK_IMAGE_ASPECT_DEPTH_BIT);
}

}  // namespace samples::viewer
