// GPU bake against the float64 CPU reference and analytic limits.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/dev/bake.hpp>
#include <jade/dev/context.hpp>
#include <jade/bake.hpp>
#include <jade/dev/names.hpp>
#include <jade/io.hpp>
#include <jade/dev/reference.hpp>
#include <jade/dev/mesh.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace jade;
using jade::test::GpuTest;

namespace {

const PreparedMesh& bunny()
{
    static PreparedMesh m = prepare_mesh(load_mesh(test::asset("bunny00.off")));
    return m;
}
const PreparedMesh& dragon()
{
    static PreparedMesh m = prepare_mesh(load_mesh(test::asset("ChineseDragon-10kv.off")));
    return m;
}

std::vector<uint32_t> sample_vertices(size_t n, size_t count)
{
    std::vector<uint32_t> v;
    for (size_t k = 0; k < count; ++k) v.push_back(uint32_t((k * 2654435761ull) % n));
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

struct RelError {
    double max = 0, rms = 0;
};
RelError relative_error(const std::vector<glm::vec3>& gpu, const std::vector<glm::dvec3>& ref,
                        std::span<const uint32_t> at)
{
    RelError e;
    for (size_t k = 0; k < at.size(); ++k)
        for (int c = 0; c < 3; ++c) {
            double r = ref[k][c], g = gpu[at[k]][c];
            double rel = std::abs(g - r) / std::max(std::abs(r), 1e-12);
            e.max = std::max(e.max, rel);
            e.rms += rel * rel;
        }
    e.rms = std::sqrt(e.rms / double(3 * at.size()));
    return e;
}

// The largest angle (radians) between the GPU's scattering normals and the reference's.
double max_angle(const std::vector<glm::vec3>& gpu, const std::vector<glm::dvec3>& ref, std::span<const uint32_t> at)
{
    double worst = 0;
    for (size_t k = 0; k < at.size(); ++k) {
        const glm::dvec3 g(gpu.at(at[k]));
        worst = std::max(worst, std::atan2(glm::length(glm::cross(g, ref[k])), glm::dot(g, ref[k])));
    }
    return worst;
}

// The largest absolute difference of per-channel values against the reference's.
double max_abs_error(const std::vector<glm::vec3>& gpu, const std::vector<glm::dvec3>& ref,
                     std::span<const uint32_t> at)
{
    double worst = 0;
    for (size_t k = 0; k < at.size(); ++k)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(gpu.at(at[k])[c]) - ref[k][c]));
    return worst;
}

void expect_finite_nonnegative(const std::vector<glm::vec3>& tm)
{
    for (size_t i = 0; i < tm.size(); ++i)
        for (int c = 0; c < 3; ++c)
            ASSERT_TRUE(std::isfinite(tm[i][c]) && tm[i][c] >= 0.0f) << "t_m[" << i << "][" << c << "] = " << tm[i][c];
}

void check_ao_against_reference(Context& ctx, const PreparedMesh& mesh, uint32_t rays)
{
    AoSettings s;
    s.rays = rays;
    Baker baker(ctx);
    auto gpu = dev::bake_ao(baker, mesh, s);
    auto ref = reference_ao(mesh, s);
    ASSERT_EQ(gpu.size(), ref.size());
    size_t same = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        if (gpu[i] == ref[i]) same++;
        EXPECT_LE(std::abs(gpu[i] - ref[i]), 2.0f / float(rays) + 1e-6f) << "vertex " << i;
    }
    double fraction = double(same) / double(gpu.size());
    EXPECT_GE(fraction, 0.999) << "identical AO on " << fraction * 100 << "% of vertices";
    ::testing::Test::RecordProperty("identical_fraction", std::to_string(fraction));
}

}  // namespace

TEST_F(GpuTest, DeviceIsCreatedWithValidation)
{
    const dev::DeviceInfo& info = dev::device_info(context());
    EXPECT_FALSE(info.name.empty());
    EXPECT_GE(info.api_version, (1u << 22) | (3u << 12)) << info.api_version_string();  // Vulkan 1.3
    EXPECT_GT(info.max_storage_buffer_range, 0u);
}

TEST_F(GpuTest, AoMatchesReferenceOnBunny) { check_ao_against_reference(context(), bunny(), 32); }
TEST_F(GpuTest, AoMatchesReferenceOnDragon) { check_ao_against_reference(context(), dragon(), 64); }

