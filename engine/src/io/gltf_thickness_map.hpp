// io/gltf_thickness_map.hpp - the baked thickness as a texture in a primitive's UV layout, for
// KHR_materials_volume.thicknessTexture (private to jade_io; docs/gltf.md, "Thickness maps").
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace jade::io {

/// Triangles with a UV and a thickness per vertex: every primitive that shares one glTF material.
struct UvTriangles {
    std::vector<glm::vec3> positions;  ///< mesh units (for the texel density)
    std::vector<glm::vec2> uv;         ///< TEXCOORD_0: u right, v down (glTF: (0, 0) is the image's first texel)
    std::vector<float> thickness;      ///< mesh units, ≥ 0
    std::vector<uint32_t> indices;     ///< 3 per triangle
};

struct ThicknessMap {
    uint32_t size = 0;  ///< width = height, texels
    double factor = 0;  ///< KHR_materials_volume.thicknessFactor: the largest thickness, mesh units
    /// size × size bytes, rows top to bottom: thickness / factor in 0..255 (rounded); texels that no
    /// triangle covers take the mean of their covered neighbours, kDilation times over, else 0.
    std::vector<uint8_t> texels;
    std::vector<uint8_t> covered;  ///< size × size: 1 where a texel's centre lies in a triangle
};

/// Texels per side: the power of two that puts kTexelsPerEdge texels along the median edge where
/// the layout's mean stretch (√(3-D area / UV area)) holds, clamped to [kMinSize, kMaxSize].
/// 0 when the layout has no area (no texture).
inline constexpr double kTexelsPerEdge = 4.0;
inline constexpr uint32_t kMinSize = 16, kMaxSize = 1024;
inline constexpr int kDilation = 4;  ///< texels the values are grown across seams
uint32_t thickness_map_size(const UvTriangles& t);

/// Rasterises the per-vertex thickness over the UV triangles (texel centres at ((i + ½)/N,
/// (j + ½)/N), barycentric interpolation, UVs wrapped as a REPEAT sampler wraps them), then
/// dilates. Triangles with a UV that is not finite are left out.
ThicknessMap bake_thickness_map(const UvTriangles& t, uint32_t size);

/// The map as an 8-bit PNG: thickness in the green channel (KHR_materials_volume), red and blue
/// 0. Defined with the image code (io/image.cpp); a build without images throws naming `file`.
std::vector<unsigned char> encode_thickness_png(const std::string& file, const ThicknessMap& map);

}  // namespace jade::io
