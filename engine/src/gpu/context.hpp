// gpu/context.hpp - instance, device, queue, and the one-shot command submission.
#pragma once

#include "gpu/release_queue.hpp"
#include "gpu/vk.hpp"

#include <jade/context.hpp>
#include <jade/dev/context.hpp>  // ObjectCounts, DeviceInfo

#include <atomic>
#include <functional>
#include <memory>
#include <string_view>

namespace jade::gpu {

using OwnedCommandPool = Owned<VkCommandPool, vkDestroyCommandPool>;

class Context : NonCopyable {
public:
    explicit Context(const ContextOptions& options);
    /// Adopts the host's objects (jade/context.hpp AdoptedVulkan); destroys only its own.
    Context(const AdoptedVulkan& host, const ContextOptions& options);
    ~Context();

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
    const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_; }
    /// maxMemoryAllocationSize (Vulkan 1.1): the largest single allocation.
    VkDeviceSize max_memory_allocation_size() const { return max_memory_allocation_size_; }
    const dev::DeviceInfo& info() const { return info_; }
    uint64_t validation_messages() const { return validation_messages_.load(); }
    bool adopted() const { return adopted_; }

    /// Records commands with `record` into a fresh primary command buffer, submits it and waits.
    /// The simple path for bakes and tests; frame loops record into their own buffers.
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record);

    /// Keeps `objects` (moved in) alive until the GPU has finished everything submitted to the
    /// queue so far, without waiting (gpu/release_queue.hpp): what replaces vkDeviceWaitIdle
    /// before releasing objects that recorded draws may still use.
    template <class... T> void release_after_gpu(T&&... objects)
    {
        std::vector<std::shared_ptr<void>> owners;
        (owners.push_back(std::make_shared<std::decay_t<T>>(std::move(objects))), ...);
        release_queue_.release(std::move(owners));
    }
    /// Frees what release_after_gpu() kept, as far as the GPU is done with it; never waits.
    void collect_released() { release_queue_.collect(); }
    size_t released_pending() const { return release_queue_.pending(); }

    /// Names a Vulkan object for validation messages and debuggers (no-op without debug utils).
    void set_name(VkObjectType type, uint64_t handle, const char* name) const;
    template <class T> void set_name(T handle, VkObjectType type, const char* name) const
    {
        set_name(type, reinterpret_cast<uint64_t>(handle), name);
    }

    /// Counts one created object for dev::created_objects() (buffer, image, pipeline);
    /// `device_bytes`: the size of a device-local (not staging) buffer.
    void count_created(VkObjectType type, bool compute = false, uint64_t device_bytes = 0) const;
    ObjectCounts created_objects() const
    {
        return {compute_pipelines_.load(), graphics_pipelines_.load(), buffers_.load(), images_.load(),
                device_buffer_bytes_.load()};
    }

    void log(std::string_view line) const;
    bool verbose() const { return verbose_; }

    // Extension entry points, loaded once.
    PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;

    static std::vector<std::string> list_devices();

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                           VkDebugUtilsMessageTypeFlagsEXT,
                                                           const VkDebugUtilsMessengerCallbackDataEXT*, void*);
    void create_instance(const ContextOptions& options);
    void choose_physical_device(const ContextOptions& options);
    void create_device();
    void check_adopted(const AdoptedVulkan& host);
    void create_submission_objects();
    void fill_info();
    void destroy();

    std::function<void(std::string_view)> log_;
    bool verbose_ = false;
    bool adopted_ = false;  // instance and device are the host's: never destroyed here
    std::atomic<uint64_t> validation_messages_{0};
    mutable std::atomic<uint64_t> compute_pipelines_{0}, graphics_pipelines_{0}, buffers_{0}, images_{0},
        device_buffer_bytes_{0};

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    bool float64_ = false;
    bool int64_atomics_ = false;  // shaderInt64 and shaderBufferInt64Atomics, enabled
    VkDeviceSize max_memory_allocation_size_ = 0;
    uint32_t queue_family_ = 0;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    dev::DeviceInfo info_;
    PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
    // Owned objects last: destroyed first, before the device (see ~Context).
    OwnedCommandPool command_pool_;
    OwnedFence fence_;
    ReleaseQueue release_queue_;  // emptied first by destroy(): its objects may use the pool's device
};

}  // namespace jade::gpu

namespace jade {

/// The engine's GPU layer behind a public jade::Context (engine sources and white-box tests).
gpu::Context& gpu_of(Context& context);

}  // namespace jade
