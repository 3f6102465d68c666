// mesh/prepare.cpp - jade::prepare_mesh: from render vertices to the one surface the bake sees.
//
// Steps, each O(n) except the O(n log n) sort of the weld:
//   1. validate_mesh: indices and positions (the first bad element is named in the error);
//   2. weld render vertices with equal positions (glTF splits vertices at UV and normal seams;
//      the bake must see one vertex there or the seam shows up as a crack in the AO);
//   3. drop triangles that repeat a vertex after welding or have zero or non-finite area;
//   4. number the bake vertices that kept triangles use, in render-vertex order;
//   5. area-weighted normals, vertex areas (a third of each adjacent triangle) and bounds.
// Sums are accumulated in double: a vertex area or normal gathers many small terms.
#include "mesh/validate.hpp"

#include <jade/dev/mesh.hpp>
#include <jade/error.hpp>
#include <jade/mesh.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <string>

namespace jade {

namespace {

[[noreturn]] void fail(const TriangleMesh& mesh, const std::string& what) { throw Error(mesh.name + ": " + what); }

/// For each render vertex, the lowest-numbered render vertex at the same position. Positions
/// are compared as values (so -0.0 welds with +0.0, which exporters mix at seams); for the
/// finite floats validated above that is bit-equality up to the sign of zero.
std::vector<uint32_t> weld_targets(const std::vector<glm::vec3>& positions)
{
    struct Key {
        std::array<uint32_t, 3> bits;
        uint32_t vertex;
    };
    std::vector<Key> keys(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) {
        keys[v].vertex = uint32_t(v);
        for (int c = 0; c < 3; ++c)
            keys[v].bits[size_t(c)] = std::bit_cast<uint32_t>(positions[v][c] + 0.0f);  // -0 -> +0
    }
    // Sorting (rather than hashing) gives a deterministic result with no worst case.
    std::sort(keys.begin(), keys.end(),
              [](const Key& a, const Key& b) { return a.bits != b.bits ? a.bits < b.bits : a.vertex < b.vertex; });
    std::vector<uint32_t> target(positions.size());
    for (size_t i = 0; i < keys.size(); ++i) {
        const bool first = i == 0 || keys[i].bits != keys[i - 1].bits;
        target[keys[i].vertex] = first ? keys[i].vertex : target[keys[i - 1].vertex];
    }
    return target;
}

/// Twice the triangle's vector area, in double.
glm::dvec3 cross_product(const std::vector<glm::vec3>& p, uint32_t a, uint32_t b, uint32_t c)
{
    const glm::dvec3 pa(p[a]), pb(p[b]), pc(p[c]);
    return glm::cross(pb - pa, pc - pa);
}

/// Kept triangles, in render-vertex indices of the weld targets.
std::vector<uint32_t> keep_triangles(const TriangleMesh& mesh, const std::vector<uint32_t>& target)
{
    std::vector<uint32_t> kept;
    kept.reserve(mesh.indices.size());
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const uint32_t a = target[mesh.indices[t]], b = target[mesh.indices[t + 1]], c = target[mesh.indices[t + 2]];
        if (a == b || b == c || a == c) continue;
        const double area2 = glm::length(cross_product(mesh.positions, a, b, c));
        if (!(area2 > 0.0) || !std::isfinite(area2)) continue;  // collinear, or overflowed
        kept.insert(kept.end(), {a, b, c});
    }
    return kept;
}

/// Numbers the used weld targets in render-vertex order and fills render_to_bake.
void number_vertices(const TriangleMesh& mesh, const std::vector<uint32_t>& target, const std::vector<uint32_t>& kept,
                     PreparedMesh& out)
{
    const size_t n = mesh.positions.size();
    std::vector<uint32_t> bake_of(n, PreparedMesh::kUnused);
    std::vector<bool> used(n, false);
    for (uint32_t v : kept) used[v] = true;
    for (size_t v = 0; v < n; ++v) {
        if (!used[v]) continue;
        bake_of[v] = uint32_t(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
    }
    out.render_to_bake.resize(n);
    for (size_t v = 0; v < n; ++v) out.render_to_bake[v] = bake_of[target[v]];
    out.indices.resize(kept.size());
    for (size_t i = 0; i < kept.size(); ++i) out.indices[i] = bake_of[kept[i]];
}

/// Area-weighted normals (the sum of the unnormalised cross products) and vertex areas.
void normals_and_areas(PreparedMesh& out)
{
    const size_t n = out.positions.size();
    std::vector<glm::dvec3> sum(n, glm::dvec3(0.0));
    std::vector<double> area(n, 0.0), largest(n, 0.0);
    std::vector<glm::dvec3> largest_normal(n, glm::dvec3(0.0));
    for (size_t t = 0; t < out.indices.size(); t += 3) {
        const glm::dvec3 cr = cross_product(out.positions, out.indices[t], out.indices[t + 1], out.indices[t + 2]);
        const double a = 0.5 * glm::length(cr);
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t v = out.indices[t + k];
            sum[v] += cr;
            area[v] += a / 3.0;
            if (a > largest[v]) largest[v] = a, largest_normal[v] = cr;
        }
    }
    out.normals.resize(n);
    out.areas.resize(n);
    for (size_t v = 0; v < n; ++v) {
        // Opposite faces can cancel (a vertex on a two-sided sheet): then the largest adjacent
        // triangle decides, and (0,0,1) only if even that is degenerate. "Cancel" allows for
        // rounding: the same triangle listed from another corner gives a slightly different
        // cross product, and normalising the residue would give an arbitrary direction.
        constexpr double kCancelled = 1e-9;
        const double magnitude = 6.0 * area[v];  // the sum of the |cross products| at v
        glm::dvec3 normal = sum[v];
        if (!(glm::length(normal) > kCancelled * magnitude)) normal = largest_normal[v];
        const double len = glm::length(normal);
        out.normals[v] = len > 0.0 && std::isfinite(len) ? glm::vec3(normal / len) : glm::vec3(0.0f, 0.0f, 1.0f);
        out.areas[v] = float(area[v]);
    }
}

void bounds(PreparedMesh& out)
{
    glm::vec3 lo = out.positions[0], hi = out.positions[0];
    for (const auto& p : out.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    out.bbox_min = lo;
    out.bbox_max = hi;
    out.diagonal = float(glm::length(glm::dvec3(hi) - glm::dvec3(lo)));
}

}  // namespace

void validate_mesh(const TriangleMesh& mesh)
{
    const size_t n = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
        fail(mesh, "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    if (n > PreparedMesh::kUnused) fail(mesh, std::to_string(n) + " vertices, more than 32-bit indices can address");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            fail(mesh, "triangle " + std::to_string(i / 3) + " (vertex index " + std::to_string(mesh.indices[i]) +
                           ") out of range for " + std::to_string(n) + " vertices");
    if (!mesh.normals.empty() && mesh.normals.size() != n)
        fail(mesh, std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) + " vertices");
    for (size_t v = 0; v < n; ++v)
        for (int c = 0; c < 3; ++c) {
            if (std::isnan(mesh.positions[v][c])) fail(mesh, "vertex " + std::to_string(v) + " position is NaN");
            if (std::isinf(mesh.positions[v][c])) fail(mesh, "vertex " + std::to_string(v) + " position is infinite");
        }
}

PreparedMesh prepare_mesh(const TriangleMesh& mesh)
{
    validate_mesh(mesh);
    const auto target = weld_targets(mesh.positions);
    const auto kept = keep_triangles(mesh, target);
    if (kept.empty())
        fail(mesh, mesh.indices.empty() ? std::string("has no triangles")
                                        : "all " + std::to_string(mesh.triangle_count()) + " triangles are degenerate");

    PreparedMesh out;
    number_vertices(mesh, target, kept, out);
    normals_and_areas(out);
    bounds(out);

    // input_vertices = bake vertices + welded_vertices + unused_vertices.
    out.input_vertices = mesh.positions.size();
    out.input_triangles = mesh.triangle_count();
    out.unused_vertices =
        size_t(std::count(out.render_to_bake.begin(), out.render_to_bake.end(), PreparedMesh::kUnused));
    out.welded_vertices = out.input_vertices - out.unused_vertices - out.vertex_count();
    out.dropped_triangles = out.input_triangles - out.triangle_count();
    return out;
}

float dev::total_area(const PreparedMesh& mesh)
{
    double total = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        total +=
            0.5 * glm::length(cross_product(mesh.positions, mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]));
    return float(total);
}

}  // namespace jade