// t_m on the dragon for d at 1 %, 5 % and 20 % of the diagonal: the all-pairs pass within
// 1e-4 relative; the clustered and the grid far fields within 1 % at the default quality and
// 0.1 % at the high one, of the float64 reference. The scattering normals too, in angle.
class TmAccuracy : public GpuTest, public ::testing::WithParamInterface<double> {};

TEST_P(TmAccuracy, DragonAgainstFloat64)
{
    const PreparedMesh& mesh = dragon();
    Material m = burley_material(glm::dvec3(GetParam() * mesh.diagonal), glm::vec3(0.8f));
    m.profile[1] = ChannelProfile::burley(GetParam() * mesh.diagonal * 0.5);  // make it coloured
    Baker baker(context());
    AoSettings ao_settings;
    ao_settings.rays = 32;
    auto ao = dev::bake_ao(baker, mesh, ao_settings);
    auto at = sample_vertices(mesh.vertex_count(), 400);
    auto ref = reference_tm(mesh, ao, m, at);
    const ReferenceScattering ref_scattering = reference_scattering(mesh, ao, m, at);
    const auto& ref_normal = ref_scattering.normal;

    BakeSettings exact;
    exact.method = TmMethod::Exact;
    const BakeResult x = dev::bake_tm(baker, mesh, ao, m, exact);
    auto e = relative_error(x.tm, ref, at);
    EXPECT_LE(e.max, 1e-4) << "exact pass, rms " << e.rms;
    EXPECT_LE(max_angle(x.scattering_normal, ref_normal, at), 2e-3) << "exact pass: the scattering normal";
    EXPECT_LE(max_abs_error(x.normal_spread, ref_scattering.spread, at), 2e-3) << "exact pass: the normal spread";

    EXPECT_EQ(dev::bake_tm(baker, mesh, ao, m, BakeSettings::preset(Quality::Default)).method_used, TmMethod::Grid)
        << "auto: the grid far field";
    for (TmMethod method : {TmMethod::Clustered, TmMethod::Grid})
        for (Quality q : {Quality::Default, Quality::High}) {
            BakeSettings settings = BakeSettings::preset(q);
            settings.method = method;
            const BakeResult r = dev::bake_tm(baker, mesh, ao, m, settings);
            EXPECT_EQ(r.method_used, method);
            expect_finite_nonnegative(r.tm);
            e = relative_error(r.tm, ref, at);
            EXPECT_LE(e.max, q == Quality::High ? 1e-3 : 1e-2)
                << dev::tm_method_name(method) << ", " << (q == Quality::High ? "high" : "default") << " quality, rms "
                << e.rms;
            // The grid carries the normal's sums exactly as t_m's; the clustered far field takes
            // each accepted node's normal sum as a monopole, whose error the sum's cancellation
            // over a wide profile magnifies (measured 0.12 rad at d = 20 %, default quality).
            // The grid's default fit (one Gaussian an octave) measured 1.9e-3 rad and 2.3e-3 in
            // spread, the high one (two an octave) 3.9e-4 and 1.4e-4.
            const double angle = max_angle(r.scattering_normal, ref_normal, at);
            const double bound =
                method == TmMethod::Grid ? (q == Quality::High ? 1e-3 : 5e-3) : (q == Quality::High ? 1.5e-2 : 0.15);
            EXPECT_LE(angle, bound) << dev::tm_method_name(method) << ", " << dev::quality_name(q)
                                    << ": the scattering normal";
            const double spread = max_abs_error(r.normal_spread, ref_scattering.spread, at);
            std::printf("%s %s: angle %.2e spread %.2e\n", dev::tm_method_name(method), dev::quality_name(q), angle,
                        spread);
            EXPECT_LE(spread, bound) << dev::tm_method_name(method) << ", " << dev::quality_name(q)
                                     << ": the normal spread";
        }
}

INSTANTIATE_TEST_SUITE_P(ProfileWidth, TmAccuracy, ::testing::Values(0.01, 0.05, 0.2));

