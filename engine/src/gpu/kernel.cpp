#include "gpu/kernel.hpp"

#include "gpu/buffer.hpp"
#include "gpu/context.hpp"
#include "gpu/texel_view.hpp"

#include <algorithm>
#include <string>

namespace jade::gpu {

Binding::Binding(const Buffer& b) : buffer(b.handle()) {}
Binding::Binding(const TexelView& v) : texel_view(v.handle()) {}

OwnedShaderModule make_shader_module(const Context& ctx, std::span<const uint32_t> spirv, const char* name)
{
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = spirv.size_bytes();
    ci.pCode = spirv.data();
    VkShaderModule m;
    check(vkCreateShaderModule(ctx.device(), &ci, nullptr, &m), (std::string("vkCreateShaderModule ") + name).c_str());
    ctx.set_name(m, VK_OBJECT_TYPE_SHADER_MODULE, name);
    return OwnedShaderModule(ctx.device(), m);
}

OwnedSetLayout make_push_set_layout(const Context& ctx, std::span<const VkDescriptorType> types,
                                    VkShaderStageFlags stages)
{
    std::vector<VkDescriptorSetLayoutBinding> b(types.size());
    for (uint32_t i = 0; i < types.size(); ++i) b[i] = {i, types[i], 1, stages, nullptr};
    VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    ci.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    ci.bindingCount = uint32_t(b.size());
    ci.pBindings = b.data();
    VkDescriptorSetLayout l;
    check(vkCreateDescriptorSetLayout(ctx.device(), &ci, nullptr, &l), "vkCreateDescriptorSetLayout");
    return OwnedSetLayout(ctx.device(), l);
}

OwnedPipelineLayout make_pipeline_layout(const Context& ctx, VkDescriptorSetLayout set_layout,
                                         VkShaderStageFlags stages, uint32_t push_size, const char* name)
{
    if (push_size > ctx.limits().maxPushConstantsSize)
        throw Error(std::string(name) + ": push constants of " + std::to_string(push_size) +
                    " bytes exceed the device's " + std::to_string(ctx.limits().maxPushConstantsSize));
    VkPushConstantRange range{stages, 0, push_size};
    VkPipelineLayoutCreateInfo lci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    lci.setLayoutCount = 1;
    lci.pSetLayouts = &set_layout;
    lci.pushConstantRangeCount = push_size ? 1 : 0;
    lci.pPushConstantRanges = &range;
    VkPipelineLayout pl;
    check(vkCreatePipelineLayout(ctx.device(), &lci, nullptr, &pl), "vkCreatePipelineLayout");
    ctx.set_name(pl, VK_OBJECT_TYPE_PIPELINE_LAYOUT, name);
    return OwnedPipelineLayout(ctx.device(), pl);
}

OwnedPipeline own_pipeline(const Context& ctx, VkPipeline pipeline, const char* name, bool compute)
{
    OwnedPipeline owned(ctx.device(), pipeline);
    ctx.set_name(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
    ctx.count_created(VK_OBJECT_TYPE_PIPELINE, compute);
    return owned;
}

Kernel::Kernel(Context& ctx, const KernelDesc& desc)
    : ctx_(&ctx), name_(desc.name), bindings_(desc.bindings), push_size_(desc.push_size), local_size_(desc.local_size)
{
    local_size_ = std::min(local_size_, ctx.limits().maxComputeWorkGroupSize[0]);
    set_layout_ = make_push_set_layout(ctx, bindings_, VK_SHADER_STAGE_COMPUTE_BIT);
    layout_ = make_pipeline_layout(ctx, set_layout_, VK_SHADER_STAGE_COMPUTE_BIT, desc.push_size, desc.name);

    // Constant 0 is the group size; the kernel's own constants follow as 1, 2, ...
    std::vector<uint32_t> values{local_size_};
    values.insert(values.end(), desc.constants.begin(), desc.constants.end());
    std::vector<VkSpecializationMapEntry> entries(values.size());
    for (uint32_t i = 0; i < values.size(); ++i) entries[i] = {i, i * 4u, 4};
    VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), values.size() * 4, values.data()};

    OwnedShaderModule module = make_shader_module(ctx, desc.spirv, desc.name);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.stage.pSpecializationInfo = &spec;
    ci.layout = layout_;
    VkPipeline p;
    check(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p),
          (std::string("vkCreateComputePipelines ") + desc.name).c_str());
    pipeline_ = own_pipeline(ctx, p, desc.name, true);
}

void Kernel::check_push(size_t bytes) const
{
    if (bytes != push_size_)
        throw Error(std::string("kernel ") + name_ + ": push constants are " + std::to_string(bytes) +
                    " bytes, the kernel declares " + std::to_string(push_size_));
}

