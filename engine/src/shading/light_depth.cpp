// shading/light_depth.cpp - the light-depth atlas of the transmission term (light_depth.hpp).
#include "shading/light_depth.hpp"

#include "gpu/context.hpp"

#include "jade_shaders.hpp"

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace jade::shading {

namespace {

constexpr VkImageUsageFlags kPeelUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

}  // namespace

LightDepth::LightDepth(gpu::Context& ctx, uint32_t tile_size)
    : ctx_(ctx), tile_(tile_size),
      atlas_(ctx, {"light depth layers", tile_size * kMaxLights, tile_size, VK_FORMAT_R32G32B32A32_SFLOAT,
                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT}),
      peel_{gpu::Image(ctx, {"light depth peel", tile_size * kMaxLights, tile_size, VK_FORMAT_D32_SFLOAT, kPeelUsage}),
            gpu::Image(ctx, {"light depth peel", tile_size * kMaxLights, tile_size, VK_FORMAT_D32_SFLOAT, kPeelUsage})},
      previous_sampler_(
          gpu::make_sampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, "light depth peel sampler"))
{
}

uint64_t LightDepth::bytes() const { return uint64_t(tile_) * tile_ * kMaxLights * (16 + 2 * 4); }

bool LightDepth::may_transmit(glm::vec3 eye, const Light& light, glm::vec3 centre, float radius)
{
    const float distance = glm::length(eye - centre);
    if (!(distance > radius) || light.type == Light::Type::Point) return true;
    // The cone of V about the direction to the eye with half-angle asin(r/D) reaches μ > 0 iff
    // the angle between that direction and −L is below 90° + asin(r/D).
    return glm::dot((eye - centre) / distance, -glm::normalize(light.vector)) > -radius / distance;
}

bool LightDepth::can_tile(const Light& light, glm::vec3 centre, float radius)
{
    return light.type == Light::Type::Directional ||
           glm::length(light.vector - centre) >= kPointMinDistance * std::max(radius, 1e-20f);
}

