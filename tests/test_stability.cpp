// Stability on stiff and extreme cases, through the public API only: the
// bake and the shading must stay finite, non-negative and right where the inputs are extreme —
// tiny and huge meshes, scattering distances from 1e-6 to 1e+6 × the diagonal, t_m of 0, 1e-30
// and 1e30, and meshes that are degenerate, non-manifold, open or a single triangle. Every
// test states what it expects; the meshes are small and procedural so the suite stays fast.
// (The > 1 M-vertex case, which needs chunked passes, is tests/test_large_mesh.cpp.)
#include "gpu_fixture.hpp"

#include <jade/dev/bake.hpp>
#include <jade/bake.hpp>
#include <jade/dev/names.hpp>
#include <jade/error.hpp>
#include <jade/dev/lut.hpp>
#include <jade/dev/reference.hpp>
#include <jade/render.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace jade;
using jade::test::GpuTest;

namespace {

// ----------------------------------------------------------------------------- meshes --

TriangleMesh merged(TriangleMesh a, const TriangleMesh& b)
{
    const auto base = uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (uint32_t i : b.indices) a.indices.push_back(base + i);
    a.normals.clear();
    return a;
}

TriangleMesh scaled(TriangleMesh m, float factor)
{
    for (auto& p : m.positions) p *= factor;
    return m;
}

/// A closed box under a lid 0.15 above it: the box's top and the lid's underside occlude each
/// other (AO well inside (0, 1)), the rest is open. 3 × 3 × 2.3 units, ~440 bake vertices.
TriangleMesh box_under_lid()
{
    TriangleMesh m = merged(dev::procedural::box({-1, -1, -1}, {1, 1, 1}, 6),
                            dev::procedural::box({-1.5f, -1.5f, 1.15f}, {1.5f, 1.5f, 1.3f}, 6));
    m.name = "box under lid";
    return m;
}

/// Three fins of 4 × 4 quads around the z axis sharing their inner edge, 120° apart, wound so
/// that the three face normals cancel on the shared edge: a non-manifold edge (three triangles
/// on each of its segments) whose vertex normals are ill-defined.
TriangleMesh three_fins()
{
    TriangleMesh m;
    m.name = "three fins";
    const uint32_t n = 4;
    for (int k = 0; k < 3; ++k) {
        const double angle = 2.0 * std::numbers::pi * k / 3.0;
        const glm::vec3 dir(float(std::cos(angle)), float(std::sin(angle)), 0.0f);
        const auto base = uint32_t(m.positions.size());
        for (uint32_t j = 0; j <= n; ++j)
            for (uint32_t i = 0; i <= n; ++i)
                m.positions.push_back(dir * (float(i) / n) + glm::vec3(0, 0, float(j) / n));
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
                m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
            }
    }
    return m;
}

/// What may go wrong in real files, each case on its own small mesh.
struct OddMesh {
    std::string what;
    TriangleMesh mesh;
};

