// gpu/adopt.cpp - a Context on the host's Vulkan objects (jade::AdoptedVulkan): what Jade
// requires of them, the check that names everything missing, and jade::HostDeviceSetup, which
// makes a device that meets it.
#include "gpu/context.hpp"

#include <jade/context.hpp>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

namespace jade::gpu {

Context::Context(const AdoptedVulkan& host, const ContextOptions& options)
    : log_(options.log), verbose_(options.verbose), adopted_(true)
{
    check_adopted(host);  // throws before anything is created
    instance_ = host.instance;
    physical_ = host.physical_device;
    device_ = host.device;
    queue_ = host.queue;
    queue_family_ = host.queue_family;
    vkGetPhysicalDeviceProperties(physical_, &properties_);
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
    auto gipa = host.get_instance_proc_addr ? host.get_instance_proc_addr : vkGetInstanceProcAddr;
    auto gdpa = host.get_device_proc_addr ? host.get_device_proc_addr : vkGetDeviceProcAddr;
    cmd_push_descriptor_set =
        reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(gdpa(device_, "vkCmdPushDescriptorSetKHR"));
    if (!cmd_push_descriptor_set) throw Error("adopted Vulkan device: vkCmdPushDescriptorSetKHR cannot be loaded");
    // Null when the host's instance has no VK_EXT_debug_utils: objects are then not named.
    set_object_name_ =
        reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(gipa(instance_, "vkSetDebugUtilsObjectNameEXT"));
    try {
        create_submission_objects();
        fill_info();
    } catch (...) {
        destroy();
        throw;
    }
    if (verbose_) log(std::string("jade: adopted the host's device ") + properties_.deviceName);
}

namespace {

// The features Jade needs, as found in (or missing from) a vkCreateDevice pNext chain.
struct RequiredFeatures {
    bool dynamic_rendering = false, synchronization2 = false, maintenance4 = false;
    bool scalar_block_layout = false, host_query_reset = false, float64 = false;
    bool int64 = false, buffer_int64_atomics = false;  // optional, both needed

    void read(const void* chain);
};

// The single-feature structs that Vulkan 1.2 and 1.3 promoted into their Vulkan12/13 structs:
// each is a header and one VkBool32, which enables the requirement `flag`.
struct PromotedFeature {
    VkStructureType type;
    bool RequiredFeatures::*flag;
    size_t offset;  // of the VkBool32
};
constexpr PromotedFeature kPromotedFeatures[] = {
    {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES, &RequiredFeatures::dynamic_rendering,
     offsetof(VkPhysicalDeviceDynamicRenderingFeatures, dynamicRendering)},
    {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES, &RequiredFeatures::synchronization2,
     offsetof(VkPhysicalDeviceSynchronization2Features, synchronization2)},
    {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_FEATURES, &RequiredFeatures::maintenance4,
     offsetof(VkPhysicalDeviceMaintenance4Features, maintenance4)},
    {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SCALAR_BLOCK_LAYOUT_FEATURES, &RequiredFeatures::scalar_block_layout,
     offsetof(VkPhysicalDeviceScalarBlockLayoutFeatures, scalarBlockLayout)},
    {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_HOST_QUERY_RESET_FEATURES, &RequiredFeatures::host_query_reset,
     offsetof(VkPhysicalDeviceHostQueryResetFeatures, hostQueryReset)},
    {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES, &RequiredFeatures::buffer_int64_atomics,
     offsetof(VkPhysicalDeviceShaderAtomicInt64Features, shaderBufferInt64Atomics)},
};

void RequiredFeatures::read(const void* chain)
{
    for (auto* s = static_cast<const VkBaseInStructure*>(chain); s; s = s->pNext) {
        switch (s->sType) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2:
            float64 |= bool(reinterpret_cast<const VkPhysicalDeviceFeatures2*>(s)->features.shaderFloat64);
            int64 |= bool(reinterpret_cast<const VkPhysicalDeviceFeatures2*>(s)->features.shaderInt64);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES: {
            auto* f = reinterpret_cast<const VkPhysicalDeviceVulkan12Features*>(s);
            scalar_block_layout |= bool(f->scalarBlockLayout);
            host_query_reset |= bool(f->hostQueryReset);
            buffer_int64_atomics |= bool(f->shaderBufferInt64Atomics);
            break;
        }
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES: {
            auto* f = reinterpret_cast<const VkPhysicalDeviceVulkan13Features*>(s);
            dynamic_rendering |= bool(f->dynamicRendering);
            synchronization2 |= bool(f->synchronization2);
            maintenance4 |= bool(f->maintenance4);
            break;
        }
        default:
            for (const PromotedFeature& p : kPromotedFeatures) {
                if (s->sType != p.type) continue;
                VkBool32 enabled;
                std::memcpy(&enabled, reinterpret_cast<const char*>(s) + p.offset, sizeof enabled);
                this->*p.flag |= bool(enabled);
            }
            break;
        }
    }
}

}  // namespace