// Every profile kind on a mesh of 10,000 vertices against float64, with every far field:
// d'Eon's skin (six Gaussians a channel), Jensen's marble as a dipole, and Burley (above). The
// Gaussian sums once ran as loops to the profile's term count; their back-edges used up the
// 65,535 that lavapipe gives a shader invocation (docs/lavapipe.md), and the all-pairs pass
// then silently left out most sources: 25 % short on this mesh.
TEST_F(GpuTest, EveryProfileKindAgreesWithFloat64OnALargeMesh)
{
    const PreparedMesh& mesh = dragon();
    const double mm_per_unit = 100.0 / mesh.diagonal;  // the dragon 100 mm across
    Material dipole = burley_material(glm::dvec3(0.05 * mesh.diagonal), glm::vec3(0.8f));
    const double sigma_s_prime[3] = {2.19, 2.62, 3.00}, sigma_a[3] = {0.0021, 0.0041, 0.0071};  // per mm
    for (int c = 0; c < 3; ++c)
        dipole.profile[c] = ChannelProfile::dipole(sigma_s_prime[c] * mm_per_unit, sigma_a[c] * mm_per_unit, 1.5);
    Baker baker(context());
    const std::vector<float> ao(mesh.vertex_count(), 0.25f);
    const auto at = sample_vertices(mesh.vertex_count(), 200);
    for (const auto& [name, m] :
         {std::pair{"skin", material_preset("skin", mm_per_unit)}, std::pair{"dipole", dipole}}) {
        const auto ref = reference_tm(mesh, ao, m, at);
        for (TmMethod method : {TmMethod::Exact, TmMethod::Clustered, TmMethod::Grid}) {
            BakeSettings settings = BakeSettings::preset(Quality::Default);
            settings.method = method;
            const BakeResult r = dev::bake_tm(baker, mesh, ao, m, settings);
            expect_finite_nonnegative(r.tm);
            const RelError e = relative_error(r.tm, ref, at);
            EXPECT_LE(e.max, method == TmMethod::Exact ? 1e-4 : 1e-2)
                << name << ", " << dev::tm_method_name(method) << ": rms " << e.rms;
        }
    }
}

// dev::BakeStudy::tm_float64_sums: the all-pairs pass with float64 sums. Both it and the
// compensated float32 sums are within 1e-4 of float64 (the pair values are float32 in both),
// and they agree with each other more closely still: the blocks of 64 pair values are float32
// in both, and the compensated sum of the blocks is as good as a float64 one (measured: the
// dragon's t_m comes out bit-identical).
TEST_F(GpuTest, Float64SumsAgreeWithCompensatedFloat32Sums)
{
    if (!dev::device_info(context()).float64) GTEST_SKIP() << "the device has no shaderFloat64";
    const PreparedMesh& mesh = dragon();
    const Material m = burley_material(glm::dvec3(0.2 * mesh.diagonal), glm::vec3(0.8f));
    Baker baker(context());
    const std::vector<float> ao(mesh.vertex_count(), 0.25f);
    BakeSettings f32;
    f32.method = TmMethod::Exact;
    BakeSettings f64 = f32;
    dev::set_study(f64, {.tm_float64_sums = true});
    const auto a = dev::bake_tm(baker, mesh, ao, m, f32).tm;
    const uint64_t pipelines = dev::created_objects(context()).compute_pipelines;
    const auto b = dev::bake_tm(baker, mesh, ao, m, f64).tm;
    EXPECT_EQ(dev::created_objects(context()).compute_pipelines, pipelines + 1)
        << "the float64 variant is a kernel of its own";
    auto at = sample_vertices(mesh.vertex_count(), 200);
    const auto ref = reference_tm(mesh, ao, m, at);
    EXPECT_LE(relative_error(a, ref, at).max, 1e-4);
    EXPECT_LE(relative_error(b, ref, at).max, 1e-4);
    double apart = 0;
    for (size_t i = 0; i < a.size(); ++i) apart = std::max(apart, double(std::abs(a[i].x - b[i].x) / b[i].x));
    EXPECT_LE(apart, 1e-6) << "compensated float32 against float64 sums";
}

TEST_F(GpuTest, ClusteredMatchesReferenceOnBunny)
{
    const PreparedMesh& mesh = bunny();
    Material m = burley_material(glm::dvec3(0.05 * mesh.diagonal), glm::vec3(0.8f));
    Baker baker(context());
    auto r = baker.bake(mesh, m, BakeSettings::preset(Quality::Default));
    expect_finite_nonnegative(r.tm);
    auto at = sample_vertices(mesh.vertex_count(), 300);
    auto e = relative_error(r.tm, reference_tm(mesh, r.ao, m, at), at);
    EXPECT_LE(e.max, 1e-2) << "rms " << e.rms;
}

