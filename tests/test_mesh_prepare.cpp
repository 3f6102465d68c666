// Tests of jade::prepare_mesh and the procedural meshes: welding, degenerate triangles, unused
// vertices, area-weighted normals and their fallbacks, vertex areas, bounds, error messages.
#include <jade/error.hpp>
#include <jade/mesh.hpp>
#include <jade/dev/mesh.hpp>

#include "test_support.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

using jade::PreparedMesh;
using jade::TriangleMesh;
using jade::test::closed_and_oriented;
using jade::test::error_of;

TriangleMesh make_mesh(std::vector<glm::vec3> positions, std::vector<uint32_t> indices, std::string name = "test")
{
    TriangleMesh m;
    m.name = std::move(name);
    m.positions = std::move(positions);
    m.indices = std::move(indices);
    return m;
}

glm::dvec3 triangle_normal(const PreparedMesh& m, size_t t)
{
    const glm::dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
        c(m.positions[m.indices[3 * t + 2]]);
    return glm::cross(b - a, c - a);
}

void expect_vec3_near(glm::vec3 actual, glm::vec3 expected, float tolerance)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expect_stats_consistent(const PreparedMesh& p)
{
    EXPECT_EQ(p.input_vertices, p.vertex_count() + p.welded_vertices + p.unused_vertices);
    EXPECT_EQ(p.input_triangles, p.triangle_count() + p.dropped_triangles);
    EXPECT_EQ(p.normals.size(), p.vertex_count());
    EXPECT_EQ(p.areas.size(), p.vertex_count());
    EXPECT_EQ(p.render_to_bake.size(), p.input_vertices);
}

// ------------------------------------------------------------------------------------ weld --

TEST(mesh_prepare, WeldsVerticesSplitAtASeam)
{
    // A unit quad as two triangles whose shared edge is duplicated (as glTF writes UV seams).
    const glm::vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
    const auto p = jade::prepare_mesh(make_mesh({a, b, c, a, c, d}, {0, 1, 2, 3, 4, 5}));
    ASSERT_EQ(p.vertex_count(), 4u);
    EXPECT_EQ(p.welded_vertices, 2u);
    EXPECT_EQ(p.unused_vertices, 0u);
    EXPECT_EQ(p.render_to_bake, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(p.positions, (std::vector<glm::vec3>{a, b, c, d}));
    EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_FLOAT_EQ(jade::dev::total_area(p), 1.0f);
    expect_stats_consistent(p);
}

TEST(mesh_prepare, WeldsNegativeZeroWithPositiveZero)
{
    const auto p = jade::prepare_mesh(
        make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0f, 0, -0.0f}, {0, 0, 1}}, {0, 1, 2, 3, 2, 4}));
    EXPECT_EQ(p.vertex_count(), 4u);
    EXPECT_EQ(p.render_to_bake[3], p.render_to_bake[0]);
}

TEST(mesh_prepare, DoesNotWeldNearbyButDifferentPositions)
{
    const float e = std::nextafter(1.0f, 2.0f);
    const auto p =
        jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {e, 0, 0}, {1, 1, 0}}, {0, 1, 2, 3, 4, 2}));
    EXPECT_EQ(p.vertex_count(), 5u);
    EXPECT_EQ(p.welded_vertices, 0u);
}

// --------------------------------------------------------------------- degenerate / unused --

TEST(mesh_prepare, DropsDegenerateTrianglesAndUnusedVertices)
{
    const std::vector<glm::vec3> positions = {
        {0, 0, 0}, {1, 0, 0}, {0, 1, 0},  // 0-2: the one good triangle
        {2, 0, 0}, {3, 0, 0},             // 3-4: collinear with 1
        {0, 0, 0},                        // 5: a copy of 0
        {7, 7, 7},                        // 6: referenced by no triangle at all
        {5, 5, 5},                        // 7: only in dropped triangles
    };
    const std::vector<uint32_t> indices = {
        0, 1, 2,  // kept
        1, 1, 2,  // repeated index
        1, 3, 4,  // zero area (collinear)
        0, 5, 1,  // repeated vertex after welding 5 into 0
        7, 7, 0,  // repeated index; vertex 7 ends up unused
    };
    const auto p = jade::prepare_mesh(make_mesh(positions, indices));
    EXPECT_EQ(p.input_vertices, 8u);
    EXPECT_EQ(p.input_triangles, 5u);
    EXPECT_EQ(p.triangle_count(), 1u);
    EXPECT_EQ(p.dropped_triangles, 4u);
    EXPECT_EQ(p.vertex_count(), 3u);
    EXPECT_EQ(p.welded_vertices, 1u);  // 5 -> 0
    EXPECT_EQ(p.unused_vertices, 4u);  // 3, 4, 6, 7
    const auto k = PreparedMesh::kUnused;
    EXPECT_EQ(p.render_to_bake, (std::vector<uint32_t>{0, 1, 2, k, k, 0, k, k}));
    expect_stats_consistent(p);
}

