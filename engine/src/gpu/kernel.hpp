// gpu/kernel.hpp - the one way to make and run a compute program (after zeux/niagara).
//
// A kernel is {SPIR-V, bindings, push-constant size, specialisation constants}. Bindings go
// through push descriptors (no pools, no sets to manage). `dispatch` takes a thread count,
// works out the group count, and spreads more than 65,535 groups over a 2-D grid: shaders get
// their linear thread index from jade_thread_index() in shaders/include/common.glsl and compare
// it with a count they receive in their push constants.
#pragma once

#include "gpu/vk.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

namespace jade::gpu {

class Context;
class Buffer;
class TexelView;

struct KernelDesc {
    const char* name = "kernel";
    std::span<const uint32_t> spirv;
    std::vector<VkDescriptorType> bindings;  ///< binding i has type bindings[i]
    uint32_t push_size = 0;                  ///< bytes, ≤ 128
    uint32_t local_size = 64;                ///< threads per group: specialisation constant 0
    std::vector<uint32_t> constants;         ///< specialisation constants 1, 2, ... (32-bit each)
};

/// KernelDesc::bindings of a kernel that binds `n` storage buffers and nothing else.
inline std::vector<VkDescriptorType> storage_bindings(size_t n)
{
    return std::vector<VkDescriptorType>(n, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

/// A bound resource: a buffer range, a texel-buffer view, or an image view (storage image or
/// sampled with sampler).
struct Binding {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0, range = VK_WHOLE_SIZE;
    VkBufferView texel_view = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
    VkSampler sampler = VK_NULL_HANDLE;

    Binding(const Buffer& b);     // NOLINT: implicit on purpose, dispatch(..., {a, b, c})
    Binding(const TexelView& v);  // NOLINT: as above
    Binding(VkBuffer b, VkDeviceSize off = 0, VkDeviceSize r = VK_WHOLE_SIZE) : buffer(b), offset(off), range(r) {}
    static Binding image(VkImageView v, VkImageLayout l, VkSampler s = VK_NULL_HANDLE)
    {
        Binding b(VK_NULL_HANDLE);
        b.view = v, b.layout = l, b.sampler = s;
        return b;
    }
};

class Kernel {
public:
    Kernel() = default;
    Kernel(Context& ctx, const KernelDesc& desc);

    /// Records one dispatch of `threads` threads. Checks the push size and the number and
    /// ranges of bindings (against maxStorageBufferRange) before recording.
    void dispatch(VkCommandBuffer cmd, uint64_t threads, const void* push,
                  std::initializer_list<Binding> bindings) const;
    template <class Push>
    void dispatch(VkCommandBuffer cmd, uint64_t threads, const Push& push,
                  std::initializer_list<Binding> bindings) const
    {
        check_push(sizeof(Push));
        dispatch(cmd, threads, static_cast<const void*>(&push), bindings);
    }

    /// Records one dispatch of threads.x × threads.y × threads.z threads, groups of local_size
    /// along x: shaders index cells with gl_GlobalInvocationID (x compared with a count they
    /// receive), with no division to turn a linear index into three.
    void dispatch_3d(VkCommandBuffer cmd, glm::uvec3 threads, const void* push,
                     std::initializer_list<Binding> bindings) const;
    template <class Push>
    void dispatch_3d(VkCommandBuffer cmd, glm::uvec3 threads, const Push& push,
                     std::initializer_list<Binding> bindings) const
    {
        check_push(sizeof(Push));
        dispatch_3d(cmd, threads, static_cast<const void*>(&push), bindings);
    }

    /// Records one dispatch whose group counts the GPU wrote: a VkDispatchIndirectCommand at
    /// `offset` in `groups` (a buffer with VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, written before an
    /// indirect_barrier).
    template <class Push>
    void dispatch_indirect(VkCommandBuffer cmd, const Buffer& groups, VkDeviceSize offset, const Push& push,
                           std::initializer_list<Binding> bindings) const
    {
        check_push(sizeof(Push));
        dispatch_indirect(cmd, groups, offset, static_cast<const void*>(&push), bindings);
    }
    void dispatch_indirect(VkCommandBuffer cmd, const Buffer& groups, VkDeviceSize offset, const void* push,
                           std::initializer_list<Binding> bindings) const;

    const char* name() const { return name_; }
    uint32_t local_size() const { return local_size_; }
    VkPipelineLayout layout() const { return layout_; }

private:
    void check_push(size_t bytes) const;
    void bind(VkCommandBuffer cmd, const void* push, std::initializer_list<Binding> bindings) const;

    Context* ctx_ = nullptr;
    const char* name_ = "";
    std::vector<VkDescriptorType> bindings_;
    uint32_t push_size_ = 0, local_size_ = 1;
    OwnedSetLayout set_layout_;  // destroyed after the layout and pipeline that use it
    OwnedPipelineLayout layout_;
    OwnedPipeline pipeline_;
};

/// Push-descriptor writes for `bindings` (shared by compute kernels and graphics pipelines).
void push_bindings(const Context& ctx, VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout,
                   std::span<const VkDescriptorType> types, std::initializer_list<Binding> bindings, const char* who);

/// A push-descriptor set layout for `types` visible to `stages`.
OwnedSetLayout make_push_set_layout(const Context& ctx, std::span<const VkDescriptorType> types,
                                    VkShaderStageFlags stages);

/// The pipeline layout every Jade pipeline has: one push-descriptor set and push constants
/// (`push_size` bytes, checked against the device limit) for `stages`.
OwnedPipelineLayout make_pipeline_layout(const Context& ctx, VkDescriptorSetLayout set_layout,
                                         VkShaderStageFlags stages, uint32_t push_size, const char* name);

OwnedShaderModule make_shader_module(const Context& ctx, std::span<const uint32_t> spirv, const char* name);

/// The owner of a pipeline vkCreate{Compute,Graphics}Pipelines just made: named `name` and
/// counted as a compute or graphics pipeline (dev::created_objects).
OwnedPipeline own_pipeline(const Context& ctx, VkPipeline pipeline, const char* name, bool compute);

/// Full memory barrier between compute passes (writes of one visible to reads of the next).
void compute_barrier(VkCommandBuffer cmd);
/// Compute shaders' writes visible to the indirect dispatches (and shaders) that read them.
void indirect_barrier(VkCommandBuffer cmd);

}  // namespace jade::gpu
