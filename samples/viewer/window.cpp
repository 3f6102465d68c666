#include "window.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace samples::viewer {

// ------------------------------------------------------------------------------------ window --

Window::Window(uint32_t width, uint32_t height, const std::string& title)
{
    glfwSetErrorCallback(
        [](int code, const char* message) { std::fprintf(stderr, "jade-view: GLFW error %d: %s\n", code, message); });
    if (!glfwInit())
        throw std::runtime_error("cannot initialise GLFW: no display? (set DISPLAY, or run under xvfb-run)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw std::runtime_error("GLFW finds no Vulkan loader (install libvulkan1)");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw std::runtime_error("cannot create a " + std::to_string(width) + "x" + std::to_string(height) + " window");
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetFramebufferSizeCallback(window_, &Window::on_resize);
}

Window::~Window()
{
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }

VkExtent2D Window::framebuffer_size() const
{
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
}

bool Window::take_resized() { return std::exchange(resized_, false); }

void Window::on_resize(GLFWwindow* window, int, int)
{
    static_cast<Window*>(glfwGetWindowUserPointer(window))->resized_ = true;
}

// ------------------------------------------------------------------------------ vulkan host --

namespace {

std::atomic<uint64_t> g_validation_messages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*)
{
    ++g_validation_messages;
    std::fprintf(stderr, "jade-view: validation: %s\n", data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

std::string lower(std::string s)
{
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

int type_rank(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

}  // namespace

uint64_t VulkanHost::validation_messages() { return g_validation_messages.load(); }

VulkanHost::VulkanHost(const Window& window, bool validation)
{
    create_instance(validation);
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    check(glfwCreateWindowSurface(instance(), window.handle(), nullptr, &surface), "glfwCreateWindowSurface");
    surface_ =
        Owned<VkSurfaceKHR>(surface, [inst = instance()](VkSurfaceKHR s) { vkDestroySurfaceKHR(inst, s, nullptr); });
    pick_physical_device();
    create_device();
}

VulkanHost::~VulkanHost()
{
    if (device_) vkDeviceWaitIdle(device_);
}

void VulkanHost::create_instance(bool validation)
{
    uint32_t glfw_count = 0;
    const char** glfw_extensions = glfwGetRequiredInstanceExtensions(&glfw_count);
    if (!glfw_extensions) throw std::runtime_error("GLFW reports no Vulkan surface extensions for this display");
    InstanceOptions options;
    options.application = "jade-view";
    options.extensions.assign(glfw_extensions, glfw_extensions + glfw_count);
    options.validation = validation;
    // JADE_SYNC_VALIDATION=1 adds the layer's synchronization validation (hazards between the
    // viewer's and Jade's commands), as for the engine's own Context.
    const char* sync_env = std::getenv("JADE_SYNC_VALIDATION");
    options.synchronization_validation = sync_env && *sync_env && std::strcmp(sync_env, "0") != 0;
    if (options.synchronization_validation) std::fprintf(stderr, "jade-view: Vulkan synchronization validation on\n");
    options.on_message = &on_message;
    instance_ = samples::create_instance(options);
}

// The best Vulkan 1.3 device (discrete first, JADE_DEVICE narrows by name) with one queue family
// that draws, computes, writes timestamps and presents to the window; Jade checks the rest.
void VulkanHost::pick_physical_device()
{
    const char* wanted = std::getenv("JADE_DEVICE");
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance(), &n, nullptr);
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance(), &n, devices.data());
    std::string rejected;
    int best_rank = 1 << 30;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        const std::string name = p.deviceName;
        if (wanted && *wanted && lower(name).find(lower(wanted)) == std::string::npos) continue;
        if (p.apiVersion < VK_API_VERSION_1_3) {
            rejected += "\n  " + name + ": Vulkan < 1.3";
            continue;
        }
        uint32_t nf = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &nf, nullptr);
        std::vector<VkQueueFamilyProperties> families(nf);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &nf, families.data());
        const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        for (uint32_t i = 0; i < nf; ++i) {
            VkBool32 present = VK_FALSE;
            vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, surface_, &present);
            if ((families[i].queueFlags & needed) != needed || !present || families[i].timestampValidBits == 0)
                continue;
            if (type_rank(p.deviceType) < best_rank) {
                best_rank = type_rank(p.deviceType);
                physical_ = pd;
                family_ = i;
                device_name_ = name;
            }
            break;
        }
        if (physical_ != pd)
            rejected += "\n  " + name + ": no queue family that draws, computes and presents to the window";
    }
    if (!physical_)
        throw std::runtime_error("no Vulkan 1.3 device can present to the window" +
                                 (wanted && *wanted ? " (JADE_DEVICE=" + std::string(wanted) + ")" : std::string()) +
                                 rejected);
}

void VulkanHost::create_device()
{
    setup_.extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    // 64-bit buffer atomics halve the grid splat's atomics in every re-bake of a deforming mesh.
    jade::Context::enable_optional_features(physical_, setup_.features, setup_.f12);
    VkDevice device = setup_.create(physical_, family_);
    device_ = Owned<VkDevice>(device, [](VkDevice d) { vkDestroyDevice(d, nullptr); });
    vkGetDeviceQueue(device, family_, 0, &queue_);
}

jade::AdoptedVulkan VulkanHost::adopted_vulkan() const
{
    return setup_.adopted(instance(), physical_, device_, family_, queue_);
}

}  // namespace samples::viewer
