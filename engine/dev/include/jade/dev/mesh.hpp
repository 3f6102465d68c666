// jade/dev/mesh.hpp - meshes for the tests and the CLI: generated boxes, grids and subdivisions
// (the sphere is the core's, jade/mesh.hpp), a prepared mesh's area, and per-bake-vertex values
// expanded back to the render vertices (what `jade bake` writes). Declared for jade::dev,
// defined in jade::jade (to_render_vertices here).
#pragma once

#include <jade/mesh.hpp>

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace jade::dev {

/// The area of the kept triangles, mesh units² (Σ of the vertex areas up to rounding).
float total_area(const PreparedMesh& mesh);

/// Expands per-bake-vertex values back to the render vertices (unused vertices get `fill`).
template <class T>
std::vector<T> to_render_vertices(const PreparedMesh& prepared, const std::vector<T>& per_bake, T fill = T{})
{
    std::vector<T> out(prepared.render_to_bake.size(), fill);
    for (size_t i = 0; i < out.size(); ++i)
        if (prepared.render_to_bake[i] != PreparedMesh::kUnused) out[i] = per_bake[prepared.render_to_bake[i]];
    return out;
}

/// Generated test meshes. Like jade::procedural::sphere, each throws jade::Error for counts or
/// sizes out of range.
namespace procedural {
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

}  // namespace jade::dev
