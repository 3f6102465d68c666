// samples/common - a host's instance (with the validation layer and a messenger on request)
// and the choice of its physical device and queue family.
#pragma once

#include "vk_util.hpp"

#include <vector>

namespace samples {

/// What the host's instance is made with. Vulkan 1.3 and `extensions` (e.g. GLFW's surface
/// extensions); with `validation` also VK_LAYER_KHRONOS_validation and VK_EXT_debug_utils, and a
/// messenger that passes warnings and errors of every type to `on_message`, from
/// vkCreateInstance to vkDestroyInstance. `synchronization_validation` adds the layer's hazard
/// checks and implies `validation`.
struct InstanceOptions {
    const char* application = nullptr;
    std::vector<const char*> extensions;
    bool validation = false;
    bool synchronization_validation = false;
    PFN_vkDebugUtilsMessengerCallbackEXT on_message = nullptr;
};

/// The instance and its messenger (empty without validation), destroyed messenger first.
struct Instance {
    Owned<VkInstance> instance;
    Owned<VkDebugUtilsMessengerEXT> messenger;
    bool validation = false;  ///< the layer is on
};

/// Throws std::runtime_error when the instance cannot be created (with validation: the layer
/// is not installed).
Instance create_instance(const InstanceOptions& options);

/// A physical device and one of its queue families.
struct DeviceChoice {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    uint32_t family = 0;
};

/// The first Vulkan 1.3 device (whose name contains `name`, when that is given and not empty)
/// with a queue family that does graphics and compute, and the first such family; Jade checks
/// the rest when it adopts the device. Throws std::runtime_error when there is none.
DeviceChoice find_device(VkInstance instance, const char* name = nullptr);

}  // namespace samples