void Context::check_adopted(const AdoptedVulkan& host)
{
    std::vector<std::string> missing;
    if (!host.instance) missing.push_back("instance is VK_NULL_HANDLE");
    if (!host.physical_device) missing.push_back("physical_device is VK_NULL_HANDLE");
    if (!host.device) missing.push_back("device is VK_NULL_HANDLE");
    if (!host.queue) missing.push_back("queue is VK_NULL_HANDLE");
    if (!missing.empty()) {
        std::string msg = "adopted Vulkan objects:";
        for (auto& m : missing) msg += " " + m + ";";
        throw Error(msg);
    }
    auto version = [](uint32_t v) {
        return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v));
    };
    if (host.api_version < VK_API_VERSION_1_3)
        missing.push_back("instance apiVersion 1.3 (AdoptedVulkan::api_version is " + version(host.api_version) + ")");
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(host.physical_device, &props);
    if (props.apiVersion < VK_API_VERSION_1_3)
        missing.push_back("device Vulkan 1.3 (" + std::string(props.deviceName) + " has " + version(props.apiVersion) +
                          ")");
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &n, families.data());
    if (host.queue_family >= n) {
        missing.push_back("queue family " + std::to_string(host.queue_family) + " (the device has " +
                          std::to_string(n) + ")");
    } else {
        const auto& f = families[host.queue_family];
        if (!(f.queueFlags & VK_QUEUE_GRAPHICS_BIT))
            missing.push_back("graphics on queue family " + std::to_string(host.queue_family));
        if (!(f.queueFlags & VK_QUEUE_COMPUTE_BIT))
            missing.push_back("compute on queue family " + std::to_string(host.queue_family));
        if (f.timestampValidBits == 0)
            missing.push_back("timestamps on queue family " + std::to_string(host.queue_family));
    }
    for (const char* ext : jade::Context::required_device_extensions())
        if (std::find(host.enabled_extensions.begin(), host.enabled_extensions.end(), ext) ==
            host.enabled_extensions.end())
            missing.push_back(std::string("extension ") + ext);
    RequiredFeatures f;
    f.read(host.enabled_features);
    if (!f.dynamic_rendering) missing.push_back("feature dynamicRendering");
    if (!f.synchronization2) missing.push_back("feature synchronization2");
    if (!f.maintenance4) missing.push_back("feature maintenance4");
    if (!f.scalar_block_layout) missing.push_back("feature scalarBlockLayout");
    if (!f.host_query_reset) missing.push_back("feature hostQueryReset");
    float64_ = f.float64;
    int64_atomics_ = f.int64 && f.buffer_int64_atomics;
    if (missing.empty()) return;
    std::string msg = "adopted Vulkan device " + std::string(props.deviceName) + " lacks what Jade needs:";
    for (auto& m : missing) msg += "\n  " + m;
    msg += "\nenable them when creating the device (jade::Context::required_device_extensions(), "
           "jade::Context::enable_required_features()) and list them in AdoptedVulkan";
    throw Error(msg);
}

}  // namespace jade::gpu

namespace jade {

std::vector<const char*> Context::required_device_extensions() { return {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME}; }
void Context::enable_required_features(VkPhysicalDeviceVulkan12Features& f12, VkPhysicalDeviceVulkan13Features& f13)
{
    f12.scalarBlockLayout = VK_TRUE;
    f12.hostQueryReset = VK_TRUE;
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    f13.maintenance4 = VK_TRUE;  // group size from a specialisation constant (LocalSizeId)
}

void Context::enable_optional_features(VkPhysicalDevice physical, VkPhysicalDeviceFeatures2& features,
                                       VkPhysicalDeviceVulkan12Features& f12)
{
    VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported12};
    vkGetPhysicalDeviceFeatures2(physical, &supported);
    if (supported.features.shaderFloat64) features.features.shaderFloat64 = VK_TRUE;
    if (supported.features.shaderInt64 && supported12.shaderBufferInt64Atomics) {  // the grid splat's packed atomics
        features.features.shaderInt64 = VK_TRUE;
        f12.shaderBufferInt64Atomics = VK_TRUE;
    }
}

HostDeviceSetup::HostDeviceSetup(bool with_jade_requirements)
{
    if (!with_jade_requirements) return;
    Context::enable_required_features(f12, f13);
    extensions = Context::required_device_extensions();
}

VkDevice HostDeviceSetup::create(VkPhysicalDevice physical, uint32_t queue_family) const
{
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    q.queueFamilyIndex = queue_family;
    q.queueCount = 1;
    q.pQueuePriorities = &priority;
    VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &q;
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    VkDevice device = VK_NULL_HANDLE;
    gpu::check(vkCreateDevice(physical, &ci, nullptr, &device), "HostDeviceSetup: vkCreateDevice");
    return device;
}

AdoptedVulkan HostDeviceSetup::adopted(VkInstance instance, VkPhysicalDevice physical, VkDevice device,
                                       uint32_t queue_family, VkQueue queue) const
{
    AdoptedVulkan a;
    a.instance = instance;
    a.physical_device = physical;
    a.device = device;
    a.queue = queue;
    a.queue_family = queue_family;
    a.api_version = VK_API_VERSION_1_3;
    a.get_instance_proc_addr = vkGetInstanceProcAddr;
    a.get_device_proc_addr = vkGetDeviceProcAddr;
    a.enabled_features = &features;
    a.enabled_extensions.assign(extensions.begin(), extensions.end());
    return a;
}

}  // namespace jade