// The grid far field on the bunny, Burley RGB with d at 1 %, 5 % and 20 % of the diagonal:
// default quality within 1 %, high within 0.1 % of the float64 reference.
class GridAccuracy : public GpuTest, public ::testing::WithParamInterface<double> {};

TEST_P(GridAccuracy, BunnyAgainstFloat64)
{
    const PreparedMesh& mesh = bunny();
    const double d = GetParam() * mesh.diagonal;
    const Material m = burley_material(glm::dvec3(d, 0.5 * d, 0.25 * d), glm::vec3(0.8f));
    Baker baker(context());
    AoSettings ao_settings;
    ao_settings.rays = 16;
    const auto ao = dev::bake_ao(baker, mesh, ao_settings);
    const auto at = sample_vertices(mesh.vertex_count(), 200);
    const auto ref = reference_tm(mesh, ao, m, at);
    for (Quality q : {Quality::Default, Quality::High}) {
        BakeSettings grid = BakeSettings::preset(q);
        grid.method = TmMethod::Grid;
        const BakeResult g = dev::bake_tm(baker, mesh, ao, m, grid);
        expect_finite_nonnegative(g.tm);
        const auto e = relative_error(g.tm, ref, at);
        EXPECT_LE(e.max, q == Quality::High ? 1e-3 : 1e-2)
            << (q == Quality::High ? "high" : "default") << ", rms " << e.rms;
        RecordProperty(q == Quality::High ? "high_max_error" : "default_max_error", std::to_string(e.max));
    }
}

INSTANTIATE_TEST_SUITE_P(ProfileWidth, GridAccuracy, ::testing::Values(0.01, 0.05, 0.2));

// A long thin mesh (1000:1) with a profile much shorter than it: the grids stay small (their
// bounds, not a cube around the mesh) and the result matches the float64 reference.
// A closed tube along x, `rings` rings of `segments` vertices, capped by two fans.
TriangleMesh long_tube(float length, float radius, uint32_t rings, uint32_t segments)
{
    TriangleMesh t;
    t.name = "tube";
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const float a = 2.0f * float(M_PI) * float(s) / float(segments);
            t.positions.push_back(
                {length * (float(r) / float(rings - 1) - 0.5f), radius * std::cos(a), radius * std::sin(a)});
        }
    for (uint32_t r = 0; r + 1 < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * segments + s, b = r * segments + (s + 1) % segments, c = a + segments,
                           d = b + segments;
            t.indices.insert(t.indices.end(), {a, c, b, b, c, d});
        }
    const uint32_t end[2] = {uint32_t(t.positions.size()), uint32_t(t.positions.size()) + 1};
    t.positions.push_back({-0.5f * length, 0, 0});
    t.positions.push_back({0.5f * length, 0, 0});
    for (uint32_t s = 0; s < segments; ++s) {
        const uint32_t n = (s + 1) % segments, last = (rings - 1) * segments;
        t.indices.insert(t.indices.end(), {end[0], s, n, end[1], last + n, last + s});
    }
    return t;
}

TEST_F(GpuTest, GridOnALongThinMeshStaysSmallAndRight)
{
    const PreparedMesh mesh = prepare_mesh(long_tube(1000.0f, 0.5f, 2001, 6));
    const Material m = burley_material(glm::dvec3(2.0, 1.0, 0.5), glm::vec3(0.8f));
    const std::vector<float> ao(mesh.vertex_count(), 0.2f);
    Baker baker(context());
    BakeSettings grid = BakeSettings::preset(Quality::Default);
    grid.method = TmMethod::Grid;
    const BakeResult g = dev::bake_tm(baker, mesh, ao, m, grid);
    EXPECT_LT(g.tm_bytes, 64u << 20) << "device memory of the t_m passes";
    const auto at = sample_vertices(mesh.vertex_count(), 200);
    EXPECT_LE(relative_error(g.tm, reference_tm(mesh, ao, m, at), at).max, 1e-2);
    // A profile within the near field's reach needs no grid at all.
    const Material stiff = burley_material(glm::dvec3(1e-3), glm::vec3(0.8f));
    const BakeResult s = dev::bake_tm(baker, mesh, ao, stiff, grid);
    EXPECT_LT(s.tm_bytes, 16u << 20);
    EXPECT_LE(relative_error(s.tm, reference_tm(mesh, ao, stiff, at), at).max, 1e-4);
}

