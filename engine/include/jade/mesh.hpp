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
    float total_area() const;
};

/// Checks what every TriangleMesh must satisfy: an index count that is a multiple of 3, indices
/// in range, finite positions, normals absent or one per position. Throws jade::Error naming
/// mesh.name and the first offending element, e.g.
/// "bunny.off: triangle 12 (vertex index 40912) out of range for 37706 vertices".
void validate_mesh(const TriangleMesh& mesh);

/// Welds, drops degenerate triangles, computes normals, vertex areas and bounds.
/// Throws jade::Error (naming mesh.name) when the mesh is empty after preparation, an index is
/// out of range, or a position is NaN or infinite.
PreparedMesh prepare_mesh(const TriangleMesh& mesh);

/// Expands per-bake-vertex values back to the render vertices (unused vertices get `fill`).
template <class T>
std::vector<T> to_render_vertices(const PreparedMesh& prepared, const std::vector<T>& per_bake, T fill = T{})
{
    std::vector<T> out(prepared.render_to_bake.size(), fill);
    for (size_t i = 0; i < out.size(); ++i)
        if (prepared.render_to_bake[i] != PreparedMesh::kUnused) out[i] = per_bake[prepared.render_to_bake[i]];
    return out;
}

/// Procedural meshes: a scene that needs no download.
namespace procedural {
/// UV sphere of the given radius centred at the origin; `rings` ≥ 2, `segments` ≥ 3.
/// Like box and grid, throws jade::Error for counts or sizes out of range.
TriangleMesh sphere(float radius, uint32_t rings, uint32_t segments);
/// Axis-aligned closed box from `lo` to `hi`, each face split into n×n quads (a thin slab or a
/// thick block). n ≥ 1.
TriangleMesh box(glm::vec3 lo, glm::vec3 hi, uint32_t n);
/// Flat square grid in the z = 0 plane, centred at the origin, `n`×`n` quads of side `spacing`,
/// normal +z. n ≥ 1.
TriangleMesh grid(uint32_t n, float spacing);
/// Midpoint subdivision, `levels` times: every triangle becomes four, each edge gets one new
/// vertex at its midpoint (shared by both sides), the surface stays where it was. Vertices grow
/// about 4× per level (the 37,706-vertex bunny: 150,776, 603,062, 2,412,206). Normals are
/// dropped. Throws jade::Error past 2^27 triangles.
TriangleMesh subdivide(const TriangleMesh& mesh, uint32_t levels);
}  // namespace procedural

}  // namespace jade
