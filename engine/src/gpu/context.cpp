#include <jade/dev/context.hpp>
#include "gpu/context.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace jade::gpu {
namespace {

bool env_flag(const char* name)
{
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

const char* type_name(VkPhysicalDeviceType t)
{
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

// Lower is better: discrete GPUs first, CPU implementations (lavapipe) last.
int type_rank(VkPhysicalDeviceType t)
{
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 4;
    default: return 3;
    }
}

bool has_layer(const char* name)
{
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool has_instance_extension(const char* name)
{
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> ext(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, ext.data());
    return std::any_of(ext.begin(), ext.end(), [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool has_device_extension(VkPhysicalDevice pd, const char* name)
{
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> ext(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data());
    return std::any_of(ext.begin(), ext.end(), [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr const char* kNoDevice = "no Vulkan device found. Install a Vulkan driver: on Debian/Ubuntu `apt-get install "
                                  "mesa-vulkan-drivers` gives lavapipe, a software device that runs everywhere "
                                  "(third_party/install_deps.sh installs it)";

struct Candidate {
    VkPhysicalDevice device;
    VkPhysicalDeviceProperties props;
    uint32_t queue_family;
    std::string rejected;  // empty when usable
};

// Why a device cannot run Jade, or "" when it can.
std::string rejection(VkPhysicalDevice pd, const VkPhysicalDeviceProperties& props, uint32_t& family)
{
    if (props.apiVersion < VK_API_VERSION_1_3)
        return "needs Vulkan 1.3, device has " + std::to_string(VK_API_VERSION_MAJOR(props.apiVersion)) + "." +
               std::to_string(VK_API_VERSION_MINOR(props.apiVersion));
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    family = UINT32_MAX;
    for (uint32_t i = 0; i < n; ++i) {
        VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) {
            family = i;
            break;
        }
    }
    if (family == UINT32_MAX) return "no queue family with graphics, compute and timestamps";
    if (!has_device_extension(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) return "no VK_KHR_push_descriptor";
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    vkGetPhysicalDeviceFeatures2(pd, &f);
    if (!f13.dynamicRendering) return "no dynamicRendering";
    if (!f13.synchronization2) return "no synchronization2";
    if (!f13.maintenance4) return "no maintenance4 (LocalSizeId)";
    if (!f12.scalarBlockLayout) return "no scalarBlockLayout";
    if (!f12.hostQueryReset) return "no hostQueryReset";
    return "";
}

}  // namespace

const char* result_name(VkResult r)
{
    switch (r) {
#define JADE_CASE(x)                                                                                                   \
    case x: return #x;
        JADE_CASE(VK_SUCCESS)
        JADE_CASE(VK_NOT_READY)
        JADE_CASE(VK_TIMEOUT)
        JADE_CASE(VK_INCOMPLETE)
        JADE_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        JADE_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        JADE_CASE(VK_ERROR_INITIALIZATION_FAILED)
        JADE_CASE(VK_ERROR_DEVICE_LOST)
        JADE_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        JADE_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        JADE_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        JADE_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        JADE_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        JADE_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        JADE_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        JADE_CASE(VK_ERROR_FRAGMENTED_POOL)
        JADE_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
        JADE_CASE(VK_ERROR_UNKNOWN)
#undef JADE_CASE
    default: return "VkResult(unknown)";
    }
}

Context::Context(const ContextOptions& options) : log_(options.log), verbose_(options.verbose)
{
    try {
        create_instance(options);
        choose_physical_device(options);
        create_device();
        fill_info();
    } catch (...) {
        destroy();  // a throwing constructor runs no destructor: release what was created
        throw;
    }
}

Context::~Context() { destroy(); }

void Context::destroy()
{
    if (adopted_) {
        // Only Jade's own objects go; the host's device and instance stay untouched.
        // Jade's own submissions were each waited for; what is left is what release_after_gpu()
        // keeps for the host's submitted draws: wait for those fences only, not for the queue.
        release_queue_.destroy_all();
        fence_.reset();
        command_pool_.reset();
        return;
    }
    if (device_) vkDeviceWaitIdle(device_);  // Jade's own device: nobody else's work to stall
    release_queue_.destroy_all();
    fence_.reset();
    command_pool_.reset();
    if (device_) vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

void Context::log(std::string_view line) const
{
    if (log_)
        log_(line);
    else
        std::fprintf(stderr, "%.*s\n", int(line.size()), line.data());
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                         VkDebugUtilsMessageTypeFlagsEXT,
                                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* user)
{
    auto* self = static_cast<Context*>(user);
    self->validation_messages_++;
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    self->log(std::string("jade: vulkan validation ") + level + ": " + (data->pMessage ? data->pMessage : ""));
    return VK_FALSE;
}

void Context::create_instance(const ContextOptions& options)
{
    const bool sync_validation = options.synchronization_validation || env_flag("JADE_SYNC_VALIDATION");
    const bool validation =
        options.validation || env_flag("JADE_VALIDATION") || sync_validation;  // sync needs the layer

    std::vector<const char*> layers, extensions;
    bool debug_utils = has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debug_utils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (validation) {
        if (!has_layer(kValidationLayer))
            throw Error(std::string("validation requested (JADE_VALIDATION) but ") + kValidationLayer +
                        " is not installed: apt-get install vulkan-validationlayers");
        if (!debug_utils) throw Error("validation requested but VK_EXT_debug_utils is missing");
        layers.push_back(kValidationLayer);
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "jade";
    app.pEngineName = "jade";
    app.apiVersion = VK_API_VERSION_1_3;

    VkValidationFeatureEnableEXT sync_feature = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync_feature;

    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger.pfnUserCallback = &Context::on_debug_message;
    messenger.pUserData = this;
    if (validation && sync_validation) messenger.pNext = &features;

    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = uint32_t(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    if (validation) ci.pNext = &messenger;  // also reports on vkCreate/DestroyInstance
    VkResult r = vkCreateInstance(&ci, nullptr, &instance_);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER) throw Error(kNoDevice);
    check(r, "vkCreateInstance");

    if (validation) {
        // Said once, so that a test job can prove the hazard checks were on (tests/CMakeLists.txt).
        if (sync_validation) log("jade: Vulkan synchronization validation on");
        messenger.pNext = nullptr;
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        check(create(instance_, &messenger, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }
    if (debug_utils)
        set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
}

void Context::choose_physical_device(const ContextOptions& options)
{
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance_, &n, nullptr);
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance_, &n, devices.data());
    if (n == 0) throw Error(kNoDevice);

    std::string wanted = options.device;
    if (wanted.empty() && std::getenv("JADE_DEVICE")) wanted = std::getenv("JADE_DEVICE");
    std::vector<Candidate> candidates;
    for (auto pd : devices) {
        Candidate c{pd, {}, 0, {}};
        vkGetPhysicalDeviceProperties(pd, &c.props);
        c.rejected = rejection(pd, c.props, c.queue_family);
        if (c.rejected.empty() && !wanted.empty() && lower(c.props.deviceName).find(lower(wanted)) == std::string::npos)
            c.rejected = "name does not match '" + wanted + "'";
        candidates.push_back(c);
    }
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return type_rank(a.props.deviceType) < type_rank(b.props.deviceType);
    });
    for (const auto& c : candidates) {
        if (!c.rejected.empty()) continue;
        physical_ = c.device;
        properties_ = c.props;
        queue_family_ = c.queue_family;
        vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
        if (verbose_) log(std::string("jade: using device ") + c.props.deviceName);
        return;
    }
    std::string msg = "no suitable Vulkan device";
    if (!wanted.empty()) msg += " matching '" + wanted + "' (from --device or JADE_DEVICE)";
    msg += ":";
    for (const auto& c : candidates) msg += std::string("\n  ") + c.props.deviceName + ": " + c.rejected;
    msg += "\nJade needs Vulkan 1.3 with dynamicRendering, synchronization2, maintenance4, scalarBlockLayout and "
           "VK_KHR_push_descriptor; lavapipe (apt-get install mesa-vulkan-drivers) has all of them";
    throw Error(msg);
}

void Context::create_device()
{
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    vkGetPhysicalDeviceFeatures2(physical_, &supported);

    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    jade::Context::enable_required_features(f12, f13);
    jade::Context::enable_optional_features(physical_, features, f12);
    features.features.sampleRateShading = supported.features.sampleRateShading;
    float64_ = features.features.shaderFloat64;
    int64_atomics_ = features.features.shaderInt64 && f12.shaderBufferInt64Atomics;

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    const char* extensions[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    ci.queueCreateInfoCount = 1;
    ci.pQueueCreateInfos = &queue;
    ci.enabledExtensionCount = 1;
    ci.ppEnabledExtensionNames = extensions;
    check(vkCreateDevice(physical_, &ci, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
    cmd_push_descriptor_set =
        reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
    create_submission_objects();
}

void Context::create_submission_objects()
{
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = queue_family_;
    VkCommandPool p;
    check(vkCreateCommandPool(device_, &pool, nullptr, &p), "vkCreateCommandPool");
    command_pool_ = OwnedCommandPool(device_, p);
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence f;
    check(vkCreateFence(device_, &fci, nullptr, &f), "vkCreateFence");
    fence_ = OwnedFence(device_, f);
    release_queue_ = ReleaseQueue(device_, queue_, !adopted_);
}

void Context::fill_info()
{
    VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &maintenance3};
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES, &driver};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &subgroup};
    vkGetPhysicalDeviceProperties2(physical_, &props);
    max_memory_allocation_size_ = maintenance3.maxMemoryAllocationSize;
    const auto& l = properties_.limits;
    info_.name = properties_.deviceName;
    info_.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    info_.type = type_name(properties_.deviceType);
    info_.api_version = properties_.apiVersion;
    info_.max_storage_buffer_range = l.maxStorageBufferRange;
    for (int i = 0; i < 3; ++i) info_.max_workgroup_count[i] = l.maxComputeWorkGroupCount[i];
    info_.max_workgroup_invocations = l.maxComputeWorkGroupInvocations;
    info_.subgroup_size = subgroup.subgroupSize;
    info_.float64 = float64_;
    info_.int64_atomics = int64_atomics_;
    info_.timestamp_period_ns = l.timestampPeriod;
    for (uint32_t i = 0; i < memory_.memoryHeapCount; ++i)
        if (memory_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            info_.device_local_heap_bytes =
                std::max<uint64_t>(info_.device_local_heap_bytes, memory_.memoryHeaps[i].size);
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record)
{
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = command_pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd;
    check(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
    struct Free {
        VkDevice d;
        VkCommandPool p;
        VkCommandBuffer c;
        ~Free() { vkFreeCommandBuffers(d, p, 1, &c); }
    } free_later{device_, command_pool_, cmd};

    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    record(cmd);
    // Make every write of the submission visible to the host (mapped read-back after the fence).
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

    VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cb.commandBuffer = cmd;
    VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    si.commandBufferInfoCount = 1;
    si.pCommandBufferInfos = &cb;
    VkFence f = fence_;
    check(vkQueueSubmit2(queue_, 1, &si, f), "vkQueueSubmit2");
    check(vkWaitForFences(device_, 1, &f, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(device_, 1, &f), "vkResetFences");
    release_queue_.collect();
}

void Context::count_created(VkObjectType type, bool compute, uint64_t device_bytes) const
{
    switch (type) {
    case VK_OBJECT_TYPE_PIPELINE: (compute ? compute_pipelines_ : graphics_pipelines_)++; break;
    case VK_OBJECT_TYPE_BUFFER: buffers_++, device_buffer_bytes_ += device_bytes; break;
    case VK_OBJECT_TYPE_IMAGE: images_++; break;
    default: break;
    }
}

void Context::set_name(VkObjectType type, uint64_t handle, const char* name) const
{
    if (!set_object_name_ || !handle) return;
    VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    ni.objectType = type;
    ni.objectHandle = handle;
    ni.pObjectName = name;
    set_object_name_(device_, &ni);
}

std::vector<std::string> Context::list_devices()
{
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    VkInstance instance;
    if (vkCreateInstance(&ci, nullptr, &instance) != VK_SUCCESS) return {};
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance, &n, nullptr);
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance, &n, devices.data());
    std::vector<std::pair<int, std::string>> named;
    for (auto pd : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        named.emplace_back(type_rank(p.deviceType), std::string(p.deviceName) + " (" + type_name(p.deviceType) + ")");
    }
    vkDestroyInstance(instance, nullptr);
    std::stable_sort(named.begin(), named.end(), [](auto& a, auto& b) { return a.first < b.first; });
    std::vector<std::string> out;
    for (auto& [rank, name] : named) out.push_back(name);
    return out;
}

}  // namespace jade::gpu

namespace jade {

std::string dev::DeviceInfo::api_version_string() const
{
    return std::to_string(VK_API_VERSION_MAJOR(api_version)) + "." + std::to_string(VK_API_VERSION_MINOR(api_version)) +
           "." + std::to_string(VK_API_VERSION_PATCH(api_version));
}

Context::Context(const ContextOptions& options) : gpu_(std::make_unique<gpu::Context>(options)) {}
Context::~Context() = default;
Context::Context(const AdoptedVulkan& host, const ContextOptions& options)
    : gpu_(std::make_unique<gpu::Context>(host, options))
{
}
bool Context::adopted() const { return gpu_->adopted(); }
ObjectCounts dev::created_objects(const Context& context)
{
    return gpu_of(const_cast<Context&>(context)).created_objects();
}
const dev::DeviceInfo& dev::device_info(const Context& context) { return gpu_of(const_cast<Context&>(context)).info(); }
uint64_t dev::validation_messages(const Context& context)
{
    return gpu_of(const_cast<Context&>(context)).validation_messages();
}
std::vector<std::string> dev::list_devices() { return gpu::Context::list_devices(); }
gpu::Context& gpu_of(Context& context) { return *context.gpu_; }

}  // namespace jade