std::vector<OddMesh> odd_meshes()
{
    std::vector<OddMesh> out;
    const TriangleMesh box = dev::procedural::box({-1, -1, -1}, {1, 1, 1}, 4);

    {  // zero-area triangles: a repeated index, three collinear points, two coincident corners
        TriangleMesh m = box;
        const auto base = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), {{2, 0, 0}, {3, 0, 0}, {4, 0, 0}, {2, 1, 0}, {2, 1, 0}});
        m.indices.insert(m.indices.end(), {0, 0, 1, base, base + 1, base + 2, base, base + 3, base + 4});
        m.normals.clear();
        m.name = "degenerate triangles";
        out.push_back({m.name, m});
    }
    {  // slivers: one column of a grid moved to 1e-5 spacing from its neighbour (aspect 1e5)
        TriangleMesh m = dev::procedural::grid(8, 0.25f);
        float left = 1e30f;
        for (auto& p : m.positions) left = std::min(left, p.x);
        for (auto& p : m.positions)
            if (std::abs(p.x - (left + 0.5f)) < 1e-3f) p.x = left + 0.25f + 1e-5f;
        m = merged(m, dev::procedural::box({-0.5f, -0.5f, -0.6f}, {0.5f, 0.5f, -0.1f}, 3));  // something to occlude
        m.name = "sliver triangles";
        out.push_back({m.name, m});
    }
    {  // every vertex twice, triangles alternating between the copies: welded back into one surface
        TriangleMesh m = box;
        const auto n = uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), box.positions.begin(), box.positions.end());
        for (size_t i = 0; i < m.indices.size(); ++i)
            if ((i / 3) % 2) m.indices[i] += n;
        m.normals.clear();
        m.name = "duplicate vertices";
        out.push_back({m.name, m});
    }
    {  // vertices no triangle uses, one far outside the box: they must not change the result
        TriangleMesh m = box;
        m.positions.insert(m.positions.end(), {{100, 100, 100}, {0, 0, 0}, {-1e6f, 3, 3}});
        m.normals.clear();
        m.name = "isolated vertices";
        out.push_back({m.name, m});
    }
    out.push_back({"non-manifold edge", three_fins()});
    {  // the box without its top face: open, its inside partly visible
        TriangleMesh m = box;
        std::vector<uint32_t> kept;
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            bool top = true;
            for (int k = 0; k < 3; ++k) top = top && m.positions[m.indices[t + k]].z > 0.999f;
            if (!top) kept.insert(kept.end(), m.indices.begin() + long(t), m.indices.begin() + long(t) + 3);
        }
        m.indices = kept;
        m.name = "open box";
        out.push_back({m.name, m});
    }
    {
        TriangleMesh m;
        m.name = "single triangle";
        m.positions = {{0, 0, 0}, {1, 0, 0}, {0.2f, 0.9f, 0}};
        m.indices = {0, 1, 2};
        out.push_back({m.name, m});
    }
    return out;
}

// ------------------------------------------------------------------------------ checks --

::testing::AssertionResult finite_nonnegative(const std::vector<float>& ao, const std::vector<glm::vec3>& tm)
{
    for (size_t i = 0; i < ao.size(); ++i)
        if (!(ao[i] >= 0.0f && ao[i] <= 1.0f)) return ::testing::AssertionFailure() << "A_o[" << i << "] = " << ao[i];
    for (size_t i = 0; i < tm.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(tm[i][c]) || tm[i][c] < 0.0f)
                return ::testing::AssertionFailure() << "t_m[" << i << "][" << c << "] = " << tm[i][c];
    return ::testing::AssertionSuccess();
}

/// Largest |a − b| / max(|b|, floor) over all vertices and channels.
double max_relative(const std::vector<glm::vec3>& a, const std::vector<glm::dvec3>& b, double floor = 1e-30)
{
    double worst = 0;
    for (size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(double(a[i][c]) - b[i][c]) / std::max(std::abs(b[i][c]), floor));
    return worst;
}

std::vector<glm::dvec3> widened(const std::vector<glm::vec3>& v) { return {v.begin(), v.end()}; }

BakeSettings exact_settings(uint32_t rays)
{
    BakeSettings s;
    s.ao.rays = rays;
    s.method = TmMethod::Exact;
    return s;
}

// ----------------------------------------------------------------------------- scale --

