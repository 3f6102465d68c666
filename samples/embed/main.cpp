// samples/embed - a host renderer that embeds Jade (docs/embedding.md walks through it).
//
// The host owns everything Vulkan: instance (with the validation layer on request), device,
// queue, an offscreen colour + depth image and its own ground-plane pipeline. It renders its
// ground into the frame, hands its objects to jade::Context (adoption: Jade destroys none of
// them), bakes t_m of a translucent sphere on them and records Jade's draw into the same
// command buffer, depth-tested against the ground. The frame is read back and written as PNG.
//
//   jade_embed OUTPUT.png [--validation]      (JADE_VALIDATION=1 also enables the layer)
// Exit status: 0 done; 1 an error (message on stderr); 2 the validation layer reported anything.
#include <jade/bake.hpp>
#include <jade/context.hpp>
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/material.hpp>
#include <jade/mesh.hpp>
#include <jade/render.hpp>

#include <glm/gtc/packing.hpp>
#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include "ground_frag.h"
#include "ground_vert.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

constexpr uint32_t kWidth = 320, kHeight = 240;
// Jade's colour format with RenderSettings::float32 = false, and its depth format.
constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// The ground cuts the unit sphere at the origin: its lowest cap is hidden by the depth test.
constexpr float kGroundHeight = -0.6f;

void check(VkResult r, const char* what)
{
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(int(r)) + ")");
}

