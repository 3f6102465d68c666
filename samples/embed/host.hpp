// samples/embed/host.hpp - the host renderer's own Vulkan, as any host would have it:
// instance (with the validation layer on request), device (made with jade::HostDeviceSetup so
// that Jade can adopt it), queue, an offscreen colour + depth frame and the ground-plane
// pipeline; the helpers it shares with samples/viewer are in samples/common. Nothing here calls
// Jade but the device set-up; main.cpp embeds Jade.
#pragma once

#include "scene.hpp"
#include "vk_instance.hpp"  // samples/common: Owned, images, buffers, barriers, the instance
#include "vk_util.hpp"

#include <jade/context.hpp>

#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include "ground_frag.h"
#include "ground_vert.h"

#include <cstdint>
#include <cstdio>

namespace samples::embed {

// Jade's colour format with RenderSettings::float32 = false, and its depth format.
constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

inline uint32_t validation_messages = 0;

inline VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                 VkDebugUtilsMessageTypeFlagsEXT,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void*)
{
    ++validation_messages;
    std::fprintf(stderr, "host: validation: %s\n", data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

// The host's Vulkan objects, one owner each, declared in creation order and so destroyed in
// reverse (~Host first waits for the device to be idle).
struct Host {
    Instance instance;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    uint32_t family = 0;
    // Jade's features and extensions, which include what this host uses (dynamic rendering,
    // synchronization2); it outlives the Context (AdoptedVulkan points into it).
    jade::HostDeviceSetup setup;
    Owned<VkDevice> device;
    VkQueue queue = VK_NULL_HANDLE;
    Image color, depth;
    HostBuffer readback;
    Owned<VkShaderModule> vert, frag;
    Owned<VkPipelineLayout> layout;
    Owned<VkPipeline> pipeline;

    ~Host()
    {
        if (device) vkDeviceWaitIdle(device);
    }

    void create_instance(bool validation)
    {
        InstanceOptions options;
        options.application = "jade_embed";
        options.validation = validation;
        options.on_message = &on_message;
        instance = samples::create_instance(options);
    }

    // The first Vulkan 1.3 device with a graphics + compute queue family; Jade checks the rest.
    void create_device()
    {
        const DeviceChoice choice = find_device(instance.instance);
        physical = choice.physical;
        family = choice.family;
        device = Owned<VkDevice>(setup.create(physical, family), [](VkDevice d) { vkDestroyDevice(d, nullptr); });
        vkGetDeviceQueue(device, family, 0, &queue);
    }

    void create_frame()
    {
        color = make_image(physical, device, kColorFormat, {kWidth, kHeight}, VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                           VK_IMAGE_ASPECT_COLOR_BIT);
        depth = make_image(physical, device, kDepthFormat, {kWidth, kHeight}, VK_SAMPLE_COUNT_1_BIT,
                           VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
        readback = make_host_buffer(physical, device, VkDeviceSize(kWidth) * kHeight * 8,
                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT);  // RGBA16F
    }

    void create_ground_pipeline()
    {
        VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        VkShaderModule module = VK_NULL_HANDLE;
        mi.codeSize = sizeof(ground_vert);
        mi.pCode = ground_vert;
        check(vkCreateShaderModule(device, &mi, nullptr, &module), "vkCreateShaderModule");
        vert = own(device.get(), module, vkDestroyShaderModule);
        mi.codeSize = sizeof(ground_frag);
        mi.pCode = ground_frag;
        check(vkCreateShaderModule(device, &mi, nullptr, &module), "vkCreateShaderModule");
        frag = own(device.get(), module, vkDestroyShaderModule);

        VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4) + 2 * sizeof(float)};
        VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        li.pushConstantRangeCount = 1;
        li.pPushConstantRanges = &range;
        VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
        check(vkCreatePipelineLayout(device, &li, nullptr, &pipeline_layout), "vkCreatePipelineLayout");
        layout = own(device.get(), pipeline_layout, vkDestroyPipelineLayout);

        VkPipelineShaderStageCreateInfo stages[2]{{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                  {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = vert;
        stages[0].pName = "main";
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = frag;
        stages[1].pName = "main";
        VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = VK_CULL_MODE_NONE;
        raster.lineWidth = 1.0f;
        VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        VkPipelineDepthStencilStateCreateInfo depth_state{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
        depth_state.depthTestEnable = VK_TRUE;
        depth_state.depthWriteEnable = VK_TRUE;
        depth_state.depthCompareOp = VK_COMPARE_OP_LESS;
        VkPipelineColorBlendAttachmentState blend_attachment{};
        blend_attachment.colorWriteMask = 0xf;
        VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        blend.attachmentCount = 1;
        blend.pAttachments = &blend_attachment;
        VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamic_states;
        VkFormat color_format = kColorFormat;
        VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachmentFormats = &color_format;
        rendering.depthAttachmentFormat = kDepthFormat;
        VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
        ci.stageCount = 2;
        ci.pStages = stages;
        ci.pVertexInputState = &vertex_input;
        ci.pInputAssemblyState = &assembly;
        ci.pViewportState = &viewport;
        ci.pRasterizationState = &raster;
        ci.pMultisampleState = &multisample;
        ci.pDepthStencilState = &depth_state;
        ci.pColorBlendState = &blend;
        ci.pDynamicState = &dynamic;
        ci.layout = layout;
        VkPipeline graphics = VK_NULL_HANDLE;
        check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &graphics),
              "vkCreateGraphicsPipelines");
        pipeline = own(device.get(), graphics, vkDestroyPipeline);
    }
};

}  // namespace samples::embed