// Expected: everything in the bake is relative — AO's ray length and offset are fractions of
// the diagonal, t_m is unitless with R normalised over the plane — so a mesh scaled by s with
// d scaled by s gives the same A_o and t_m for s = 1e-4 … 1e+4. Float32 positions are rounded
// differently at each scale (s is not a power of two), which moves a ray that grazes an edge
// from hit to miss: A_o may differ by a ray or two on a few vertices (allowed: ±2 rays on at
// most 2 % of them; measured on lavapipe: none differs). t_m, baked from the same A_o, differs
// only by float32 rounding: measured max relative difference 1.9e-6 (s = 1e-4 … 1e4, exact and
// clustered, the cluster tree built at each scale); the tolerance 2e-5 leaves room for other
// devices' rounding while still catching any absolute length (an ε, a cut-off) in the passes.
TEST_F(GpuTest, ScaledMeshWithScaledDistanceGivesTheSameResult)
{
    const TriangleMesh base = box_under_lid();
    const PreparedMesh unit = prepare_mesh(base);
    const double d = 0.2;
    const uint32_t rays = 64;
    Baker baker(context());
    const auto reference = baker.bake(unit, burley_material(glm::dvec3(d), glm::vec3(0.8f)), exact_settings(rays));
    ASSERT_TRUE(finite_nonnegative(reference.ao, reference.tm));
    const auto clustered_reference =
        dev::bake_tm(baker, unit, reference.ao, burley_material(glm::dvec3(d), glm::vec3(0.8f)),
                     BakeSettings::preset(Quality::Default))
            .tm;
    double worst_ao_fraction = 0, worst_tm = 0;
    for (double s : {1e-4, 1e-3, 1e-2, 1e-1, 1e1, 1e2, 1e3, 1e4}) {
        const PreparedMesh mesh = prepare_mesh(scaled(base, float(s)));
        ASSERT_EQ(mesh.vertex_count(), unit.vertex_count()) << "scale " << s;
        const Material m = burley_material(glm::dvec3(d * s), glm::vec3(0.8f));
        const auto r = baker.bake(mesh, m, exact_settings(rays));
        ASSERT_TRUE(finite_nonnegative(r.ao, r.tm)) << "scale " << s;
        size_t differing = 0;
        for (size_t i = 0; i < r.ao.size(); ++i) {
            EXPECT_LE(std::abs(r.ao[i] - reference.ao[i]), 2.0f / rays + 1e-6f) << "vertex " << i << ", scale " << s;
            differing += r.ao[i] != reference.ao[i];
        }
        const double fraction = double(differing) / double(r.ao.size());
        EXPECT_LE(fraction, 0.02) << "A_o differs on " << differing << " vertices at scale " << s;
        worst_ao_fraction = std::max(worst_ao_fraction, fraction);

        // t_m from the unscaled A_o: only the t_m pass's scale invariance is measured.
        const auto exact = dev::bake_tm(baker, mesh, reference.ao, m, exact_settings(rays)).tm;
        const auto clustered = dev::bake_tm(baker, mesh, reference.ao, m, BakeSettings::preset(Quality::Default)).tm;
        ASSERT_TRUE(finite_nonnegative(reference.ao, exact));
        ASSERT_TRUE(finite_nonnegative(reference.ao, clustered));
        const double e = max_relative(exact, widened(reference.tm)),
                     c = max_relative(clustered, widened(clustered_reference));
        EXPECT_LE(e, 2e-5) << "exact t_m at scale " << s;
        EXPECT_LE(c, 2e-5) << "clustered t_m at scale " << s;
        worst_tm = std::max({worst_tm, e, c});
    }
    std::printf("scale 1e-4..1e4: A_o differs on at most %.2f %% of vertices; t_m max relative difference %.2e\n",
                100 * worst_ao_fraction, worst_tm);
    RecordProperty("tm_max_relative_difference", std::to_string(worst_tm));
}

// ------------------------------------------------------------------ scattering distance --

// Expected for d = 1e-6 … 1e+6 × the diagonal, exact and clustered: t_m finite and ≥ 0, and
// equal to the float64 reference (relative 1e-4 exact, 1e-2 clustered as in test_gpu_bake;
// below 1e-30 absolute both are zero). Limits: for tiny d each vertex's own disk holds the whole
// profile, t_m → 1 − A_o (to 1e-5); for huge d the profile is flat over the mesh, R ≈ 1/(8π d r),
// so t_m falls as 1/d: t_m·d at 1e5 and 1e6 × the diagonal agree to 1e-3.
TEST_F(GpuTest, ScatteringDistanceFromTinyToHugeStaysFiniteAndReachesItsLimits)
{
    const PreparedMesh mesh = prepare_mesh(box_under_lid());
    Baker baker(context());
    AoSettings ao_settings;
    ao_settings.rays = 32;
    const auto ao = dev::bake_ao(baker, mesh, ao_settings);
    const TmMethod methods[3] = {TmMethod::Exact, TmMethod::Clustered, TmMethod::Grid};
    std::vector<glm::vec3> at_1e5[3];
    double worst[3] = {0, 0, 0};
    for (int k = -6; k <= 6; ++k) {
        const double d = std::pow(10.0, k) * mesh.diagonal;
        const Material m = burley_material(glm::dvec3(d), glm::vec3(0.8f));
        const auto reference = reference_tm(mesh, ao, m);
        for (int method = 0; method < 3; ++method) {
            SCOPED_TRACE(std::string(dev::tm_method_name(methods[method])) + ", d = 1e" + std::to_string(k) +
                         " x diagonal");
            BakeSettings s = BakeSettings::preset(Quality::Default);
            s.method = methods[method];
            const auto tm = dev::bake_tm(baker, mesh, ao, m, s).tm;
            ASSERT_TRUE(finite_nonnegative(ao, tm));
            const double e = max_relative(tm, reference, 1e-30);
            EXPECT_LE(e, method == 0 ? 1e-4 : 1e-2);
            worst[method] = std::max(worst[method], e);
            if (k == -6)
                for (size_t i = 0; i < tm.size(); ++i) ASSERT_NEAR(tm[i].x, 1.0f - ao[i], 1e-5f) << "vertex " << i;
            if (k == 5) at_1e5[method] = tm;
            if (k == 6)
                for (size_t i = 0; i < tm.size(); ++i) {
                    ASSERT_GT(tm[i].x, 0.0f) << "vertex " << i;
                    EXPECT_NEAR(double(tm[i].x) * 10.0 / double(at_1e5[method][i].x), 1.0, 1e-3) << "vertex " << i;
                }
        }
    }
    std::printf(
        "max relative error against float64 over d = 1e-6..1e6 x diagonal: exact %.2e, clustered %.2e, grid %.2e\n",
        worst[0], worst[1], worst[2]);
}