// Stiff: the self disk holds all of the profile, t_m = 1 − A_o. At d = 1e-6 × diagonal that
// holds for every vertex whose nearest neighbour is more than 200 d away (the dragon has
// sliver pairs 4e-5 × diagonal apart, where the surface itself is still resolved); at
// d = 1e-8 × diagonal for all. Huge: t_m falls as 1/d (t_m·d converges).
TEST_F(GpuTest, ExtremeProfileWidthsReachTheirLimits)
{
    const PreparedMesh& mesh = dragon();
    Baker baker(context());
    AoSettings ao_settings;
    ao_settings.rays = 16;
    auto ao = dev::bake_ao(baker, mesh, ao_settings);
    std::vector<float> nearest(mesh.vertex_count(), 1e30f);
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = mesh.indices[3 * t + e], b = mesh.indices[3 * t + (e + 1) % 3];
            float len = glm::distance(mesh.positions[a], mesh.positions[b]);
            nearest[a] = std::min(nearest[a], len), nearest[b] = std::min(nearest[b], len);
        }
    for (TmMethod method : {TmMethod::Exact, TmMethod::Clustered, TmMethod::Grid}) {
        SCOPED_TRACE(dev::tm_method_name(method));
        BakeSettings s;
        s.method = method;
        for (double rel : {1e-6, 1e-8}) {
            double d = rel * mesh.diagonal;
            auto stiff = dev::bake_tm(baker, mesh, ao, burley_material(glm::dvec3(d), glm::vec3(1)), s).tm;
            expect_finite_nonnegative(stiff);
            size_t checked = 0;
            for (size_t i = 0; i < mesh.vertex_count(); ++i) {
                if (rel == 1e-6 && nearest[i] < 200 * d) continue;
                ++checked;
                ASSERT_NEAR(stiff[i].x, 1.0f - ao[i], 1e-5f) << "vertex " << i << ", d = " << rel << " x diagonal";
            }
            EXPECT_GE(checked, mesh.vertex_count() * 99 / 100);
        }
        double d = 1e6 * mesh.diagonal;
        auto huge = dev::bake_tm(baker, mesh, ao, burley_material(glm::dvec3(d), glm::vec3(1)), s).tm;
        auto huger = dev::bake_tm(baker, mesh, ao, burley_material(glm::dvec3(10 * d), glm::vec3(1)), s).tm;
        expect_finite_nonnegative(huge);
        for (size_t i = 0; i < mesh.vertex_count(); i += 97) {
            ASSERT_GT(huge[i].x, 0.0f);
            EXPECT_NEAR(double(huge[i].x) * d / (double(huger[i].x) * 10 * d), 1.0, 1e-3) << "vertex " << i;
        }
    }
}

// An open flat grid of spacing d: t_m at the centre is the plane's 1 within 1 %.
TEST_F(GpuTest, FlatGridIntegratesToOne)
{
    const float spacing = 1.0f;
    PreparedMesh grid = prepare_mesh(dev::procedural::grid(160, spacing));
    std::vector<float> open(grid.vertex_count(), 0.0f);
    Baker baker(context());
    auto tm = dev::bake_tm(baker, grid, open, burley_material(glm::dvec3(spacing), glm::vec3(1))).tm;
    size_t centre = 0;
    for (size_t i = 0; i < grid.vertex_count(); ++i)
        if (glm::length(grid.positions[i]) < glm::length(grid.positions[centre])) centre = i;
    EXPECT_NEAR(tm[centre].x, 1.0, 0.01);
}