uint32_t validation_messages = 0;

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*)
{
    ++validation_messages;
    std::fprintf(stderr, "host: validation: %s\n", data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

// The host's Vulkan objects, destroyed in reverse order of creation by ~Host.
struct Host {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    std::vector<const char*> extensions;

    struct Image { VkImage image = VK_NULL_HANDLE; VkDeviceMemory memory = VK_NULL_HANDLE; VkImageView view = VK_NULL_HANDLE; };
    Image color, depth;
    VkBuffer readback = VK_NULL_HANDLE;
    VkDeviceMemory readback_memory = VK_NULL_HANDLE;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;

    ~Host()
    {
        if (device) {
            vkDeviceWaitIdle(device);
            vkDestroyFence(device, fence, nullptr);
            vkDestroyCommandPool(device, pool, nullptr);
            vkDestroyPipeline(device, pipeline, nullptr);
            vkDestroyPipelineLayout(device, layout, nullptr);
            vkDestroyShaderModule(device, frag, nullptr);
            vkDestroyShaderModule(device, vert, nullptr);
            vkDestroyBuffer(device, readback, nullptr);
            vkFreeMemory(device, readback_memory, nullptr);
            for (Image* i : {&depth, &color}) {
                vkDestroyImageView(device, i->view, nullptr);
                vkDestroyImage(device, i->image, nullptr);
                vkFreeMemory(device, i->memory, nullptr);
            }
            vkDestroyDevice(device, nullptr);
        }
        if (messenger) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
            destroy(instance, messenger, nullptr);
        }
        if (instance) vkDestroyInstance(instance, nullptr);
    }

    void create_instance(bool validation)
    {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "jade_embed";
        app.apiVersion = VK_API_VERSION_1_3;
        const char* layer = "VK_LAYER_KHRONOS_validation";
        const char* debug_utils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
        mci.pfnUserCallback = &on_message;
        VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ci.pApplicationInfo = &app;
        if (validation) {
            ci.enabledLayerCount = 1;
            ci.ppEnabledLayerNames = &layer;
            ci.enabledExtensionCount = 1;
            ci.ppEnabledExtensionNames = &debug_utils;
            ci.pNext = &mci;
        }
        check(vkCreateInstance(&ci, nullptr, &instance), "vkCreateInstance (validation needs vulkan-validationlayers)");
        if (validation) {
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
            check(create(instance, &mci, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
        }
    }

    // The first Vulkan 1.3 device with a graphics + compute queue family; Jade checks the rest.
    void create_device()
    {
        uint32_t n = 0;
        vkEnumeratePhysicalDevices(instance, &n, nullptr);
        std::vector<VkPhysicalDevice> devices(n);
        vkEnumeratePhysicalDevices(instance, &n, devices.data());
        for (VkPhysicalDevice pd : devices) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(pd, &p);
            if (p.apiVersion < VK_API_VERSION_1_3) continue;
            uint32_t nf = 0;
            vkGetPhysicalDeviceQueueFamilyProperties(pd, &nf, nullptr);
            std::vector<VkQueueFamilyProperties> families(nf);
            vkGetPhysicalDeviceQueueFamilyProperties(pd, &nf, families.data());
            for (uint32_t i = 0; i < nf && !physical; ++i)
                if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
                    physical = pd;
                    family = i;
                }
            if (physical) break;
        }
        if (!physical) throw std::runtime_error("no Vulkan 1.3 device with a graphics + compute queue");

        // The host's own needs (dynamic rendering, synchronization2) plus what Jade needs.
        jade::Context::enable_required_features(f12, f13);
        extensions = jade::Context::required_device_extensions();
        float priority = 1.0f;
        VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        q.queueFamilyIndex = family;
        q.queueCount = 1;
        q.pQueuePriorities = &priority;
        VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
        ci.queueCreateInfoCount = 1;
        ci.pQueueCreateInfos = &q;
        ci.enabledExtensionCount = uint32_t(extensions.size());
        ci.ppEnabledExtensionNames = extensions.data();
        check(vkCreateDevice(physical, &ci, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);

        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.queueFamilyIndex = family;
        check(vkCreateCommandPool(device, &pci, nullptr, &pool), "vkCreateCommandPool");
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(vkCreateFence(device, &fci, nullptr, &fence), "vkCreateFence");
    }

    uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const
    {
        VkPhysicalDeviceMemoryProperties mp;
        vkGetPhysicalDeviceMemoryProperties(physical, &mp);
        for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
        throw std::runtime_error("no suitable memory type");
    }

    Image make_image(VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect)
    {
        Image img;
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = VK_IMAGE_TYPE_2D;
        ci.format = format;
        ci.extent = {kWidth, kHeight, 1};
        ci.mipLevels = 1;
        ci.arrayLayers = 1;
        ci.samples = VK_SAMPLE_COUNT_1_BIT;
        ci.tiling = VK_IMAGE_TILING_OPTIMAL;
        ci.usage = usage;
        check(vkCreateImage(device, &ci, nullptr, &img.image), "vkCreateImage");
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device, img.image, &req);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        check(vkAllocateMemory(device, &ai, nullptr, &img.memory), "vkAllocateMemory");
        check(vkBindImageMemory(device, img.image, img.memory, 0), "vkBindImageMemory");
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = img.image;
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.format = format;
        vi.subresourceRange = {aspect, 0, 1, 0, 1};
        check(vkCreateImageView(device, &vi, nullptr, &img.view), "vkCreateImageView");
        return img;
    }

    void create_frame()
    {
        color = make_image(kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                           VK_IMAGE_ASPECT_COLOR_BIT);
        depth = make_image(kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
        VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bi.size = VkDeviceSize(kWidth) * kHeight * 8;  // RGBA16F
        bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        check(vkCreateBuffer(device, &bi, nullptr, &readback), "vkCreateBuffer");
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, readback, &req);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = memory_type(req.memoryTypeBits,
                                         VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        check(vkAllocateMemory(device, &ai, nullptr, &readback_memory), "vkAllocateMemory");
        check(vkBindBufferMemory(device, readback, readback_memory, 0), "vkBindBufferMemory");
    }

    void create_ground_pipeline()
    {
        VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        mi.codeSize = sizeof(ground_vert);
        mi.pCode = ground_vert;
        check(vkCreateShaderModule(device, &mi, nullptr, &vert), "vkCreateShaderModule");
        mi.codeSize = sizeof(ground_frag);
        mi.pCode = ground_frag;
        check(vkCreateShaderModule(device, &mi, nullptr, &frag), "vkCreateShaderModule");

        VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4) + 2 * sizeof(float)};
        VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        li.pushConstantRangeCount = 1;
        li.pPushConstantRanges = &range;
        check(vkCreatePipelineLayout(device, &li, nullptr, &layout), "vkCreatePipelineLayout");

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
        check(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline), "vkCreateGraphicsPipelines");
    }
};

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkPipelineStageFlags2 src_stage,
                   VkAccessFlags2 src_access, VkImageLayout old_layout, VkPipelineStageFlags2 dst_stage,
                   VkAccessFlags2 dst_access, VkImageLayout new_layout)
{
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    b.oldLayout = old_layout;
    b.newLayout = new_layout;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspect, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

int run(const char* output, bool validation)
{
    Host host;
    host.create_instance(validation);
    host.create_device();
    host.create_frame();
    host.create_ground_pipeline();

    // One camera for the host's ground and Jade's sphere: explicit planes make the depth
    // buffer shared between the two draws meaningful.
    jade::Camera camera;
    camera.eye = {0.0f, 1.4f, 5.0f};
    camera.target = {0.0f, -0.3f, 0.0f};
    camera.fov_y_degrees = 35.0f;
    camera.near_plane = 0.1f;
    camera.far_plane = 50.0f;
    const glm::mat4 clip_from_world = camera.view_projection(float(kWidth) / float(kHeight));

    int status = 0;
    {
        // Jade adopts the host's objects; everything Jade creates is gone when this scope ends,
        // before ~Host destroys the device.
        jade::AdoptedVulkan adopted;
        adopted.instance = host.instance;
        adopted.physical_device = host.physical;
        adopted.device = host.device;
        adopted.queue = host.queue;
        adopted.queue_family = host.family;
        adopted.api_version = VK_API_VERSION_1_3;
        adopted.get_instance_proc_addr = vkGetInstanceProcAddr;
        adopted.get_device_proc_addr = vkGetDeviceProcAddr;
        adopted.enabled_features = &host.features;
        adopted.enabled_extensions.assign(host.extensions.begin(), host.extensions.end());
        jade::Context context(adopted);

        // A unit sphere of jade (10 mm per unit), baked on the host's queue (Baker submits and waits).
        const jade::PreparedMesh sphere = jade::prepare_mesh(jade::procedural::sphere(1.0f, 32, 48));
        const jade::Material material = jade::material_preset("jade", 10.0);
        jade::Baker baker(context);
        const jade::BakeResult baked = baker.bake(sphere, material, jade::BakeSettings::preset(jade::Quality::Draft));
        jade::Renderer renderer(context);
        renderer.set_mesh(sphere, baked.tm);
        renderer.set_material(material);

        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = host.pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        VkCommandBuffer cmd;
        check(vkAllocateCommandBuffers(host.device, &ai, &cmd), "vkAllocateCommandBuffers");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");

        // 1. The host's pass: clear to a sky colour and draw the ground.
        image_barrier(cmd, host.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        image_barrier(cmd, host.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_PIPELINE_STAGE_2_NONE, 0, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = host.color.view;
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        color.clearValue.color = {{0.45f, 0.6f, 0.85f, 1.0f}};
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = host.depth.view;
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {1.0f, 0};
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, {kWidth, kHeight}};
        ri.layerCount = 1;
        ri.colorAttachmentCount = 1;
        ri.pColorAttachments = &color;
        ri.pDepthAttachment = &depth;
        vkCmdBeginRendering(cmd, &ri);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, host.pipeline);
        VkViewport vp{0.0f, 0.0f, float(kWidth), float(kHeight), 0.0f, 1.0f};
        VkRect2D scissor{{0, 0}, {kWidth, kHeight}};
        vkCmdSetViewport(cmd, 0, 1, &vp);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        struct { glm::mat4 clip_from_world; float half_size, height; } push{clip_from_world, 4.0f, kGroundHeight};
        vkCmdPushConstants(cmd, host.layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
        vkCmdDraw(cmd, 6, 1, 0, 0);
        vkCmdEndRendering(cmd);

        // 2. Jade's draw over it (docs/embedding.md): the host makes its attachment writes
        //    visible to Jade's attachment reads and writes; layouts stay attachment-optimal.
        image_barrier(cmd, host.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        const VkPipelineStageFlags2 fragment_tests =
            VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
        image_barrier(cmd, host.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, fragment_tests,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                      fragment_tests,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
        jade::RenderSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        settings.samples = 1;
        settings.mode = jade::ShadingMode::Tm;
        jade::RenderTarget target;
        target.color = host.color.view;
        target.depth = host.depth.view;
        target.width = kWidth;
        target.height = kHeight;
        target.load = true;
        const auto lights = jade::default_lights(camera);
        renderer.record(cmd, target, camera, lights, settings);

        // 3. The host reads the frame back.
        image_barrier(cmd, host.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {kWidth, kHeight, 1};
        vkCmdCopyImageToBuffer(cmd, host.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.readback, 1, &copy);
        VkMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        to_host.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
        to_host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
        to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &to_host;
        vkCmdPipelineBarrier2(cmd, &dep);
        check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        check(vkQueueSubmit(host.queue, 1, &si, host.fence), "vkQueueSubmit");
        check(vkWaitForFences(host.device, 1, &host.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vkFreeCommandBuffers(host.device, host.pool, 1, &cmd);

        void* mapped = nullptr;
        check(vkMapMemory(host.device, host.readback_memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
        const auto* half = static_cast<const uint16_t*>(mapped);
        std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
        for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = glm::unpackHalf1x16(half[i]);
        vkUnmapMemory(host.device, host.readback_memory);
        jade::save_image(output, int(kWidth), int(kHeight), rgba);
        std::printf("jade_embed: wrote %s (%ux%u), sphere of %zu vertices baked in %.1f ms\n", output, kWidth, kHeight,
                    sphere.vertex_count(), baked.timings.wall_ms);
    }
    if (validation_messages > 0) {
        std::fprintf(stderr, "jade_embed: the validation layer reported %u message(s)\n", validation_messages);
        status = 2;
    }
    return status;
}

}  // namespace

int main(int argc, char** argv)
{
    const char* output = nullptr;
    bool validation = false;
    if (const char* v = std::getenv("JADE_VALIDATION"); v && *v && std::strcmp(v, "0") != 0) validation = true;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--validation") == 0) validation = true;
        else if (!output && argv[i][0] != '-') output = argv[i];
        else {
            std::fprintf(stderr, "jade_embed: unknown argument '%s'\nusage: jade_embed OUTPUT.png [--validation]\n", argv[i]);
            return 1;
        }
    }
    if (!output) {
        std::fprintf(stderr, "usage: jade_embed OUTPUT.png [--validation]\n");
        return 1;
    }
    try {
        return run(output, validation);
    } catch (const std::exception& e) {  // jade::Error and the host's own failures
        std::fprintf(stderr, "jade_embed: %s\n", e.what());
        return 1;
    }
}