// ----------------------------------------------------------------------- t_m extremes --

// Expected from the LUT's float64 reference f(θ, t): t = 0 is exactly Lambert max(cos θ, 0);
// t = 1e-30 is Lambert to 1e-12 (the Gaussian is far narrower than anything); t = 1e30 and
// t = FLT_MAX are the flat limit 1/π to 1e-12. Decision for t = +∞: accepted as that limit
// (f = 1/π), since it is the mathematical limit and a caller's overflow should not throw; NaN
// and negative t are errors. (Baked t_m itself is never infinite: the renderer refuses it.)
TEST(Stability, LutReferenceAtZeroTinyHugeAndInfiniteVariance)
{
    const double inv_pi = 1.0 / std::numbers::pi;
    for (int i = 0; i <= 40; ++i) {
        const double c = -1.0 + i / 20.0;
        EXPECT_NEAR(lut_reference(c, 0.0), std::max(c, 0.0), 1e-15) << "cos " << c;
        EXPECT_NEAR(lut_reference(c, 1e-30), std::max(c, 0.0), 1e-12) << "cos " << c;
        for (double t : {1e30, double(std::numeric_limits<float>::max()), std::numeric_limits<double>::max(),
                         std::numeric_limits<double>::infinity()}) {
            const double f = lut_reference(c, t);
            EXPECT_TRUE(std::isfinite(f)) << "cos " << c << ", t " << t;
            EXPECT_NEAR(f, inv_pi, 1e-12) << "cos " << c << ", t " << t;
        }
    }
    EXPECT_THROW(lut_reference(0.5, -1e-30), Error);
    EXPECT_THROW(lut_reference(0.5, std::nan("")), Error);
    EXPECT_THROW(lut_reference(0.5, -std::numeric_limits<double>::infinity()), Error);
}

class StabilityRender : public GpuTest {};

