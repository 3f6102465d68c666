// shading/light_depth.hpp - how far light travels inside the object before it reaches a point,
// for the transmission term: per directional light behind the object, the depth of the surface
// nearest to the light, rendered orthographically along the light into one tile of a D32 atlas.
// The fragment shader turns it into t_L = (its own depth − that depth) along the light, the
// distance from where the light enters the object, so parts the body shadows from the light
// (a paw behind the body) are thick even where their local thickness t̄ is small.
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

    LightDepth(gpu::Context& ctx, uint32_t tile_size);

    /// Whether light from `light` can reach the eye through an object in the bounding sphere
    /// (centre, radius), i.e. the forward lobe max(V·(−L), 0) is non-zero for some V from the
    /// sphere towards the eye: exact for directional lights; point lights, and an eye inside the
    /// sphere, always count.
    static bool may_transmit(glm::vec3 eye, const Light& light, glm::vec3 centre, float radius);

    /// The tiles of the directional lights that may transmit (the first kMaxLights of them),
    /// rendered from the mesh into the atlas; returns each light's tile + 1, 0 for none (and
    /// records nothing when every entry is 0). `geometry_version` changes whenever the vertices
    /// may have: with the same version, lights and bounds as the last call the atlas still holds
    /// the right depths and nothing is recorded (a still mesh under still lights costs no pass).
    /// Records outside any rendering scope; the atlas is left ready for fragment-shader reads.
    std::vector<uint32_t> record(VkCommandBuffer cmd, glm::vec3 eye, std::span<const Light> lights, VkBuffer vertices,
                                 uint32_t vertex_stride, VkBuffer indices, uint32_t index_count, glm::vec3 centre,
                                 float radius, uint64_t geometry_version);

    /// World → light clip space of tile k (x, y ∈ [−1, 1] over the tile, depth ∈ [0, 1]).
    const glm::mat4& view_projection(uint32_t k) const { return view_proj_[k]; }
    /// Mesh units per unit of stored depth (the orthographic depth range).
    float depth_range() const { return depth_range_; }
    uint32_t tile_size() const { return tile_; }
    const gpu::Image& atlas() const { return atlas_; }

private:
    gpu::Context& ctx_;
    uint32_t tile_;
    gpu::Image atlas_;  // kMaxLights tiles side by side
    std::optional<gpu::GraphicsPipeline> pipeline_;
    std::array<glm::mat4, kMaxLights> view_proj_{};
    float depth_range_ = 1.0f;
    // What the atlas holds now.
    struct Contents {
        uint64_t geometry_version = ~uint64_t(0);
        std::vector<glm::vec3> towards_light;
        glm::vec3 centre{0.0f};
        float radius = -1.0f;
        bool operator==(const Contents&) const = default;
    } contents_;
};

}  // namespace jade::shading
