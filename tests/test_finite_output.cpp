// Never a NaN or an Inf in an output (docs/robustness.md): profiles at extreme scales are
// refused naming the flag, the writers refuse non-finite values naming the file, attribute and
// vertex, non-finite or zero input normals are recomputed (OFF, PLY, OBJ) or refused (a glTF
// asset, written back as read), and EXR pixels saturate at half's largest value.
#include "test_support.hpp"

#include <jade/dev/io.hpp>
#include <jade/io.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using jade::test::data;
using jade::test::error_of;
using jade::test::run_cli;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

/// A small closed sphere (radius 1, diagonal about 3.5) as OFF.
fs::path sphere_off(const fs::path& dir)
{
    const jade::TriangleMesh m = jade::procedural::sphere(1.0f, 12, 24);
    fs::create_directories(dir);
    std::ofstream f(dir / "sphere.off");
    f << "OFF\n" << m.positions.size() << " " << m.indices.size() / 3 << " 0\n";
    for (const auto& p : m.positions) f << p.x << " " << p.y << " " << p.z << "\n";
    for (size_t i = 0; i < m.indices.size(); i += 3)
        f << "3 " << m.indices[i] << " " << m.indices[i + 1] << " " << m.indices[i + 2] << "\n";
    return dir / "sphere.off";
}

bool all_finite(const std::vector<glm::vec3>& v)
{
    for (const auto& x : v)
        if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) return false;
    return true;
}

// ------------------------------------------------------------ profiles at extreme scales --

