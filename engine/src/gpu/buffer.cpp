#include "gpu/buffer.hpp"

#include "gpu/context.hpp"

#include <jade/context.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

namespace jade::gpu {

namespace {

std::string mib(VkDeviceSize bytes)
{
    const double m = double(bytes) / double(1u << 20);
    char text[64];
    std::snprintf(text, sizeof text, m >= 100 ? "%.0f MiB" : "%.3g MiB", m);
    return std::to_string(bytes) + " bytes (" + text + ")";
}

constexpr VkMemoryPropertyFlags kHostFlags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

BufferLimits limits_of(const Context& ctx, bool host_visible)
{
    BufferLimits l;
    l.max_storage_range = ctx.limits().maxStorageBufferRange;
    l.max_allocation = ctx.max_memory_allocation_size();
    // The buffer's memory type must have these flags (allocate_memory); its heap is one of theirs.
    const VkMemoryPropertyFlags required =
        host_visible ? kHostFlags : VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    const auto& mem = ctx.memory_properties();
    for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
        if ((mem.memoryTypes[i].propertyFlags & required) == required)
            l.heap_bytes = std::max(l.heap_bytes, mem.memoryHeaps[mem.memoryTypes[i].heapIndex].size);
    return l;
}

}  // namespace

void check_buffer_size(const BufferLimits& limits, VkDeviceSize bytes, VkBufferUsageFlags usage, StorageBinding binding,
                       const char* name)
{
    const std::string what = std::string("GPU buffer '") + name + "' of " + mib(bytes);
    if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && binding == StorageBinding::Whole &&
        bytes > limits.max_storage_range)
        throw Error(what + " exceeds the device's maxStorageBufferRange of " + mib(limits.max_storage_range) +
                    " (the largest storage buffer a shader can bind)");
    if (limits.max_allocation && bytes > limits.max_allocation)
        throw Error(what + " exceeds the device's maxMemoryAllocationSize of " + mib(limits.max_allocation));
    if (bytes > limits.heap_bytes)
        throw Error(what + " exceeds the largest memory heap it can use, " + mib(limits.heap_bytes));
}

BufferLimits buffer_limits(jade::Context& ctx, bool host_visible) { return limits_of(gpu_of(ctx), host_visible); }

uint32_t find_memory_type(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred)
{
    const auto& mem = ctx.memory_properties();
    for (VkMemoryPropertyFlags want : {required | preferred, required})
        for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
            if ((type_bits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) return i;
    throw Error("no Vulkan memory type with the required properties");
}

OwnedMemory allocate_memory(const Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred, void** mapped, const char* what)
{
    uint32_t type = find_memory_type(ctx, req.memoryTypeBits, required, preferred);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    VkDeviceMemory memory;
    VkResult r = vkAllocateMemory(ctx.device(), &ai, nullptr, &memory);
    if (r != VK_SUCCESS)
        throw Error(std::string("cannot allocate ") + std::to_string(req.size) + " bytes of GPU memory for " + what +
                    ": " + result_name(r));
    OwnedMemory owned(ctx.device(), memory);
    const auto flags = ctx.memory_properties().memoryTypes[type].propertyFlags;
    if (mapped) {
        *mapped = nullptr;
        if ((flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) && (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT))
            check(vkMapMemory(ctx.device(), memory, 0, VK_WHOLE_SIZE, 0, mapped), "vkMapMemory");
    }
    return owned;
}

Buffer::Buffer(Context& ctx, VkDeviceSize bytes, VkBufferUsageFlags usage, const char* name, bool host_visible,
               StorageBinding binding)
    : ctx_(&ctx), size_(std::max(bytes, kMinBufferBytes))
{
    check_buffer_size(limits_of(ctx, host_visible), size_, usage, binding, name);  // before any Vulkan call
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size_;
    ci.usage = usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer b;
    check(vkCreateBuffer(ctx.device(), &ci, nullptr, &b), "vkCreateBuffer");
    OwnedBuffer owned(ctx.device(), b);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device(), b, &req);
    const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    memory_ = host_visible ? allocate_memory(ctx, req, host, 0, &mapped_, name)
                           : allocate_memory(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, host, &mapped_, name);
    check(vkBindBufferMemory(ctx.device(), b, memory_, 0), "vkBindBufferMemory");
    buffer_ = std::move(owned);
    ctx.set_name(b, VK_OBJECT_TYPE_BUFFER, name);
    ctx.count_created(VK_OBJECT_TYPE_BUFFER, false, host_visible ? 0 : size_);
}

void Buffer::upload(const void* data, size_t bytes, size_t offset)
{
    if (bytes == 0) return;
    if (offset + bytes > size_) throw Error("Buffer::upload: " + std::to_string(bytes) + " bytes do not fit");
    if (mapped_) {
        std::memcpy(static_cast<char*>(mapped_) + offset, data, bytes);
        return;
    }
    Buffer staging(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "staging (upload)", true);
    std::memcpy(staging.mapped_, data, bytes);
    ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, offset, bytes};
        vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &region);
    });
}

void Buffer::download(void* data, size_t bytes, size_t offset) const
{
    if (bytes == 0) return;
    if (offset + bytes > size_) throw Error("Buffer::download: " + std::to_string(bytes) + " bytes out of range");
    if (mapped_) {
        std::memcpy(data, static_cast<const char*>(mapped_) + offset, bytes);
        return;
    }
    Buffer staging(*ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, "staging (read-back)", true);
    ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{offset, 0, bytes};
        vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &region);
    });
    std::memcpy(data, staging.mapped_, bytes);
}

}  // namespace jade::gpu
