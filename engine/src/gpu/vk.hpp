// gpu/vk.hpp - Vulkan include, result checking and the one RAII handle type.
#pragma once

#include <jade/error.hpp>

#include <vulkan/vulkan.h>

#include <string>
#include <utility>

namespace jade::gpu {

const char* result_name(VkResult result);

/// Throws jade::Error "<what>: VK_ERROR_..." unless result is VK_SUCCESS. Always on (never an
/// assert): a failed Vulkan call in Release must still say what failed.
inline void check(VkResult result, const char* what)
{
    if (result != VK_SUCCESS) throw Error(std::string(what) + ": " + result_name(result));
}

/// Owns one Vulkan object: destroys it with `destroy(device, handle, nullptr)` unless it is
/// VK_NULL_HANDLE. Movable, not copyable. Members of a class are destroyed in reverse order of
/// declaration, so declare owners after what they depend on.
template <class T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)> class Owned {
public:
    Owned() = default;
    Owned(VkDevice device, T handle) : device_(device), handle_(handle) {}
    Owned(Owned&& o) noexcept : device_(o.device_), handle_(std::exchange(o.handle_, VK_NULL_HANDLE)) {}
    Owned& operator=(Owned&& o) noexcept
    {
        if (this != &o) {
            reset();
            device_ = o.device_;
            handle_ = std::exchange(o.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    ~Owned() { reset(); }
    void reset()
    {
        if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
        handle_ = VK_NULL_HANDLE;
    }
    T get() const { return handle_; }
    operator T() const { return handle_; }
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    T handle_ = VK_NULL_HANDLE;
};

// The owners several modules share. One module's own kind (texel views, query pools, the
// command pool and fences) is declared in that module's header.
using OwnedBuffer = Owned<VkBuffer, vkDestroyBuffer>;
using OwnedImage = Owned<VkImage, vkDestroyImage>;
using OwnedImageView = Owned<VkImageView, vkDestroyImageView>;
using OwnedSampler = Owned<VkSampler, vkDestroySampler>;
using OwnedMemory = Owned<VkDeviceMemory, vkFreeMemory>;
using OwnedPipeline = Owned<VkPipeline, vkDestroyPipeline>;
using OwnedPipelineLayout = Owned<VkPipelineLayout, vkDestroyPipelineLayout>;
using OwnedSetLayout = Owned<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using OwnedShaderModule = Owned<VkShaderModule, vkDestroyShaderModule>;

/// One global memory barrier (synchronization2): writes of `src_access` in `src_stage` made
/// visible to `dst_access` in `dst_stage`. Every barrier Jade records goes through here.
inline void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                           VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access)
{
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace jade::gpu