TEST(mesh_prepare, ToRenderVerticesFillsUnusedVertices)
{
    const auto p =
        jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {9, 9, 9}, {0, 0, 0}}, {0, 1, 2, 4, 1, 2}));
    const auto values = jade::dev::to_render_vertices(p, std::vector<float>{10.0f, 20.0f, 30.0f}, -1.0f);
    EXPECT_EQ(values, (std::vector<float>{10.0f, 20.0f, 30.0f, -1.0f, 10.0f}));
}

// ------------------------------------------------------------------------ normals / areas --

TEST(mesh_prepare, NormalsAreAreaWeightedAndAreasAreAThirdOfEachTriangle)
{
    // O and P are shared by a triangle of area 1 facing +z and one of area 1/2 facing +x. An
    // area-weighted normal at O is (1,0,2)/√5; a plain average of unit normals would be (1,0,1)/√2.
    const glm::vec3 o(0, 0, 0), q(2, 0, 0), pp(0, 1, 0), r(0, 0, 1);
    const auto p = jade::prepare_mesh(make_mesh({o, q, pp, r}, {0, 1, 2, 0, 2, 3}));
    const float s5 = std::sqrt(5.0f);
    expect_vec3_near(p.normals[0], {1 / s5, 0, 2 / s5}, 1e-6f);
    expect_vec3_near(p.normals[2], {1 / s5, 0, 2 / s5}, 1e-6f);
    expect_vec3_near(p.normals[1], {0, 0, 1}, 1e-6f);
    expect_vec3_near(p.normals[3], {1, 0, 0}, 1e-6f);
    EXPECT_FLOAT_EQ(p.areas[0], 0.5f);
    EXPECT_FLOAT_EQ(p.areas[1], 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(p.areas[2], 0.5f);
    EXPECT_FLOAT_EQ(p.areas[3], 1.0f / 6.0f);
    EXPECT_FLOAT_EQ(jade::dev::total_area(p), 1.5f);
}

TEST(mesh_prepare, CancellingNormalsFallBackToTheLargestAdjacentTriangle)
{
    // At A the cross products (0,0,-2), (0,0,1), (0,0,1) sum to zero: the largest triangle
    // (area 1, facing -z) decides. (-z, not the +z last resort.)
    const glm::vec3 a(0, 0, 0), b(2, 0, 0), c(0, 1, 0), d(1, 0, 0), e(0, -1, 0), f(-1, 0, 0);
    const auto p = jade::prepare_mesh(make_mesh({a, b, c, d, e, f}, {0, 2, 1, 0, 4, 3, 0, 2, 5}));
    ASSERT_EQ(p.render_to_bake[0], 0u);
    expect_vec3_near(p.normals[0], {0, 0, -1}, 0.0f);
    for (const auto& n : p.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
}

TEST(mesh_prepare, TwoSidedSheetGetsTheNormalOfOneSideNotRoundingNoise)
{
    // The same triangle twice with opposite windings, the second listed from another corner:
    // the cross products cancel only up to rounding.
    const glm::vec3 a(0.1f, 0.2f, 0.3f), b(1.7f, 0.35f, -0.2f), c(0.4f, 1.9f, 0.05f);
    const auto p = jade::prepare_mesh(make_mesh({a, b, c}, {0, 1, 2, 1, 0, 2}));
    const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
    for (size_t v = 0; v < 3; ++v) EXPECT_NEAR(std::abs(glm::dot(p.normals[v], face)), 1.0f, 1e-6f) << "vertex " << v;
}

TEST(mesh_prepare, BoundsAndDiagonal)
{
    const auto p = jade::prepare_mesh(make_mesh({{-1, 2, 3}, {4, 2, 3}, {-1, 6, 3}, {-1, 2, 15}}, {0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(p.bbox_min, glm::vec3(-1, 2, 3));
    EXPECT_EQ(p.bbox_max, glm::vec3(4, 6, 15));
    EXPECT_FLOAT_EQ(p.diagonal, std::sqrt(25.0f + 16.0f + 144.0f));
}

TEST(mesh_prepare, BoundsIgnoreUnusedVertices)
{
    const auto p = jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {100, 100, 100}}, {0, 1, 2}));
    EXPECT_EQ(p.bbox_max, glm::vec3(1, 1, 0));
}

// ------------------------------------------------------------------------------- errors --

TEST(mesh_prepare, ErrorsNameTheMeshAndTheElement)
{
    EXPECT_EQ(
        error_of(
            [] {
        jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 1, 2, 0, 7, 3}, "bunny.off"));
        }),
        "bunny.off: triangle 1 (vertex index 7) out of range for 4 vertices");
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(error_of([&] {
                  jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, nan, 0}}, {0, 1, 2}, "x.ply"));
              }),
              "x.ply: vertex 2 position is NaN");
    EXPECT_EQ(error_of([&] {
                  jade::prepare_mesh(make_mesh({{0, 0, 0}, {inf, 0, 0}, {0, 1, 0}}, {0, 1, 2}, "x.ply"));
              }),
              "x.ply: vertex 1 position is infinite");
    EXPECT_EQ(error_of([] { jade::prepare_mesh(make_mesh({}, {}, "empty.obj")); }), "empty.obj: has no triangles");
    EXPECT_EQ(error_of([] {
                  jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2, 0, 0, 1}, "flat.off"));
              }),
              "flat.off: all 2 triangles are degenerate");
    EXPECT_EQ(error_of([] {
                  jade::prepare_mesh(make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2, 0}, "odd.off"));
              }),
              "odd.off: index count 4 is not a multiple of 3");
}