// An unwelded seam: the grid's middle column of vertices doubled, the copies 1e-5 spacings
// apart (prepare_mesh welds only exact duplicates), as at the seams of glTF assets. Each copy is
// within a hair of the other: the vertex-disk rule must count it as area nearby, not as a point
// at r → 0 (it once gave t_m ≈ 1e5 there). t_m stays near 1 of the open plane, and the GPU
// matches the float64 reference on the seam.
TEST_F(GpuTest, NearlyCoincidentSeamVerticesStayFinite)
{
    TriangleMesh mesh = dev::procedural::grid(40, 1.0f);
    const size_t n = mesh.positions.size();
    std::vector<uint32_t> copy(n, ~0u);
    float mid_x = 0;
    for (const glm::vec3& p : mesh.positions) mid_x += p.x / float(n);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        glm::vec3 c(0.0f);
        for (int k = 0; k < 3; ++k) c += mesh.positions[mesh.indices[3 * t + k]] / 3.0f;
        if (c.x < mid_x) continue;  // triangles right of the seam take the copies
        for (int k = 0; k < 3; ++k) {
            uint32_t& v = mesh.indices[3 * t + k];
            if (std::abs(mesh.positions[v].x - mid_x) > 1e-3f) continue;
            if (copy[v] == ~0u) {
                copy[v] = uint32_t(mesh.positions.size());
                mesh.positions.push_back(mesh.positions[v] + glm::vec3(1e-5f, 0.0f, 0.0f));
            }
            v = copy[v];
        }
    }
    ASSERT_GT(mesh.positions.size(), n) << "the grid has a column of vertices at its centre";
    mesh.normals.clear();  // prepare_mesh computes them
    const PreparedMesh grid = prepare_mesh(mesh);
    ASSERT_EQ(grid.vertex_count(), mesh.positions.size()) << "the copies are not welded";
    const std::vector<float> open(grid.vertex_count(), 0.0f);
    const Material m = burley_material(glm::dvec3(2.0), glm::vec3(1));
    Baker baker(context());
    BakeSettings exact;
    exact.method = TmMethod::Exact;
    const auto tm = dev::bake_tm(baker, grid, open, m, exact).tm;
    std::vector<uint32_t> seam;
    for (uint32_t i = 0; i < grid.vertex_count(); ++i)
        if (std::abs(grid.positions[i].x - mid_x) < 1e-3f && std::abs(grid.positions[i].y) < 10.0f) seam.push_back(i);
    const auto ref = reference_tm(grid, open, m, seam);
    for (size_t k = 0; k < seam.size(); ++k) {
        EXPECT_LT(tm[seam[k]].x, 1.3f) << "seam vertex " << seam[k];
        EXPECT_NEAR(tm[seam[k]].x, ref[k].x, 1e-4 * ref[k].x) << "seam vertex " << seam[k];
    }
}

// Thin things let more light through: a slab's top centre has a larger t_m than a block's.
TEST_F(GpuTest, ThinSlabIsMoreTranslucentThanThickBlock)
{
    Baker baker(context());
    Material m = burley_material(glm::dvec3(0.3), glm::vec3(1));
    auto top_centre_tm = [&](float thickness) {
        PreparedMesh box = prepare_mesh(dev::procedural::box({-2, -2, -thickness}, {2, 2, 0}, 24));
        auto r = baker.bake(box, m, BakeSettings::preset(Quality::Default));
        size_t best = 0;
        for (size_t i = 0; i < box.vertex_count(); ++i)
            if (glm::length(box.positions[i]) < glm::length(box.positions[best])) best = i;
        return r.tm[best].x;
    };
    float slab = top_centre_tm(0.1f), block = top_centre_tm(4.0f);
    EXPECT_GT(slab, block * 1.2f) << "slab " << slab << " block " << block;
}

// `jade bench bake` measures the AO pass against Embree on the same rays: the yardstick is only
// fair if Embree traces exactly those rays, so nearly every vertex's AO must agree (both trace
// in float32; a ray grazing an edge may differ).
TEST(BenchCli, BakeComparesTheGpuAoWithEmbreeOnTheSameRays)
{
    const auto r = test::run_cli({"bench", "bake", test::asset("ChineseDragon-10kv.off").string(), "--ao-rays", "8",
                                  "--repeat", "1", "--sample", "4"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    if (r.output.find("not built in (install libembree-dev") != std::string::npos)
        GTEST_SKIP() << "this build has no Embree (libembree-dev)";
    const size_t at = r.output.find("GPU / Embree time");
    ASSERT_NE(at, std::string::npos) << r.output;
    const size_t semicolon = r.output.find("; ", at);
    ASSERT_NE(semicolon, std::string::npos) << r.output;
    const double identical = std::stod(r.output.substr(semicolon + 2));
    EXPECT_GE(identical, 99.5) << r.output;
    EXPECT_LE(identical, 100.0);
}
