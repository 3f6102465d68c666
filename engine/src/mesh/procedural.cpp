// mesh/procedural.cpp - jade::procedural::sphere and jade::dev::procedural: meshes that need no
// file (tests, demos, calibration).
//
// All triangles are counter-clockwise seen from outside (the box, the sphere) or from +z (the
// grid). The sphere shares its seam and pole vertices, so it is closed as generated; the box
// has separate vertices per face (flat render normals, like a glTF cube) whose positions come
// from one table per axis, so shared edges are bit-identical and prepare_mesh welds them.
#include <jade/dev/mesh.hpp>
#include <jade/error.hpp>
#include <jade/mesh.hpp>

#include <cmath>
#include <unordered_map>
#include <numbers>
#include <string>

namespace jade {
namespace {

[[noreturn]] void bad_parameter(const char* generator, const std::string& what)
{
    throw Error(std::string("procedural::") + generator + ": " + what);
}

/// Generated meshes stay well inside 32-bit indices and a sane memory budget.
constexpr uint64_t kMaxGeneratedVertices = uint64_t(1) << 28;

void check_vertex_budget(const char* generator, uint64_t vertices)
{
    if (vertices > kMaxGeneratedVertices)
        bad_parameter(generator, std::to_string(vertices) + " vertices requested, more than the limit of " +
                                     std::to_string(kMaxGeneratedVertices));
}

/// Two triangles per cell of an (n+1)×(n+1) vertex lattice whose vertex (i, j) is
/// base + i·(n+1) + j, counter-clockwise when i runs along u and j along v (normal u × v).
void add_lattice_triangles(std::vector<uint32_t>& indices, uint32_t base, uint32_t n)
{
    const uint32_t row = n + 1;
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t q00 = base + i * row + j, q10 = q00 + row, q11 = q10 + 1, q01 = q00 + 1;
            indices.insert(indices.end(), {q00, q10, q11, q00, q11, q01});
        }
}

}  // namespace

TriangleMesh procedural::sphere(float radius, uint32_t rings, uint32_t segments)
{
    if (!(radius > 0.0f) || !std::isfinite(radius)) bad_parameter("sphere", "radius must be positive and finite");
    if (rings < 2) bad_parameter("sphere", "rings must be at least 2 (got " + std::to_string(rings) + ")");
    if (segments < 3) bad_parameter("sphere", "segments must be at least 3 (got " + std::to_string(segments) + ")");
    check_vertex_budget("sphere", uint64_t(rings - 1) * segments + 2);

    TriangleMesh mesh;
    mesh.name = "sphere";
    // Poles on ±z; ring i at polar angle π·i/rings, segment j at azimuth 2π·j/segments.
    mesh.positions.push_back({0.0f, 0.0f, radius});
    for (uint32_t i = 1; i < rings; ++i) {
        const double theta = std::numbers::pi * i / rings;
        for (uint32_t j = 0; j < segments; ++j) {
            const double phi = 2.0 * std::numbers::pi * j / segments;
            mesh.positions.push_back(glm::vec3(
                glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)) *
                double(radius)));
        }
    }
    mesh.positions.push_back({0.0f, 0.0f, -radius});
    for (const auto& p : mesh.positions) mesh.normals.push_back(p / radius);

    const uint32_t south = uint32_t(mesh.positions.size() - 1);
    auto ring = [segments](uint32_t i, uint32_t j) { return 1 + (i - 1) * segments + j % segments; };
    for (uint32_t j = 0; j < segments; ++j) {
        mesh.indices.insert(mesh.indices.end(), {0u, ring(1, j), ring(1, j + 1)});
        for (uint32_t i = 1; i + 1 < rings; ++i) {
            const uint32_t a0 = ring(i, j), a1 = ring(i, j + 1), b0 = ring(i + 1, j), b1 = ring(i + 1, j + 1);
            mesh.indices.insert(mesh.indices.end(), {a0, b0, b1, a0, b1, a1});
        }
        mesh.indices.insert(mesh.indices.end(), {south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    }
    return mesh;
}

TriangleMesh dev::procedural::box(glm::vec3 lo, glm::vec3 hi, uint32_t n)
{
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(hi[a] > lo[a]))
            bad_parameter("box", "hi must be greater than lo on every axis, and both finite");
    if (n < 1) bad_parameter("box", "n must be at least 1");
    check_vertex_budget("box", 6 * (uint64_t(n) + 1) * (uint64_t(n) + 1));

    // One coordinate table per axis, so that faces meeting at an edge share exact positions.
    std::vector<float> coord[3];
    for (int a = 0; a < 3; ++a)
        for (uint32_t i = 0; i <= n; ++i)
            coord[a].push_back(i == n ? hi[a] : float(double(lo[a]) + (double(hi[a]) - double(lo[a])) * i / n));

    TriangleMesh mesh;
    mesh.name = "box";
    for (int a = 0; a < 3; ++a) {
        for (int side = 0; side < 2; ++side) {
            // (u, v) cyclic after a gives u × v = +a; swapped for the face facing -a.
            int u = (a + 1) % 3, v = (a + 2) % 3;
            if (side == 0) std::swap(u, v);
            glm::vec3 normal(0.0f);
            normal[a] = side == 0 ? -1.0f : 1.0f;
            const uint32_t base = uint32_t(mesh.positions.size());
            for (uint32_t i = 0; i <= n; ++i)
                for (uint32_t j = 0; j <= n; ++j) {
                    glm::vec3 p;
                    p[a] = side == 0 ? lo[a] : hi[a];
                    p[u] = coord[u][i];
                    p[v] = coord[v][j];
                    mesh.positions.push_back(p);
                    mesh.normals.push_back(normal);
                }
            add_lattice_triangles(mesh.indices, base, n);
        }
    }
    return mesh;
}

