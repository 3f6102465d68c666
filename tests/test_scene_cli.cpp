// The scene commands of the CLI: jade plan and jade scene on a mixed scene (passes, variants,
// memory and the cache's state), bad scenes, the memory budget, and jade bench render --scene.
#include "scene_gltf.hpp"
#include "test_support.hpp"

#include <jade/dev/mesh.hpp>
#include <jade/mesh.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace jade;
using jade::test::write_gltf;

TEST(SceneCli, PlanPrintsPassesVariantsMemoryAndCacheState)
{
    const auto cache = test::out("scene_cli/cache/x").parent_path();
    std::filesystem::remove_all(cache);
    const std::string scene = test::data("scene_mixed.gltf").string();
    auto r = test::run_cli({"plan", scene, "--cache", cache.string(), "--quality", "draft"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* line :
         {"object 0 'floor/0': 98 vertices, 192 triangles, opaque, no t_m", "shader variant: mode lambert",
          "shader variant: mode tm, CHANNELS=1", "not cached (bakes once)", "pass static bake (once), freed after",
          "pass deform (every frame), kept", "pass dynamic bake (every frame), kept", "kept while drawing"})
        EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;

    // A render fills the cache (--verbose lists the passes); the next plan sees it, the next
    // render reads it.
    const std::string png = test::out("scene_cli/scene.png").string();
    r = test::run_cli(
        {"scene", scene, "--cache", cache.string(), "--quality", "draft", "--size", "48", "--out", png, "--verbose"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("grey_sphere/0            static bake"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("bending_bar/0            dynamic bake"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("tm, CHANNELS=1"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(png));
    r = test::run_cli({"plan", scene, "--cache", cache.string(), "--quality", "draft"});
    EXPECT_NE(r.output.find("in the cache (no bake will run)"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("not cached"), std::string::npos) << r.output;
    r = test::run_cli(
        {"scene", scene, "--cache", cache.string(), "--quality", "draft", "--size", "48", "--out", png, "--verbose"});
    EXPECT_NE(r.output.find("grey_sphere/0            cache read"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("static bake"), std::string::npos) << r.output;

    // An entry damaged on disk is baked again and said so, without --verbose.
    for (const auto& entry : std::filesystem::directory_iterator(cache)) {
        std::fstream f(entry.path(), std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(-1, std::ios::end);
        f.put('\x7f');
    }
    r = test::run_cli({"scene", scene, "--cache", cache.string(), "--quality", "draft", "--size", "48", "--out", png});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("grey_sphere/0: cache entry not used (checksum mismatch); baked again and stored"),
              std::string::npos)
        << r.output;
}

TEST(SceneCli, BadScenesFailWithTheFileNamed)
{
    const auto bad = test::out("scene_cli/bad.gltf");
    std::ofstream(bad) << "{\"asset\":";
    auto r = test::run_cli({"plan", bad.string()});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.output.find("bad.gltf"), std::string::npos) << r.output;
    r = test::run_cli({"plan"});
    EXPECT_EQ(r.exit_code, 2) << r.output;
    r = test::run_cli({"plan", test::data("scene_mixed.gltf").string(), "--mode", "lambert"});
    EXPECT_EQ(r.exit_code, 2) << r.output;
}

TEST(SceneCli, AScenePastTheMemoryBudgetIsRefusedBeforeAnythingIsAllocated)
{
    // The mixed scene's plan needs about 6.5 MiB (jade plan); a budget of 1 MiB refuses it with
    // the plan's figure, writes nothing and creates no GPU object of the scene.
    const auto png = test::out("scene_cli/over_budget.png");
    std::filesystem::remove(png);
    const auto r = test::run_cli(
        {"scene", test::data("scene_mixed.gltf").string(), "--max-memory", "1", "--out", png.string(), "--verbose"});
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("scene_mixed.gltf: the scene's plan needs"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("over --max-memory 1.0 MiB"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("passes run"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(png));
}

TEST(SceneCli, BenchRenderSceneComparesCachedWithNeverBaked)
{
    const auto cache = test::out("scene_cli/bench_cache/x").parent_path();
    auto r = test::run_cli(
        {"bench", "render", "--scene", test::data("scene_mixed.gltf").string(), "--cache", cache.string()});
    EXPECT_EQ(r.exit_code, 2) << r.output;  // the mixed scene deforms: not a static benchmark
    EXPECT_NE(r.output.find("bending_bar/0' deforms"), std::string::npos) << r.output;

    const auto scene =
        write_gltf("bench_static",
                   {{procedural::sphere(0.05f, 8, 12), 0, {}},
                    {dev::procedural::box({-0.1f, -0.06f, -0.1f}, {0.1f, -0.05f, 0.1f}, 1), 1, {}}},
                   R"([{"extensions":{"KHR_materials_diffuse_transmission":{"diffuseTransmissionFactor":1}}},{}])");
    std::filesystem::remove_all(cache);
    r = test::run_cli({"bench", "render", "--scene", scene.string(), "--cache", cache.string(), "--repeat", "2",
                       "--size", "32", "--quality", "draft"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("1 static bakes were missing and ran now"), std::string::npos) << r.output;
    // The shared LUT's builder and the one transmitting object's attenuation table.
    EXPECT_NE(r.output.find("created 2 compute pipelines (2 objects"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("cached / never baked: GPU"), std::string::npos) << r.output;
}
