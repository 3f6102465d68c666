// TmMethod::Auto's far field: the bake (prepare_tm) and the estimate of its buffers (plan_scene)
// take it from one rule (bake/far_field.hpp); here both are asked on the test meshes, and the
// meshes between them reach every outcome of the rule.
#include "gpu_fixture.hpp"
#include "test_support.hpp"

#include "bake/buffer_estimate.hpp"
#include "bake/far_field.hpp"

#include <jade/dev/bake.hpp>
#include <jade/bake.hpp>
#include <jade/dev/names.hpp>
#include <jade/dev/scene.hpp>
#include <jade/io.hpp>
#include <jade/dev/mesh.hpp>

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

using namespace jade;
using jade::test::GpuTest;

namespace {

// What the estimate's buffers say the bake will run: the grid's cells, the cluster tree, or
// neither (all pairs).
TmMethod method_of(const std::vector<dev::BufferEstimate>& buffers)
{
    auto has = [&](const std::string& name) {
        return std::any_of(buffers.begin(), buffers.end(),
                           [&](const dev::BufferEstimate& b) { return b.name == name; });
    };
    if (has("t_m grid")) return TmMethod::Grid;
    if (has("point tree nodes")) return TmMethod::Clustered;
    return TmMethod::Exact;
}

// Two dense spheres far apart: vast bounds for their vertex spacing.
TriangleMesh far_apart_spheres()
{
    TriangleMesh a = procedural::sphere(0.01f, 48, 96), b = a;
    const uint32_t offset = uint32_t(a.positions.size());
    for (glm::vec3 p : b.positions) a.positions.push_back(p + glm::vec3(100.0f, 0.0f, 0.0f));
    for (uint32_t i : b.indices) a.indices.push_back(i + offset);
    a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
    a.name = "two spheres far apart";
    return a;
}

// A coarse sphere with a tiny dense one on its surface: the near lists of the dense patch are
// far longer than the grid's plan expects of the mean vertex spacing, though the grids fit.
TriangleMesh sphere_with_a_dense_patch()
{
    TriangleMesh a = procedural::sphere(1.0f, 32, 64), b = procedural::sphere(0.02f, 48, 96);
    const uint32_t offset = uint32_t(a.positions.size());
    for (glm::vec3 p : b.positions) a.positions.push_back(p + glm::vec3(0.0f, 0.0f, 1.02f));
    for (uint32_t i : b.indices) a.indices.push_back(i + offset);
    a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
    a.name = "sphere with a dense patch";
    return a;
}

}  // namespace

TEST_F(GpuTest, AutoFarFieldIsTheSameInTheBakeAndInItsBufferPlan)
{
    struct Case {
        std::string name;
        PreparedMesh mesh;
    };
    std::vector<Case> cases;
    cases.push_back({"bunny00.off", prepare_mesh(load_mesh(test::asset("bunny00.off")))});
    cases.push_back({"ChineseDragon-10kv.off", prepare_mesh(load_mesh(test::asset("ChineseDragon-10kv.off")))});
    cases.push_back({"sphere 16×32", prepare_mesh(procedural::sphere(1.0f, 16, 32))});
    cases.push_back({"sphere 64×128", prepare_mesh(procedural::sphere(1.0f, 64, 128))});
    cases.push_back({"box 24", prepare_mesh(dev::procedural::box(glm::vec3(-1.0f), glm::vec3(1.0f), 24))});
    cases.push_back({"grid 80", prepare_mesh(dev::procedural::grid(80, 0.05f))});
    cases.push_back({"two spheres far apart", prepare_mesh(far_apart_spheres())});
    cases.push_back({"sphere with a dense patch", prepare_mesh(sphere_with_a_dense_patch())});

    Baker baker(context());
    std::set<TmMethod> seen;
    for (const Case& c : cases) {
        const Material material = burley_material(glm::dvec3(0.02 * c.mesh.diagonal), glm::vec3(0.8f));
        const BakeSettings settings = BakeSettings::preset(Quality::Default);
        ASSERT_EQ(settings.method, TmMethod::Auto);
        const std::vector<float> ao(c.mesh.vertex_count(), 0.0f);
        const TmMethod baked = dev::bake_tm(baker, c.mesh, ao, material, settings).method_used;
        const TmMethod planned = method_of(bake::estimate_buffers(c.mesh, material, settings, false, false));
        EXPECT_EQ(dev::tm_method_name(planned), std::string(dev::tm_method_name(baked))) << c.name;
        // The grids alone fit the dense patch (not coarsened): its long near lists decide, the
        // part of the rule that the estimate once left out.
        const bake::GridPlan plan = bake::plan_grid(c.mesh, material, 3, settings.tm_grid_resolution, false,
                                                    1.05f);  // a static bake's near margin, kStaticNearMargin
        if (c.name == "sphere with a dense patch") {
            EXPECT_FALSE(plan.coarsened);
            EXPECT_EQ(baked, TmMethod::Clustered);
        }
        std::printf("%-26s %6zu vertices: %s (grids coarsened: %d)\n", c.name.c_str(), c.mesh.vertex_count(),
                    dev::tm_method_name(baked), int(plan.coarsened));
        seen.insert(baked);
    }
    EXPECT_EQ(seen.size(), 3u) << "the meshes reach all pairs, the grid and the clustered far field";
}