// Expected in a render of a unit sphere lit from the side (one directional light, E = 1,
// albedo 0.8, no specular), t_m the same on every vertex: no pixel is NaN or infinite for any
// t_m and strength; t_m = 0 and 1e-30 give the Lambert image; t_m = 1e30 and FLT_MAX
// (and strength 1e30, where strength·t_m overflows float) give the flat limit: every sphere
// pixel k_d/π · 1/π · E, lit side and dark side alike (to 1e-4 relative: the LUT's last row is
// 2e-6 from 1/π); strength 0 is Lambert whatever t_m; false colour (and the curvature mode,
// which ignores t_m) stay finite over t_m from 0 to FLT_MAX, also mixed on neighbouring vertices. t_m = ∞, NaN or < 0 is refused by
// set_mesh with an error naming t_m and the vertex (decision: never clamped silently).
TEST_F(StabilityRender, ZeroTinyAndHugeTmRenderFiniteWithTheirLimits)
{
    const PreparedMesh sphere = prepare_mesh(procedural::sphere(1.0f, 16, 32));
    Renderer renderer(context());
    Material matte = burley_material(glm::dvec3(0.1), glm::vec3(0.8f));
    matte.specular = 0.0f;
    const Camera camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30.0f};
    const std::vector<Light> lights = {Light::directional({1, 0, 0}, glm::vec3(1.0f))};  // the left half is dark
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.samples = 1;
    settings.float32 = true;
    settings.transparent_background = true;

    auto render_with = [&](const std::vector<glm::vec3>& per_vertex, float strength, ShadingMode mode) {
        const float tm = per_vertex[0].x;
        renderer.set_mesh(sphere, per_vertex);
        Material m = matte;
        m.strength = strength;
        renderer.set_material(m);
        settings.mode = mode;
        RenderedImage img = renderer.render(camera, lights, settings);
        for (size_t k = 0; k < img.rgba.size(); ++k)
            EXPECT_TRUE(std::isfinite(img.rgba[k])) << "t_m " << tm << ", strength " << strength << ", float " << k;
        return img;
    };
    auto render = [&](float tm, float strength, ShadingMode mode) {
        return render_with(std::vector<glm::vec3>(sphere.vertex_count(), glm::vec3(tm)), strength, mode);
    };
    const RenderedImage lambert = render(0.0f, 1.0f, ShadingMode::Lambert);
    size_t sphere_pixels = 0, dark_pixels = 0;
    for (size_t p = 0; p < lambert.rgba.size(); p += 4) {
        sphere_pixels += lambert.rgba[p + 3] == 1.0f;
        dark_pixels += lambert.rgba[p + 3] == 1.0f && lambert.rgba[p] == 0.0f;
    }
    ASSERT_GT(sphere_pixels, 500u);
    ASSERT_GT(dark_pixels, sphere_pixels / 3) << "the unlit half must be in the test";

    // Lambert to 1e-3 relative + 1e-5 absolute per pixel (the LUT's row 0 is max(cos θ, 0)
    // interpolated linearly in cos θ), as in test_render's TmWithZeroStrengthIsLambert.
    auto differs_from_lambert = [&](const RenderedImage& img) {
        double worst = 0;
        for (size_t k = 0; k < img.rgba.size(); ++k) {
            const double a = lambert.rgba[k], b = img.rgba[k];
            worst = std::max(worst, std::abs(a - b) / (1e-3 * std::max(std::abs(a), std::abs(b)) + 1e-5));
        }
        return worst;
    };
    using Case = std::pair<float, float>;  // t_m, strength
    const float flt_max = std::numeric_limits<float>::max();
    for (auto [tm, strength] : std::vector<Case>{{0.0f, 1.0f}, {1e-30f, 1.0f}, {1e-30f, 1e-30f}, {flt_max, 0.0f}})
        EXPECT_LE(differs_from_lambert(render(tm, strength, ShadingMode::Tm)), 1.0)
            << "t_m " << tm << ", strength " << strength;

    const double flat = 0.8 / std::numbers::pi / std::numbers::pi;
    for (auto [tm, strength] : std::vector<Case>{{1e30f, 1.0f}, {flt_max, 1.0f}, {flt_max, 1e30f}, {1.0f, flt_max}}) {
        const RenderedImage img = render(tm, strength, ShadingMode::Tm);
        for (size_t p = 0; p < img.rgba.size(); p += 4) {
            if (img.rgba[p + 3] != 1.0f) continue;
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(img.rgba[p + c], flat, 1e-4 * flat)
                    << "pixel " << p / 4 << ", t_m " << tm << ", strength " << strength;
        }
    }
    // Mixed extremes (0 and FLT_MAX on neighbouring vertices: interpolation may round to +Inf)
    // and false colour over the whole range: finite everywhere (checked inside render_with).
    std::vector<glm::vec3> mixed(sphere.vertex_count());
    for (size_t i = 0; i < mixed.size(); ++i)
        mixed[i] = glm::vec3(i % 2 ? flt_max : 0.0f, i % 3 ? 1e-30f : flt_max, 1.0f);
    for (ShadingMode mode : {ShadingMode::Tm, ShadingMode::TmFalseColor, ShadingMode::Curvature}) {
        render_with(mixed, 0.0f, mode);
        render_with(mixed, 1e30f, mode);
        for (float tm : {0.0f, 1e-30f, 1e30f, flt_max}) render(tm, 1.0f, mode);
    }

    for (float bad : {std::numeric_limits<float>::infinity(), std::nanf(""), -1e-30f}) {
        std::vector<glm::vec3> tm(sphere.vertex_count(), glm::vec3(1.0f));
        tm[7].y = bad;
        try {
            renderer.set_mesh(sphere, tm);
            ADD_FAILURE() << "t_m " << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("t_m of vertex 7"), std::string::npos) << e.what();
        }
    }
}

