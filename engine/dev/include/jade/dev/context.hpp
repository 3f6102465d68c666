// jade/dev/context.hpp - what a Context says about itself, for `jade info`, the tests and the
// benchmarks: the device's properties, the validation messages seen, the devices present, and
// counts of the GPU objects it created (proof that skipped work created nothing). Declared for
// jade::dev, defined in jade::jade.
#pragma once

#include <jade/context.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace jade {

/// How many GPU objects a Context has created since construction (never decremented): lets
/// tests prove that skipped work created nothing (e.g. a bake served from the cache).
struct ObjectCounts {
    uint64_t compute_pipelines = 0;   ///< bake kernels, LUT builders
    uint64_t graphics_pipelines = 0;  ///< renderer variants
    uint64_t buffers = 0;             ///< every VkBuffer (device-local and staging)
    uint64_t images = 0;
    /// Bytes of the device-local buffers among `buffers` (their requested sizes, at least 16
    /// each; host-visible staging and read-back buffers are left out): what jade::plan_scene
    /// estimates.
    uint64_t device_buffer_bytes = 0;
};

namespace dev {
/// Objects created so far through `context` (thread-safe read).
ObjectCounts created_objects(const Context& context);

/// What `jade info` prints about the device, and what the tests and benchmarks check of it.
struct DeviceInfo {
    std::string name, driver,
        type;                  ///< device and driver names; type: "discrete", "integrated", "virtual", "cpu", "other"
    uint32_t api_version = 0;  ///< VK_MAKE_API_VERSION encoded
    uint64_t max_storage_buffer_range = 0;        ///< bytes
    uint32_t max_workgroup_count[3] = {0, 0, 0};  ///< compute dispatch limits
    uint32_t max_workgroup_invocations = 0;
    uint32_t subgroup_size = 0;              ///< default subgroup size (8 on lavapipe)
    bool float64 = false;                    ///< shaderFloat64
    bool int64_atomics = false;              ///< shaderInt64 and shaderBufferInt64Atomics, both enabled
    double timestamp_period_ns = 0;          ///< nanoseconds per timestamp tick
    uint64_t device_local_heap_bytes = 0;    ///< size of the largest device-local heap
    std::string api_version_string() const;  ///< "1.3.238"
};

/// Filled once at the Context's construction.
const DeviceInfo& device_info(const Context& context);
/// Validation warnings and errors seen so far (0 when validation is off, and for an adopted
/// Context: the host's messenger sees Jade's messages).
uint64_t validation_messages(const Context& context);
/// Names of the Vulkan devices present, best first (no context needed).
std::vector<std::string> list_devices();
}  // namespace dev

}  // namespace jade