TriangleMesh dev::procedural::grid(uint32_t n, float spacing)
{
    if (!(spacing > 0.0f) || !std::isfinite(spacing)) bad_parameter("grid", "spacing must be positive and finite");
    if (n < 1) bad_parameter("grid", "n must be at least 1");
    check_vertex_budget("grid", (uint64_t(n) + 1) * (uint64_t(n) + 1));

    TriangleMesh mesh;
    mesh.name = "grid";
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j) {
            const auto x = float((double(i) - 0.5 * n) * spacing), y = float((double(j) - 0.5 * n) * spacing);
            mesh.positions.push_back({x, y, 0.0f});
            mesh.normals.push_back({0.0f, 0.0f, 1.0f});
        }
    add_lattice_triangles(mesh.indices, 0, n);  // i along x, j along y: normal +z
    return mesh;
}

TriangleMesh dev::procedural::subdivide(const TriangleMesh& mesh, uint32_t levels)
{
    TriangleMesh out = mesh;
    out.normals.clear();
    out.baked_ao.clear();
    out.baked_tm.clear();
    for (uint32_t level = 0; level < levels; ++level) {
        if (out.triangle_count() * 4 >= (uint64_t(1) << 27)) bad_parameter("subdivide", "more than 2^27 triangles");
        // One midpoint per undirected edge, keyed by its (lower, higher) vertex pair.
        std::unordered_map<uint64_t, uint32_t> midpoint;
        midpoint.reserve(out.indices.size());
        auto mid = [&](uint32_t a, uint32_t b) {
            const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
            auto [it, added] = midpoint.try_emplace(key, uint32_t(out.positions.size()));
            if (added) out.positions.push_back(0.5f * (out.positions[a] + out.positions[b]));
            return it->second;
        };
        std::vector<uint32_t> indices;
        indices.reserve(out.indices.size() * 4);
        for (size_t t = 0; t < out.triangle_count(); ++t) {
            const uint32_t a = out.indices[3 * t], b = out.indices[3 * t + 1], c = out.indices[3 * t + 2];
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            for (uint32_t v : {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca}) indices.push_back(v);
        }
        out.indices = std::move(indices);
    }
    out.name = mesh.name + " (subdivided " + std::to_string(levels) + "x)";
    return out;
}

}  // namespace jade
