// samples/common - the Vulkan helpers both host programs (samples/embed, samples/viewer) use:
// one owner per handle, error checks, images with their memory and view, host-visible buffers,
// barriers and a one-off submission. A host owns every Vulkan object it creates (Jade adopts
// its device and destroys none of them).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

namespace samples {

/// Throws std::runtime_error naming the call when a Vulkan call failed.
inline void check(VkResult r, const char* what)
{
    if (r != VK_SUCCESS)
        throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(int(r)) + ")");
}

/// The one owner of a Vulkan handle: destroys it with the function given at construction.
/// Move-only; reset() destroys early.
template <class T> class Owned {
public:
    Owned() = default;
    Owned(T handle, std::function<void(T)> destroy) : handle_(handle), destroy_(std::move(destroy)) {}
    ~Owned() { reset(); }
    Owned(Owned&& o) noexcept : handle_(std::exchange(o.handle_, T(VK_NULL_HANDLE))), destroy_(std::move(o.destroy_)) {}
    Owned& operator=(Owned&& o) noexcept
    {
        if (this != &o) {
            reset();
            handle_ = std::exchange(o.handle_, T(VK_NULL_HANDLE));
            destroy_ = std::move(o.destroy_);
        }
        return *this;
    }
    Owned(const Owned&) = delete;
    Owned& operator=(const Owned&) = delete;
    void reset()
    {
        if (handle_ != T(VK_NULL_HANDLE) && destroy_) destroy_(handle_);
        handle_ = T(VK_NULL_HANDLE);
    }
    T get() const { return handle_; }
    operator T() const { return handle_; }

private:
    T handle_ = T(VK_NULL_HANDLE);
    std::function<void(T)> destroy_;
};

/// Device-level destroy functions bound to a device: Owned<VkX> makers.
template <class T> Owned<T> own(VkDevice device, T handle, void (*destroy)(VkDevice, T, const VkAllocationCallbacks*))
{
    return Owned<T>(handle, [device, destroy](T h) { destroy(device, h, nullptr); });
}

/// An image with its own memory and one view (members destroyed view, image, memory).
struct Image {
    Owned<VkDeviceMemory> memory;
    Owned<VkImage> image;
    Owned<VkImageView> view;
};

/// A host-visible, coherent buffer (read-backs).
struct HostBuffer {
    Owned<VkDeviceMemory> memory;
    Owned<VkBuffer> buffer;
    VkDeviceSize size = 0;
};

uint32_t memory_type(VkPhysicalDevice physical, uint32_t bits, VkMemoryPropertyFlags wanted);
/// A 2-D view of the whole of `image` (one mip, one layer).
Owned<VkImageView> make_view(VkDevice device, VkImage image, VkFormat format, VkImageAspectFlags aspect);
/// A 2-D image (one mip, one layer, optimal tiling) in device-local memory, with its view.
Image make_image(VkPhysicalDevice physical, VkDevice device, VkFormat format, VkExtent2D extent,
                 VkSampleCountFlagBits samples, VkImageUsageFlags usage, VkImageAspectFlags aspect);
HostBuffer make_host_buffer(VkPhysicalDevice physical, VkDevice device, VkDeviceSize size, VkBufferUsageFlags usage);

/// One image layout transition / memory dependency (synchronization2).
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 src_stage,
                   VkAccessFlags2 src_access, VkImageLayout old_layout, VkPipelineStageFlags2 dst_stage,
                   VkAccessFlags2 dst_access, VkImageLayout new_layout);
/// Makes the writes of earlier copies (into a read-back buffer) visible to the host.
void host_read_barrier(VkCommandBuffer cmd);

/// Records `record` into a one-off command buffer (from a pool of its own on `queue_family`),
/// submits it to `queue` and waits for it with a fence.
void submit_and_wait(VkDevice device, VkQueue queue, uint32_t queue_family,
                     const std::function<void(VkCommandBuffer)>& record);

}  // namespace samples
