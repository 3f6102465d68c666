// gpu/buffer.hpp - one VkBuffer with its own memory, and upload/read-back.
#pragma once

#include "gpu/buffer_limits.hpp"
#include "gpu/vk.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace jade::gpu {

class Context;

/// The smallest buffer: Vulkan forbids empty ones, so a Buffer of fewer bytes gets this many.
inline constexpr VkDeviceSize kMinBufferBytes = 16;

/// A storage (or other) buffer with dedicated memory. Memory is device-local; when the device
/// also exposes it to the host (lavapipe, integrated GPUs, resizable BAR) it stays mapped and
/// upload/download are memcpy, else they go through a temporary staging buffer.
/// The size is checked against the device limits (check_buffer_size) before any Vulkan call:
/// a buffer too large is a jade::Error naming it and the limit, never a device error or crash.
class Buffer {
public:
    Buffer() = default;
    Buffer(Context& ctx, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* name, bool host_visible = false,
           StorageBinding binding = StorageBinding::Whole);

    template <class T>
    static Buffer from(Context& ctx, std::span<const T> data, VkBufferUsageFlags usage, const char* name)
    {
        Buffer b(ctx, data.size_bytes(), usage, name);
        b.upload(data.data(), data.size_bytes());
        return b;
    }
    template <class T>
    static Buffer from(Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage, const char* name)
    {
        return from(ctx, std::span<const T>(data), usage, name);
    }

    void upload(const void* data, size_t bytes, size_t offset = 0);
    void download(void* data, size_t bytes, size_t offset = 0) const;
    template <class T> std::vector<T> read(size_t count) const
    {
        std::vector<T> out(count);
        download(out.data(), count * sizeof(T));
        return out;
    }

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }
    explicit operator bool() const { return bool(buffer_); }

private:
    Context* ctx_ = nullptr;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
    OwnedMemory memory_;  // declared before buffer_: the buffer is destroyed first
    OwnedBuffer buffer_;
};

/// Index of a memory type allowed by `type_bits` with all `required` flags, preferring one
/// that also has `preferred`; throws jade::Error when none exists.
uint32_t find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred);

/// Allocates and binds memory for a buffer or image; returns the memory (and maps it if host
/// visible and `mapped` is not null).
OwnedMemory allocate_memory(const Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred, void** mapped, const char* what);

}  // namespace jade::gpu
