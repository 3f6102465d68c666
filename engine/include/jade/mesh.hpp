// jade/mesh.hpp - triangle meshes and their preparation for the bake.
//
// Conventions: positions are in the mesh's own units (Jade never rescales silently); the
// coordinate system is right-handed; triangles are counter-clockwise when seen from outside.
// Meshes are plain data; the functions here are CPU-only and thread-safe (no shared state).
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace jade {

/// A triangle mesh as loaded or generated: "render vertices", possibly split at UV or normal
/// seams. Indices are triangle lists (3 per triangle).
struct TriangleMesh {
    std::string name;                  ///< file name or generator name, used in messages
    std::vector<glm::vec3> positions;  ///< mesh units
    std::vector<glm::vec3> normals;    ///< optional (empty or one per position)
    std::vector<uint32_t> indices;     ///< 3 per triangle, each < positions.size()

    /// Baked attributes, present when the mesh was read from a file written by `jade bake`
    /// (glTF attributes `_AO`, `_TM`, `_THICKNESS`, ...), else empty. One per render vertex.
    std::vector<float> baked_ao;
    std::vector<glm::vec3> baked_tm;
    std::vector<float> baked_thickness;  ///< mesh units
    /// `_SCATTERING_NORMAL` (BakeResult::scattering_normal, in the mesh's space) and
    /// `_NORMAL_SPREAD` (BakeResult::normal_spread, [0, 1] per channel).
    std::vector<glm::vec3> baked_scattering_normal, baked_normal_spread;

    size_t triangle_count() const { return indices.size() / 3; }
};

/// The mesh as the bake sees it: one surface. Render vertices that share a position are welded
/// into one "bake vertex", degenerate triangles are dropped, and vertices no triangle uses are
/// left out.
struct PreparedMesh {
    std::vector<glm::vec3> positions;  ///< bake vertices, mesh units
    std::vector<glm::vec3> normals;    ///< area-weighted vertex normals, unit length
    std::vector<float> areas;          ///< a third of the area of each adjacent triangle (units²)
    std::vector<uint32_t> indices;     ///< 3 per kept triangle, into the bake vertices

    /// For each render vertex of the input TriangleMesh, its bake vertex, or kUnused when no
    /// kept triangle references it.
    std::vector<uint32_t> render_to_bake;
    static constexpr uint32_t kUnused = 0xffffffffu;

    glm::vec3 bbox_min{0.0f}, bbox_max{0.0f};
    float diagonal = 0.0f;  ///< |bbox_max - bbox_min|, mesh units

    // What preparation did, for `jade info` and tests. They add up:
    // input_vertices = vertex_count() + welded_vertices + unused_vertices and
    // input_triangles = triangle_count() + dropped_triangles.
    size_t input_vertices = 0, input_triangles = 0;
    size_t welded_vertices = 0;    ///< render vertices merged into another one
    size_t dropped_triangles = 0;  ///< zero-area or repeated-index triangles
    size_t unused_vertices = 0;    ///< render vertices no kept triangle references

    size_t vertex_count() const { return positions.size(); }
    size_t triangle_count() const { return indices.size() / 3; }
};

/// Welds, drops degenerate triangles, computes normals, vertex areas and bounds.
/// Throws jade::Error (naming mesh.name and the first offending element, e.g. "bunny.off:
/// triangle 12 (vertex index 40912) out of range for 37706 vertices") when the mesh is empty
/// after preparation, an index is out of range, the index count is not a multiple of 3, a
/// position is NaN or infinite, or normals are given but not one per position.
PreparedMesh prepare_mesh(const TriangleMesh& mesh);

/// A mesh that needs no download (the box, grid and subdivision of the tests: jade/dev/mesh.hpp).
namespace procedural {
/// UV sphere of the given radius centred at the origin; `rings` ≥ 2, `segments` ≥ 3.
/// Throws jade::Error for counts or sizes out of range.
TriangleMesh sphere(float radius, uint32_t rings, uint32_t segments);
}  // namespace procedural

}  // namespace jade
