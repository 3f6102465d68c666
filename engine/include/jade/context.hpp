// jade/context.hpp - the GPU context every Jade operation runs on.
//
// A Context owns (or, for embedding, adopts) a Vulkan 1.3 instance, device and one queue that
// does both compute and graphics. It is not thread-safe: use one Context from one thread at a
// time. Destroying it waits for the GPU to finish with the objects it still holds (owned: for
// the device to be idle; adopted: only for those objects' fences, see AdoptedVulkan).
// See docs/embedding.md for adopting a host's device.
#pragma once

#include <jade/noncopyable.hpp>

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace jade {

namespace gpu {
class Context;
}

struct ContextOptions {
    /// Pick the device whose name contains this (case-insensitive). Empty: the environment
    /// variable JADE_DEVICE, else the best device (discrete GPU, integrated, virtual, then CPU
    /// implementations such as lavapipe).
    std::string device;
    /// Enable VK_LAYER_KHRONOS_validation (also on when JADE_VALIDATION=1). Every warning or
    /// error message is logged (and counted for the tests: jade/dev/context.hpp).
    bool validation = false;
    /// Also enable the layer's synchronization validation (also JADE_SYNC_VALIDATION=1); implies
    /// `validation`. Logs "jade: Vulkan synchronization validation on" once.
    bool synchronization_validation = false;
    /// Where log lines go (validation messages, device choice with verbose). Default: stderr.
    std::function<void(std::string_view)> log;
    bool verbose = false;  ///< log the chosen (or adopted) device
};

/// The host's Vulkan objects, for a Context that adopts them instead of creating its own
/// (embedding Jade in another renderer). Jade never destroys them; they must outlive the Context.
///
/// Requirements, checked by the Context constructor (a jade::Error lists everything missing):
/// - instance created with apiVersion ≥ 1.3 (`api_version`), physical device with Vulkan ≥ 1.3;
/// - `queue` from `queue_family`, a family with graphics, compute and timestamps;
/// - device extensions (`enabled_extensions`): VK_KHR_push_descriptor;
/// - device features (`enabled_features`, the pNext chain given to vkCreateDevice: a
///   VkPhysicalDeviceFeatures2 and/or VkPhysicalDeviceVulkan12Features/Vulkan13Features or the
///   matching single-feature structs): dynamicRendering, synchronization2, maintenance4,
///   scalarBlockLayout, hostQueryReset. Context::enable_required_features() sets them.
/// Optional: shaderFloat64 (float64 sums for measurements), and shaderInt64 with
/// shaderBufferInt64Atomics (the grid far field's splat takes half the atomics).
///
/// Function loading: the extension entry points Jade needs (vkCmdPushDescriptorSetKHR,
/// vkSetDebugUtilsObjectNameEXT) are loaded through `get_device_proc_addr` /
/// `get_instance_proc_addr` when given. Core Vulkan 1.3 commands are called through the Vulkan
/// loader that Jade links (libvulkan), whose entry points dispatch on the handle: the host's
/// handles must therefore come from the system loader (linking libvulkan or using volk both do);
/// a host that bypasses the loader and talks to a driver directly is not supported.
///
/// Queue use: Jade submits to `queue` itself (buffer uploads, LUT builds, bakes, render()) and
/// waits for each submission with its own fence; it never waits for the device or the queue to
/// be idle. Vulkan requires the host to synchronise access to the queue and device externally:
/// do not submit to it from another thread while a Jade call runs.
///
/// Releasing objects: what Renderer::set_mesh/set_material, DynamicBake::set_amortisation and
/// the destructors of Renderer, DynamicBake and MeshDeformer replace may still be used by
/// command buffers the host recorded with their record() calls. Jade submits an empty batch with
/// a fence to `queue` (its signal covers every earlier submission to the queue) and frees the
/// objects in a later Jade call once that fence has signalled, without waiting; the Context's
/// destructor waits for those fences only. So submit recorded command buffers to this queue,
/// before such a call (or never).
struct AdoptedVulkan {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    uint32_t api_version = 0;  ///< the apiVersion the host's instance was created with
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;  ///< null: the loader's
    PFN_vkGetDeviceProcAddr get_device_proc_addr = nullptr;      ///< null: the loader's
    const void* enabled_features = nullptr;                      ///< VkDeviceCreateInfo::pNext chain the host used
    std::vector<std::string> enabled_extensions;                 ///< device extensions the host enabled
};

/// A host's device made the way AdoptedVulkan needs it, for hosts that create their own device
/// for Jade to adopt (samples/embed, the viewer): Jade's features and device extensions enabled,
/// one queue of the family the host picked, and the AdoptedVulkan to give Context. A host with
/// needs of its own sets more fields of f12, f13 and features.features (or chains more structs
/// after f13) and appends to `extensions` before create(). The chain points into this object and
/// AdoptedVulkan::enabled_features at it: neither copied nor moved, it must outlive the Context.
struct HostDeviceSetup : private NonCopyable {
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    std::vector<const char*> extensions;

    /// With Jade's requirements (Context::enable_required_features, required_device_extensions)
    /// or, `with_jade_requirements` false, none: a device Jade refuses to adopt (tests).
    explicit HostDeviceSetup(bool with_jade_requirements = true);

    /// vkCreateDevice with one queue of `queue_family` and these features and extensions. The
    /// caller owns the device (vkDestroyDevice after the Context). Throws jade::Error.
    VkDevice create(VkPhysicalDevice physical, uint32_t queue_family) const;
    /// What Context(const AdoptedVulkan&) takes for a device made by create() on an instance
    /// created with apiVersion 1.3 (the loader's entry points).
    AdoptedVulkan adopted(VkInstance instance, VkPhysicalDevice physical, VkDevice device, uint32_t queue_family,
                          VkQueue queue) const;
};

/// The device Jade runs on; every other GPU object (Baker, Renderer) takes one and must be
/// destroyed before it. Move-less and not copyable.
class Context : NonCopyable {
public:
    /// Creates an instance and device. Throws jade::Error when no suitable device exists, with
    /// every device considered and why it was rejected, and what to install.
    explicit Context(const ContextOptions& options = {});
    /// Adopts the host's instance, device and queue (see AdoptedVulkan): creates only Jade's
    /// own command pool and fence on them. Throws jade::Error listing every missing version,
    /// queue capability, extension and feature. `options.device` and `options.validation` are
    /// ignored (the host owns the instance and its layers; the host's messenger sees Jade's
    /// messages); `log` and `verbose` apply.
    Context(const AdoptedVulkan& host, const ContextOptions& options = {});
    ~Context();

    /// True when this Context adopted the host's objects (and will not destroy them).
    bool adopted() const;

    /// The device extensions Jade needs (for the host's VkDeviceCreateInfo).
    static std::vector<const char*> required_device_extensions();
    /// Sets the features Jade needs in the host's feature structs (leaves the others alone).
    static void enable_required_features(VkPhysicalDeviceVulkan12Features& f12, VkPhysicalDeviceVulkan13Features& f13);
    /// Sets the optional features Jade uses (shaderFloat64; shaderInt64 with
    /// shaderBufferInt64Atomics) in the host's feature structs where `physical` supports them.
    static void enable_optional_features(VkPhysicalDevice physical, VkPhysicalDeviceFeatures2& features,
                                         VkPhysicalDeviceVulkan12Features& f12);

private:
    friend gpu::Context& gpu_of(Context& context);  // the engine's GPU layer, for engine sources only
    std::unique_ptr<gpu::Context> gpu_;
};

}  // namespace jade
