#include "app.hpp"

#include "swapchain.hpp"
#include "ui.hpp"
#include "window.hpp"

#include <jade/io.hpp>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <numeric>

namespace samples::viewer {

namespace {

double now_ms()
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

float srgb_to_linear(uint8_t v)
{
    const float c = float(v) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Mouse wheel steps since the last frame (the scroll callback is installed before ImGui's,
// which chains to it).
double g_wheel = 0.0;

// Waits for the device to be idle when the loop's scope ends (normally or by an exception),
// before the objects declared earlier are destroyed.
struct IdleOnExit {
    VkDevice device;
    ~IdleOnExit() { vkDeviceWaitIdle(device); }
};

// The per-frame objects of the single frame in flight.
struct FrameSync {
    Owned<VkCommandPool> pool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    Owned<VkFence> done;
    Owned<VkSemaphore> acquired;
    Owned<VkQueryPool> timestamps;  // 0: start, 1: after Jade's draw, 2: after blit + panel
    double timestamp_period_ns = 1.0;

    explicit FrameSync(const VulkanHost& host)
    {
        const VkDevice device = host.device();
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pi.queueFamilyIndex = host.queue_family();
        VkCommandPool p = VK_NULL_HANDLE;
        check(vkCreateCommandPool(device, &pi, nullptr, &p), "vkCreateCommandPool");
        pool = own(device, p, vkDestroyCommandPool);
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = p;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        check(vkAllocateCommandBuffers(device, &ai, &cmd), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence f = VK_NULL_HANDLE;
        check(vkCreateFence(device, &fi, nullptr, &f), "vkCreateFence");
        done = own(device, f, vkDestroyFence);
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore s = VK_NULL_HANDLE;
        check(vkCreateSemaphore(device, &si, nullptr, &s), "vkCreateSemaphore");
        acquired = own(device, s, vkDestroySemaphore);
        VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = 3;
        VkQueryPool q = VK_NULL_HANDLE;
        check(vkCreateQueryPool(device, &qi, nullptr, &q), "vkCreateQueryPool");
        timestamps = own(device, q, vkDestroyQueryPool);
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(host.physical(), &props);
        timestamp_period_ns = props.limits.timestampPeriod;
    }
};

// Records one frame: Jade's draw, resolve (inside Jade's pass), blit into the swapchain image,
// the panel, and for the screenshot a copy of the presented image into `readback`.
void record_frame(FrameSync& sync, Scene& scene, const ViewState& state, const RenderImages& images,
                  const Swapchain& swapchain, uint32_t index, Ui* ui, const HostBuffer* readback)
{
    const VkCommandBuffer cmd = sync.cmd;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    vkCmdResetQueryPool(cmd, sync.timestamps, 0, 3);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, sync.timestamps, 0);

    // Jade's attachments: previous contents are not needed (cleared by the draw).
    const VkPipelineStageFlags2 color_out = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    const VkPipelineStageFlags2 tests =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    const VkImage source = images.presented_source();
    image_barrier(cmd, images.color.image, VK_IMAGE_ASPECT_COLOR_BIT, color_out | VK_PIPELINE_STAGE_2_BLIT_BIT, 0,
                  VK_IMAGE_LAYOUT_UNDEFINED, color_out, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    if (images.resolve.image)
        image_barrier(cmd, images.resolve.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, 0,
                      VK_IMAGE_LAYOUT_UNDEFINED, color_out, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    image_barrier(cmd, images.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, tests, 0, VK_IMAGE_LAYOUT_UNDEFINED, tests,
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    jade::RenderTarget target;
    target.color = images.color.view;
    target.resolve = images.resolve.view ? images.resolve.view.get() : VK_NULL_HANDLE;
    target.depth = images.depth.view;
    target.width = images.extent.width;
    target.height = images.extent.height;
    scene.record(cmd, target, state, uint32_t(images.samples));
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, sync.timestamps, 1);

    // Blit (linear RGBA16F → sRGB 8 bit) into the swapchain image. Its acquire semaphore is
    // waited on at the transfer stage, which the first barrier's source scope chains to.
    const VkImage present = swapchain.image(index);
    image_barrier(cmd, source, VK_IMAGE_ASPECT_COLOR_BIT, color_out, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                  VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    image_barrier(cmd, present, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT, 0, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkImageBlit region{};
    region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    const VkExtent2D e = swapchain.extent();
    region.srcOffsets[1] = {int32_t(std::min(e.width, images.extent.width)),
                            int32_t(std::min(e.height, images.extent.height)), 1};
    region.dstOffsets[1] = region.srcOffsets[1];
    vkCmdBlitImage(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, present, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &region, VK_FILTER_NEAREST);
    // Where the swapchain image is now, and which writes to it the next barrier waits for.
    VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_BLIT_BIT;
    VkAccessFlags2 access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    if (ui) {
        image_barrier(cmd, present, VK_IMAGE_ASPECT_COLOR_BIT, stage, access, layout, color_out,
                      VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        ui->record(cmd, index, e);  // its render pass ends in PRESENT_SRC_KHR (dependency at color_out)
        layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        stage = color_out;
        access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    }
    if (readback) {
        image_barrier(cmd, present, VK_IMAGE_ASPECT_COLOR_BIT, stage, access, layout, VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {e.width, e.height, 1};
        vkCmdCopyImageToBuffer(cmd, present, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback->buffer, 1, &copy);
        layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        stage = VK_PIPELINE_STAGE_2_COPY_BIT;
        access = 0;
        host_read_barrier(cmd);
    }
    if (layout != VK_IMAGE_LAYOUT_PRESENT_SRC_KHR)
        image_barrier(cmd, present, VK_IMAGE_ASPECT_COLOR_BIT, stage, access, layout, VK_PIPELINE_STAGE_2_NONE, 0,
                      VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, sync.timestamps, 2);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

void save_screenshot(const std::string& path, const VulkanHost& host, const HostBuffer& readback,
                     const Swapchain& swapchain)
{
    const VkExtent2D e = swapchain.extent();
    void* mapped = nullptr;
    check(vkMapMemory(host.device(), readback.memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    const auto* bytes = static_cast<const uint8_t*>(mapped);
    const bool bgra = swapchain.format() == VK_FORMAT_B8G8R8A8_SRGB;
    std::vector<float> rgba(size_t(e.width) * e.height * 4);
    for (size_t i = 0; i < size_t(e.width) * e.height; ++i) {
        const uint8_t* p = bytes + 4 * i;
        rgba[4 * i + 0] = srgb_to_linear(bgra ? p[2] : p[0]);
        rgba[4 * i + 1] = srgb_to_linear(p[1]);
        rgba[4 * i + 2] = srgb_to_linear(bgra ? p[0] : p[2]);
        rgba[4 * i + 3] = 1.0f;  // the window is opaque
    }
    vkUnmapMemory(host.device(), readback.memory);
    jade::save_image(path, int(e.width), int(e.height), rgba);
}

// The viewer's objects live in this function; run() counts validation messages after they
// were all destroyed (the layer reports leaks at vkDestroyDevice).
void run_window(const Options& options)
{
    Window window(options.width, options.height, "jade-view");
    VulkanHost host(window, options.validation);
    std::printf("jade-view: %s, validation %s\n", host.device_name().c_str(), host.validation() ? "on" : "off");
    ViewState state = options.state;
    Scene scene(host.adopted_vulkan(), options.mesh, state);
    std::printf("jade-view: %s, %zu bake vertices\n", scene.mesh_name().c_str(), scene.vertex_count());

    auto swapchain = std::make_unique<Swapchain>(host, window.framebuffer_size(), options.vsync);
    auto images = std::make_unique<RenderImages>(host, swapchain->extent(), VkSampleCountFlagBits(options.samples));
    glfwSetScrollCallback(window.handle(), [](GLFWwindow*, double, double dy) { g_wheel += dy; });
    std::unique_ptr<Ui> ui;
    if (options.ui) ui = std::make_unique<Ui>(host, window.handle(), *swapchain);
    FrameSync sync(host);
    std::unique_ptr<HostBuffer> readback;
    IdleOnExit idle{host.device()};

    std::deque<double> frame_ms;                            // the last 30 frames, for the panel
    std::vector<double> all_frame_ms, draw_ms, present_ms;  // every frame, for the summary
    double last = now_ms(), gpu_draw = 0, gpu_present = 0;
    double mouse_x = 0, mouse_y = 0;
    glfwGetCursorPos(window.handle(), &mouse_x, &mouse_y);
    for (uint32_t frame = 0; !window.should_close() && (options.frames == 0 || frame < options.frames);) {
        glfwPollEvents();
        if (glfwGetKey(window.handle(), GLFW_KEY_ESCAPE) == GLFW_PRESS)
            glfwSetWindowShouldClose(window.handle(), GLFW_TRUE);
        const double t = now_ms(), dt = t - last;
        last = t;
        // Orbit with the left mouse button, zoom with the wheel, unless the panel has the mouse.
        double x = 0, y = 0;
        glfwGetCursorPos(window.handle(), &x, &y);
        const bool panel_mouse = ui && ui->wants_mouse();
        if (!panel_mouse && glfwGetMouseButton(window.handle(), GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
            state.yaw = float(std::remainder(state.yaw - 0.3 * (x - mouse_x), 360.0));
            state.pitch = std::clamp(state.pitch + 0.3f * float(y - mouse_y), -89.0f, 89.0f);
        }
        if (!panel_mouse && g_wheel != 0.0)
            state.zoom = std::clamp(state.zoom * float(std::pow(0.9, g_wheel)), 0.2f, 5.0f);
        g_wheel = 0.0;
        mouse_x = x;
        mouse_y = y;
        if (state.deformation != 0 && state.animate && frame > 0) state.time = std::fmod(state.time + dt / 1000.0, 2.0);

        if (ui) {
            PanelInfo info{host.device_name(), scene.mesh_name(), scene.vertex_count(), 0.0, scene.times().stages};
            if (!frame_ms.empty())
                info.frame_ms = std::accumulate(frame_ms.begin(), frame_ms.end(), 0.0) / double(frame_ms.size());
            info.stages.emplace_back("jade draw (GPU)", gpu_draw);
            info.stages.emplace_back("blit + panel (GPU)", gpu_present);
            ui->build(state, info);
        }
        scene.update(state);

        const VkExtent2D size = window.framebuffer_size();
        if (size.width == 0 || size.height == 0) continue;  // minimised
        if (window.take_resized() || size.width != swapchain->extent().width ||
            size.height != swapchain->extent().height) {
            vkDeviceWaitIdle(host.device());
            swapchain = std::make_unique<Swapchain>(host, size, options.vsync, swapchain.get());
            images = std::make_unique<RenderImages>(host, swapchain->extent(), VkSampleCountFlagBits(options.samples));
            if (ui) ui->on_swapchain(*swapchain);
        }
        uint32_t index = 0;
        const VkResult acquired = vkAcquireNextImageKHR(host.device(), swapchain->handle(), UINT64_MAX, sync.acquired,
                                                        VK_NULL_HANDLE, &index);
        if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
            window.take_resized();
            vkDeviceWaitIdle(host.device());
            swapchain = std::make_unique<Swapchain>(host, window.framebuffer_size(), options.vsync, swapchain.get());
            images = std::make_unique<RenderImages>(host, swapchain->extent(), VkSampleCountFlagBits(options.samples));
            if (ui) ui->on_swapchain(*swapchain);
            continue;
        }
        if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");

        const bool last_frame = options.frames != 0 && frame + 1 == options.frames;
        const bool screenshot = last_frame && !options.screenshot.empty();
        if (screenshot)
            readback = std::make_unique<HostBuffer>(
                make_host_buffer(host.physical(), host.device(),
                                 VkDeviceSize(swapchain->extent().width) * swapchain->extent().height * 4,
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT));
        record_frame(sync, scene, state, *images, *swapchain, index, ui.get(), screenshot ? readback.get() : nullptr);
        const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        const VkSemaphore finished = swapchain->render_finished(index);
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.waitSemaphoreCount = 1;
        const VkSemaphore acquired_semaphore = sync.acquired;
        si.pWaitSemaphores = &acquired_semaphore;
        si.pWaitDstStageMask = &wait_stage;
        si.commandBufferCount = 1;
        si.pCommandBuffers = &sync.cmd;
        si.signalSemaphoreCount = 1;
        si.pSignalSemaphores = &finished;
        check(vkQueueSubmit(host.queue(), 1, &si, sync.done), "vkQueueSubmit");
        VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        pi.waitSemaphoreCount = 1;
        pi.pWaitSemaphores = &finished;
        pi.swapchainCount = 1;
        const VkSwapchainKHR sc = swapchain->handle();
        pi.pSwapchains = &sc;
        pi.pImageIndices = &index;
        const VkResult presented = vkQueuePresentKHR(host.queue(), &pi);
        if (presented != VK_SUBOPTIMAL_KHR && presented != VK_ERROR_OUT_OF_DATE_KHR)
            check(presented, "vkQueuePresentKHR");
        // One frame in flight: Jade's calls of the next update (bakes, set_mesh) need the queue.
        const VkFence done = sync.done;
        check(vkWaitForFences(host.device(), 1, &done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        check(vkResetFences(host.device(), 1, &done), "vkResetFences");
        uint64_t stamps[3] = {};
        check(vkGetQueryPoolResults(host.device(), sync.timestamps, 0, 3, sizeof(stamps), stamps, sizeof(uint64_t),
                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "vkGetQueryPoolResults");
        gpu_draw = double(stamps[1] - stamps[0]) * sync.timestamp_period_ns * 1e-6;
        gpu_present = double(stamps[2] - stamps[1]) * sync.timestamp_period_ns * 1e-6;
        if (screenshot) {
            save_screenshot(options.screenshot, host, *readback, *swapchain);
            std::printf("jade-view: wrote %s (%ux%u)\n", options.screenshot.c_str(), swapchain->extent().width,
                        swapchain->extent().height);
        }
        const double frame_time = now_ms() - t;
        frame_ms.push_back(frame_time);
        if (frame_ms.size() > 30) frame_ms.pop_front();
        all_frame_ms.push_back(frame_time);
        draw_ms.push_back(gpu_draw);
        present_ms.push_back(gpu_present);
        ++frame;
    }
    if (ui) {
        for (const PanelRect& r : ui->panel_rects())
            std::printf("jade-view: panel at %d,%d size %dx%d\n", r.x, r.y, r.width, r.height);
    }
    // Frame 0 creates Jade's pipelines: the summary leaves it out when there are others.
    const size_t skip = all_frame_ms.size() > 1 ? 1 : 0;
    if (all_frame_ms.size() > skip) {
        const double n = double(all_frame_ms.size() - skip);
        auto mean = [&](const std::vector<double>& v) {
            return std::accumulate(v.begin() + long(skip), v.end(), 0.0) / n;
        };
        std::printf(
            "jade-view: %zu frames at %ux%u, mean frame %.1f ms: Jade draw %.1f ms, blit + panel %.1f ms (GPU); "
            "first frame %.1f ms\n",
            all_frame_ms.size(), swapchain->extent().width, swapchain->extent().height, mean(all_frame_ms),
            mean(draw_ms), mean(present_ms), all_frame_ms.front());
    }
    for (const auto& [name, ms] : scene.times().stages) std::printf("jade-view:   %-28s %9.2f ms\n", name.c_str(), ms);
}

}  // namespace

int run(const Options& options)
{
    run_window(options);
    const uint64_t messages = VulkanHost::validation_messages();
    if (messages)
        std::fprintf(stderr, "jade-view: the validation layer reported %llu message(s)\n",
                     (unsigned long long)messages);
    return messages ? 2 : 0;
}

}  // namespace samples::viewer
