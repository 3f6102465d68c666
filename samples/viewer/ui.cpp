#include "ui.hpp"

#include "swapchain.hpp"
#include "window.hpp"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <jade/material.hpp>

#include <cmath>
#include <cstdio>

namespace samples::viewer {

namespace {

constexpr float kPanelWidth = 290.0f;
constexpr float kItemWidth = 160.0f;  // sliders and combos; the labels take the rest

void check_imgui(VkResult r)
{
    if (r != VK_SUCCESS) std::fprintf(stderr, "jade-view: ImGui Vulkan back-end: VkResult %d\n", int(r));
}

// A combo box over a list of strings; returns true when the selection changed.
bool combo(const char* label, int* index, const std::vector<std::string>& items)
{
    return ImGui::Combo(
        label, index,
        [](void* data, int i, const char** out) {
        *out = (*static_cast<const std::vector<std::string>*>(data))[size_t(i)].c_str();
        return true;
        },
        const_cast<std::vector<std::string>*>(&items), int(items.size()));
}

// ImGui's colours are sRGB values; the swapchain has an sRGB format that encodes what is
// written, so the style's colours are decoded once to keep the panel's intended look.
void linearise_style()
{
    auto decode = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
    for (ImVec4& c : ImGui::GetStyle().Colors) {
        c.x = decode(c.x);
        c.y = decode(c.y);
        c.z = decode(c.z);
    }
}

}  // namespace

Ui::Ui(const VulkanHost& host, GLFWwindow* window, const Swapchain& swapchain) : device_(host.device())
{
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pi.maxSets = 4;
    pi.poolSizeCount = 1;
    pi.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device_, &pi, nullptr, &pool), "vkCreateDescriptorPool");
    pool_ = own(device_, pool, vkDestroyDescriptorPool);

    VkAttachmentDescription attachment{};
    attachment.format = swapchain.format();
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // Jade's frame, blitted in before
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    // In: the caller's barrier made the blit visible to COLOR_ATTACHMENT_OUTPUT; this orders the
    // load after it. Out: the panel's writes and the transition to PRESENT_SRC_KHR happen before
    // the caller's later barriers that start at COLOR_ATTACHMENT_OUTPUT (the screenshot copy).
    VkSubpassDependency dependencies[2]{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstAccessMask = 0;
    VkRenderPassCreateInfo ri{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    ri.attachmentCount = 1;
    ri.pAttachments = &attachment;
    ri.subpassCount = 1;
    ri.pSubpasses = &subpass;
    ri.dependencyCount = 2;
    ri.pDependencies = dependencies;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    check(vkCreateRenderPass(device_, &ri, nullptr, &render_pass), "vkCreateRenderPass");
    render_pass_ = own(device_, render_pass, vkDestroyRenderPass);
    on_swapchain(swapchain);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    imgui_context_ = true;
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the binary
    ImGui::StyleColorsDark();
    linearise_style();
    if (!ImGui_ImplGlfw_InitForVulkan(window, true)) throw std::runtime_error("ImGui_ImplGlfw_InitForVulkan failed");
    glfw_backend_ = true;
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = host.instance();
    info.PhysicalDevice = host.physical();
    info.Device = device_;
    info.QueueFamily = host.queue_family();
    info.Queue = host.queue();
    info.DescriptorPool = pool_;
    info.MinImageCount = swapchain.min_image_count();
    info.ImageCount = swapchain.image_count();
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = &check_imgui;
    if (!ImGui_ImplVulkan_Init(&info, render_pass_)) throw std::runtime_error("ImGui_ImplVulkan_Init failed");
    vulkan_backend_ = true;

    // Font upload: a one-off command buffer on the host's queue.
    submit_and_wait(device_, host.queue(), host.queue_family(),
                    [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Ui::~Ui()
{
    vkDeviceWaitIdle(device_);
    if (vulkan_backend_) ImGui_ImplVulkan_Shutdown();
    if (glfw_backend_) ImGui_ImplGlfw_Shutdown();
    if (imgui_context_) ImGui::DestroyContext();
}

void Ui::on_swapchain(const Swapchain& swapchain)
{
    framebuffers_.clear();
    for (uint32_t i = 0; i < swapchain.image_count(); ++i) {
        VkImageView view = swapchain.view(i);
        VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fi.renderPass = render_pass_;
        fi.attachmentCount = 1;
        fi.pAttachments = &view;
        fi.width = swapchain.extent().width;
        fi.height = swapchain.extent().height;
        fi.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        check(vkCreateFramebuffer(device_, &fi, nullptr, &fb), "vkCreateFramebuffer");
        framebuffers_.push_back(own(device_, fb, vkDestroyFramebuffer));
    }
    if (vulkan_backend_) ImGui_ImplVulkan_SetMinImageCount(swapchain.min_image_count());
}

bool Ui::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }

bool Ui::build(ViewState& s, const PanelInfo& info)
{
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, 0.0f), ImGuiCond_Always);
    ImGui::Begin("jade", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(kItemWidth);
    bool changed = false;
    ImGui::TextUnformatted(info.device.c_str());
    ImGui::Text("%s, %zu vertices", info.mesh.c_str(), info.vertices);

    if (ImGui::CollapsingHeader("camera and lights", ImGuiTreeNodeFlags_DefaultOpen)) {
        changed |= ImGui::SliderFloat("yaw", &s.yaw, -180.0f, 180.0f, "%.0f deg");
        changed |= ImGui::SliderFloat("pitch", &s.pitch, -89.0f, 89.0f, "%.0f deg");
        changed |= ImGui::SliderFloat("zoom", &s.zoom, 0.2f, 5.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        changed |= ImGui::Checkbox("back light (figure 1)", &s.figure1_lights);
        changed |= ImGui::SliderFloat("light yaw", &s.light_yaw, -180.0f, 180.0f, "%.0f deg");
        changed |= ImGui::SliderFloat("light pitch", &s.light_pitch, -89.0f, 89.0f, "%.0f deg");
        if (ImGui::Button("reset view")) {
            s.yaw = s.pitch = s.light_yaw = s.light_pitch = 0.0f;
            s.zoom = 1.0f;
            changed = true;
        }
    }
    if (ImGui::CollapsingHeader("material and shading", ImGuiTreeNodeFlags_DefaultOpen)) {
        static const std::vector<std::string> materials = jade::material_preset_names();
        changed |= combo("material", &s.material, materials);
        changed |= ImGui::SliderFloat("strength", &s.strength, 0.0f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        static const std::vector<std::string> modes = {"lambert", "curvature", "tm", "tm-false-color", "filament"};
        int mode = int(s.mode);
        if (combo("shading", &mode, modes)) {
            s.mode = jade::ShadingMode(mode);
            changed = true;
        }
        static const std::vector<std::string> qualities = {"draft", "default", "high"};
        int quality = int(s.quality);
        if (combo("bake quality", &quality, qualities)) {
            s.quality = jade::Quality(quality);
            changed = true;
        }
    }
    if (ImGui::CollapsingHeader("deformation", ImGuiTreeNodeFlags_DefaultOpen)) {
        changed |= combo("deformer", &s.deformation, deformation_names());
        changed |= ImGui::Checkbox("animate", &s.animate);
        float t = float(s.time);
        if (ImGui::SliderFloat("time", &t, 0.0f, 2.0f, "%.2f s")) {
            s.time = t;
            changed = true;
        }
    }
    ImGui::PopItemWidth();
    rects_.clear();
    auto add_rect = [this] {
        const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        rects_.push_back({int(pos.x), int(pos.y), int(size.x + 0.5f), int(size.y + 0.5f)});
    };
    add_rect();
    ImGui::End();

    // Frame and stage times: a small translucent overlay in the bottom-right corner.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 6.0f, display.y - 6.0f), ImGuiCond_Always, ImVec2(1.0f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.55f);
    ImGui::Begin("timings", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs);
    ImGui::Text("frame %.1f ms (%.1f fps)", info.frame_ms, info.frame_ms > 0 ? 1000.0 / info.frame_ms : 0.0);
    ImGui::Separator();
    for (const auto& [name, ms] : info.stages) ImGui::Text("%-30s %9.2f ms", name.c_str(), ms);
    add_rect();
    ImGui::End();
    ImGui::Render();
    return changed;
}

void Ui::record(VkCommandBuffer cmd, uint32_t index, VkExtent2D extent)
{
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = render_pass_;
    bi.framebuffer = framebuffers_.at(index);
    bi.renderArea = {{0, 0}, extent};
    vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
}

}  // namespace samples::viewer
