// A mesh of more than a million vertices: the Stanford bunny subdivided
// three times, 2.4 M vertices and 4.8 M triangles. It crosses lavapipe's limits, so every
// pass must chunk: 2.4 M × 4 rays is 150,000 work groups of 64 (maxComputeWorkGroupCount is
// 65,535 per dimension), and the near-field lists (~17 entries a vertex, 167 MB) outgrow one
// 128 MiB storage-buffer binding (they are read as texels: one view of up to 512 MiB here; the
// windows that longer lists take are tested in test_buffer_limits). Expected: no validation
// message, no NaN, Inf or negative value, AO identical to the float64 reference on the same
// rays, and t_m within the draft quality's bound of the float64 reference on sampled vertices.
// About three minutes on 2 cores.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include <jade/dev/bake.hpp>
#include <jade/dev/context.hpp>
#include <jade/bake.hpp>
#include <jade/error.hpp>
#include <jade/io.hpp>
#include <jade/dev/reference.hpp>
#include <jade/dev/mesh.hpp>

#include <algorithm>
#include <cmath>

using namespace jade;
using jade::test::GpuTest;

TEST_F(GpuTest, MillionVertexMeshBakesInChunksAndMatchesTheFloat64Reference)
{
    const PreparedMesh mesh = prepare_mesh(dev::procedural::subdivide(load_mesh(test::asset("bunny00.off")), 3));
    ASSERT_GT(mesh.vertex_count(), 1'000'000u);
    const dev::DeviceInfo& device = dev::device_info(context());
    BakeSettings settings = BakeSettings::preset(Quality::Draft);
    settings.ao.rays = 4;
    // The AO dispatch alone needs more work groups than one dimension allows.
    ASSERT_GT(mesh.vertex_count() * settings.ao.rays / 64, device.max_workgroup_count[0]);

    const double d = 0.002 * mesh.diagonal;  // a few edge lengths of the subdivided mesh
    const Material material = burley_material(glm::dvec3(d, 2 * d, 4 * d), glm::vec3(0.8f));
    Baker baker(context());
    const BakeResult r = baker.bake(mesh, material, settings);
    ASSERT_EQ(r.ao.size(), mesh.vertex_count());
    ASSERT_EQ(r.method_used, TmMethod::Clustered);
    for (size_t i = 0; i < r.tm.size(); ++i) {
        ASSERT_TRUE(r.ao[i] >= 0.0f && r.ao[i] <= 1.0f) << "AO of vertex " << i << " = " << r.ao[i];
        for (int c = 0; c < 3; ++c)
            ASSERT_TRUE(std::isfinite(r.tm[i][c]) && r.tm[i][c] >= 0.0f)
                << "t_m of vertex " << i << " = " << r.tm[i][c];
    }

    // Sampled vertices spread over the whole index range (every chunk of every pass).
    std::vector<uint32_t> at;
    for (uint32_t k = 0; k < 64; ++k) at.push_back(uint32_t((uint64_t(k) * 2654435761ull) % mesh.vertex_count()));
    std::sort(at.begin(), at.end());
    at.erase(std::unique(at.begin(), at.end()), at.end());

    const std::vector<float> ao_ref = reference_ao(mesh, settings.ao, at);
    size_t same = 0;
    for (size_t k = 0; k < at.size(); ++k) {
        EXPECT_LE(std::abs(r.ao[at[k]] - ao_ref[k]), 1.0f / float(settings.ao.rays) + 1e-6f) << "vertex " << at[k];
        same += r.ao[at[k]] == ao_ref[k];
    }
    EXPECT_GE(same, at.size() - 1) << "AO should equal the float64 reference on the same rays";

    const auto tm_ref = reference_tm(mesh, r.ao, material, at);
    double worst = 0;
    for (size_t k = 0; k < at.size(); ++k)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(r.tm[at[k]][c] - tm_ref[k][c]) / tm_ref[k][c]);
    // Draft (theta 1.6) is documented at <= 1e-2 of float64 (docs/accuracy.md).
    EXPECT_LE(worst, 1e-2) << "t_m against float64";
    RecordProperty("max_rel_tm_error", std::to_string(worst));

    // The grid far field would need more cells than its limit even with a wider near field:
    // auto took the clustered one (above), and asking for the grid is a clear error.
    BakeSettings grid = settings;
    grid.method = TmMethod::Grid;
    try {
        dev::bake_tm(baker, mesh, r.ao, material, grid);
        ADD_FAILURE() << "the grid far field accepted a plan beyond its memory limit";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("use the clustered far field"), std::string::npos) << e.what();
    }
}