// --------------------------------------------------------------------------- procedural --

TEST(mesh_procedural, SphereIsClosedAndItsAreaApproaches4PiR2)
{
    const float r = 2.5f;
    const double exact = 4.0 * std::numbers::pi * r * r;
    double previous_error = 1.0;
    for (uint32_t rings : {8u, 32u, 128u}) {
        const auto mesh = jade::procedural::sphere(r, rings, 2 * rings);
        EXPECT_EQ(mesh.positions.size(), size_t(rings - 1) * 2 * rings + 2);
        const auto p = jade::prepare_mesh(mesh);
        EXPECT_EQ(p.vertex_count(), mesh.positions.size());
        EXPECT_EQ(p.dropped_triangles, 0u);
        EXPECT_TRUE(closed_and_oriented(p)) << rings << " rings";
        const double error = (exact - jade::dev::total_area(p)) / exact;  // inscribed: always a little less
        EXPECT_GT(error, 0.0);
        EXPECT_LT(error, previous_error / 10.0) << rings << " rings";  // O(1/n²) convergence
        previous_error = error;
        for (size_t v = 0; v < p.vertex_count(); ++v) {
            EXPECT_NEAR(glm::length(p.positions[v]), r, 1e-5f);
            EXPECT_GT(glm::dot(p.normals[v], glm::normalize(p.positions[v])), 0.99f);
        }
        for (size_t t = 0; t < p.triangle_count(); ++t)
            EXPECT_GT(glm::dot(triangle_normal(p, t), glm::dvec3(p.positions[p.indices[3 * t]])), 0.0)
                << "inward triangle " << t;
    }
    EXPECT_LT(previous_error, 2e-4);  // 1.25e-4 at 128 rings × 256 segments
}

