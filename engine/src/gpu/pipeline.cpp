#include "gpu/pipeline.hpp"

#include "gpu/context.hpp"

#include <string>

namespace jade::gpu {

namespace {
constexpr VkShaderStageFlags kStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
}

GraphicsPipeline::GraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc)
    : ctx_(&ctx), name_(desc.name), bindings_(desc.bindings), push_size_(desc.push_size)
{
    set_layout_ = make_push_set_layout(ctx, bindings_, kStages);
    layout_ = make_pipeline_layout(ctx, set_layout_, kStages, desc.push_size, desc.name);

    std::vector<VkSpecializationMapEntry> entries(desc.constants.size());
    for (uint32_t i = 0; i < entries.size(); ++i) entries[i] = {i, i * 4u, 4};
    VkSpecializationInfo spec{uint32_t(entries.size()), entries.data(), desc.constants.size() * 4,
                              desc.constants.data()};

    OwnedShaderModule vs = make_shader_module(ctx, desc.vertex_spirv, desc.name);
    OwnedShaderModule fs = make_shader_module(ctx, desc.fragment_spirv, desc.name);
    VkPipelineShaderStageCreateInfo stages[2]{};
    for (auto& s : stages) {
        s.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        s.pName = "main";
        s.pSpecializationInfo = &spec;
    }
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;

    VkVertexInputBindingDescription vb{0, desc.vertex_stride, VK_VERTEX_INPUT_RATE_VERTEX};
    std::vector<VkVertexInputAttributeDescription> attrs;
    for (const auto& a : desc.attributes) attrs.push_back({a.location, 0, a.format, a.offset});
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = desc.vertex_stride ? 1 : 0;
    vi.pVertexBindingDescriptions = &vb;
    vi.vertexAttributeDescriptionCount = uint32_t(attrs.size());
    vi.pVertexAttributeDescriptions = attrs.data();

    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = desc.topology;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = desc.cull;
    rs.frontFace = desc.front_face;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = desc.samples;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = desc.depth_test;
    ds.depthWriteEnable = desc.depth_write;
    ds.depthCompareOp = desc.depth_compare;
    std::vector<VkPipelineColorBlendAttachmentState> blend(desc.color_formats.size());
    for (auto& b : blend) {
        b.colorWriteMask = desc.color_write_mask;
        if (desc.blend == Blend::AddColor) {
            b.blendEnable = VK_TRUE;
            b.srcColorBlendFactor = b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
            b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO, b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
            b.colorBlendOp = b.alphaBlendOp = VK_BLEND_OP_ADD;
        }
    }
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = uint32_t(blend.size());
    cb.pAttachments = blend.data();
    VkDynamicState dyn_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = 2;
    dyn.pDynamicStates = dyn_states;

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = uint32_t(desc.color_formats.size());
    rendering.pColorAttachmentFormats = desc.color_formats.data();
    rendering.depthAttachmentFormat = desc.depth_format;

    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    ci.stageCount = 2;
    ci.pStages = stages;
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = desc.depth_format != VK_FORMAT_UNDEFINED ? &ds : nullptr;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dyn;
    ci.layout = layout_;
    VkPipeline p;
    check(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &p),
          (std::string("vkCreateGraphicsPipelines ") + desc.name).c_str());
    pipeline_ = own_pipeline(ctx, p, desc.name, false);
}

void GraphicsPipeline::bind(VkCommandBuffer cmd, VkExtent2D extent, const void* push, size_t push_bytes,
                            std::initializer_list<Binding> bindings) const
{
    if (push_bytes != push_size_)
        throw Error(std::string("pipeline ") + name_ + ": push constants are " + std::to_string(push_bytes) +
                    " bytes, the pipeline declares " + std::to_string(push_size_));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    if (!bindings_.empty())
        push_bindings(*ctx_, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, bindings_, bindings, name_);
    if (push_size_) vkCmdPushConstants(cmd, layout_, kStages, 0, push_size_, push);
    VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace jade::gpu
