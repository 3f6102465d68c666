// jade/dev/context.hpp - counts of the GPU objects a Context created, for tests and `jade bench`
// (proof that skipped work created nothing). Declared for jade::dev, defined in jade::jade.
#pragma once

#include <jade/context.hpp>

#include <cstdint>

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
}  // namespace dev

}  // namespace jade
