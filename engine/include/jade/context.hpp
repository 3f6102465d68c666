// jade/context.hpp - the GPU context every Jade operation runs on.
//
// A Context owns (or, for embedding, adopts) a Vulkan 1.3 instance, device and one queue that
// does both compute and graphics. It is not thread-safe: use one Context from one thread at a
// time. Destroying it waits for the GPU.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace jade {

namespace gpu { class Context; }

struct ContextOptions {
    /// Pick the device whose name contains this (case-insensitive). Empty: the environment
    /// variable JADE_DEVICE, else the best device (discrete GPU, integrated, virtual, then CPU
    /// implementations such as lavapipe).
    std::string device;
    /// Enable VK_LAYER_KHRONOS_validation (also on when JADE_VALIDATION=1). Every warning or
    /// error message is logged and counted (validation_messages()).
    bool validation = false;
    /// Also enable the layer's synchronization validation (also JADE_SYNC_VALIDATION=1); implies
    /// `validation`. Logs "jade: Vulkan synchronization validation on" once.
    bool synchronization_validation = false;
    /// Where log lines go (validation messages, device choice with verbose). Default: stderr.
    std::function<void(std::string_view)> log;
    bool verbose = false;
};

/// What `jade info` prints and what code may want to know about the device.
struct DeviceInfo {
    std::string name, driver, type;       ///< type: "discrete", "integrated", "virtual", "cpu", "other"
    uint32_t api_version = 0;             ///< VK_MAKE_API_VERSION encoded
    uint64_t max_storage_buffer_range = 0;
    uint32_t max_workgroup_count[3] = {0, 0, 0};
    uint32_t max_workgroup_invocations = 0;
    uint32_t subgroup_size = 0;
    bool float64 = false;                 ///< shaderFloat64
    double timestamp_period_ns = 0;       ///< nanoseconds per timestamp tick
    uint64_t device_local_heap_bytes = 0;
    std::string api_version_string() const;
};

class Context {
public:
    /// Creates an instance and device. Throws jade::Error when no suitable device exists, with
    /// every device considered and why it was rejected, and what to install.
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& device_info() const;
    /// Validation warnings and errors seen so far (0 when validation is off).
    uint64_t validation_messages() const;
    /// Names of the Vulkan devices present, best first (no context needed).
    static std::vector<std::string> list_devices();

    gpu::Context& gpu();  ///< internal: the engine's GPU layer
private:
    std::unique_ptr<gpu::Context> gpu_;
};

}  // namespace jade