TEST(mesh_procedural, BoxAreaIsExactAndItIsClosedAfterWelding)
{
    const glm::vec3 lo(-1, -2, -3), hi(2, 1, 0.5f);
    const uint32_t n = 3;
    const auto mesh = jade::dev::procedural::box(lo, hi, n);
    EXPECT_EQ(mesh.positions.size(), 6u * (n + 1) * (n + 1));
    EXPECT_EQ(mesh.triangle_count(), 12u * n * n);
    const auto p = jade::prepare_mesh(mesh);
    EXPECT_EQ(p.vertex_count(), 6u * n * n + 2);  // the lattice on the surface of a cube
    EXPECT_EQ(p.dropped_triangles, 0u);
    EXPECT_TRUE(closed_and_oriented(p));
    EXPECT_FLOAT_EQ(jade::dev::total_area(p), 2.0f * (3 * 3 + 3 * 3.5f + 3.5f * 3));
    double area_sum = 0.0;
    for (float a : p.areas) area_sum += a;
    EXPECT_NEAR(area_sum, 60.0, 1e-4);
    const glm::vec3 centre = 0.5f * (lo + hi);
    for (size_t v = 0; v < p.vertex_count(); ++v) EXPECT_GT(glm::dot(p.normals[v], p.positions[v] - centre), 0.0f);
    EXPECT_EQ(p.bbox_min, lo);
    EXPECT_EQ(p.bbox_max, hi);
}

TEST(mesh_procedural, GridAreaIsExactAndInteriorVerticesHaveSpacingSquared)
{
    const uint32_t n = 8;
    const float spacing = 0.25f;
    const auto p = jade::prepare_mesh(jade::dev::procedural::grid(n, spacing));
    EXPECT_EQ(p.vertex_count(), size_t(n + 1) * (n + 1));
    EXPECT_EQ(p.triangle_count(), 2u * n * n);
    EXPECT_FLOAT_EQ(jade::dev::total_area(p), 4.0f);
    EXPECT_EQ(p.bbox_min, glm::vec3(-1, -1, 0));
    EXPECT_EQ(p.bbox_max, glm::vec3(1, 1, 0));
    size_t interior = 0;
    for (size_t v = 0; v < p.vertex_count(); ++v) {
        EXPECT_EQ(p.normals[v], glm::vec3(0, 0, 1));
        const glm::vec3 q = p.positions[v];
        if (std::abs(q.x) < 1.0f && std::abs(q.y) < 1.0f) {
            EXPECT_FLOAT_EQ(p.areas[v], spacing * spacing) << "vertex " << v;
            ++interior;
        }
    }
    EXPECT_EQ(interior, size_t(n - 1) * (n - 1));
    for (size_t t = 0; t < p.triangle_count(); ++t) EXPECT_GT(triangle_normal(p, t).z, 0.0) << "triangle " << t;
}

TEST(mesh_procedural, GridWithInexactSpacingStillSumsToItsArea)
{
    const auto p = jade::prepare_mesh(jade::dev::procedural::grid(10, 0.1f));
    EXPECT_NEAR(jade::dev::total_area(p), 1.0f, 1e-5f);
    EXPECT_NEAR(p.areas[5 * 11 + 5], 0.01f, 1e-7f);
}

TEST(mesh_procedural, RejectsBadParameters)
{
    EXPECT_THROW(jade::procedural::sphere(1.0f, 1, 8), jade::Error);
    EXPECT_THROW(jade::procedural::sphere(1.0f, 4, 2), jade::Error);
    EXPECT_THROW(jade::procedural::sphere(-1.0f, 4, 8), jade::Error);
    EXPECT_THROW(jade::dev::procedural::box({0, 0, 0}, {1, 0, 1}, 1), jade::Error);
    EXPECT_THROW(jade::dev::procedural::box({0, 0, 0}, {1, 1, 1}, 0), jade::Error);
    EXPECT_THROW(jade::dev::procedural::grid(0, 1.0f), jade::Error);
    EXPECT_THROW(jade::dev::procedural::grid(4, 0.0f), jade::Error);
    EXPECT_THROW(jade::dev::procedural::grid(1u << 20, 1.0f), jade::Error);  // 2^40 vertices
    EXPECT_NE(error_of([] { jade::procedural::sphere(1.0f, 1, 8); }).find("procedural::sphere: rings"),
              std::string::npos);
}

}  // namespace