void push_bindings(const Context& ctx, VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout,
                   std::span<const VkDescriptorType> types, std::initializer_list<Binding> bindings, const char* who)
{
    if (bindings.size() != types.size())
        throw Error(std::string(who) + ": " + std::to_string(bindings.size()) + " bindings given, " +
                    std::to_string(types.size()) + " declared");
    std::vector<VkWriteDescriptorSet> writes(bindings.size());
    std::vector<VkDescriptorBufferInfo> buffers(bindings.size());
    std::vector<VkDescriptorImageInfo> images(bindings.size());
    uint32_t i = 0;
    for (const Binding& b : bindings) {
        auto& w = writes[i];
        w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = i;
        w.descriptorCount = 1;
        w.descriptorType = types[i];
        if (types[i] == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || types[i] == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
            if (!b.buffer) throw Error(std::string(who) + ": binding " + std::to_string(i) + " needs a buffer");
            if (b.range != VK_WHOLE_SIZE && b.range > ctx.limits().maxStorageBufferRange)
                throw Error(std::string(who) + ": binding " + std::to_string(i) + " range of " +
                            std::to_string(b.range) + " bytes exceeds maxStorageBufferRange " +
                            std::to_string(ctx.limits().maxStorageBufferRange));
            buffers[i] = {b.buffer, b.offset, b.range};
            w.pBufferInfo = &buffers[i];
        } else if (types[i] == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER ||
                   types[i] == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER) {
            if (!b.texel_view)
                throw Error(std::string(who) + ": binding " + std::to_string(i) + " needs a texel-buffer view");
            w.pTexelBufferView = &b.texel_view;
        } else {
            if (!b.view) throw Error(std::string(who) + ": binding " + std::to_string(i) + " needs an image");
            images[i] = {b.sampler, b.view, b.layout};
            w.pImageInfo = &images[i];
        }
        ++i;
    }
    ctx.cmd_push_descriptor_set(cmd, point, layout, 0, uint32_t(writes.size()), writes.data());
}

void Kernel::bind(VkCommandBuffer cmd, const void* push, std::initializer_list<Binding> bindings) const
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    push_bindings(*ctx_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, bindings_, bindings, name_);
    if (push_size_) vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size_, push);
}

void Kernel::dispatch_3d(VkCommandBuffer cmd, glm::uvec3 threads, const void* push,
                         std::initializer_list<Binding> bindings) const
{
    if (threads.x == 0 || threads.y == 0 || threads.z == 0) return;
    const auto& lim = ctx_->limits();
    const uint32_t gx = (threads.x + local_size_ - 1) / local_size_;
    if (gx > lim.maxComputeWorkGroupCount[0] || threads.y > lim.maxComputeWorkGroupCount[1] ||
        threads.z > lim.maxComputeWorkGroupCount[2])
        throw Error(std::string("kernel ") + name_ + ": a " + std::to_string(threads.x) + "×" +
                    std::to_string(threads.y) + "×" + std::to_string(threads.z) +
                    " dispatch exceeds the device's work-group limits");
    bind(cmd, push, bindings);
    vkCmdDispatch(cmd, gx, threads.y, threads.z);
}

void Kernel::dispatch_indirect(VkCommandBuffer cmd, const Buffer& groups, VkDeviceSize offset, const void* push,
                               std::initializer_list<Binding> bindings) const
{
    bind(cmd, push, bindings);
    vkCmdDispatchIndirect(cmd, groups.handle(), offset);
}

void Kernel::dispatch(VkCommandBuffer cmd, uint64_t threads, const void* push,
                      std::initializer_list<Binding> bindings) const
{
    if (threads == 0) return;
    bind(cmd, push, bindings);

    const auto& lim = ctx_->limits();
    uint64_t groups = (threads + local_size_ - 1) / local_size_;
    uint64_t max_x = std::min<uint64_t>(lim.maxComputeWorkGroupCount[0], 65535);
    uint64_t gx = std::min(groups, max_x);
    uint64_t gy = (groups + gx - 1) / gx;
    if (gy > lim.maxComputeWorkGroupCount[1])
        throw Error(std::string("kernel ") + name_ + ": " + std::to_string(threads) +
                    " threads exceed the device's work-group limits");
    vkCmdDispatch(cmd, uint32_t(gx), uint32_t(gy), 1);
}

void indirect_barrier(VkCommandBuffer cmd)
{
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_READ_BIT);
}

void compute_barrier(VkCommandBuffer cmd)
{
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                   VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                   VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

}  // namespace jade::gpu
