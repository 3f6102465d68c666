// samples/viewer - the Dear ImGui panel (Debian libimgui-dev 1.86, GLFW and Vulkan back-ends).
//
// The 1.86 Vulkan back-end draws inside a VkRenderPass (it predates dynamic rendering), so the
// panel owns a one-subpass render pass that loads the swapchain image (Jade's frame, already
// blitted into it) and leaves it in PRESENT_SRC_KHR, one framebuffer per swapchain image and
// the descriptor pool of the font texture.
#pragma once

#include "scene.hpp"
#include "vk_util.hpp"

#include <string>
#include <vector>

struct GLFWwindow;

namespace samples::viewer {

class Swapchain;
class VulkanHost;

/// What the panel shows besides the controls.
struct PanelInfo {
    std::string device, mesh;
    size_t vertices = 0;
    double frame_ms = 0;                                 ///< wall time per frame, averaged
    std::vector<std::pair<std::string, double>> stages;  ///< ms
};

/// Where a window of the panel was drawn, pixels (the Xvfb test compares the rest of the image).
struct PanelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

class Ui {
public:
    /// Installs ImGui's GLFW callbacks (they chain to callbacks set before) and uploads the
    /// font texture (submits to the host's queue and waits).
    Ui(const VulkanHost& host, GLFWwindow* window, const Swapchain& swapchain);
    ~Ui();
    Ui(const Ui&) = delete;
    Ui& operator=(const Ui&) = delete;

    /// Recreates the framebuffers after the swapchain was recreated (same format).
    void on_swapchain(const Swapchain& swapchain);
    /// Builds the panel for this frame; returns true when the user changed a setting.
    bool build(ViewState& state, const PanelInfo& info);
    /// True when ImGui uses the mouse (the camera ignores drags and the wheel then).
    bool wants_mouse() const;
    /// The controls window and the timings overlay, as drawn in the last frame.
    const std::vector<PanelRect>& panel_rects() const { return rects_; }
    /// Records the panel's render pass on swapchain image `index` (layout
    /// COLOR_ATTACHMENT_OPTIMAL before, PRESENT_SRC_KHR after).
    void record(VkCommandBuffer cmd, uint32_t index, VkExtent2D extent);

private:
    VkDevice device_;
    Owned<VkDescriptorPool> pool_;
    Owned<VkRenderPass> render_pass_;
    std::vector<Owned<VkFramebuffer>> framebuffers_;
    std::vector<PanelRect> rects_;
    bool imgui_context_ = false, glfw_backend_ = false, vulkan_backend_ = false;
};

}  // namespace samples::viewer
