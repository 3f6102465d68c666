// samples/viewer - the window and the Vulkan objects the viewer owns and Jade adopts.
//
// GLFW gives the window and the instance extensions its surface needs; the viewer creates the
// instance (with the validation layer on request), the surface, and a device with
// VK_KHR_swapchain plus everything jade::Context needs (Context::required_device_extensions,
// Context::enable_required_features). jade::Context then adopts instance, device and queue
// (adopted_vulkan()): Jade creates its own command pool and fences on them and destroys none
// of the viewer's objects.
#pragma once

#include "vk_instance.hpp"  // samples/common
#include "vk_util.hpp"

#include <jade/context.hpp>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace samples::viewer {

/// GLFW initialised and one window without a client API (Vulkan draws into it).
class Window {
public:
    /// Throws std::runtime_error when GLFW cannot open the display or has no Vulkan support.
    Window(uint32_t width, uint32_t height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;
    GLFWwindow* handle() const { return window_; }
    bool should_close() const;
    VkExtent2D framebuffer_size() const;  ///< pixels; 0 × 0 while minimised
    /// True once after the framebuffer changed size (the swapchain must be recreated).
    bool take_resized();

private:
    GLFWwindow* window_ = nullptr;
    bool resized_ = false;
    static void on_resize(GLFWwindow* window, int width, int height);
};

/// Instance, debug messenger, surface, device and its one graphics + compute + present queue.
/// Members are declared in creation order and so destroyed in reverse.
class VulkanHost {
public:
    VulkanHost(const Window& window, bool validation);
    ~VulkanHost();
    VulkanHost(const VulkanHost&) = delete;
    VulkanHost& operator=(const VulkanHost&) = delete;

    VkInstance instance() const { return instance_.instance; }
    VkSurfaceKHR surface() const { return surface_; }
    VkPhysicalDevice physical() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return family_; }
    const std::string& device_name() const { return device_name_; }
    bool validation() const
    {
        return instance_.validation;
    }  ///< the layer is on (--validation, JADE_VALIDATION, JADE_SYNC_VALIDATION)
    /// What jade::Context(const AdoptedVulkan&) needs to adopt this device.
    jade::AdoptedVulkan adopted_vulkan() const;
    /// Warnings and errors the validation layer reported so far (also printed to stderr).
    static uint64_t validation_messages();

private:
    Instance instance_;  // and its messenger
    Owned<VkSurfaceKHR> surface_;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    std::string device_name_;
    jade::HostDeviceSetup setup_;  // Jade's features and extensions, plus the swapchain
    Owned<VkDevice> device_;
    VkQueue queue_ = VK_NULL_HANDLE;

    void create_instance(bool validation);
    void pick_physical_device();
    void create_device();
};

}  // namespace samples::viewer
