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

#include "host.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace samples::embed {
namespace {

// The frame, in one command buffer: the host's ground, Jade's sphere over it, the read-back.
void record_frame(VkCommandBuffer cmd, const Host& host, jade::Renderer& renderer, const jade::Camera& camera)
{
    // 1. The host's pass: clear to a sky colour and draw the ground.
    image_barrier(cmd, host.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                  VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    image_barrier(cmd, host.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_PIPELINE_STAGE_2_NONE, 0,
                  VK_IMAGE_LAYOUT_UNDEFINED,
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
    const glm::mat4 clip_from_world = camera.view_projection(float(kWidth) / float(kHeight));
    struct {
        glm::mat4 clip_from_world;
        float half_size, height;
    } push{clip_from_world, 4.0f, kGroundHeight};
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
    vkCmdCopyImageToBuffer(cmd, host.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.readback.buffer, 1, &copy);
    host_read_barrier(cmd);
}

}  // namespace

int run(const char* output, bool validation)
{
    Host host;
    host.create_instance(validation);
    host.create_device();
    host.create_frame();
    host.create_ground_pipeline();
    const jade::Camera camera = embed::camera();

    int status = 0;
    {
        // Jade adopts the host's objects; everything Jade creates is gone when this scope ends,
        // before ~Host destroys the device.
        jade::Context context(
            host.setup.adopted(host.instance.instance, host.physical, host.device, host.family, host.queue));

        // A unit sphere of jade (10 mm per unit), baked on the host's queue (Baker submits and waits).
        const jade::PreparedMesh sphere = jade::prepare_mesh(jade::procedural::sphere(1.0f, 32, 48));
        const jade::Material material = jade::material_preset("jade", 10.0);
        jade::Baker baker(context);
        const jade::BakeResult baked = baker.bake(sphere, material, jade::BakeSettings::preset(jade::Quality::Draft));
        jade::Renderer renderer(context);
        renderer.set_mesh(sphere, baked.tm);
        renderer.set_material(material);

        submit_and_wait(host.device, host.queue, host.family,
                        [&](VkCommandBuffer cmd) { record_frame(cmd, host, renderer, camera); });

        void* mapped = nullptr;
        check(vkMapMemory(host.device, host.readback.memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
        const auto* half = static_cast<const uint16_t*>(mapped);
        std::vector<float> rgba(size_t(kWidth) * kHeight * 4);
        for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = glm::unpackHalf1x16(half[i]);
        vkUnmapMemory(host.device, host.readback.memory);
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

}  // namespace samples::embed

int main(int argc, char** argv)
{
    const char* output = nullptr;
    bool validation = false;
    if (const char* v = std::getenv("JADE_VALIDATION"); v && *v && std::strcmp(v, "0") != 0) validation = true;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--validation") == 0)
            validation = true;
        else if (!output && argv[i][0] != '-')
            output = argv[i];
        else {
            std::fprintf(stderr, "jade_embed: unknown argument '%s'\nusage: jade_embed OUTPUT.png [--validation]\n",
                         argv[i]);
            return 1;
        }
    }
    if (!output) {
        std::fprintf(stderr, "usage: jade_embed OUTPUT.png [--validation]\n");
        return 1;
    }
    try {
        return samples::embed::run(output, validation);
    } catch (const std::exception& e) {  // jade::Error and the host's own failures
        std::fprintf(stderr, "jade_embed: %s\n", e.what());
        return 1;
    }
}
