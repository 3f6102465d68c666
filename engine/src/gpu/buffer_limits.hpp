// gpu/buffer_limits.hpp - the device limits one buffer must fit, checked before the GPU is
// touched. Self-contained (Vulkan types and jade::Error only) so tests can check the rule with
// made-up limits.
#pragma once

#include <jade/error.hpp>

#include <vulkan/vulkan.h>

namespace jade {
class Context;
}

namespace jade::gpu {

/// What bounds the size of one buffer on a device.
struct BufferLimits {
    VkDeviceSize max_storage_range = 0;  ///< maxStorageBufferRange: the largest storage binding
    VkDeviceSize max_allocation = 0;     ///< maxMemoryAllocationSize (Vulkan 1.1): one allocation
    VkDeviceSize heap_bytes = 0;         ///< the largest memory heap the buffer's memory may come from
};

/// How a storage buffer is bound: as a whole (the default; its size must be within
/// maxStorageBufferRange) or only in windows no larger than that (the caller chunks).
enum class StorageBinding { Whole, Windows };

/// Throws jade::Error naming the buffer, its size and the limit it exceeds when a buffer of
/// `bytes` cannot exist under `limits`: a whole-bound storage buffer over maxStorageBufferRange,
/// any buffer over maxMemoryAllocationSize or over the largest heap it may live in.
void check_buffer_size(const BufferLimits& limits, VkDeviceSize bytes, VkBufferUsageFlags usage, StorageBinding binding,
                       const char* name);

/// The limits of the device of `ctx` for device-local (or host-visible) buffers.
BufferLimits buffer_limits(Context& ctx, bool host_visible);

}  // namespace jade::gpu
