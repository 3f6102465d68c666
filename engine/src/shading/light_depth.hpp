// shading/light_depth.hpp - how far light travels inside the object before it reaches a point,
// for the transmission term. Per light, the depths of the first four surfaces along the light
// (depth peeling: entry, exit, entry, exit for a closed mesh), rendered into one tile of an
// RGBA32F atlas, a layer per channel: orthographically along a directional light, in perspective
// from a point light (the frustum just holding the bounding sphere; the layers then hold the
// distance along the light's ray, so that differences of layers are lengths along it). The fragment shader turns them into the path t_L inside the medium from where the
// light enters to the point (transmission.glsl): the length of [entry 1, exit 1] and of
// [entry 2, exit 2] up to the point, without the air between them, so that a finger in front of
// a fist is as thin as it is, while a paw that the body shadows from the light stays thick.
#pragma once

#include "gpu/image.hpp"
#include "gpu/pipeline.hpp"

#include <jade/render.hpp>

#include "shading_interface.h"  // JADE_MAX_LIGHT_DEPTH_TILES

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <optional>
#include <span>
#include <vector>

namespace jade::shading {

class LightDepth {
public:
    static constexpr uint32_t kMaxLights =
        JADE_MAX_LIGHT_DEPTH_TILES;  ///< lights with a depth tile; others use t̄ alone
    /// A point light gets a tile only from at least this many bounding radii from the centre:
    /// nearer, the frustum that holds the sphere is too wide (at 1.05 radii already 2 · 72°) and
    /// its texels too uneven; inside the sphere none holds it. Such a light keeps t̄ alone.
    static constexpr float kPointMinDistance = 1.05f;
    /// Surfaces kept per texel: the four channels of the layers atlas.
    static constexpr uint32_t kLayers = 4;
    /// A tile spans kMargin bounding radii each side of the centre (room for a deforming mesh).
    static constexpr float kMargin = 1.1f;

    LightDepth(gpu::Context& ctx, uint32_t tile_size);

    /// Whether light from `light` can reach the eye through an object in the bounding sphere
    /// (centre, radius), i.e. the forward lobe max(V·(−L), 0) is non-zero for some V from the
    /// sphere towards the eye: exact for directional lights; point lights, and an eye inside the
    /// sphere, always count.
    static bool may_transmit(glm::vec3 eye, const Light& light, glm::vec3 centre, float radius);

    /// Whether `light` can have a tile for an object in the bounding sphere (centre, radius):
    /// every directional light; a point light from kPointMinDistance radii or farther.
    static bool can_tile(const Light& light, glm::vec3 centre, float radius);

    /// The tiles of the lights with `wanted[k]` > 0 that can have one, rendered from the mesh into
    /// the atlas: the first kMaxLights of them in order of `wanted` (2: the transmission term's
    /// path needs it, 1: only a shadow), then of the lights, numbered in the lights' order; returns each light's tile + 1, 0 for none (and
    /// records nothing when every entry is 0). `geometry_version` changes whenever the vertices
    /// may have: with the same version, lights and bounds as the last call the atlas still holds
    /// the right depths and nothing is recorded (a still mesh under still lights costs no pass).
    /// Records outside any rendering scope; the atlas is left ready for fragment-shader reads.
    std::vector<uint32_t> record(VkCommandBuffer cmd, std::span<const Light> lights, std::span<const uint8_t> wanted,
                                 VkBuffer vertices, uint32_t vertex_stride, VkBuffer indices, uint32_t index_count,
                                 glm::vec3 centre, float radius, uint64_t geometry_version);

    /// Tile k as the shaders read it: its matrix, kind, origin and depth mapping.
    const LightTile& tile(uint32_t k) const { return tiles_[k]; }
    uint32_t tile_size() const { return tile_; }
    /// The layers' depths (RGBA: layers 0 … 3, 1 where there is none), kMaxLights tiles side by side.
    const gpu::Image& atlas() const { return atlas_; }
    /// GPU memory of the atlas and the peeling's two depth buffers, bytes.
    uint64_t bytes() const;

private:
    gpu::Context& ctx_;
    uint32_t tile_;
    gpu::Image atlas_;                    // RGBA32F, kMaxLights tiles side by side
    std::array<gpu::Image, 2> peel_;      // D32: the pass's depth buffer, and the previous layer's
    gpu::OwnedSampler previous_sampler_;  // nearest: the previous layer at the same texel
    std::array<std::optional<gpu::GraphicsPipeline>, kLayers> pipelines_;  // one per layer
    std::array<LightTile, kMaxLights> tiles_{};
    // What the atlas holds now.
    struct Contents {
        uint64_t geometry_version = ~uint64_t(0);
        std::vector<glm::vec4> lights;  // xyz: Light::vector, w: Light::type
        glm::vec3 centre{0.0f};
        float radius = -1.0f;
        uint32_t layers = 0;  // peeled: kLayers, or 2 for shadows alone
        bool operator==(const Contents&) const = default;
    } contents_;
};

}  // namespace jade::shading