TEST(finite_output, ExtremeMmPerUnitIsRefusedNamingTheFlagAndTheMaterial)
{
    const fs::path dir = jade::test::test_folder("finite");
    const fs::path mesh = sphere_off(dir);
    // The examples that wrote NaN _TM, and the other side of each material's range.
    const std::vector<std::pair<std::string, std::string>> refused = {{"apple", "1e15"},  {"apple", "1e-25"},
                                                                      {"skin", "1e19"},   {"skin", "1e30"},
                                                                      {"cream", "1e-20"}, {"jade", "1e-12"}};
    for (const auto& [material, mm] : refused) {
        const auto r = run_cli({"bake", mesh.string(), "--material", material, "--mm-per-unit", mm, "--out",
                                (dir / "o.glb").string(), "--quality", "draft"});
        EXPECT_EQ(r.exit_code, 2) << material << " " << mm << ": " << r.output;
        EXPECT_NE(r.output.find("--mm-per-unit"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("material " + material), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("baking"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir / "o.glb"));
    }
    // Inside the range, near both ends: every value finite.
    for (const auto& [material, mm] : std::vector<std::pair<std::string, std::string>>{
             {"apple", "1e-8"}, {"apple", "1e8"}, {"skin", "1e-8"}, {"cream", "1e-8"}, {"marble", "1e8"}}) {
        const fs::path out = dir / (material + mm + ".glb");
        const auto r = run_cli({"bake", mesh.string(), "--material", material, "--mm-per-unit", mm, "--out",
                                out.string(), "--quality", "draft", "--ao-rays", "4"});
        ASSERT_EQ(r.exit_code, 0) << material << " " << mm << ": " << r.output;
        const jade::TriangleMesh baked = jade::load_mesh(out);
        ASSERT_FALSE(baked.baked_tm.empty());
        EXPECT_TRUE(all_finite(baked.baked_tm)) << material << " " << mm;
    }
}

// ------------------------------------------------------------------------ the writers --

TEST(finite_output, SaveBakedGltfRefusesNonFiniteValuesNamingAttributeAndVertex)
{
    const fs::path dir = jade::test::test_folder("finite");
    fs::create_directories(dir);
    jade::TriangleMesh mesh = jade::procedural::sphere(1.0f, 4, 6);
    mesh.name = "sphere";
    const size_t n = mesh.positions.size();
    struct Case {
        const char* expected;
        std::function<void(jade::BakedAttributes&, jade::TriangleMesh&)> spoil;
    };
    const std::vector<Case> cases = {
        {"_TM of vertex 3 is not finite", [](auto& b, auto&) { b.tm[3].y = kNaN; }},
        {"_TM of vertex 2 is not finite", [](auto& b, auto&) { b.tm[2].x = kInf; }},
        {"_AO of vertex 1 is not finite", [](auto& b, auto&) { b.ao[1] = kNaN; }},
        {"_THICKNESS of vertex 5 is not finite", [](auto& b, auto&) { b.thickness[5] = -kInf; }},
        {"NORMAL of vertex 4 is not finite", [](auto&, auto& m) { m.normals[4].z = kNaN; }},
        {"NORMAL of vertex 0 is zero", [](auto&, auto& m) { m.normals[0] = glm::vec3(0.0f); }},
    };
    for (const auto& c : cases) {
        jade::BakedAttributes b;
        b.ao.assign(n, 0.5f), b.tm.assign(n, glm::vec3(1.0f)), b.thickness.assign(n, 1.0f);
        jade::TriangleMesh m = mesh;
        c.spoil(b, m);
        const std::string e = error_of([&] { jade::save_baked_gltf(dir / "o.glb", m, b); });
        EXPECT_NE(e.find("o.glb: cannot save: "), std::string::npos) << e;
        EXPECT_NE(e.find(c.expected), std::string::npos) << e;
        EXPECT_FALSE(fs::exists(dir / "o.glb"));
    }
}

TEST(finite_output, ExrPixelsSaturateAtHalfsLargestValueAndNaNIsStoredAsZero)
{
    const fs::path dir = jade::test::test_folder("finite");
    fs::create_directories(dir);
    std::vector<float> rgba = {1e6f, -1e9f, kInf, 1.0f, 0.5f, 70000.0f, -kInf, 1.0f};
    jade::save_image(dir / "bright.exr", 2, 1, rgba);
    const jade::dev::LoadedImage img = jade::dev::load_image(dir / "bright.exr");
    const std::vector<float> expected = {65504.0f, -65504.0f, 65504.0f, 1.0f, 0.5f, 65504.0f, -65504.0f, 1.0f};
    EXPECT_EQ(img.rgba, expected);

    rgba[5] = kNaN;  // stored as 0, as PNG stores it
    jade::save_image(dir / "nan.exr", 2, 1, rgba);
    EXPECT_EQ(jade::dev::load_image(dir / "nan.exr").rgba[5], 0.0f);

    // The example: a render under a huge exposure.
    const auto r = run_cli({"render", sphere_off(dir).string(), "--exposure", "1e6", "--size", "32x32", "--quality",
                            "draft", "--ao-rays", "4", "--out", (dir / "render.exr").string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const jade::dev::LoadedImage render = jade::dev::load_image(dir / "render.exr");
    for (float v : render.rgba) ASSERT_TRUE(std::isfinite(v) && std::abs(v) <= 65504.0f) << v;
}

// ---------------------------------------------------------------------- input normals --

TEST(finite_output, BadInputNormalsAreRecomputedWithAWarning)
{
    const fs::path dir = jade::test::test_folder("finite");
    fs::create_directories(dir);
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\nelement face 4\nproperty list uchar int "
        "vertex_indices\nend_header\n1 1 1 0.57 0.57 0.57\n1 -1 -1 nan 0 0\n-1 1 -1 0 0 0\n-1 -1 1 -0.57 -0.57 "
        "0.57\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";
    const std::string off = "NOFF\n4 4 6\n1 1 1 0.57 0.57 0.57\n1 -1 -1 0 0 0\n-1 1 -1 1e39 0 0\n"
                            "-1 -1 1 -0.57 -0.57 0.57\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";
    const std::string obj = "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nvn 0 0 0\nvn 0.57 0.57 0.57\n"
                            "f 1//2 2//1 3//2\nf 1//2 4//2 2//1\nf 1//2 3//2 4//2\nf 2//1 4//2 3//2\n";
    for (const auto& [file, text, first] : std::vector<std::tuple<std::string, std::string, std::string>>{
             {"n.ply", ply, "vertex 1, not finite"}, {"n.off", off, "vertex 1, zero"}, {"n.obj", obj, "zero"}}) {
        std::ofstream(dir / file) << text;
        std::vector<std::string> warnings;
        jade::ReadOptions options;
        options.warnings = &warnings;
        jade::TriangleMesh m;
        try {
            m = jade::load_mesh(dir / file, options);
        } catch (const jade::Error& e) {
            // A reader may refuse the value itself (a number out of float's range): also clean.
            EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
            continue;
        }
        ASSERT_EQ(warnings.size(), 1u) << file;
        EXPECT_NE(warnings[0].find(file + ": "), std::string::npos) << warnings[0];
        EXPECT_NE(warnings[0].find(first), std::string::npos) << warnings[0];
        ASSERT_EQ(m.normals.size(), m.positions.size()) << file;
        for (const auto& n : m.normals) {
            EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << file;
            EXPECT_NEAR(glm::length(n), 1.0f, 0.05f) << file;
        }
        // Through the CLI: the warning is printed and the output's NORMAL is finite.
        const auto r = run_cli({"bake", (dir / file).string(), "--out", (dir / (file + ".glb")).string(), "--quality",
                                "draft", "--ao-rays", "4"});
        ASSERT_EQ(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find("jade: warning: " + file + ": "), std::string::npos) << r.output;
        EXPECT_TRUE(all_finite(jade::load_mesh(dir / (file + ".glb")).normals));
    }
}

TEST(finite_output, AGltfAssetWithBadNormalsIsRefusedNamingThePrimitiveAndVertex)
{
    const fs::path dir = jade::test::test_folder("finite");
    fs::create_directories(dir);
    fs::copy_file(data("cube_external.gltf"), dir / "cube_external.gltf");
    fs::copy_file(data("cube_external.bin"), dir / "cube_external.bin");
    // bufferView 1 (bytes 288..575) holds the NORMALs: vertex 2 gets a NaN.
    std::fstream bin(dir / "cube_external.bin", std::ios::in | std::ios::out | std::ios::binary);
    bin.seekp(288 + 2 * 12 + 4);
    bin.write(reinterpret_cast<const char*>(&kNaN), 4);
    bin.close();
    const std::string e = error_of([&] { jade::GltfAsset::load(dir / "cube_external.gltf"); });
    EXPECT_NE(e.find("cube_external.gltf: mesh 0"), std::string::npos) << e;
    EXPECT_NE(e.find("primitive 0: NORMAL of vertex 2 is not finite"), std::string::npos) << e;
}

/// Bakes a small sphere into DIR/sphere.glb and overwrites the R channel of _TM at vertices 0
/// and 1 with `value`, as a hand-made file would carry it.
fs::path baked_sphere_with_tm(const fs::path& dir, float value)
{
    const fs::path baked = dir / "sphere.glb";
    const auto r = run_cli({"bake", sphere_off(dir).string(), "--quality", "draft", "--out", baked.string()});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::fstream f(baked, std::ios::in | std::ios::out | std::ios::binary);
    uint32_t header[5];
    f.read(reinterpret_cast<char*>(header), sizeof header);  // magic, version, length, JSON length, type
    std::string text(header[3], ' ');
    f.read(text.data(), std::streamsize(text.size()));
    const auto gltf = nlohmann::json::parse(text);
    const auto& accessor = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["attributes"]["_TM"].get<int>()];
    const auto& view = gltf["bufferViews"][accessor["bufferView"].get<int>()];
    const size_t bin = 20 + header[3] + 8;  // the BIN chunk's data
    const size_t at = bin + view.value("byteOffset", size_t(0)) + accessor.value("byteOffset", size_t(0));
    for (int i = 0; i < 2; ++i) {
        f.seekp(std::streamoff(at + size_t(i) * 12));
        f.write(reinterpret_cast<const char*>(&value), 4);
    }
    return baked;
}

TEST(finite_output, InfoCountsTheNonFiniteValuesOfABakedAttribute)
{
    // NaN written by hand (Jade's writer refuses it): `jade info` gives the range of the finite
    // values and counts the others.
    const fs::path baked = baked_sphere_with_tm(jade::test::test_folder("finite_info"), kNaN);
    const auto info = run_cli({"info", baked.string()});
    ASSERT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NE(info.output.find("R "), std::string::npos) << info.output;
    EXPECT_NE(info.output.find("(2 of "), std::string::npos) << info.output;
    EXPECT_NE(info.output.find(" not finite)"), std::string::npos) << info.output;
    // Rendering it is refused naming the file, the attribute and the vertex.
    const auto render =
        run_cli({"render", baked.string(), "--size", "16x16", "--out", (baked.parent_path() / "nan.png").string()});
    EXPECT_EQ(render.exit_code, 1) << render.output;
    EXPECT_NE(render.output.find("sphere.glb: _TM of vertex 0 is negative or not finite"), std::string::npos)
        << render.output;
}

TEST(finite_output, AHugeFiniteTmRendersFiniteNonNegativePixels)
{
    // t_m = 1e38 is finite, so set_mesh takes it; the blur's variance saturates at the LUT's flat
    // limit instead of overflowing (and the MSAA samples outside a triangle cannot extrapolate it
    // below 0).
    const fs::path dir = jade::test::test_folder("finite_huge_tm");
    const fs::path baked = baked_sphere_with_tm(dir, 1e38f);
    const auto r = run_cli({"render", baked.string(), "--size", "64x64", "--out", (dir / "huge.exr").string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const jade::dev::LoadedImage img = jade::dev::load_image(dir / "huge.exr");
    float lo = INFINITY, hi = -INFINITY;
    for (float v : img.rgba) lo = std::min(lo, v), hi = std::max(hi, v);
    EXPECT_GE(lo, 0.0f);
    EXPECT_LT(hi, 100.0f) << "a light of irradiance ~3 on a sphere";
    EXPECT_GT(hi, 0.01f);
}

}  // namespace