// ------------------------------------------------------------------------- odd meshes --

// Expected for each odd mesh (zero-area and sliver triangles, duplicate and isolated vertices,
// a non-manifold edge, an open box, a single triangle): prepare_mesh keeps a valid surface
// (no zero or NaN normal, positive areas); the GPU bake gives A_o in [0, 1] and finite,
// non-negative t_m; A_o is the float64 reference's (same rays; ±2 rays on a vertex where
// float32 and float64 disagree about a grazing hit, as on the bunny) and t_m matches
// reference_tm to 1e-4 (exact) and 1e-2 (clustered, default θ). Isolated vertices change nothing:
// the bake equals the plain box's.
TEST_F(GpuTest, OddMeshesBakeFiniteAndMatchTheFloat64Reference)
{
    Baker baker(context());
    std::vector<float> plain_box_ao;
    std::vector<glm::vec3> plain_box_tm;
    for (const auto& [what, input] : odd_meshes()) {
        SCOPED_TRACE(what);
        const PreparedMesh mesh = prepare_mesh(input);
        ASSERT_GT(mesh.vertex_count(), 0u);
        for (size_t i = 0; i < mesh.vertex_count(); ++i) {
            ASSERT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-4f) << "normal of vertex " << i;
            ASSERT_GT(mesh.areas[i], 0.0f) << "area of vertex " << i;
        }
        const Material m = burley_material(glm::dvec3(0.1 * mesh.diagonal), glm::vec3(0.8f));
        const BakeSettings exact = exact_settings(32);
        const auto r = baker.bake(mesh, m, exact);
        ASSERT_TRUE(finite_nonnegative(r.ao, r.tm));
        const auto ref_ao = reference_ao(mesh, exact.ao);
        for (size_t i = 0; i < r.ao.size(); ++i)
            EXPECT_LE(std::abs(r.ao[i] - ref_ao[i]), 2.0f / 32 + 1e-6f) << "vertex " << i;
        const auto ref_tm = reference_tm(mesh, r.ao, m);
        const double exact_error = max_relative(r.tm, ref_tm, 1e-12);
        EXPECT_LE(exact_error, 1e-4);
        BakeSettings clustered = BakeSettings::preset(Quality::Default);
        clustered.method = TmMethod::Clustered;  // Auto would choose Exact on meshes this small
        const auto def = dev::bake_tm(baker, mesh, r.ao, m, clustered).tm;
        ASSERT_TRUE(finite_nonnegative(r.ao, def));
        const double default_error = max_relative(def, ref_tm, 1e-12);
        EXPECT_LE(default_error, 1e-2);
        BakeSettings grid = clustered;
        grid.method = TmMethod::Grid;
        const auto by_grid = dev::bake_tm(baker, mesh, r.ao, m, grid).tm;
        ASSERT_TRUE(finite_nonnegative(r.ao, by_grid));
        const double grid_error = max_relative(by_grid, ref_tm, 1e-12);
        EXPECT_LE(grid_error, 1e-2);
        std::printf("%-20s %4zu vertices: t_m max relative error exact %.1e, clustered %.1e, grid %.1e\n", what.c_str(),
                    mesh.vertex_count(), exact_error, default_error, grid_error);

        if (what == "degenerate triangles") {
            EXPECT_EQ(mesh.dropped_triangles, 3u);
        } else if (what == "duplicate vertices") {
            EXPECT_EQ(mesh.vertex_count(),
                      prepare_mesh(dev::procedural::box({-1, -1, -1}, {1, 1, 1}, 4)).vertex_count());
        } else if (what == "isolated vertices") {
            const PreparedMesh plain = prepare_mesh(dev::procedural::box({-1, -1, -1}, {1, 1, 1}, 4));
            ASSERT_EQ(mesh.vertex_count(), plain.vertex_count());
            EXPECT_EQ(mesh.unused_vertices, 3u);
            EXPECT_EQ(mesh.diagonal, plain.diagonal) << "unused vertices widened the bounds";
            const auto p = baker.bake(plain, m, exact);
            EXPECT_EQ(r.ao, p.ao);
            EXPECT_LE(max_relative(r.tm, widened(p.tm)), 1e-6);
        } else if (what == "single triangle") {
            for (float a : r.ao) EXPECT_EQ(a, 0.0f) << "nothing can occlude a lone triangle";
        }
    }
}

}  // namespace
