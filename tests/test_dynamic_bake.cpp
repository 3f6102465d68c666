// Per-frame GPU re-bake of a deforming mesh (DynamicBake): each frame of a twisted bunny and
// dragon against a from-scratch float64 CPU bake of the same deformed mesh, and against a
// from-scratch GPU bake (a rebuild of both trees) of it.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/bake.hpp>
#include <jade/error.hpp>
#include <jade/io.hpp>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

using namespace jade;
using jade::test::GpuTest;

namespace {

// Twists the mesh about the vertical axis through its centre: angle = turns·2π·(y − y_min)/height.
// A bijection, so no vertices weld together and the deformed mesh keeps the rest pose's vertices.
TriangleMesh twisted(TriangleMesh mesh, double turns)
{
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::vec3 c = 0.5f * (lo + hi);
    for (auto& p : mesh.positions) {
        const double a = turns * 2 * M_PI * (p.y - lo.y) / (hi.y - lo.y);
        const double x = p.x - c.x, z = p.z - c.z;
        p.x = float(c.x + std::cos(a) * x - std::sin(a) * z);
        p.z = float(c.z + std::sin(a) * x + std::cos(a) * z);
    }
    return mesh;
}

std::vector<uint32_t> every(size_t n, size_t count)
{
    std::vector<uint32_t> v;
    for (size_t k = 0; k < count; ++k) v.push_back(uint32_t(k * n / count));
    return v;
}

void check_frames(Context& ctx, const char* asset, double d_rel)
{
    const TriangleMesh source = load_mesh(test::asset(asset));
    const PreparedMesh rest = prepare_mesh(source);
    Material material = burley_material(glm::dvec3(d_rel * rest.diagonal), glm::vec3(0.8f));
    material.profile[0] = ChannelProfile::burley(d_rel * rest.diagonal * 0.5);  // coloured
    BakeSettings settings = BakeSettings::preset(Quality::Default);
    settings.ao.rays = 32;
    Baker baker(ctx);
    DynamicBake dynamic(baker, rest, material, settings);

    for (double turns : {0.05, 0.15, 0.3}) {
        SCOPED_TRACE(std::string(asset) + ", twist " + std::to_string(turns) + " turns");
        PreparedMesh frame = prepare_mesh(twisted(source, turns));
        ASSERT_EQ(frame.vertex_count(), rest.vertex_count());
        frame.diagonal = rest.diagonal;  // DynamicBake keeps the rest pose's AO distances
        BakeResult refit = dynamic.bake(frame.positions, frame.normals, frame.areas);

        // AO: the same rays as the float64 reference over the deformed mesh.
        auto ao_ref = reference_ao(frame, settings.ao);
        size_t same = 0;
        for (size_t i = 0; i < ao_ref.size(); ++i) {
            same += refit.ao[i] == ao_ref[i];
            ASSERT_LE(std::abs(refit.ao[i] - ao_ref[i]), 2.0f / float(settings.ao.rays) + 1e-6f) << "vertex " << i;
        }
        EXPECT_GE(double(same) / double(ao_ref.size()), 0.999);

        // t_m: the default quality's bound against float64, given the same AO.
        auto at = every(frame.vertex_count(), 300);
        auto tm_ref = reference_tm(frame, refit.ao, material, at);
        double worst = 0;
        for (size_t k = 0; k < at.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(refit.tm[at[k]][c]) && refit.tm[at[k]][c] >= 0);
                worst = std::max(worst, std::abs(refit.tm[at[k]][c] - tm_ref[k][c]) / tm_ref[k][c]);
            }
        EXPECT_LE(worst, 1e-2) << "refit t_m against float64";

        // A rebuild (a from-scratch GPU bake of the deformed mesh) agrees as closely.
        BakeResult rebuilt = baker.bake(frame, material, settings);
        EXPECT_EQ(rebuilt.ao, refit.ao);
        double apart = 0;
        for (size_t i = 0; i < rebuilt.tm.size(); ++i)
            for (int c = 0; c < 3; ++c)
                apart = std::max(apart, double(std::abs(rebuilt.tm[i][c] - refit.tm[i][c]) / rebuilt.tm[i][c]));
        EXPECT_LE(apart, 2e-2) << "refit and rebuild t_m";
    }
}

}  // namespace

TEST_F(GpuTest, DynamicBakeFollowsATwistedDragon) { check_frames(context(), "ChineseDragon-10kv.off", 0.05); }
TEST_F(GpuTest, DynamicBakeFollowsATwistedBunny) { check_frames(context(), "bunny00.off", 0.05); }

TEST_F(GpuTest, DynamicBakeRejectsInputsOfTheWrongSize)
{
    const PreparedMesh rest = prepare_mesh(procedural::sphere(1.0f, 16, 8));
    Baker baker(context());
    DynamicBake dynamic(baker, rest, burley_material(glm::dvec3(0.1), glm::vec3(0.8f)));
    std::vector<glm::vec3> two(2);
    std::vector<float> areas(2, 1.0f);
    EXPECT_THROW(dynamic.bake(two, two, areas), Error);
    auto positions = rest.positions;
    positions[3].y = NAN;
    EXPECT_THROW(dynamic.bake(positions, rest.normals, rest.areas), Error);
}