namespace {

// Tile of a directional light towards `l`: the orthographic box holds the bounding sphere
// (radius r, margin included): 2r across, depth from r in front of it to r behind.
LightTile orthographic_tile(glm::vec3 l, glm::vec3 centre, float r, uint32_t size)
{
    l = glm::normalize(l);
    const glm::vec3 up = std::abs(l.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::mat4 view = glm::lookAtRH(centre + 2.0f * r * l, centre, up);
    LightTile t;
    t.view_proj = glm::orthoRH_ZO(-r, r, -r, r, r, 3.0f * r) * view;
    t.origin = glm::vec4(0.0f);
    t.depth = glm::vec4(r, 2.0f * r, 2.0f * r / float(size), 0.0f);  // near r, far 3r
    return t;
}

// Tile of a point light at `p`, at distance D from the centre (D ≥ kPointMinDistance · radius):
// looking at the centre, its cone just holds the sphere, half-angle asin(radius / D) widened by
// kMargin (and below 85°); depth from D − margin · radius (but at least halfway to the sphere) to
// D + margin · radius. The layers store the distance from the light, not the clip depth.
LightTile perspective_tile(glm::vec3 p, glm::vec3 centre, float radius, uint32_t size)
{
    const glm::vec3 axis = centre - p;
    const float d = glm::length(axis), r = LightDepth::kMargin * radius;
    const glm::vec3 dir = axis / d;
    const glm::vec3 up = std::abs(dir.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const float half = std::min(std::asin(std::min(radius / d, 1.0f)) * LightDepth::kMargin, glm::radians(85.0f));
    const float near = std::max(d - r, 0.5f * (d - radius)), far = d + r;
    LightTile t;
    t.view_proj = glm::perspectiveRH_ZO(2.0f * half, 1.0f, near, far) * glm::lookAtRH(p, centre, up);
    t.origin = glm::vec4(p, 1.0f);
    t.depth = glm::vec4(near, far - near, 2.0f * std::tan(half) / float(size), 0.0f);
    return t;
}

}  // namespace

std::vector<uint32_t> LightDepth::record(VkCommandBuffer cmd, std::span<const Light> lights,
                                         std::span<const uint8_t> wanted, VkBuffer vertices, uint32_t vertex_stride,
                                         VkBuffer indices, uint32_t index_count, glm::vec3 centre, float radius,
                                         uint64_t geometry_version)
{
    std::vector<uint32_t> tile(lights.size(), 0);
    std::vector<glm::vec4> tiled;
    // Which lights: by priority; their tiles: in the lights' order, so that draws that want the
    // same lights for other reasons (a shadow here, a path there) share the atlas.
    std::vector<uint8_t> chosen(lights.size(), 0);
    size_t count = 0;
    for (uint8_t priority : {uint8_t(2), uint8_t(1)})
        for (size_t k = 0; k < lights.size() && count < kMaxLights; ++k)
            if (wanted[k] == priority && can_tile(lights[k], centre, radius)) chosen[k] = 1, ++count;
    // Shadows read layers 0 and 1 only: without a transmitter two passes, the other two layers
    // left at 1 (no surface).
    const uint32_t layers = std::any_of(wanted.begin(), wanted.end(), [](uint8_t w) { return w == 2; }) ? kLayers : 2;
    for (size_t k = 0; k < lights.size(); ++k)
        if (chosen[k]) {
            tiled.push_back(glm::vec4(lights[k].vector, float(lights[k].type)));
            tile[k] = uint32_t(tiled.size());
        }
    if (tiled.empty()) return tile;
    // Four layers serve a draw that needs two (a shadowed draw after a transmitting one).
    Contents wanted_contents{geometry_version, tiled, centre, radius, std::max(layers, contents_.layers)};
    if (wanted_contents == contents_) return tile;
    wanted_contents.layers = layers;
    contents_ = std::move(wanted_contents);
    for (uint32_t layer = 0; layer < kLayers; ++layer)
        if (!pipelines_[layer]) {
            gpu::GraphicsPipelineDesc d;
            d.name = "light depth layer";
            d.vertex_spirv = shaders::light_depth_vert();
            d.fragment_spirv = shaders::light_depth_frag();
            d.color_formats = {VK_FORMAT_R32G32B32A32_SFLOAT};
            d.color_write_mask = VK_COLOR_COMPONENT_R_BIT << layer;  // channel `layer`
            d.samples = VK_SAMPLE_COUNT_1_BIT;
            d.cull = VK_CULL_MODE_NONE;  // every surface along the light, facing it or not
            d.vertex_stride = vertex_stride;
            d.attributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
            d.bindings = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
            d.push_size = sizeof(LightTile);
            d.constants = {layer};
            pipelines_[layer].emplace(ctx_, d);
        }
    // A little margin for a deforming mesh that leaves its rest bounds.
    const float r = std::max(radius, 1e-20f) * kMargin;
    for (uint32_t k = 0; k < tiled.size(); ++k)
        tiles_[k] = tiled[k].w == float(Light::Type::Point)
                        ? perspective_tile(glm::vec3(tiled[k]), centre, std::max(radius, 1e-20f), tile_)
                        : orthographic_tile(glm::vec3(tiled[k]), centre, r, tile_);
    // Layer i: the nearest surface beyond layer i − 1, which the previous pass left in the other
    // depth buffer. The layers atlas starts as 1 (no surface) and takes one channel a pass.
    atlas_.transition(cmd, gpu::use::kColorAttachment, true);
    for (uint32_t layer = 0; layer < layers; ++layer) {
        gpu::Image& depth_buffer = peel_[layer % 2];
        gpu::Image& previous = peel_[(layer + 1) % 2];
        depth_buffer.transition(cmd, gpu::use::kDepthAttachment, true);
        previous.transition(cmd, gpu::use::kSampled, layer == 0);
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = atlas_.view();
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = layer == 0 ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        // A loaded attachment keeps a zero clear value: lavapipe clears to a non-zero one
        // (docs/lavapipe.md §5).
        if (layer == 0) color.clearValue.color = {{1.0f, 1.0f, 1.0f, 1.0f}};
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = depth_buffer.view();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;  // the next layer's `previous`
        depth.clearValue.depthStencil = {1.0f, 0};
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = {{0, 0}, {atlas_.width(), atlas_.height()}};
        ri.layerCount = 1;
        ri.colorAttachmentCount = 1;
        ri.pColorAttachments = &color;
        ri.pDepthAttachment = &depth;
        vkCmdBeginRendering(cmd, &ri);
        const VkDeviceSize offset = 0;
        for (uint32_t k = 0; k < tiled.size(); ++k) {
            pipelines_[layer]->bind(
                cmd, {tile_, tile_}, tiles_[k],
                {gpu::Binding::image(previous.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, previous_sampler_)});
            // Tile k: viewport and scissor moved to its column of the atlas.
            const VkViewport vp{float(k * tile_), 0.0f, float(tile_), float(tile_), 0.0f, 1.0f};
            const VkRect2D sc{{int32_t(k * tile_), 0}, {tile_, tile_}};
            vkCmdSetViewport(cmd, 0, 1, &vp);
            vkCmdSetScissor(cmd, 0, 1, &sc);
            vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
            vkCmdBindIndexBuffer(cmd, indices, 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
        }
        vkCmdEndRendering(cmd);
        if (layer + 1 < layers)
            gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    }
    atlas_.transition(cmd, gpu::use::kSampled);
    return tile;
}

}  // namespace jade::shading
